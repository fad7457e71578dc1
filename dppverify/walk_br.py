"""Best responses over ALL walks (any length) against a progress-rule Defender (proofs/WALKBR.md).

Against the progress rule towards goal ``g`` (σ* when ``g = g1``), with ``g'`` the other goal:

- the type whose goal is ``g`` pays at least ``d(s0, g)``, attained (telescoping, TEL/L1);
- the type whose goal is ``g'`` pays at least ``min(min_u F(u), d'(s0, g) + d(g, g')) − d(s0, g)``
  with ``F(u) = d'(s0, u) + d(u, g) + d''(u, g')``, attained. ``d'`` are distances from ``s0``
  whose interior avoids both goals, ``d''`` distances to ``g'`` that avoid ``g``.

Three shortest-path computations, no enumeration. Distances use scipy's Dijkstra on the
weights scaled to integers when every path sum stays below ``2**53`` (float64 is then exact),
and the checker's exact Dijkstra (:mod:`dppverify.distances`) otherwise; float mode uses scipy.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import dijkstra as sp_dijkstra

from dppverify.distances import dijkstra
from dppverify.exact import INF, Number, normalize
from dppverify.instance import Instance

__all__ = ["WalkMinima", "avoiding_distances", "walk_minima"]

EXACT_FLOAT_LIMIT = 2**53
"""Integer path sums below this are exact in float64."""


def avoiding_distances(instance: Instance, source: int, *, reverse: bool,
                       blocked: frozenset[int]) -> list[Number]:
    """Distances from ``source`` (to it, with ``reverse``) whose interior avoids ``blocked``.

    A blocked node may be an endpoint but is never passed through (its arcs are not followed).

    Examples
    --------
    >>> from dppverify.examples import triangle
    >>> inst = triangle()          # s–g2 (2), g2–g1 (2), s–g1 (3); nodes s, g1, g2 = 0, 1, 2
    >>> avoiding_distances(inst, 0, reverse=False, blocked=frozenset({1, 2}))
    [0, 3, 2]
    >>> avoiding_distances(inst, 2, reverse=True, blocked=frozenset({1}))   # to g2 avoiding g1
    [2, 2, 0]
    """
    adj = instance.pred if reverse else instance.succ
    n = instance.n_nodes
    keep = [[] if (v in blocked and v != source) else list(adj[v]) for v in range(n)]
    if instance.exact:
        den = 1
        for arcs in keep:
            for _, w in arcs:
                if isinstance(w, Fraction):
                    den = math.lcm(den, w.denominator)
        total = sum(int(w * den) for arcs in keep for _, w in arcs)
        if total >= EXACT_FLOAT_LIMIT:
            return dijkstra(keep, source)
        rows, cols, vals = _coo(keep, lambda w: float(int(w * den)))
        dist = _scipy(n, rows, cols, vals, source)
        return [INF if math.isinf(x) else normalize(Fraction(int(x), den)) for x in dist]
    rows, cols, vals = _coo(keep, float)
    return [float(x) for x in _scipy(n, rows, cols, vals, source)]


def _coo(adj: list[list[tuple[int, Number]]], conv: object) -> tuple[list[int], list[int],
                                                                      list[float]]:
    rows: list[int] = []
    cols: list[int] = []
    vals: list[float] = []
    f = conv  # a callable: Number -> float
    for u, arcs in enumerate(adj):
        for v, w in arcs:
            rows.append(u)
            cols.append(v)
            vals.append(f(w))  # type: ignore[operator]
    return rows, cols, vals


def _scipy(n: int, rows: list[int], cols: list[int], vals: list[float],
           source: int) -> np.ndarray:
    m = sp.csr_matrix((np.asarray(vals, dtype=np.float64), (rows, cols)), shape=(n, n))
    return np.asarray(sp_dijkstra(m, directed=True, indices=source), dtype=np.float64)


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
    >>> from dppverify.examples import triangle
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
