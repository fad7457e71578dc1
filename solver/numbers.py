"""Exact numbers at the edges: parse JSON numbers/strings to ``Fraction`` and write them back.

Floats enter only through ``str`` (``Fraction("0.6") == 3/5``), never through their binary
value, so ``0.6`` in a JSON file means exactly 3/5.
"""

from __future__ import annotations

import math
from fractions import Fraction
from numbers import Rational

from solver.errors import InvalidInstanceError

__all__ = ["Number", "format_number", "parse_number"]

Number = Fraction | float
"""An exact rational, or a float in float mode (e.g. octile weights)."""


def parse_number(value: object, *, where: str, allow_float: bool = False) -> Number:
    """Parse an exact number from JSON-like input.

    Parameters
    ----------
    value : int, Fraction, str, float
        ``3``, ``"3/5"``, ``"0.25"``; a ``float`` is read through ``str`` (exact decimal)
        unless ``allow_float`` is set, in which case it is kept as a float.
    where : str
        Names the value in error messages (e.g. ``"weight of edge ('a', 'b')"``).
    allow_float : bool
        Keep Python floats as floats (float mode) instead of converting them.

    Returns
    -------
    Fraction or float

    Raises
    ------
    InvalidInstanceError
        If ``value`` is not a finite number.

    Examples
    --------
    >>> parse_number("3/5", where="prior")
    Fraction(3, 5)
    >>> parse_number(0.6, where="prior")
    Fraction(3, 5)
    """
    if isinstance(value, bool):
        raise InvalidInstanceError(f"{where}: expected a number, got {value!r}")
    if isinstance(value, Rational):
        return Fraction(int(value.numerator), int(value.denominator))
    if isinstance(value, float):
        if not math.isfinite(value):
            raise InvalidInstanceError(f"{where}: expected a finite number, got {value!r}")
        return value if allow_float else Fraction(repr(value))
    if isinstance(value, str):
        try:
            return Fraction(value.strip())
        except (ValueError, ZeroDivisionError):
            raise InvalidInstanceError(f"{where}: {value!r} is not a number") from None
    raise InvalidInstanceError(f"{where}: expected a number, got {value!r}")


def format_number(value: Number) -> str | float:
    """Write a number for JSON: exact values as ``"p/q"`` strings, floats as floats.

    Examples
    --------
    >>> format_number(Fraction(12, 5)), format_number(Fraction(3)), format_number(0.5)
    ('12/5', '3', 0.5)
    """
    if isinstance(value, float):
        return value
    return str(Fraction(value))
