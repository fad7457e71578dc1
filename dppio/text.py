"""How both packages show numbers and JSON values in text: one rule, in one place.

- :func:`decimal`: every decimal in text output and figures (an approximation beside an exact
  ``p/q``, a float-mode result, an LP value, a mean) has :data:`DIGITS` significant digits,
  trailing zeros dropped, powers of ten outside ``[10^-4, 10^6)`` written ``×10^e``; the
  exact value (or the full float) is in the command's JSON or CSV output.
- :func:`show`: a number in a message: an exact rational as ``p/q`` while it is at most
  :data:`MAX_EXACT_CHARS` characters long, else (and for a float) its :func:`decimal`;
- :func:`json_shown`: a value from a user's JSON document, written back as the user wrote
  it for a one-line message (never a Python repr such as ``Fraction(7, 10)``).

These decide no result (formatting only), so they live in the shared edges.
"""

from __future__ import annotations

import json
import math
from decimal import Decimal, localcontext
from fractions import Fraction
from typing import Any

__all__ = ["DIGITS", "MAX_EXACT_CHARS", "count", "decimal", "json_shown", "show"]

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


_PLURALS = {"prefix": "prefixes", "leaf": "leaves", "entry": "entries", "match": "matches"}


def count(n: int, noun: str) -> str:
    """``n`` and ``noun``, plural unless ``n`` is 1 (the last word of ``noun`` is inflected).

    Examples
    --------
    >>> count(1, "example"), count(3, "example"), count(0, "DP step"), count(1, "prefix")
    ('1 example', '3 examples', '0 DP steps', '1 prefix')
    >>> count(2, "prefix"), count(2, "leaf"), count(5, "information set"), count(2, "entry")
    ('2 prefixes', '2 leaves', '5 information sets', '2 entries')
    """
    if n == 1:
        return f"{n} {noun}"
    head, _, last = noun.rpartition(" ")
    plural = _PLURALS.get(last, last + "s")
    return f"{n} {head + ' ' if head else ''}{plural}"


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
