"""Counts and numbers in text meant for people follow one rule each, in one helper each:
``dppio.text.count`` / ``dppio.text.plural`` (``1 step``, ``2 primary walks``, ``missing
keys``) and ``dppio.text.decimal`` (four significant digits; tests/test_workflow.py keeps
format specs out). No message writes ``walk(s)``."""

from __future__ import annotations

import io
import re
import tokenize
from pathlib import Path

import pytest

from dppio.text import count, decimal, plural

ROOT = Path(__file__).resolve().parents[1]
HEDGED = re.compile(r"[a-z]\((s|es)\)")


def _strings(path: Path) -> list[tuple[int, str]]:
    """The string literals of a module (f-string parts included), docstrings excepted."""
    out = []
    previous = tokenize.INDENT
    for tok in tokenize.generate_tokens(io.StringIO(path.read_text(encoding="utf-8")).readline):
        kind = tok.type
        docstring = (kind == tokenize.STRING and previous in (tokenize.INDENT, tokenize.NEWLINE)
                     and tok.string.startswith(('"""', "'''")))
        if kind in (tokenize.STRING, getattr(tokenize, "FSTRING_MIDDLE", -1)) and not docstring:
            out.append((tok.start[0], tok.string))
        if kind not in (tokenize.NL, tokenize.COMMENT):
            previous = kind
    return out


def test_no_message_hedges_a_plural() -> None:
    found = [f"{p.relative_to(ROOT)}:{line}: {text[:80]}"
             for pkg in ("solver", "dppverify", "dppio") for p in sorted((ROOT / pkg).rglob("*.py"))
             for line, text in _strings(p)
             if HEDGED.search(re.sub(r"\{[^{}]*\}", "", text))]  # the text, not the code
    assert not found, "write dppio.text.count(n, noun), not noun(s):\n" + "\n".join(found)


@pytest.mark.parametrize("n, noun, text", [
    (1, "step", "1 step"), (17, "step", "17 steps"), (1, "secondary walk", "1 secondary walk"),
    (2, "primary walk", "2 primary walks"), (6, "primary strategy", "6 primary strategies"),
    (8, "float probability", "8 float probabilities"), (3, "prefix", "3 prefixes"),
    (0, "reached information set", "0 reached information sets")])
def test_count(n: int, noun: str, text: str) -> None:
    assert count(n, noun) == text
    assert plural(n, noun) == text.split(" ", 1)[1]


@pytest.mark.parametrize("x, text", [(1 / 22, "0.04545"), (0.0, "0"), (15 / 22, "0.6818"),
                                     (2.5e-17, "2.5×10^-17"), (1e-9, "1×10^-9")])
def test_decimal_has_four_significant_digits(x: float, text: str) -> None:
    assert decimal(x) == text
    assert decimal(x, sign=True) == (text if x == 0 else "+" + text)
