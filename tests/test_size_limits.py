"""Size limits of the package code: no function over 80 lines or with more than 9
parameters, no module over 500 lines (``dppverify``, ``solver``, ``dppio``, ``dpp``).

A function's length runs from its ``def`` line to its last line (its docstring counts, its
decorators do not). Its parameters are the named ones a caller passes (positional-only,
positional, keyword-only), ``self`` and ``cls`` excepted, as pylint's ``max-args`` counts
them; ``*args`` and ``**kwargs`` are not counted. A click command's callback is excepted from
the parameter limit only: its parameters are its options, and ``--help`` documents them (it
builds one record from them, as ``dpp audit`` builds ``AuditConfig``). The scan reads the
sources with :mod:`ast`.

:data:`KNOWN` lists what is still over a limit, each with the reason; an entry that is no
longer over its limit fails the test, so the list only shrinks.
"""

from __future__ import annotations

import ast
from pathlib import Path

from tests.test_docstrings import _is_click

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("dppverify", "solver", "dppio", "dpp")
MAX_FUNCTION_LINES = 80
MAX_PARAMETERS = 9
MAX_MODULE_LINES = 500

KNOWN: dict[str, str] = {}
"""``path`` (a module), ``path:function lines`` or ``path:function parameters`` -> why it is
still over its limit."""


def _parameters(function: ast.FunctionDef | ast.AsyncFunctionDef) -> int:
    args = function.args
    names = [a.arg for a in (*args.posonlyargs, *args.args, *args.kwonlyargs)]
    return len(names) - (1 if names[:1] in (["self"], ["cls"]) else 0)


def scan_source(source: str, where: str) -> list[str]:
    """Every limit the module's source exceeds, as ``KNOWN`` keys with the measure."""
    found = []
    lines = len(source.splitlines())
    if lines > MAX_MODULE_LINES:
        found.append(f"{where} ({lines} lines)")
    for node in ast.walk(ast.parse(source)):
        if not isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
            continue
        length = (node.end_lineno or node.lineno) - node.lineno + 1
        if length > MAX_FUNCTION_LINES:
            found.append(f"{where}:{node.name} lines ({length})")
        n = _parameters(node)
        if n > MAX_PARAMETERS and not _is_click(node):
            found.append(f"{where}:{node.name} parameters ({n})")
    return found


def _over() -> dict[str, str]:
    """The measured violations of the packages, keyed as :data:`KNOWN` (measure dropped)."""
    out = {}
    for package in PACKAGES:
        for path in sorted((ROOT / package).rglob("*.py")):
            where = path.relative_to(ROOT).as_posix()
            for item in scan_source(path.read_text(encoding="utf-8"), where):
                out[item.rsplit(" (", 1)[0]] = item
    return out


def test_no_function_or_module_is_over_its_limit() -> None:
    over = _over()
    new = sorted(item for key, item in over.items() if key not in KNOWN)
    assert not new, "over the size limits:\n" + "\n".join(new)


def test_every_known_exception_is_still_over_its_limit() -> None:
    gone = sorted(set(KNOWN) - set(_over()))
    assert not gone, "no longer over the limits, remove from KNOWN:\n" + "\n".join(gone)


_SAMPLE = '''
import click

@click.command()
def cmd(a, b, c, d, e, f, g, h, i, j):
    """A click command: its options are its parameters."""

class C:
    def method(self, a, b, c, d, e, f, g, h, i, *args, **kwargs):
        pass

def wide(a, b, c, d, e, f, g, h, i, j):
    pass

def long():
''' + "    x = 1\n" * 80


def test_the_scan_measures_a_sample() -> None:
    found = scan_source(_SAMPLE, "s.py")
    assert found == ["s.py:wide parameters (10)", "s.py:long lines (81)"]
    assert scan_source("x = 1\n" * 501, "m.py") == ["m.py (501 lines)"]
    assert scan_source("x = 1\n" * 500, "m.py") == []
