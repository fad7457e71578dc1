"""The three phases of ξ² (Section V-B), read off σ*(g1) along ξ² exactly.

Phase I: the maximal initial run of steps with σ* = 1 (ends at ``t_I``). ``t_II``: the last
step with σ* > 0, or ``t_I`` when no later step has σ* > 0 (proofs/L5.md; the paper's eq. (11)).
Phase III: the steps after ``t_II``. Phase II may contain steps with σ* = 1 or σ* = 0.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from solver.numbers import Number


@dataclass(frozen=True)
class Phases:
    """Phase boundaries of ξ²: steps ``1..t_I`` are phase I, ``t_I+1..t_II`` phase II,
    ``t_II+1..T`` phase III (``0 <= t_I <= t_II <= T``)."""

    t_I: int
    t_II: int
    T: int


def phases_of(schedule: Sequence[Number]) -> Phases:
    """Phase boundaries from σ*(g1) at steps ``1..T`` of ξ².

    Examples
    --------
    >>> from fractions import Fraction as F
    >>> phases_of([F(1), F(1), F(1, 2), F(0), F(1), F(0), F(0)])
    Phases(t_I=2, t_II=5, T=7)
    >>> phases_of([F(0), F(0)]), phases_of([])
    (Phases(t_I=0, t_II=0, T=2), Phases(t_I=0, t_II=0, T=0))
    """
    t_i = 0
    while t_i < len(schedule) and schedule[t_i] == 1:
        t_i += 1
    positive = [t for t, s in enumerate(schedule, start=1) if s > 0]
    t_ii = max(t_i, positive[-1]) if positive else t_i
    return Phases(t_i, t_ii, len(schedule))
