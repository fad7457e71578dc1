"""The arc condition of the guarantee rule's sets, exactly (``proofs/NRULE.md`` NR.2).

With ``m_a(v)`` the rule's DP at ``H = inf`` over its normals ``A``
(:mod:`dppverify.structured.normal_fixpoint`; the coalition DP for the 0/1 vectors) and
``F_v = { r : a·r <= m_a(v), a ∈ A }``, the **arc condition** ``F_v ⊆ F_u + wΔ^N`` on every arc
``(v, u)`` that a walk can take (``v`` not a goal, some goal reachable from ``u``) makes the
rule's ``F`` non-empty on every walk and guarantees every type ``h_θ`` (NR.2, NSOLVE.1). By
Farkas' lemma it holds iff ``h_{F_v}(y) <= h_{F_u}(y) + w`` for the finitely many directions
``y`` of the packing polytope's vertices
(:func:`~dppverify.structured.packing.packing_directions`, each with ``max y = 1``); for the 0/1
vectors alone the support numbers are closed and the DP's fixpoint gives the 0/1 directions,
so only the others are tested (none for ``N <= 3``; NSOLVE.2's non-pattern rays
:func:`bad_rays` are the same test in ray form). The support functions are exact cover LPs at
every node (:func:`~dppverify.structured.cover_lp.cover_values`).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from fractions import Fraction
from functools import cache
from typing import Any

import numpy as np

from dppverify.structured.cover_lp import cover_values
from dppverify.structured.exact_bases import dets
from dppverify.structured.normal_fixpoint import NormalSets
from dppverify.structured.packing import packing_directions
from dppverify.structured.set_vertices import SetVertex, maximal_vertices
from dppverify.structured.sum_membership import sum_membership


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
        Directions checked on each arc (0 for N <= 3 and 0/1 normals).
    failure : tuple or None
        ``(v, u, (("y", y),))`` of the first arc where the test fails in direction ``y`` (the
        step inequality's failures name the normal as ``y``).
    failing : tuple of tuple of int
        Every failing arc ``(v, u)``.
    directions : tuple
        Every direction ``y`` in which some arc fails (the vertex route: the most violated
        direction at each failing vertex).
    vertices : int
        (Arc, vertex of ``F_v``) pairs tested by the vertex route (0 for the directions).
    """

    holds: bool
    arcs: int
    rays: int
    failure: tuple[int, int, tuple[tuple[Any, Any], ...]] | None
    failing: tuple[tuple[int, int], ...] = ()
    directions: tuple[tuple[Fraction, ...], ...] = ()
    vertices: int = 0


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


def arc_condition(sets: NormalSets, start: int | None = None, *,
                  route: str = "auto") -> ArcCondition:
    """Check the arc condition exactly on every walkable arc (see the module docstring).

    ``start``: only the arcs a walk from ``start`` can take. ``route``: ``"auto"`` (the
    vertices of ``F_v`` when there are extra normals, else the few non-0/1 directions),
    ``"directions"`` (the support functions in every packing direction, NR.2(a)), or
    ``"vertices"``.

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
    if route not in ("auto", "directions", "vertices"):
        raise ValueError(f"arc_condition: unknown route {route!r}")
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
    if route == "vertices" or (route == "auto" and sets.extras):
        return vertex_test(sets, tails, heads, w_scaled)
    return direction_test(sets, tails, heads, w_scaled)


def vertex_test(sets: NormalSets, tails: list[int], heads: list[int], w_scaled: np.ndarray
                ) -> ArcCondition:
    """``F_v ⊆ F_u + wΔ^N`` on every arc by the maximal vertices of ``F_v`` (``proofs/NRULE.md``
    NR.2(b)): each vertex ``r`` (:func:`~dppverify.structured.set_vertices.maximal_vertices`,
    once per tail) must satisfy ``φ_u(r) <= w``, one exact LP per vertex and arc with its
    certificate (:func:`~dppverify.structured.sum_membership.sum_membership`). A failing
    vertex names the most violated direction ``y_λ`` of its LP.

    Examples
    --------
    >>> from dppverify.game.examples import hub4
    >>> from dppverify.structured.guarantee import guarantee_sets
    >>> sets = guarantee_sets(hub4())
    >>> t, h, w = walkable_arcs(sets, 0)
    >>> got = vertex_test(sets, t, h, np.array([int(x * sets.scale) for x in w], dtype=object))
    >>> got.holds, got.failing, [str(x) for x in got.failure[2][0][1]]
    (False, ((0, 1),), ['1', '1', '1', '1/2'])
    """
    narcs = len(tails)
    normals = sets.normals
    n = len(normals[0])
    cols: dict[int, list[int]] = {}

    def column(v: int) -> list[int]:
        if v not in cols:
            cols[v] = [int(row[v]) for row in sets.rows]
        return cols[v]

    verts: dict[int, tuple[SetVertex, ...]] = {}
    failing: list[tuple[int, int]] = []
    first: tuple[int, int, tuple[tuple[Any, Any], ...]] | None = None
    bad_ys: dict[tuple[Fraction, ...], None] = {}
    tested = 0
    for k in range(narcs):
        v, u, w = tails[k], heads[k], int(w_scaled[k])
        if v not in verts:
            verts[v] = maximal_vertices(normals, column(v))
        mu = column(u)
        bad = False
        for x, t, _ in verts[v]:
            tested += 1
            b = [sum(a[i] * x[i] for i in range(n) if a[i]) - t * m for a, m in
                 zip(normals, mu, strict=True)]
            got = sum_membership(normals, b, t * w)
            if not got.inside:
                y = got.direction(normals)
                bad_ys.setdefault(y, None)
                if first is None:
                    first = (v, u, (("y", y),))
                bad = True
        if bad:
            failing.append((v, u))
    return ArcCondition(first is None, narcs, 0, first, tuple(sorted(set(failing))),
                        tuple(bad_ys), vertices=tested)


def direction_test(sets: NormalSets, tails: list[int], heads: list[int],
                   w_scaled: np.ndarray) -> ArcCondition:
    """``h_{F_v}(y) <= h_{F_u}(y) + w`` on every arc for every packing direction ``y``
    (``proofs/NRULE.md`` NR.2(a); ``max y = 1``). Without extra normals the support numbers
    are closed and the 0/1 directions hold by the fixpoint's step inequality (NG.8(c)), so
    only the others are tested. With extra normals the directions number in the thousands
    (:func:`vertex_test` is the default there; this route stays as its independent
    cross-check)."""
    narcs = len(tails)
    ys = [y for y in packing_directions(sets.normals)
          if sets.extras or any(x not in (0, 1) for x in y)]
    if not ys:
        return ArcCondition(True, narcs, 0, None)
    nodes = np.unique(np.asarray(tails + heads, dtype=np.int64))
    stacked = np.stack([np.asarray(r, dtype=object)[nodes] for r in sets.rows])
    t_pos = np.searchsorted(nodes, np.asarray(tails, dtype=np.int64))
    h_pos = np.searchsorted(nodes, np.asarray(heads, dtype=np.int64))
    failing = np.zeros(narcs, dtype=bool)
    first: tuple[int, int, tuple[tuple[Any, Any], ...]] | None = None
    bad_ys = []
    for y in ys:
        s = math.lcm(*(x.denominator for x in y))
        num, den = cover_values(sets.normals, stacked, tuple(int(x * s) for x in y))
        bad = num[t_pos] > num[h_pos] + w_scaled * (s * den)
        if bad.any():
            bad_ys.append(y)
            if first is None:
                k = int(np.flatnonzero(bad)[0])
                first = (tails[k], heads[k], (("y", y),))
        failing |= np.asarray(bad, dtype=bool)
    fail = tuple(sorted({(tails[i], heads[i]) for i in np.flatnonzero(failing).tolist()}))
    return ArcCondition(first is None, narcs, len(ys), first, fail, tuple(bad_ys))
