"""The coalition DP of the N-goal game at ``H = inf``, with its argmins (the solver's own).

For a non-empty set ``S`` of types (a bitmask) and a node ``v``, ``m_S(v)`` is the cost of a
*coalition*: every type of ``S`` at ``v`` with unit mass, walking together (a shared step costs
its weight once) and splitting into sub-coalitions (``proofs/NSOLVE.md``)::

    m_S(g) = Σ_{θ ∈ S} d(g, g^θ)                                 at a goal g (walks end there)
    m_S(v) = min( min_{(v,u)} [ w(v,u) + m_S(u) ],  split_S(v) )   elsewhere
    split_S(v) = min { Σ_{T ⊊ S} λ_T m_T(v) : λ a minimal balanced collection of S }

By increasing ``|S|``, ``split_S`` is known before ``m_S``, and ``m_S`` is a shortest-path
problem with sources: ``m_S(v) = min_x [ dist(v → x) + init_S(x) ]`` over walks whose interior
avoids the goals, ``init_S`` the split at non-goals and the terminal cost at goals. One
Dijkstra per ``S`` (exact: integers scaled by ``W·L^(N-1)``, ``W`` the weights' denominator,
``L`` the lcm of the collections' denominators;
:func:`~solver.graph.distances.distances_from_sources`).

The balanced collections are the vertices of ``{λ >= 0 : Σ_{T ⊊ S} λ_T 1_T = 1_S}``, found by
trying every basis (a float pre-filter on the integer determinants, then exact integers).
The cover LP at the start, ``min Σ_S c_S m_S(s0)`` s.t. ``Σ_S c_S 1_S = b``, is the normals'
cover LP over the subsets' 0/1 vectors (:func:`~solver.coalitions.normal_cover.normal_cover_lp`),
which also returns its dual ``h`` (``h(S) <= m_S(s0)``, ``h·b`` = the value).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from dataclasses import dataclass
from fractions import Fraction
from functools import cache

import numpy as np

from solver.game.instance import Instance
from solver.graph.distances import distances_from_sources

__all__ = ["Coalitions", "balanced_collections", "coalition_dp", "subset_members"]



def subset_members(mask: int) -> tuple[int, ...]:
    """The types of a subset mask.

    Examples
    --------
    >>> subset_members(0b1101)
    (0, 2, 3)
    """
    return tuple(i for i in range(mask.bit_length()) if mask >> i & 1)


@cache
def balanced_collections(size: int) -> tuple[tuple[tuple[int, Fraction], ...], ...]:
    """The minimal balanced collections of ``{0, …, size-1}``: ``((T, λ_T), …)`` per collection.

    Examples
    --------
    >>> [len(balanced_collections(s)) for s in (2, 3, 4)]
    [1, 5, 41]
    >>> balanced_collections(2)
    (((1, Fraction(1, 1)), (2, Fraction(1, 1))),)
    """
    full = (1 << size) - 1
    cols = list(range(1, full))
    inc = np.array([[(t >> i) & 1 for t in cols] for i in range(size)], dtype=np.float64)
    combos = np.array(list(itertools.combinations(range(len(cols)), size)), dtype=np.int64)
    mats = np.transpose(inc[:, combos], (1, 0, 2))  # (k, size, size): columns = subsets
    det = np.linalg.det(mats)
    ok = np.abs(det) > 0.5  # integer determinants: non-singular iff |det| >= 1
    mats, combos, det = mats[ok], combos[ok], np.rint(det[ok]).astype(np.int64)
    sol = np.linalg.solve(mats, np.ones((mats.shape[0], size, 1)))[:, :, 0]
    feasible = np.all(sol > -1e-9, axis=1)  # a negative entry is at most -1/|det| <= -1/120
    found: set[tuple[tuple[int, Fraction], ...]] = set()
    for k in np.flatnonzero(feasible):
        d = int(det[k])
        nums = [round(x * d) for x in sol[k]]
        lam = [Fraction(x, d) for x in nums]
        members = [cols[int(c)] for c in combos[k]]
        # exact verification: Σ λ_T 1_T = 1_S, λ >= 0
        for i in range(size):
            if sum(lam[j] for j, t in enumerate(members) if t >> i & 1) != 1:
                raise AssertionError("balanced_collections: inexact basis solution")
        if any(x < 0 for x in lam):
            continue
        found.add(tuple(sorted((t, x) for t, x in zip(members, lam, strict=True) if x)))
    return tuple(sorted(found))


@dataclass(frozen=True, eq=False)
class Coalitions:
    """``m_S(v)`` at ``H = inf`` for every subset and node, with argmins.

    Attributes
    ----------
    instance : Instance
        The game.
    scale : int
        ``m_S(v) = cost[S][v] / scale`` (``scale = W·L^(N-1)``).
    cost : Mapping
        Subset mask -> array of scaled integer costs (``-1`` where no goal is reachable).
    split : Mapping
        Subset mask -> array of ``split_S(v)`` (scaled; ``-1`` where undefined).
    split_choice : Mapping
        Subset mask -> array: index into :func:`balanced_collections` of an argmin split.
    """

    instance: Instance
    scale: int
    cost: Mapping[int, np.ndarray]
    split: Mapping[int, np.ndarray]
    split_choice: Mapping[int, np.ndarray]

    def m(self, mask: int, v: int) -> Fraction | None:
        """``m_S(v)`` exactly (None where no goal is reachable from ``v``)."""
        x = int(self.cost[mask][v])
        return None if x < 0 else Fraction(x, self.scale)


def _collections_in(mask: int) -> list[tuple[tuple[int, Fraction], ...]]:
    elems = subset_members(mask)
    out = []
    for coll in balanced_collections(len(elems)):
        out.append(tuple((sum(1 << elems[i] for i in subset_members(t)), lam)
                         for t, lam in coll))
    return out


def coalition_dp(game: Instance) -> Coalitions:
    """The coalition DP at ``H = inf`` (one Dijkstra per subset, by increasing size).

    Examples
    --------
    The hub: ``s -> m`` then ``m -> a | b | c`` (unit weights), ``s -> a`` weight 2:

    >>> from solver.game.instance_reading import instance_from_json
    >>> doc = {"graph": {"directed": True, "nodes": [{"id": x} for x in "smabc"],
    ...        "edges": [{"source": "s", "target": "m"}, {"source": "m", "target": "a"},
    ...                  {"source": "m", "target": "b"}, {"source": "m", "target": "c"},
    ...                  {"source": "s", "target": "a", "weight": 2},
    ...                  {"source": "a", "target": "s"}, {"source": "b", "target": "s"},
    ...                  {"source": "c", "target": "s"}]},
    ...        "start": "s", "goals": ["a", "b", "c"], "prior": ["1/2", "1/3", "1/6"]}
    >>> dp = coalition_dp(instance_from_json(doc))
    >>> [str(dp.m(t, 0)) for t in (1, 2, 4, 7)]
    ['2', '2', '2', '4']
    """
    n_goals = game.n_goals
    net = game.network
    n = net.n_nodes
    sizes = range(2, n_goals + 1)
    lcm = math.lcm(1, *(lam.denominator for s in sizes for coll in balanced_collections(s)
                        for _, lam in coll))
    scale = lcm ** (n_goals - 1)
    is_goal = np.zeros(n, dtype=bool)
    is_goal[list(game.targets)] = True
    tails = np.repeat(np.arange(n, dtype=np.int64), np.diff(net.indptr))
    keep = ~is_goal[tails]  # walks end at the first goal: arcs out of goals are never used
    t_arc, h_arc = tails[keep], net.indices[keep].astype(np.int64)
    w_arc = [int(x) * scale for x in net.weights[keep].tolist()]
    reach = np.zeros(n, dtype=bool)  # nodes from which some goal is reachable
    for d in game.dist_to:
        reach |= np.isfinite(d.astype(np.float64))
    term: dict[int, list[int]] = {}
    for g in game.targets:
        term[g] = [int(game.dist_to[t][g]) * scale for t in range(n_goals)]
    cost: dict[int, np.ndarray] = {}
    split: dict[int, np.ndarray] = {}
    choice: dict[int, np.ndarray] = {}
    nodes = np.flatnonzero(reach & ~is_goal)
    for mask in sorted(range(1, 1 << n_goals), key=lambda t: (bin(t).count("1"), t)):
        init = np.full(n, -1, dtype=object)
        for g in game.targets:
            init[g] = sum(term[g][t] for t in subset_members(mask))
        spl = np.full(n, -1, dtype=object)
        pick = np.full(n, -1, dtype=np.int64)
        if mask & (mask - 1):  # |S| >= 2: the split is known from smaller subsets
            best = None
            for k, coll in enumerate(_collections_in(mask)):
                tot = np.zeros(nodes.size, dtype=object)
                for t, lam in coll:
                    tot = tot + cost[t][nodes] * (lam.numerator * (lcm // lam.denominator))
                if best is None:
                    best, arg = tot, np.zeros(nodes.size, dtype=np.int64)
                else:
                    better = tot < best
                    best = np.where(better, tot, best)
                    arg = np.where(better, k, arg)
            assert best is not None
            if any(int(x) % lcm for x in best):  # pragma: no cover - guaranteed by the scale
                raise AssertionError("coalition DP: a split is not a multiple of 1/scale")
            spl[nodes] = best // lcm
            pick[nodes] = arg
            init[nodes] = spl[nodes]
        cost[mask] = distances_from_sources(n, t_arc, h_arc, w_arc, init)
        split[mask] = spl
        choice[mask] = pick
    return Coalitions(game, scale * game.denominator, cost, split, choice)
