"""Numbers: the exact number type, formatting, and the comparison rule.

The checker's own number handling (``docs/formats.md``, "Numbers"): JSON integers are exact
integers, JSON decimal literals are the exact decimals they spell (``0.6`` is 3/5, never a
binary float), and strings ``"p/q"``, ``"p"``, ``"-p/q"``, ``"0.25"`` are exact rationals.
Reading them from JSON is :func:`dppverify.json_reading.parse_number` (and
:func:`~dppverify.json_reading.parse_json` for whole documents); this module holds what is
done with the numbers once read.

Exact values are kept as ``int`` when integral and as ``Fraction`` otherwise (integer
arithmetic is much faster than ``Fraction`` arithmetic, and most instances have integer
weights). Float mode (instances with ``"numbers": "float"``) keeps edge weights as floats;
every comparison then goes through a :class:`Tolerance`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

__all__ = ["FLOAT_TOLERANCE", "INF", "Number", "Tolerance", "format_number", "normalize",
           "to_float"]

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
