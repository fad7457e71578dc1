"""Best responses over ALL walks (any length) against a progress-rule Defender (proofs/WALKBR.md).

Against the progress rule towards goal ``g`` (σ* when ``g = g1``), with ``g'`` the other goal:

- the type whose goal is ``g`` pays at least ``d(s0, g)``, attained (telescoping, TEL/L1);
- the type whose goal is ``g'`` pays at least ``min(min_u F(u), d'(s0, g) + d(g, g')) − d(s0, g)``
  with ``F(u) = d'(s0, u) + d(u, g) + d''(u, g')``, attained. ``d'`` are distances from ``s0``
  whose interior avoids both goals, ``d''`` distances to ``g'`` that avoid ``g``.

Three shortest-path computations, no enumeration. Distances use scipy's Dijkstra on the
weights scaled to integers when every path sum stays below ``2**53`` (float64 is then exact),
and the checker's exact Dijkstra (:mod:`dppverify.game.distances`) otherwise; float mode uses scipy.
"""

from __future__ import annotations

import math
import weakref
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from dppverify.exact import INF, Number, normalize
from dppverify.game.distances import ArcArrays, dijkstra, sparse_dijkstra
from dppverify.game.instance import Instance, arc_arrays, goal_distance_fields


@dataclass(frozen=True, eq=False)
class ScaledArcs:
    """An exact instance's arcs (:class:`~dppverify.game.distances.ArcArrays`) with their
    weights scaled to integers held in float64.

    Attributes
    ----------
    arrays : ArcArrays
        The arcs (tails and heads, in ``succ`` order).
    weights : numpy.ndarray
        ``weight * scale`` of every arc as ``float64``: exact integers, since their total is
        below :data:`~dppverify.game.distances.EXACT_FLOAT_LIMIT` (only then is one built).
    scale : int
        The common denominator of the weights.
    distances : dict
        Memo of :func:`scaled_distances` results for this instance.
    """

    arrays: ArcArrays
    weights: np.ndarray
    scale: int
    distances: dict[tuple[int, bool, frozenset[int]], np.ndarray]


_ARCS: weakref.WeakKeyDictionary[Instance, ScaledArcs | None] = weakref.WeakKeyDictionary()


def scaled_arcs(instance: Instance) -> ScaledArcs | None:
    """The instance's arcs as arrays (built once per instance), or None when float64 is unsafe.

    None in float mode, and when four times the total scaled weight reaches
    :data:`~dppverify.game.distances.EXACT_FLOAT_LIMIT` (a sum of three distances must stay exact):
    the callers then use the exact Python-integer Dijkstra.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> a = scaled_arcs(triangle())
    >>> a.arrays.tails.tolist(), a.arrays.heads.tolist(), a.weights.tolist(), a.scale
    ([0, 0, 1, 1, 2, 2], [1, 2, 0, 2, 0, 1], [3.0, 2.0, 3.0, 2.0, 2.0, 2.0], 1)
    """
    if instance in _ARCS:
        return _ARCS[instance]
    out: ScaledArcs | None = None
    if instance.exact:
        arrays = arc_arrays(instance)
        got = arrays.scaled(arrays.values, paths=4)  # a sum of three distances stays exact
        if got is not None:
            scale, scaled = got
            out = ScaledArcs(arrays=arrays,
                             weights=np.asarray(scaled, dtype=np.float64)[arrays.codes],
                             scale=scale, distances={})
            shared = goal_distance_fields(instance)
            if shared is not None and shared[0] == scale:  # d(., goal): the reader's fields
                for goal, row in shared[1].items():
                    out.distances[(goal, True, frozenset())] = row
    _ARCS[instance] = out
    return out


def scaled_distances(arcs: ScaledArcs, n: int, source: int, *, reverse: bool,
                     blocked: frozenset[int]) -> np.ndarray:
    """Scaled distances from ``source`` (to it, with ``reverse``) avoiding ``blocked`` inside.

    Exact integers in float64 (``inf`` when unreachable); memoised on ``arcs``.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> scaled_distances(scaled_arcs(triangle()), 3, 0, reverse=False,
    ...                  blocked=frozenset({1, 2})).tolist()
    [0.0, 3.0, 2.0]
    """
    key = (source, reverse, blocked)
    if key not in arcs.distances:
        import scipy.sparse as sp

        # the graph's CSR rows (reversed: the arcs by head), built once per instance
        indptr, indices, order = arcs.arrays.rows(n, reverse=reverse)
        w = arcs.weights if order is None else arcs.weights[order]
        drop = [v for v in blocked if v != source]
        if drop:  # a blocked node's arcs are never followed: weight inf, which no path uses
            w = w.copy()
            for v in drop:
                w[indptr[v]:indptr[v + 1]] = np.inf
        m = sp.csr_matrix((w, indices, indptr), shape=(n, n), copy=False)
        arcs.distances[key] = sparse_dijkstra(m, source)
    return arcs.distances[key]


def _unscale(x: float, scale: int) -> Number:
    if math.isinf(x):
        return INF
    return int(x) if scale == 1 else normalize(Fraction(int(x), scale))


def avoiding_distances(instance: Instance, source: int, *, reverse: bool,
                       blocked: frozenset[int]) -> list[Number]:
    """Distances from ``source`` (to it, with ``reverse``) whose interior avoids ``blocked``.

    A blocked node may be an endpoint but is never passed through (its arcs are not followed).

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> inst = triangle()          # s–g2 (2), g2–g1 (2), s–g1 (3); nodes s, g1, g2 = 0, 1, 2
    >>> avoiding_distances(inst, 0, reverse=False, blocked=frozenset({1, 2}))
    [0, 3, 2]
    >>> avoiding_distances(inst, 2, reverse=True, blocked=frozenset({1}))   # to g2 avoiding g1
    [2, 2, 0]
    """
    n = instance.n_nodes
    arcs = scaled_arcs(instance)
    if arcs is not None:
        dist = scaled_distances(arcs, n, source, reverse=reverse, blocked=blocked)
        return [_unscale(x, arcs.scale) for x in dist.tolist()]
    adj = instance.pred if reverse else instance.succ
    keep = [[] if (v in blocked and v != source) else list(adj[v]) for v in range(n)]
    if instance.exact:  # the total is too large for float64: exact Python integers
        return dijkstra(keep, source)
    return [float(x) for x in _float_distances(n, ArcArrays.from_adjacency(keep), source)]


def _float_distances(n: int, arcs: ArcArrays, source: int) -> np.ndarray:
    """Float-mode distances from ``source`` by scipy's Dijkstra."""
    import scipy.sparse as sp

    w = np.asarray([float(x) for x in arcs.weights()], dtype=np.float64)
    m = sp.csr_matrix((w, (arcs.tails, arcs.heads)), shape=(n, n))
    return sparse_dijkstra(m, source)


def split_minimum(instance: Instance, a: int, b: int) -> Number:
    """``min_v d(s0, v) + d(v, a) + d(v, b)`` over plain full-graph distances.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> split_minimum(triangle(), 1, 2)   # v = g2: 2 + 2 + 0
    4
    """
    s0, n = instance.start, instance.n_nodes
    arcs = scaled_arcs(instance)
    none: frozenset[int] = frozenset()
    if arcs is not None:
        total = (scaled_distances(arcs, n, s0, reverse=False, blocked=none)
                 + scaled_distances(arcs, n, a, reverse=True, blocked=none)
                 + scaled_distances(arcs, n, b, reverse=True, blocked=none))
        return _unscale(float(total.min()), arcs.scale)
    d0 = avoiding_distances(instance, s0, reverse=False, blocked=none)
    da = instance.dist_to[instance.goals.index(a)]
    db = instance.dist_to[instance.goals.index(b)]
    return min(d0[v] + da[v] + db[v] for v in range(n)
               if d0[v] != INF and da[v] != INF and db[v] != INF)


@dataclass(frozen=True)
class WalkMinima:
    """Minimum over all walks of each type's cost against the progress rule towards ``goal``.

    Attributes
    ----------
    goal : int
        The goal the progress rule measures progress towards and allocates to.
    same : Number
        Minimum cost of the type whose goal is ``goal``: ``d(s0, goal)``.
    other : Number
        Minimum cost of the other type (the formula of the module docstring).
    witness : int
        The minimising split node ``u`` (``goal`` itself for the walk ending at ``goal``).
    """

    goal: int
    same: Number
    other: Number
    witness: int


def walk_minima(instance: Instance, goal: int) -> WalkMinima:
    """Both types' minimum cost over ALL walks against the progress rule towards ``goal``.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> inst = triangle()
    >>> walk_minima(inst, inst.roles().g1)   # σ*: primary pays d(s,g1) = 3, secondary 4 − 3
    WalkMinima(goal=1, same=3, other=1, witness=2)
    """
    g = goal
    g_other = instance.goals[1] if instance.goals[0] == g else instance.goals[0]
    s0 = instance.start
    goals = frozenset(instance.goals)
    d_to_g = instance.dist_to[instance.goals.index(g)]
    d_to_other = instance.dist_to[instance.goals.index(g_other)]
    if s0 in goals:  # the empty walk is the only one
        same, other = d_to_g[s0], d_to_other[s0]
        return WalkMinima(goal=g, same=same, other=other, witness=s0)
    arcs = scaled_arcs(instance)
    if arcs is not None:
        return _walk_minima_scaled(instance, arcs, g, g_other)
    d1 = avoiding_distances(instance, s0, reverse=False, blocked=goals)
    d2 = avoiding_distances(instance, g_other, reverse=True, blocked=frozenset({g}))
    best: Number = d1[g] + d_to_other[g]
    witness = g
    for u in range(instance.n_nodes):
        if u == g or d1[u] == INF or d2[u] == INF or d_to_g[u] == INF:
            continue
        if u != g_other and u in goals:  # pragma: no cover - goals are g and g_other
            continue
        f = d1[u] + d_to_g[u] + d2[u]
        if f < best:
            best, witness = f, u
    c0 = d_to_g[s0]
    other = best - c0
    if instance.exact:
        return WalkMinima(goal=g, same=normalize(c0), other=normalize(other), witness=witness)
    return WalkMinima(goal=g, same=float(c0), other=float(other), witness=witness)


def _walk_minima_scaled(instance: Instance, arcs: ScaledArcs, g: int,
                        g_other: int) -> WalkMinima:
    """:func:`walk_minima` on exact scaled integers in float64 (vectorised, same tie rule)."""
    n, s0, k = instance.n_nodes, instance.start, arcs.scale
    d1 = scaled_distances(arcs, n, s0, reverse=False, blocked=frozenset(instance.goals))
    d2 = scaled_distances(arcs, n, g_other, reverse=True, blocked=frozenset({g}))
    dg = scaled_distances(arcs, n, g, reverse=True, blocked=frozenset())
    d_to_other = instance.dist_to[instance.goals.index(g_other)]
    best: int | None = None if math.isinf(d1[g]) else int(d1[g]) + int(d_to_other[g] * k)
    witness = g
    f = d1 + dg + d2
    f[g] = np.inf
    u = int(np.argmin(f))  # the first minimiser, as the loop over nodes in order would pick
    if not math.isinf(f[u]) and (best is None or f[u] < best):
        best, witness = int(f[u]), u
    c0 = instance.dist_to[instance.goals.index(g)][s0]
    other = INF if best is None else normalize(Fraction(best, k) - c0)
    return WalkMinima(goal=g, same=normalize(c0), other=other, witness=witness)
