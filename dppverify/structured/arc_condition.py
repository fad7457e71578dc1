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
from dppverify.structured.dp_certificate import direction_checks, failing_arc_mask
from dppverify.structured.normal_fixpoint import NormalSets

__all__ = ["MAX_DIRECTION_BASES", "ArcCondition", "arc_condition", "bad_rays", "walkable_arcs"]


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
    """Whether ``F_v ⊆ F_u + wΔ^N`` was established on every walkable arc.

    Attributes
    ----------
    holds : bool
    arcs : int
        Walkable arcs checked.
    rays : int
        Non-pattern directions checked on each arc (0 for N <= 3 and 0/1 normals).
    failure : tuple or None
        ``(v, u, ray)`` of the first arc where the test fails (``ray``: the failing cover
        ``((mask, coefficient), …)`` for 0/1 normals, ``(("y", direction),)`` otherwise).
    failing : tuple of tuple of int
        Every failing arc ``(v, u)``.
    decided : bool
        False when the test was not run (the normals' direction tables exceed
        :data:`MAX_DIRECTION_BASES`); then ``holds`` is False.
    """

    holds: bool
    arcs: int
    rays: int
    failure: tuple[int, int, tuple[tuple[Any, Any], ...]] | None
    failing: tuple[tuple[int, int], ...] = ()
    decided: bool = True


MAX_DIRECTION_BASES = 2_000_000
"""Most bases :func:`~dppverify.structured.cover.packing_vertices` may enumerate for the arc
test of a normal set with extras (``C(|A| + N, N)``); beyond it the test is not run."""


def walkable_arcs(sets: NormalSets, start: int | None = None
                  ) -> tuple[list[int], list[int], list[Any]]:
    """The arcs ``(v, u)`` a walk can take: ``v`` not a goal, both reaching a goal; with
    ``start``, only those whose tail a walk from ``start`` reaches (interior avoiding goals).

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> from dppverify.structured.guarantee import guarantee_sets
    >>> t, h, w = walkable_arcs(guarantee_sets(star3()))
    >>> list(zip(t, h))
    [(0, 1), (0, 2), (1, 0), (1, 2), (1, 3), (1, 4)]
    """
    inst = sets.instance
    reach = sets.finite
    ok = np.ones(inst.n_nodes, dtype=bool)
    if start is not None:
        ok[:] = False
        ok[start] = True
        stack = [start]
        while stack:
            v = stack.pop()
            if inst.is_goal(v):
                continue
            for u, _ in inst.succ[v]:
                if not ok[u] and reach[u]:
                    ok[u] = True
                    stack.append(u)
    tails, heads, wts = [], [], []
    for v in range(inst.n_nodes):
        if inst.is_goal(v) or not reach[v] or not ok[v]:
            continue
        for u, w in inst.succ[v]:
            if reach[u]:
                tails.append(v)
                heads.append(u)
                wts.append(w)
    return tails, heads, wts


def arc_condition(sets: NormalSets, start: int | None = None) -> ArcCondition:
    """Check the arc condition exactly on every walkable arc (see the module docstring).

    With extra normals the test is NG.8(c) over the packing polytope's directions
    (:func:`~dppverify.structured.dp_certificate.direction_checks`); without, NSOLVE.2's
    non-pattern rays. ``start``: only the arcs a walk from ``start`` can take.

    Examples
    --------
    >>> from dppverify.game.examples import hub4, star3
    >>> from dppverify.structured.guarantee import guarantee_sets
    >>> arc_condition(guarantee_sets(star3())).holds
    True
    >>> a = arc_condition(guarantee_sets(hub4()))
    >>> a.holds, a.failing
    (False, ((0, 1),))
    >>> extras = [(2, 2, 2, 1), (2, 2, 1, 2), (2, 1, 2, 2), (1, 2, 2, 2)]
    >>> arc_condition(guarantee_sets(hub4(), extras)).holds
    True
    """
    inst = sets.instance
    n = inst.n_goals
    tails, heads, weights = walkable_arcs(sets, start)
    narcs = len(tails)
    if narcs == 0:
        return ArcCondition(True, 0, 0, None)
    scaled: dict[Any, int] = {}
    wts = []
    for w in weights:
        if w not in scaled:
            scaled[w] = int(Fraction(w) * sets.scale)
        wts.append(scaled[w])
    t_idx = np.asarray(tails, dtype=np.int64)
    h_idx = np.asarray(heads, dtype=np.int64)
    w_scaled = np.array(wts, dtype=object)
    # the DP step inequality m_a(v) <= w·max(a) + m_a(u) (a fixpoint property; checked, cheap)
    for a, vals in zip(sets.normals, sets.rows, strict=True):
        here = np.asarray(vals, dtype=object)[t_idx]
        step = w_scaled * max(a) + np.asarray(vals, dtype=object)[h_idx]
        bad = np.flatnonzero(here > step)
        if bad.size:
            k = int(bad[0])
            fail = tuple((tails[i], heads[i]) for i in bad.tolist())
            return ArcCondition(False, narcs, 0, (tails[k], heads[k], (("y", a),)), fail)
    if sets.extras:
        return _direction_test(sets, tails, heads, w_scaled)
    rays = bad_rays(n)
    if not rays:
        return ArcCondition(True, narcs, 0, None)
    # m at the tails and heads as integer matrices (one column per subset mask 1 … 2^n - 1)
    mt = np.stack([np.asarray(sets.rows[s - 1], dtype=object)[t_idx] for s in range(1, 1 << n)],
                  axis=1)
    mh = np.stack([np.asarray(sets.rows[s - 1], dtype=object)[h_idx] for s in range(1, 1 << n)],
                  axis=1)
    by_y: dict[tuple[Fraction, ...], list[tuple[tuple[int, Fraction], ...]]] = {}
    for ray, _star in rays:
        y = tuple(sum((c for s, c in ray if s >> i & 1), Fraction(0)) for i in range(n))
        by_y.setdefault(y, []).append(ray)
    zero_one = zero_one_normals(n)
    failing = np.zeros(narcs, dtype=bool)
    first: tuple[int, int, tuple[tuple[Any, Any], ...]] | None = None
    for y, group in by_y.items():
        den = math.lcm(*(v.denominator for v in y))
        table = symmetric_table(zero_one, tuple(int(v * den) for v in y))
        cols = np.asarray(table.columns, dtype=np.int64)
        vden = table.lcm * den
        # vden · cov(y) at every tail and head; AC at y: cov_v(y) <= cov_u(y) + w · max y
        lhs = np.asarray(cheapest(mt[:, cols], table.scaled), dtype=object)
        rhs = (np.asarray(cheapest(mh[:, cols], table.scaled), dtype=object)
               + w_scaled * vden * max(y))
        worse = lhs > rhs
        if worse.any() and first is None:
            k = int(np.flatnonzero(worse)[0])
            first = (tails[k], heads[k], group[0])
        failing |= worse
    fail = tuple((tails[i], heads[i]) for i in np.flatnonzero(failing).tolist())
    return ArcCondition(first is None, narcs, len(rays), first, fail)


def _direction_test(sets: NormalSets, tails: list[int], heads: list[int],
                    w_scaled: np.ndarray) -> ArcCondition:
    """NG.8(c) for a normal set with extras: every packing-polytope direction, the 0/1 ones
    included (the rule's support numbers need not be closed, ``proofs/NRULE.md`` NR.2)."""
    n = sets.instance.n_goals
    narcs = len(tails)
    if math.comb(len(sets.normals) + n, n) > MAX_DIRECTION_BASES:
        return ArcCondition(False, narcs, 0, None, (), decided=False)
    checks = direction_checks(sets.normals, True)
    stacked = np.stack([np.asarray(r, dtype=object) for r in sets.rows])
    src = np.asarray(tails, dtype=np.int64)
    dst = np.asarray(heads, dtype=np.int64)
    failing: set[tuple[int, int]] = set()
    first: tuple[int, int, tuple[tuple[Any, Any], ...]] | None = None
    for chk in checks:
        bad = failing_arc_mask(chk, stacked, stacked, src, dst, w_scaled)
        for i in np.flatnonzero(bad).tolist():
            failing.add((tails[i], heads[i]))
            if first is None:
                first = (tails[i], heads[i], (("y", chk.y),))
    return ArcCondition(first is None, narcs, len(checks), first, tuple(sorted(failing)))
