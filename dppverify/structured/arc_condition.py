"""The arc condition of the guarantee sets (``proofs/NSOLVE.md`` NSOLVE.2), exactly.

With ``m_S(v)`` the coalition DP at ``H = inf`` (:func:`dppverify.structured.guarantee.
guarantee_sets`) and ``G_v = { r : r(S) <= m_S(v) for every non-empty S }``, the **arc
condition** ``G_v ⊆ G_u + wΔ^N`` on every arc ``(v, u)`` that a walk can take (``v`` not a
goal, some goal reachable from ``u``) makes the guarantee rule's ``F`` non-empty on every walk
(NSOLVE.1). It is verified as follows: ``m`` is a fixpoint of the DP (steps and splits), which
gives it for every direction ``y`` whose optimal covers regroup into fractional partitions of
sets containing a type of largest ``y`` (NSOLVE.2); the remaining directions are the finitely
many *non-pattern extreme rays* ``ρ`` of the cones ``{c >= 0 : y_c maximal at θ*}``
(:func:`bad_rays`: none for ``N <= 3``, the merging lemma), each checked on every arc:
``cov_v(y_ρ) <= cov_u(y_ρ) + w·max y_ρ`` (the arc condition in the direction ``y_ρ``:
necessary, and with the fixpoint sufficient). The covers come from the exact vertex tables
of :mod:`dppverify.structured.cover`.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from fractions import Fraction
from functools import cache
from typing import Any

import numpy as np

from dppverify.structured.cover import cheapest, dets, symmetric_table, zero_one_normals
from dppverify.structured.guarantee import GuaranteeSets

__all__ = ["ArcCondition", "arc_condition", "bad_rays"]


def _minors(mats: np.ndarray) -> np.ndarray:
    """Signed maximal minors of a batch of ``(j, j+1)`` integer matrices: ``x_c = (-1)^c
    det(A without column c)``, a null vector (exact integer determinants)."""
    batch, j, k = mats.shape
    if j == 0:
        return np.ones((batch, 1), dtype=np.int64)
    out = np.empty((batch, k), dtype=np.int64)
    for c in range(k):
        entries = [[np.ascontiguousarray(mats[:, r, cc]) for cc in range(k) if cc != c]
                   for r in range(j)]
        out[:, c] = dets(entries) * (-1 if c % 2 else 1)
    return out


@cache
def bad_rays(n: int) -> tuple[tuple[tuple[tuple[int, Fraction], ...], int], ...]:
    """Extreme rays of ``{c >= 0 : y_c(θ*) >= y_c(θ) ∀θ}`` (``y_c = Σ_S c_S 1_S``, any ``θ*``)
    that are not fractional partitions of a set containing ``θ*``; each as
    ``(((S, ρ_S), …), θ*)`` scaled so that ``max y_ρ = 1``.

    An extreme ray has ``k <= n`` positive entries and ``k - 1`` independent tight rows
    ``y(θ*) = y(θ)``; its direction is the null vector of those rows on its support (signed
    maximal minors, exact integers). Enumerated for ``θ* = 0``, then permuted.

    Examples
    --------
    >>> [len(bad_rays(n)) for n in (2, 3)]
    [0, 0]
    >>> rays = bad_rays(4)
    >>> len(rays), sorted(rays)[0]
    (36, (((3, Fraction(1, 2)), (5, Fraction(1, 2)), (14, Fraction(1, 2))), 0))
    """
    masks = np.arange(1, 1 << n, dtype=np.int64)
    bits = (masks[None, :] >> np.arange(n)[:, None]) & 1  # (n, M): bits[i, s] = [i ∈ S]
    diff = bits[0][None, :] - bits[1:]  # rows y(0) - y(θ), θ = 1..n-1
    base: set[tuple[tuple[int, Fraction], ...]] = set()
    for k in range(1, n + 1):
        sup = np.array(list(itertools.combinations(range(masks.size), k)), dtype=np.int64)
        for tight in itertools.combinations(range(n - 1), k - 1):
            mats = diff[np.asarray(tight, dtype=np.int64)][:, sup]  # (k-1, K, k)
            x = _minors(np.transpose(mats, (1, 0, 2)))  # (K, k)
            neg = np.all(x < 0, axis=1)
            x[neg] = -x[neg]
            ok = np.all(x > 0, axis=1)
            if not ok.any():
                continue
            xs, ss = x[ok], sup[ok]
            y = np.einsum("bk,ibk->bi", xs, bits[:, ss])  # (B, n) integer type masses
            ok2 = np.all(y[:, :1] >= y[:, 1:], axis=1) & (y[:, 0] > 0)
            pattern = np.all((y == 0) | (y == y[:, :1]), axis=1)
            for b in np.flatnonzero(ok2 & ~pattern):
                top = int(y[b, 0])
                base.add(tuple(sorted((int(masks[s]), Fraction(int(c), top))
                                      for s, c in zip(ss[b], xs[b], strict=True))))
    out: set[tuple[tuple[tuple[int, Fraction], ...], int]] = set()
    for ray in base:
        for perm in itertools.permutations(range(n)):
            moved = {sum(1 << perm[i] for i in range(n) if s >> i & 1): c for s, c in ray}
            out.add((tuple(sorted(moved.items())), perm[0]))
    return tuple(sorted(out))


@dataclass(frozen=True)
class ArcCondition:
    """Whether ``G_v ⊆ G_u + wΔ^N`` was established on every walkable arc.

    Attributes
    ----------
    holds : bool
    arcs : int
        Walkable arcs checked.
    rays : int
        Non-pattern extreme rays checked on each arc (0 for N <= 3).
    failure : tuple or None
        ``(v, u, ray)`` of the first arc where the ray inequality does not hold.
    """

    holds: bool
    arcs: int
    rays: int
    failure: tuple[int, int, tuple[tuple[int, Fraction], ...]] | None


def arc_condition(sets: GuaranteeSets) -> ArcCondition:
    """Check the arc condition exactly on every walkable arc (see the module docstring).

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> from dppverify.structured.guarantee import guarantee_sets
    >>> arc_condition(guarantee_sets(star3())).holds
    True
    """
    inst = sets.instance
    n = inst.n_goals
    tails, heads, wts = [], [], []
    reach = sets.m[1] < sets.big
    scaled: dict[Any, int] = {}
    for v in range(inst.n_nodes):
        if inst.is_goal(v) or not reach[v]:
            continue
        for u, w in inst.succ[v]:
            if not reach[u]:
                continue
            tails.append(v)
            heads.append(u)
            if w not in scaled:
                scaled[w] = int(Fraction(w) * sets.scale)
            wts.append(scaled[w])
    narcs = len(tails)
    if narcs == 0:
        return ArcCondition(True, 0, 0, None)
    t_idx = np.asarray(tails, dtype=np.int64)
    h_idx = np.asarray(heads, dtype=np.int64)
    w_scaled = np.array(wts, dtype=object)
    # the DP step inequality m_S(v) <= w + m_S(u) (a fixpoint property; checked, it is cheap)
    for mask, vals in sets.m.items():
        here = vals[t_idx].astype(object)
        step = w_scaled + vals[h_idx].astype(object)
        bad = np.flatnonzero(here > step)
        if bad.size:
            k = int(bad[0])
            return ArcCondition(False, narcs, 0, (tails[k], heads[k], ((mask, Fraction(1)),)))
    rays = bad_rays(n)
    if not rays:
        return ArcCondition(True, narcs, 0, None)
    # m at the tails and heads as integer matrices (one column per subset mask 1 … 2^n - 1)
    mt = np.stack([sets.m[s][t_idx] for s in range(1, 1 << n)], axis=1)
    mh = np.stack([sets.m[s][h_idx] for s in range(1, 1 << n)], axis=1)
    by_y: dict[tuple[Fraction, ...], list[tuple[tuple[int, Fraction], ...]]] = {}
    for ray, _star in rays:
        y = tuple(sum((c for s, c in ray if s >> i & 1), Fraction(0)) for i in range(n))
        by_y.setdefault(y, []).append(ray)
    zero_one = zero_one_normals(n)
    for y, group in by_y.items():
        den = math.lcm(*(v.denominator for v in y))
        table = symmetric_table(zero_one, tuple(int(v * den) for v in y))
        cols = np.asarray(table.columns, dtype=np.int64)
        vden = table.lcm * den
        # vden · cov(y) at every tail and head; AC at y: cov_v(y) <= cov_u(y) + w · max y
        lhs = cheapest(mt[:, cols], table.scaled).astype(object)
        rhs = cheapest(mh[:, cols], table.scaled).astype(object) + w_scaled * vden * max(y)
        worse = np.flatnonzero(lhs > rhs)
        if worse.size:
            k = int(worse[0])
            return ArcCondition(False, narcs, len(rays), (tails[k], heads[k], group[0]))
    return ArcCondition(True, narcs, len(rays), None)
