"""How both packages show numbers and JSON values in text: one rule, in one place.

- :func:`decimal`: every decimal in text output and figures (an approximation beside an exact
  ``p/q``, a float-mode result, an LP value, a mean) has :data:`DIGITS` significant digits,
  trailing zeros dropped, powers of ten outside ``[10^-4, 10^6)`` written ``×10^e``; the
  exact value (or the full float) is in the command's JSON or CSV output.
- :func:`show`: a number in a message: an exact rational as ``p/q`` while it is at most
  :data:`MAX_EXACT_CHARS` characters long, else (and for a float) its :func:`decimal`;
- :func:`json_shown`: a value from a user's JSON document, written back as the user wrote
  it for a one-line message (never a Python repr such as ``Fraction(7, 10)``).
- :func:`escaped`: a string from a document (a certificate's version, a map name, a CSV
  cell, a file name) as it may reach a terminal: every character that could move the cursor,
  end the line or reorder the text (control characters, line and paragraph separators,
  bidirectional overrides) written as a visible escape, and the text cut at a bound — so no
  document can forge or hide a line. :func:`terminal_line` applies the same rule to a whole
  message at the place where it is printed.

These decide no result (formatting only), so they live in the shared edges.
"""

from __future__ import annotations

import json
import math
import unicodedata
from decimal import Decimal, localcontext
from fractions import Fraction
from typing import Any

MAX_SHOWN_CHARS = 80
"""Characters of a document's string quoted in a message (:func:`escaped`'s default)."""

MAX_LINE_CHARS = 2000
"""Characters of one printed message line (:func:`terminal_line`): beyond, cut in the middle."""

_SAFE_FORMAT = frozenset("\u200d")  # the zero-width joiner of emoji sequences: harmless


def _unsafe(ch: str) -> bool:
    """True for a character a terminal does not show as itself: a control character (C0,
    DEL, C1), a line or paragraph separator, a format character (bidirectional overrides and
    isolates, zero-width spaces, the byte-order mark), a lone surrogate (a file name that is
    not UTF-8)."""
    if " " <= ch <= "~":
        return False
    return unicodedata.category(ch) in ("Cc", "Cf", "Zl", "Zp", "Cs", "Co", "Cn") \
        and ch not in _SAFE_FORMAT


def _escape(ch: str) -> str:
    n = ord(ch)
    if n < 0x100:
        return f"\\x{n:02x}"
    return f"\\u{n:04x}" if n < 0x10000 else f"\\U{n:08x}"


def escaped(text: object, limit: int = MAX_SHOWN_CHARS) -> str:
    """``text`` (a string from a document, or any value as ``str``) safe to print inside a
    one-line message: every character a terminal would not show as itself written as a
    ``\\xNN`` / ``\\uNNNN`` escape, and at most ``limit`` characters of it kept (then
    ``…`` and the full length).

    Examples
    --------
    >>> escaped("0.1.0\\rprovenance OK")
    '0.1.0\\\\x0dprovenance OK'
    >>> escaped("a\\x1b[2Kb"), escaped("\\u202egnp.exe"), escaped("café σ*")
    ('a\\\\x1b[2Kb', '\\\\u202egnp.exe', 'café σ*')
    >>> escaped("v" * 5_000_000, limit=10)
    'vvvvvvvvvv… (5000000 characters)'
    >>> escaped(None), escaped(3)
    ('None', '3')
    """
    s = text if isinstance(text, str) else str(text)
    cut = len(s) > limit
    head = s[:limit] if cut else s
    if not head.isascii() or not head.isprintable():
        head = "".join(_escape(c) if _unsafe(c) else c for c in head)
    return f"{head}… ({len(s)} characters)" if cut else head


def json_escaped(text: str) -> str:
    """JSON text (``json.dumps(..., ensure_ascii=False)``: readable σ\\*, ≈) with every
    character a terminal would not show as itself written as its ``\\uXXXX`` escape (a
    surrogate pair beyond the BMP) — the same JSON value, which no document can use to
    forge or reorder the lines around it. Control characters are escaped by ``json`` itself.

    Examples
    --------
    >>> json_escaped(json.dumps({"node": "\u202eg1", "σ*": 1}, ensure_ascii=False))
    '{"node": "\\\\u202eg1", "σ*": 1}'
    >>> json.loads(json_escaped(json.dumps(["\U000e0001"], ensure_ascii=False)))
    ['\U000e0001']
    """
    if text.isascii():
        return text
    return "".join(_json_escape(c) if not c.isascii() and _unsafe(c) else c for c in text)


def _json_escape(ch: str) -> str:
    n = ord(ch)
    if n < 0x10000:
        return f"\\u{n:04x}"
    n -= 0x10000
    return f"\\u{0xD800 + (n >> 10):04x}\\u{0xDC00 + (n & 0x3FF):04x}"


def terminal_text(text: str) -> str:
    """Text output of several lines (a report, a table) as it is printed: the line breaks
    kept, every other character a terminal would not show as itself escaped
    (:func:`escaped`), however long the lines.

    Examples
    --------
    >>> print(terminal_text("path: s → \\x1b[2Ka\\ntotal 3"))
    path: s → \\x1b[2Ka
    total 3
    """
    if text.isprintable() or not any(_unsafe(c) for c in text if c != "\n"):
        return text
    return "\n".join(escaped(line, limit=len(line)) for line in text.split("\n"))


def terminal_line(text: str, limit: int = MAX_LINE_CHARS) -> str:
    """One message line as it is printed: a line break or any other white space but the
    space becomes a space, every other character a terminal would not show as itself an
    escape (:func:`escaped`), and a line longer than ``limit`` characters is cut in the
    middle — the last defence at the print sites, whatever a message quotes.

    Examples
    --------
    >>> terminal_line("error: bad\\r\\nname\\x1b[1A in x.json")
    'error: bad  name\\\\x1b[1A in x.json'
    >>> len(terminal_line("x" * 10_000)) < 2100
    True
    """
    flat = text
    if not text.isprintable():
        flat = "".join(" " if c.isspace() else c for c in text)
    if len(flat) > limit:
        half = limit // 2
        flat = f"{flat[:half]} … ({len(flat)} characters) … {flat[-half:]}"
    return escaped(flat, limit=len(flat))

DIGITS = 4
"""Significant digits of every decimal shown in text and figures."""

MAX_EXACT_CHARS = 24
"""An exact number longer than this is shown as a decimal (its exact form is in ``--json``)."""


def decimal(x: float | int | Fraction, *, sign: bool = False) -> str:
    """``x`` with :data:`DIGITS` significant digits (``sign``: a ``+`` before positives).

    Examples
    --------
    >>> decimal(Fraction(5, 22)), decimal(Fraction(71, 18)), decimal(13.6), decimal(2.4000001)
    ('0.2273', '3.944', '13.6', '2.4')
    >>> decimal(228.25), decimal(24.970562748477143), decimal(0.0), decimal(-0.0478)
    ('228.2', '24.97', '0', '-0.0478')
    >>> decimal(Fraction(10**30 + 1, 3)), decimal(2.5e-7), decimal(0.012, sign=True)
    ('3.333×10^29', '2.5×10^-7', '+0.012')
    >>> decimal(Fraction(10**80 * 109, 100)), decimal(123456), decimal(1234567)
    ('1.09×10^80', '123500', '1.235×10^6')
    >>> decimal(float("inf")), decimal(float("nan"))
    ('inf', 'nan')
    """
    if isinstance(x, float) and not math.isfinite(x):
        return str(x)
    q = Fraction(x)  # exact: a rational of any size never overflows a float
    with localcontext() as ctx:
        ctx.prec = DIGITS
        d = (Decimal(q.numerator) / Decimal(q.denominator)).normalize()
    plus = "+" if sign and q > 0 else ""
    if d == 0:
        return plus + "0"
    e = d.adjusted()
    if -4 <= e < 6:
        return plus + f"{d:f}"
    return plus + f"{d.scaleb(-e).normalize():f}×10^{e}"


def show(x: float | int | Fraction | None) -> str:
    """A number for a message: exact rationals as ``p/q``, floats as :func:`decimal`.

    An exact number longer than :data:`MAX_EXACT_CHARS` characters is shown as ``≈`` and its
    :func:`decimal` (powers of ten for large ones): the exact value is in the ``--json``
    output.

    Examples
    --------
    >>> show(Fraction(12, 5)), show(3), show(2.4000000000001), show(None)
    ('12/5', '3', '2.4', '-')
    >>> show(Fraction(10**30 + 1, 3)), show(2**300)
    ('≈3.333×10^29', '≈2.037×10^90')
    >>> show(Fraction(2**100 + 1, 2**100))
    '≈1'
    """
    if x is None:
        return "-"
    if isinstance(x, float):
        return decimal(x)
    text = str(Fraction(x))
    if len(text) <= MAX_EXACT_CHARS:
        return text
    return "≈" + decimal(x)


_PLURALS = {"prefix": "prefixes", "leaf": "leaves", "entry": "entries", "match": "matches",
            "probability": "probabilities", "strategy": "strategies"}


def count(n: int, noun: str) -> str:
    """``n`` and ``noun``, plural unless ``n`` is 1 (the last word of ``noun`` is inflected).

    Examples
    --------
    >>> count(1, "example"), count(3, "example"), count(0, "DP step"), count(1, "prefix")
    ('1 example', '3 examples', '0 DP steps', '1 prefix')
    >>> count(2, "prefix"), count(2, "leaf"), count(5, "information set"), count(2, "entry")
    ('2 prefixes', '2 leaves', '5 information sets', '2 entries')
    >>> count(1, "step"), count(3, "float probability"), count(6, "primary strategy")
    ('1 step', '3 float probabilities', '6 primary strategies')
    """
    if n == 1:
        return f"{n} {noun}"
    head, _, last = noun.rpartition(" ")
    plural = _PLURALS.get(last, last + "s")
    return f"{n} {head + ' ' if head else ''}{plural}"


def plural(n: int, noun: str) -> str:
    """``noun``, plural unless ``n`` is 1 (the word alone, for a list that follows it).

    Examples
    --------
    >>> plural(1, "key"), plural(3, "key"), plural(2, "map character"), plural(0, "entry")
    ('key', 'keys', 'map characters', 'entries')
    """
    return count(n, noun).split(" ", 1)[1]


def json_shown(x: Any, limit: int = 80) -> str:
    """A parsed JSON value as the user wrote it, for a one-line message (never a repr).

    Numbers read as ``Fraction`` are written back as the decimal they were (``0.7``) or as
    ``p/q`` when they are no finite decimal; the text is cut at ``limit`` characters.

    Examples
    --------
    >>> json_shown([Fraction(7, 10)]), json_shown({"a": [1, "x", None, Fraction(1, 3)]})
    ('[0.7]', '{"a": [1, "x", null, 1/3]}')
    >>> json_shown([Fraction(-1, 8), 0.25, True]), json_shown(list(range(100)), limit=20)
    ('[-0.125, 0.25, true]', '[0, 1, 2, 3, 4, 5, 6...')
    """
    text = _shown(x)
    return text if len(text) <= limit else text[:limit] + "..."


def _shown(x: Any) -> str:
    if isinstance(x, list | tuple):
        return "[" + ", ".join(_shown(v) for v in x) + "]"
    if isinstance(x, dict):
        return "{" + ", ".join(f"{json.dumps(str(k))}: {_shown(v)}" for k, v in x.items()) + "}"
    if isinstance(x, Fraction):
        return _fraction_text(x)
    return json.dumps(x, default=str)


def _fraction_text(x: Fraction) -> str:
    """``x`` as the finite decimal it is, else ``p/q``."""
    if x.denominator == 1:
        return str(x.numerator)
    den, twos, fives = x.denominator, 0, 0
    while den % 2 == 0:
        den, twos = den // 2, twos + 1
    while den % 5 == 0:
        den, fives = den // 5, fives + 1
    if den != 1:
        return f"{x.numerator}/{x.denominator}"
    places = max(twos, fives)
    digits = str(abs(x.numerator) * 10**places // x.denominator).rjust(places + 1, "0")
    return f"{'-' if x < 0 else ''}{digits[:-places]}.{digits[-places:]}"
