"""Exact lower bounds on the N-goal value ``V_H`` (``proofs/NGOAL.md``): two simple Defenders
(NG.9) and the coalition DP's fixpoint sets translated into a sub-fixpoint (NG.10), once on the
coalition DP's layered tables (finite ``H``) and once in support-function form on the
label-setting fixpoint's sets (``H = inf``).
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

from dppverify.game.instance import Instance
from dppverify.structured.arc_condition import walkable_arcs
from dppverify.structured.coalition import CoalitionRunner
from dppverify.structured.cover import cheapest, min_cover_vectors, zero_one_normals
from dppverify.structured.cover_lp import cover_values
from dppverify.structured.dp_certificate import direction_checks
from dppverify.structured.normal_fixpoint import NormalSets
from dppverify.structured.packing import packing_directions


def lower_bound_simple(instance: Instance) -> tuple[Fraction, str]:
    """A cheap exact lower bound on every ``V_H`` (and ``V_inf``) from two simple Defenders.

    A Defender that always guards goal ``θ`` makes type ``θ`` pay at least ``d(s0, g^θ)``
    (the walk's weight plus the terminal cost); the uniform Defender makes every type ``θ``
    pay at least ``d(s0, g^θ)/N``. The bound is the better of ``max_θ b_θ d(s0, g^θ)`` and
    ``Σ_θ b_θ d(s0, g^θ) / N`` (``proofs/NGOAL.md`` NG.9).

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> lower_bound_simple(star3())
    (Fraction(1, 1), 'a Defender that always guards goal 1 (NG.9)')
    """
    inst = instance
    d = [Fraction(inst.dist_to[t][inst.start]) for t in range(inst.n_goals)]
    guard = [inst.prior[t] * d[t] for t in range(inst.n_goals)]
    best = max(range(inst.n_goals), key=lambda t: guard[t])
    uniform = sum(guard, Fraction(0)) / inst.n_goals
    if uniform > guard[best]:
        return uniform, "the uniform Defender (NG.9)"
    return guard[best], f"a Defender that always guards goal {best + 1} (NG.9)"


def deflated_lower(run: CoalitionRunner, layer: dict[int, np.ndarray]) -> Fraction | None:
    """NG.10: ``DP_inf - t(s0)`` for the least translations ``t`` making ``F - t·1`` a sub-fixpoint.

    ``F`` are the coalition DP's sets at its fixpoint ``layer``. With ``F'_v = F_v - t_v·1``
    (``t >= 0``, ``t = 0`` at goals) the arc condition for ``(v, u)`` reads
    ``t_v - t_u >= ℓ(v, u)``, the largest ``(h_{F_v}(y_λ) - w - λ·m_u) / (1·y_λ)`` over the vertices
    ``λ`` of the packing polytope (the 0/1 ones give ``(m_A(v) - w - m_A(u)) / |A|``). The least
    such ``t`` is a longest-path fixpoint (Bellman-Ford from ``t = 0``); None if it does not
    settle within ``n + 1`` rounds (a positive cycle).
    """
    inst = run.inst
    arr, finite = run.stacked(layer)
    keep = finite[run.src] & finite[run.dst]
    src, dst, wts = run.src[keep], run.dst[keep], run.wts[keep].astype(object)
    scale = run.scale
    frac = np.frompyfunc(lambda num, den: Fraction(int(num), int(den)), 2, 1)
    ell: np.ndarray | None = None
    for mask in range(1, 1 << inst.n_goals):
        size = bin(mask).count("1")
        e = arr[mask - 1][src].astype(object) - wts - arr[mask - 1][dst].astype(object)
        cand = frac(e, scale * size)
        ell = cand if ell is None else np.maximum(ell, cand)
    zo = zero_one_normals(inst.n_goals)
    for chk in direction_checks(zo):
        cols = np.asarray(chk.cover.columns, dtype=np.int64)
        hv = np.asarray(cheapest(arr[cols][:, src].T, chk.cover.scaled), dtype=object)
        mu = np.asarray(cheapest(arr[:, dst].T, chk.lams.T), dtype=object)
        num = (hv * chk.lam_lcm - wts * chk.cover.lcm * chk.scale * chk.lam_lcm
               - mu * chk.cover.lcm * chk.scale)
        ones = sum(chk.y, Fraction(0))
        den = scale * chk.cover.lcm * chk.scale * chk.lam_lcm
        cand = frac(num, den) / ones
        ell = cand if ell is None else np.maximum(ell, cand)
    if ell is None or src.size == 0:
        return Fraction(0)
    tails = np.unique(src)
    seg = np.searchsorted(src, tails)
    den = math.lcm(1, *{int(x.denominator) for x in ell})
    nums = [int(x * den) for x in ell]
    bound = (max(abs(x) for x in nums) + 1) * (inst.n_nodes + 2)
    lengths = np.asarray(nums, dtype=np.int64 if bound < 2 ** 62 else object)
    t = np.zeros(inst.n_nodes, dtype=lengths.dtype)  # t · den, exact integers
    for _ in range(inst.n_nodes + 1):
        best = np.maximum.reduceat(t[dst] + lengths, seg)
        new = t.copy()
        new[tails] = np.maximum(best, 0)
        if np.array_equal(new, t):
            return Fraction(int(t[inst.start]), den)
        t = new
    return None


def sets_value(sets: NormalSets) -> Fraction:
    """The DP value of ``sets`` at the start and the prior: the cheapest cover of the prior by
    their normals."""
    inst = sets.instance
    col = sets.column(inst.start)
    assert col is not None  # the start reaches a goal
    return Fraction(min_cover_vectors(sets.normals, col, inst.prior).value)


def translated_lower(sets: NormalSets) -> Fraction | None:
    """NG.10 in support-function form: ``DP_inf - t(s0)`` for the least ``t >= 0`` (0 at the
    goals) with ``(t_v - t_u)·(1·y) >= h_{F_v}(y) - h_{F_u}(y) - w`` for every walkable arc and
    packing direction ``y``; None if that longest-path problem does not settle (a positive
    cycle)."""
    inst = sets.instance
    tails, heads, weights = walkable_arcs(sets, inst.start)
    if not tails:
        return sets_value(sets)
    nodes = np.unique(np.asarray(tails + heads, dtype=np.int64))
    stacked = np.stack([np.asarray(r, dtype=object)[nodes] for r in sets.rows])
    t_pos = np.searchsorted(nodes, np.asarray(tails, dtype=np.int64))
    h_pos = np.searchsorted(nodes, np.asarray(heads, dtype=np.int64))
    wts = [Fraction(w) for w in weights]
    ell = [Fraction(-10 ** 30)] * len(tails)
    for y in packing_directions(sets.normals):
        s = math.lcm(*(x.denominator for x in y))
        num, den = cover_values(sets.normals, stacked, tuple(int(x * s) for x in y))
        size = sum(y, Fraction(0))
        for k in range(len(tails)):
            gap = (Fraction(int(num[t_pos[k]]) - int(num[h_pos[k]]), den * sets.scale * s)
                   - wts[k]) / size
            if gap > ell[k]:
                ell[k] = gap
    t = dict.fromkeys(nodes.tolist(), Fraction(0))
    for _ in range(len(t) + 1):
        changed = False
        for k, (v, u) in enumerate(zip(tails, heads, strict=True)):
            want = max(Fraction(0), t[u] + ell[k])
            if not inst.is_goal(v) and want > t[v]:
                t[v] = want
                changed = True
        if not changed:
            return sets_value(sets) - t[inst.start]
    return None


def translation_at_start(sets: NormalSets) -> Fraction | None:
    """NG.10's least translation ``t(s0)``: ``F_v − t_v·1`` is a sub-fixpoint, so
    ``F_s0 − t(s0)·1`` lies in the exact guarantee set; None if the longest-path problem does
    not settle.

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> from dppverify.structured.normal_fixpoint import normal_sets
    >>> translation_at_start(normal_sets(star3()))
    Fraction(0, 1)
    """
    lower = translated_lower(sets)
    return None if lower is None else sets_value(sets) - lower
