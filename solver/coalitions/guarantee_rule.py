"""The guarantee-vector Defender of the N-goal game: ``σ`` from the state ``r`` (exact).

State ``r ∈ Q^N``, ``r = h`` at the start. On a step ``v -> u`` of weight ``w`` the Defender
plays the canonical point of

    F = { σ ∈ Δ^N : σ(S) >= (r(S) - m_S(u)) / w  for every non-empty S }

(``m_S`` the coalition DP at ``H = inf``; ``S`` with ``m_S(u)`` undefined give no constraint),
namely its lexicographic minimum in the *priority order* (types by decreasing prior, ties by
index): least mass on the most likely type, then on the next, and so on. Then
``r <- r - w·σ``. If ``F`` is empty the Defender puts all the weight on the first type of the
priority order (this never happens when the arc condition holds, ``proofs/NSOLVE.md``).
With two goals this is the paper's σ* (least mass on the primary goal).

The lexicographic minimum of a polytope is one of its vertices; the vertices of ``F`` are
found exactly by trying every choice of ``N - 1`` tight constraints among the non-redundant
ones (``σ_θ >= 0``, and ``σ(S) >= a_S`` for ``a_S > 0`` not implied by a subset ``T ⊆ S`` with
``a_T >= a_S``), in exact rationals.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Sequence
from fractions import Fraction

from solver.numbers import solve_exact

__all__ = ["guarantee_step", "priority_order"]


def priority_order(prior: Sequence[Fraction]) -> tuple[int, ...]:
    """Types by decreasing prior, ties by increasing index.

    Examples
    --------
    >>> priority_order([Fraction(1, 4), Fraction(1, 2), Fraction(1, 4)])
    (1, 0, 2)
    """
    return tuple(sorted(range(len(prior)), key=lambda t: (-prior[t], t)))


def guarantee_step(r: Sequence[Fraction], m_next: Callable[[int], Fraction | None], w: Fraction,
                   order: Sequence[int]) -> tuple[tuple[Fraction, ...], bool]:
    """The canonical ``σ`` of one step and whether ``F`` was non-empty.

    Parameters
    ----------
    r : sequence of Fraction
        The state before the step.
    m_next : callable
        ``mask -> m_S(u)`` at the step's head (None: no constraint).
    w : Fraction
        The step's weight.
    order : sequence of int
        The priority order (:func:`priority_order`).

    Examples
    --------
    Two types, ``r = (3, 1)``, ``m(u) = {1}: 2, {2}: 1, {12}: 3`` and ``w = 1``: type 1 must
    get at least 1, so ``σ = (1, 0)``:

    >>> m = {1: Fraction(2), 2: Fraction(1), 3: Fraction(3)}
    >>> guarantee_step([Fraction(3), Fraction(1)], m.get, Fraction(1), (0, 1))
    ((Fraction(1, 1), Fraction(0, 1)), True)
    """
    n = len(r)
    lows: dict[int, Fraction] = {}
    for mask in range(1, 1 << n):
        m = m_next(mask)
        if m is None:
            continue
        a = (sum((r[i] for i in range(n) if mask >> i & 1), Fraction(0)) - m) / w
        if a > 0:
            lows[mask] = a
    # σ(S) >= 1 forces σ inside S: when those sets meet in one type, F is that vertex or empty
    forced = (1 << n) - 1
    for mask, a in lows.items():
        if a >= 1:
            forced &= mask
    if forced and forced & (forced - 1) == 0:
        theta = forced.bit_length() - 1
        point = tuple(Fraction(int(i == theta)) for i in range(n))
        if all(mask >> theta & 1 or a <= 0 for mask, a in lows.items()) and all(
                a <= 1 for a in lows.values()):
            return point, True
    # drop constraints implied by a subset with a larger bound
    keep = {s: a for s, a in lows.items()
            if not any(t != s and t & s == t and lows[t] >= a for t in lows)}
    if not keep:
        return tuple(Fraction(int(i == order[-1])) for i in range(n)), True
    cons: list[tuple[list[Fraction], Fraction]] = [
        ([Fraction(int(i == j)) for j in range(n)], Fraction(0)) for i in range(n)]
    cons += [([Fraction(s >> j & 1) for j in range(n)], a) for s, a in sorted(keep.items())]
    ones = [Fraction(1)] * n
    best: tuple[Fraction, ...] | None = None
    best_key: tuple[Fraction, ...] | None = None
    for tight in itertools.combinations(range(len(cons)), n - 1):
        sol = solve_exact([cons[k][0] for k in tight] + [ones],
                     [cons[k][1] for k in tight] + [Fraction(1)])
        if sol is None:
            continue
        if any(sum((c * x for c, x in zip(row, sol, strict=True)), Fraction(0)) < lo
               for row, lo in cons):
            continue
        key = tuple(sol[t] for t in order)
        if best_key is None or key < best_key:
            best, best_key = tuple(sol), key
    if best is None:
        return tuple(Fraction(int(i == order[0])) for i in range(n)), False
    return best, True
