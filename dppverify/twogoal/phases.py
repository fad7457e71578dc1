"""The phases of the secondary's walk ξ² under σ* (eqs. (10)-(11), proofs/L5.md).

Phase I is the maximal initial run of steps with σ*(g1) = 1 (ends at ``t_I``); ``t_II`` is the
last step with σ*(g1) > 0 (``t_I`` if there is none after it); phase III is the steps after
``t_II``.
"""

from __future__ import annotations

from dataclasses import dataclass

from dppverify.exact import Number
from dppverify.numbers import EXACT, NumberMode


@dataclass(frozen=True)
class Phases:
    """Phase boundaries of ξ²: steps ``1..t_I`` are phase I, ``t_I+1..t_II`` phase II,
    ``t_II+1..T`` phase III (``0 <= t_I <= t_II <= T``).

    Examples
    --------
    >>> ph = Phases(t_I=1, t_II=2, T=3)
    >>> [ph.phase(t) for t in (0, 1, 2, 3)], ph.as_tuple()
    ([1, 1, 2, 3], (1, 2, 3))
    """

    t_I: int
    t_II: int
    T: int

    def phase(self, t: int) -> int:
        """The phase (1, 2 or 3) of step ``t``; the start (``t = 0``) counts as phase I."""
        if t <= self.t_I:
            return 1
        return 2 if t <= self.t_II else 3

    def as_tuple(self) -> tuple[int, int, int]:
        """``(t_I, t_II, T)``."""
        return (self.t_I, self.t_II, self.T)


def phases_of(schedule: list[Number], numbers: NumberMode = EXACT) -> Phases:
    """``(t_I, t_II, T)`` of a σ*(g1) schedule along ξ² (eqs. (10)-(11), proofs/L5.md).

    Phase I is the maximal initial run of steps with σ* = 1; ``t_II`` is the last step with
    σ* > 0 (``t_I`` if there is none after it). In float mode "= 1" and "> 0" are decided
    within ``numbers``' tolerance.

    Examples
    --------
    >>> from fractions import Fraction
    >>> phases_of([1, 1, Fraction(1, 2), 0, 1, 0, 0])
    Phases(t_I=2, t_II=5, T=7)
    >>> phases_of([0, 0]).as_tuple(), phases_of([]).as_tuple(), phases_of([1, 1]).as_tuple()
    ((0, 0, 2), (0, 0, 0), (2, 2, 2))
    >>> from dppverify.numbers import FloatNumbers
    >>> phases_of([0.9999999999999998, 1e-17], FloatNumbers())
    Phases(t_I=1, t_II=1, T=2)
    """
    T = len(schedule)
    t1 = 0
    while t1 < T and numbers.equal(schedule[t1], 1):
        t1 += 1
    positive = [t for t, s in enumerate(schedule, start=1) if numbers.less_than(0, s)]
    t2 = max([t1, *positive])
    return Phases(t_I=t1, t_II=t2, T=T)
