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
from collections.abc import Sequence
from fractions import Fraction

from solver.numbers import solve_exact


def priority_order(prior: Sequence[Fraction]) -> tuple[int, ...]:
    """Types by decreasing prior, ties by increasing index.

    Examples
    --------
    >>> priority_order([Fraction(1, 4), Fraction(1, 2), Fraction(1, 4)])
    (1, 0, 2)
    """
    return tuple(sorted(range(len(prior)), key=lambda t: (-prior[t], t)))


def rule_step(r: Sequence[Fraction], normals: Sequence[Sequence[int]],
              m_next: Sequence[Fraction | None], w: Fraction, order: Sequence[int]
              ) -> tuple[tuple[Fraction, ...], bool]:
    """The guarantee rule with normals: the canonical ``σ`` of one step, and whether ``F`` was
    non-empty (``docs/formats.md`` §2b).

    ``F = {σ ∈ Δ^N : a·σ >= (a·r − m_a(u)) / w for every normal a with m_a(u) defined}``;
    ``σ`` is its lexicographic minimum in the priority order (all weight on ``order[0]`` when
    ``F`` is empty). Exact: the vertices of ``F`` from every choice of ``N − 1`` tight
    constraints among the non-redundant ones (``σ_θ >= 0``; ``a·σ >= ℓ_a`` for ``ℓ_a > 0`` not
    implied by a normal ``b <= a`` with ``ℓ_b >= ℓ_a``); a constraint with ``ℓ_a = max a``
    confines ``σ`` to ``argmax a`` first.

    Examples
    --------
    Two types, ``r = (3, 1)``, ``m(u) = (2, 1, 3)`` for the normals (1, 0), (0, 1), (1, 1)
    and ``w = 1``: type 1 must get at least 1, so ``σ = (1, 0)``; with the normal (2, 1)
    bounded by 5 as well ``F = {(1, 0)}``; bounded by 4 it is empty (``2σ_1 + σ_2 >= 3``):

    >>> normals = ((1, 0), (0, 1), (1, 1), (2, 1))
    >>> m = [Fraction(2), Fraction(1), Fraction(3), Fraction(5)]
    >>> rule_step([Fraction(3), Fraction(1)], normals, m, Fraction(1), (0, 1))
    ((Fraction(1, 1), Fraction(0, 1)), True)
    >>> rule_step([Fraction(3), Fraction(1)], normals, m[:3] + [Fraction(4)], Fraction(1),
    ...           (0, 1))[1]
    False
    """
    n = len(r)
    lows: list[tuple[tuple[int, ...], Fraction]] = []
    for a, m in zip(normals, m_next, strict=True):
        if m is None:
            continue
        ell = (sum((x * y for x, y in zip(a, r, strict=True) if x), Fraction(0)) - m) / w
        if ell > 0:
            lows.append((tuple(int(x) for x in a), ell))
    support = [True] * n
    for a, ell in lows:  # a·σ <= max a on Δ: ℓ_a = max a forces σ onto argmax a
        top = max(a)
        if ell > top:
            return tuple(Fraction(int(i == order[0])) for i in range(n)), False
        if ell == top:
            support = [s and a[i] == top for i, s in enumerate(support)]
    free = [i for i in range(n) if support[i]]
    if not free:
        return tuple(Fraction(int(i == order[0])) for i in range(n)), False
    # drop constraints implied by another one: b <= a (on the free types) with ℓ_b >= ℓ_a
    sub = [(tuple(a[i] for i in free), ell) for a, ell in lows]
    keep = [(a, ell) for k, (a, ell) in enumerate(sub)
            if not any(j != k and all(x <= y for x, y in zip(b, a, strict=True))
                       and (lb > ell or (lb == ell and j < k)) for j, (b, lb) in enumerate(sub))]
    d = len(free)
    cons: list[tuple[list[Fraction], Fraction]] = [
        ([Fraction(int(i == j)) for j in range(d)], Fraction(0)) for i in range(d)]
    cons += [([Fraction(x) for x in a], ell) for a, ell in keep]
    ones = [Fraction(1)] * d
    rank = {t: k for k, t in enumerate(order)}
    local_order = sorted(range(d), key=lambda i: rank[free[i]])
    best: list[Fraction] | None = None
    best_key: tuple[Fraction, ...] | None = None
    for tight in itertools.combinations(range(len(cons)), d - 1):
        sol = solve_exact([cons[k][0] for k in tight] + [ones],
                          [cons[k][1] for k in tight] + [Fraction(1)])
        if sol is None:
            continue
        if any(sum((c * x for c, x in zip(row, sol, strict=True)), Fraction(0)) < lo
               for row, lo in cons):
            continue
        key = tuple(sol[i] for i in local_order)
        if best_key is None or key < best_key:
            best, best_key = sol, key
    if best is None:
        return tuple(Fraction(int(i == order[0])) for i in range(n)), False
    out = [Fraction(0)] * n
    for i, x in zip(free, best, strict=True):
        out[i] = x
    return tuple(out), True
