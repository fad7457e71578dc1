"""Numbers: exact parsing of JSON numbers, formatting, and the comparison rule.

The checker's own number handling (``docs/formats.md``, "Numbers"): JSON integers are exact
integers, JSON decimal literals are the exact decimals they spell (``0.6`` is 3/5, never a
binary float: documents are read with ``json.loads(..., parse_float=Fraction)``), and
strings ``"p/q"``, ``"p"``, ``"-p/q"``, ``"0.25"`` are exact rationals.

Exact values are kept as ``int`` when integral and as ``Fraction`` otherwise (integer
arithmetic is much faster than ``Fraction`` arithmetic, and most instances have integer
weights). Float mode (instances with ``"numbers": "float"``) keeps edge weights as floats;
every comparison then goes through a :class:`Tolerance`.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from fractions import Fraction
from numbers import Rational
from typing import Any

from dppverify.limits import MAX_JSON_DEPTH, MAX_NUMERAL_CHARS, check_numeral, check_rational

__all__ = ["FLOAT_TOLERANCE", "INF", "Number", "Tolerance", "format_number", "normalize",
           "parse_json", "parse_number", "to_float"]

Number = int | Fraction | float
"""An exact rational (``int`` or ``Fraction``) or, in float mode, a ``float``."""

INF = math.inf
"""Distance to an unreachable node."""

FLOAT_TOLERANCE = 1e-9
"""Relative tolerance of float mode: ``|a - b| <= 1e-9 * max(1, |a|, |b|)``."""


def normalize(x: Number) -> Number:
    """Return ``x`` as an ``int`` when it is an integral rational, else unchanged.

    Examples
    --------
    >>> normalize(Fraction(6, 3)), normalize(Fraction(1, 2)), normalize(0.5)
    (2, Fraction(1, 2), 0.5)
    """
    if isinstance(x, Fraction) and x.denominator == 1:
        return int(x.numerator)
    return x


def parse_number(value: object, *, where: str, allow_float: bool = False) -> Number:
    """Parse one number of a JSON document exactly.

    Parameters
    ----------
    value : object
        An ``int``, a ``Fraction`` (a JSON decimal literal read with
        ``parse_float=Fraction``), a string ``"p/q"`` / ``"0.25"``, or a ``float``.
    where : str
        Names the value in the error message.
    allow_float : bool
        Float mode: decimal literals and floats become binary floats.

    Returns
    -------
    int, Fraction or float
        Exact (``int`` when integral) unless ``allow_float`` is set.

    Raises
    ------
    ValueError
        One line naming ``where`` when ``value`` is not a finite number (the callers turn it
        into the error class of their document).

    Examples
    --------
    >>> parse_number("3/5", where="prior"), parse_number(Fraction("0.6"), where="prior")
    (Fraction(3, 5), Fraction(3, 5))
    >>> parse_number(4, where="w"), parse_number("2/1", where="w")
    (4, 2)
    >>> parse_number(Fraction("0.1"), where="w", allow_float=True)
    0.1
    >>> parse_number("x", where="weight of edge 3")
    Traceback (most recent call last):
    ValueError: weight of edge 3: 'x' is not a number
    """
    if isinstance(value, bool) or value is None:
        raise ValueError(f"{where}: expected a number, got {json.dumps(value)}")
    if isinstance(value, Rational):
        exact = normalize(Fraction(int(value.numerator), int(value.denominator)))
        check_rational(exact, where=where)
        if allow_float and not isinstance(value, int):
            return float(exact)
        return exact
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ValueError(f"{where}: expected a finite number, got {value!r}")
        return value if allow_float else normalize(Fraction(repr(value)))
    if isinstance(value, str):
        check_numeral(value, where=where)
        try:
            exact = normalize(Fraction(value.strip()))
        except (ValueError, ZeroDivisionError):
            raise ValueError(f"{where}: {value!r} is not a number") from None
        check_rational(exact, where=where)
        return exact
    raise ValueError(f"{where}: expected a number, got {type(value).__name__}")


def format_number(x: Number | None) -> str | float | int | None:
    """Write a number for JSON: exact values as ``"p/q"`` strings, floats as floats.

    Examples
    --------
    >>> format_number(Fraction(12, 5)), format_number(3), format_number(0.25), format_number(None)
    ('12/5', '3', 0.25, None)
    """
    if x is None:
        return None
    if isinstance(x, float):
        return x if math.isfinite(x) else str(x)
    return str(Fraction(x))


def to_float(x: Number) -> float:
    """``float(x)`` (for LP data and reports).

    Examples
    --------
    >>> to_float(Fraction(1, 4))
    0.25
    """
    return float(x)


def _reject_constant(name: str) -> Any:
    raise ValueError(f"non-finite number {name} is not allowed")


def _parse_float(text: str) -> Fraction:
    check_numeral(text, where="JSON number")
    return Fraction(text)


def _parse_int(text: str) -> int:
    if len(text) > MAX_NUMERAL_CHARS:  # an integer literal has no exponent to check
        check_numeral(text, where="JSON number")
    return int(text)


def parse_json(text: str | bytes) -> Any:
    """Parse JSON text with decimal literals as exact ``Fraction`` (``NaN``/``Infinity`` refused).

    Numerals beyond the limits of :mod:`dppverify.limits` (length, exponent) and documents
    nested deeper than ``MAX_JSON_DEPTH`` are refused before they can hang the parser.

    Raises ``ValueError`` (``json.JSONDecodeError`` for syntax errors; ``UnicodeDecodeError``
    for bytes that are not UTF-8).

    Examples
    --------
    >>> parse_json('{"p": 0.6, "q": 2}')
    {'p': Fraction(3, 5), 'q': 2}
    >>> parse_json("[" * 100 + "]" * 100)
    Traceback (most recent call last):
    ValueError: JSON nested deeper than 64 levels
    """
    try:
        doc = json.loads(text, parse_float=_parse_float, parse_int=_parse_int,
                         parse_constant=_reject_constant)
    except RecursionError:
        raise ValueError(f"JSON nested deeper than {MAX_JSON_DEPTH} levels") from None
    _check_depth(doc)
    return doc


def _check_depth(doc: Any) -> None:
    stack = [(doc, 1)]
    while stack:
        x, depth = stack.pop()
        if isinstance(x, dict | list):
            if depth > MAX_JSON_DEPTH:
                raise ValueError(f"JSON nested deeper than {MAX_JSON_DEPTH} levels")
            stack.extend((y, depth + 1) for y in (x.values() if isinstance(x, dict) else x))


@dataclass(frozen=True)
class Tolerance:
    """Equality and order of numbers: exact, or within a relative tolerance in float mode.

    Exact mode (``exact=True``) compares with ``==`` and ``<=``: no tolerance is ever
    applied to rational inputs. Float mode treats ``a`` and ``b`` as equal when
    ``|a - b| <= rel * max(1, |a|, |b|)``.

    Examples
    --------
    >>> Tolerance(exact=True).eq(Fraction(1, 3), Fraction(2, 6))
    True
    >>> Tolerance(exact=False).eq(0.1 + 0.2, 0.3), Tolerance(exact=True).eq(0.1 + 0.2, 0.3)
    (True, False)
    >>> Tolerance(exact=False).lt(1.0, 1.0 + 1e-12)
    False
    """

    exact: bool
    rel: float = FLOAT_TOLERANCE

    @property
    def tolerance(self) -> float | None:
        """The relative tolerance in float mode, ``None`` when exact."""
        return None if self.exact else self.rel

    def _slack(self, a: Number, b: Number) -> float:
        return self.rel * max(1.0, abs(float(a)), abs(float(b)))

    def eq(self, a: Number, b: Number) -> bool:
        """``a == b`` (within the tolerance in float mode)."""
        if self.exact:
            return bool(a == b)
        return abs(float(a) - float(b)) <= self._slack(a, b)

    def le(self, a: Number, b: Number) -> bool:
        """``a <= b`` (within the tolerance in float mode)."""
        if self.exact:
            return bool(a <= b)
        return float(a) <= float(b) + self._slack(a, b)

    def lt(self, a: Number, b: Number) -> bool:
        """``a < b`` by more than the tolerance (strictly, in exact mode)."""
        return not self.le(b, a)
