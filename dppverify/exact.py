"""Numbers: the exact number type, formatting, the comparison rule, and the exact bracket.

The checker's own number handling (``docs/formats.md``, "Numbers"): JSON integers are exact
integers, JSON decimal literals are the exact decimals they spell (``0.6`` is 3/5, never a
binary float), and strings ``"p/q"``, ``"p"``, ``"-p/q"``, ``"0.25"`` are exact rationals.
Reading them from JSON is :func:`dppverify.formats.json_reading.parse_number` (and
:func:`~dppverify.formats.json_reading.parse_json` for whole documents); this module holds what is
done with the numbers once read.

Exact values are kept as ``int`` when integral and as ``Fraction`` otherwise (integer
arithmetic is much faster than ``Fraction`` arithmetic, and most instances have integer
weights). Float mode (instances with ``"numbers": "float"``) keeps edge weights as floats;
how numbers are compared is the instance's number mode (:mod:`dppverify.numbers`).

:class:`Bracket` is the one type of an exact value or exact bounds on ``V_H`` with where each
bound comes from, for both routes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

Number = int | Fraction | float
"""An exact rational (``int`` or ``Fraction``) or, in float mode, a ``float``."""

INF = math.inf
"""Distance to an unreachable node."""


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


@dataclass(frozen=True)
class Bracket:
    """Exact bounds ``lower <= V_H <= upper``, where they come from, and why still open.

    The one type of an exact value or bracket, for the tree route
    (:mod:`dppverify.tree_route.bracket`) and the structured route
    (:class:`dppverify.structured.proved_value.NValue`) alike.

    Examples
    --------
    >>> b = Bracket(Fraction(2), Fraction(5, 2), "a Defender", "an Attacker", "no exact LP")
    >>> b.closed, b.exact, Bracket(2, 2, "x", "y").exact
    (False, None, 2)
    """

    lower: Number
    upper: Number
    lower_source: str
    upper_source: str
    reason: str | None = None

    @property
    def closed(self) -> bool:
        """True when the bounds coincide: ``V_H`` is then known exactly."""
        return self.lower == self.upper

    @property
    def exact(self) -> Number | None:
        """``V_H`` exactly when the bracket is closed, else None."""
        return self.lower if self.closed else None
