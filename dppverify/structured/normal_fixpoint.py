"""The normal-restricted DP at ``H = inf`` by label setting (``proofs/NRULE.md`` NR.1).

For a finite set ``A`` of facet normals (every 0/1 vector ``1_S`` plus *extra* non-negative
integer vectors) the normal-restricted DP of ``proofs/NGOAL.md`` NG.7 has, at ``H = inf``, one
number ``m_a(v)`` per normal and node, the unique finite solution of

    m_a(g) = a·d(g, g^·)                                                     (goal g)
    m_a(v) = min( min_{(v,u)} [ w(v,u)·max(a) + m_a(u) ],  split_a(v) )        (v not a goal)
    split_a(v) = min { Σ_{a'} c_{a'} m_{a'}(v) : c >= 0, Σ c_{a'} a' = a, a' ∈ A, a' != a }

on the nodes ``R`` that reach a goal (a cover of ``a`` only uses normals ``a' <= a``
componentwise, so by increasing entry sum every split is known before its normal's pass).
For each normal it is one shortest-path computation (NR.1, the extension of NSOLVE.3):
``m_a(v) = min_x [max(a)·dist°(v, x) + init_a(x)]`` over walks whose interior avoids the goals,
with ``init_a`` the terminal cost at a goal and the split elsewhere. The 0/1 rows are the
coalition DP's fixpoint whatever the extras (a cover of ``1_S`` uses 0/1 vectors only).

``F_v = { r : a·r <= m_a(v) for a ∈ A }`` are the sets of the guarantee rule with normals
(``docs/formats.md`` §2b) and an outer bound of the exact guarantee sets (NG.7).

Exact: integers at one scale ``D`` (every ``m_a(v)·D`` is an integer). The 0/1 splits are exact
integer matrix products over the tables of minimal balanced collections
(:mod:`dppverify.structured.cover`; float64 BLAS only where every partial sum is provably an
integer below 2**53); an extra normal's split is its dominated-cover LP, solved exactly at
every node at once (:func:`dppverify.structured.cover_lp.cover_values`: a handful of optimal
bases, not the cover polytope's every vertex); the scale grows only when a split's
denominator requires it.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np

from dppverify.exact import INF, Number
from dppverify.game.distances import EXACT_FLOAT_LIMIT, dijkstra
from dppverify.game.instance import Instance
from dppverify.structured.coalition import Split, coalition_scale, splits
from dppverify.structured.cover import Normal, cheapest, zero_one_normals
from dppverify.structured.cover_lp import cover_values


@dataclass(frozen=True, eq=False)
class NormalSets:
    """``m_a(v)`` at ``H = inf`` for every normal ``a ∈ A`` and node ``v`` (scaled integers).

    Attributes
    ----------
    instance : Instance
    normals : tuple of Normal
        ``A``: the ``2^N - 1`` 0/1 vectors in mask order (row ``mask - 1`` is ``1_S``), then the
        extra normals in the order given.
    scale : int
        ``m_a(v) = rows[j][v] / scale``.
    rows : tuple of numpy.ndarray
        One integer array over the nodes per normal (int64 or Python ints); entries of nodes
        outside :attr:`finite` are meaningless.
    finite : numpy.ndarray
        ``finite[v]``: some goal is reachable from ``v`` (every ``m_a(v)`` is finite there).
    """

    instance: Instance
    normals: tuple[Normal, ...]
    scale: int
    rows: tuple[np.ndarray, ...]
    finite: np.ndarray

    @property
    def extras(self) -> tuple[Normal, ...]:
        """The normals beyond the 0/1 vectors."""
        return self.normals[(1 << self.instance.n_goals) - 1:]

    def value(self, mask: int, v: int) -> Fraction | None:
        """``m_{1_S}(v)`` for the subset mask ``S`` exactly, None where no goal is reachable.

        Examples
        --------
        >>> from dppverify.game.examples import star3
        >>> normal_sets(star3()).value(0b111, 0)
        Fraction(4, 1)
        """
        return self.value_at(mask - 1, v)

    def value_at(self, j: int, v: int) -> Fraction | None:
        """``m_a(v)`` for the normal ``a = normals[j]``, None where no goal is reachable."""
        if not self.finite[v]:
            return None
        return Fraction(int(self.rows[j][v]), self.scale)

    def column(self, v: int) -> list[Fraction] | None:
        """Every ``m_a(v)`` (in :attr:`normals` order) exactly, None where no goal is reachable."""
        if not self.finite[v]:
            return None
        return [Fraction(int(row[v]), self.scale) for row in self.rows]

    @property
    def m(self) -> dict[int, np.ndarray]:
        """The 0/1 rows by subset mask (``m[mask][v] / scale``; unreachable nodes ``>= big``)."""
        big = self.big
        out = {}
        for mask in range(1, 1 << self.instance.n_goals):
            row = np.asarray(self.rows[mask - 1], dtype=object).copy()
            row[~self.finite] = big
            out[mask] = row
        return out

    @property
    def big(self) -> int:
        """A number above every finite scaled value (marks unreachable nodes in :attr:`m`)."""
        top = max((int(np.max(np.asarray(r)[self.finite], initial=0)) for r in self.rows),
                  default=0)
        return 2 * top + 2


def reach_mask(instance: Instance) -> np.ndarray:
    """``R``: the nodes from which a walk reaches a goal (its interior avoiding the goals).

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> reach_mask(star3()).tolist()
    [True, True, True, True, True]
    """
    inst = instance
    out = np.zeros(inst.n_nodes, dtype=bool)
    goal = np.zeros(inst.n_nodes, dtype=bool)
    goal[list(inst.goals)] = True
    out[goal] = True
    stack = list(inst.goals)
    while stack:
        x = stack.pop()
        for y, _ in inst.pred[x]:
            if not out[y] and not goal[y]:
                out[y] = True
                stack.append(y)
    return out


def dominated_normals(normals: Sequence[Normal], a: Normal) -> list[int]:
    """The indices of the normals that a dominated cover of ``a`` may use: ``a' <= a``
    componentwise, ``a' != a`` (empty for a unit vector).

    Examples
    --------
    >>> zo = zero_one_normals(3)
    >>> [zo[j] for j in dominated_normals(zo + ((2, 1, 0),), (2, 1, 0))]
    [(1, 0, 0), (0, 1, 0), (1, 1, 0)]
    """
    if sum(a) == 1:
        return []
    return [j for j, n in enumerate(normals)
            if tuple(n) != tuple(a) and all(x <= y for x, y in zip(n, a, strict=True))]


def normal_sets(instance: Instance, extras: Sequence[Normal] = (),
                base: NormalSets | None = None) -> NormalSets:
    """``m_a`` at ``H = inf`` for the 0/1 normals and ``extras``: one label-setting pass each.

    Parameters
    ----------
    instance : Instance
        The game (2 to 5 goals).
    extras : sequence of Normal
        Extra normals: non-negative integer vectors of length N, not 0/1, distinct (the
        profile reader validates them).
    base : NormalSets, optional
        Sets of the same instance over fewer normals: the rows of its normals are reused
        unless a new normal lies below them (then their splits may change).

    Examples
    --------
    The hub of ``proofs/NGOAL.md``: at the start the normal (2, 2, 2, 1) has ``m = 12``, less
    than the cover {1, 2} + {1, 3} + {2, 3, 4} by 0/1 vectors:

    >>> from dppverify.game.examples import hub4
    >>> s = normal_sets(hub4(), [(2, 2, 2, 1)])
    >>> s.value_at(15, 0), s.value(0b0011, 0) + s.value(0b0101, 0) + s.value(0b1110, 0)
    (Fraction(12, 1), Fraction(13, 1))
    """
    inst = instance
    zero_one = zero_one_normals(inst.n_goals)
    normals = zero_one + tuple(tuple(int(x) for x in e) for e in extras)
    finite = reach_mask(inst)
    goal = np.zeros(inst.n_nodes, dtype=bool)
    goal[list(inst.goals)] = True
    live = np.flatnonzero(finite & ~goal)
    arcs = _arcs(inst, finite, goal)
    split_of = {sp.mask: sp for sp in splits(inst.n_goals)}
    reuse = _reusable(base, inst, normals)
    scale = base.scale if base is not None and reuse else coalition_scale(
        inst, list(split_of.values()))
    rows: list[np.ndarray | None] = [None] * len(normals)
    for j in sorted(range(len(normals)), key=lambda j: (sum(normals[j]), j)):
        a = normals[j]
        if base is not None and j in reuse:
            rows[j] = reuse[j] * (scale // base.scale)
            continue
        init = _goal_costs(inst, a, scale)
        if j < len(zero_one) and sum(a) > 1 and live.size:
            init[live] = _zero_one_split(split_of[j + 1], rows, live)
        elif j >= len(zero_one) and live.size:
            split, grow = _extra_split(normals, a, rows, live)
            if grow > 1:  # the split needs a finer scale: rescale everything computed so far
                scale *= grow
                rows = [None if row is None else np.asarray(row, dtype=object) * grow
                        for row in rows]
                for g in inst.goals:
                    init[g] *= grow
            init[live] = split
        rows[j] = _label_setting(inst.n_nodes, arcs, scale, max(a), init)
    done = tuple(np.asarray(r) for r in rows)
    return NormalSets(inst, normals, scale, tuple(_compact(r, finite) for r in done), finite)


def _reusable(base: NormalSets | None, inst: Instance, normals: Sequence[Normal]
              ) -> dict[int, np.ndarray]:
    """The rows of ``base`` (at its scale) that stay valid for ``normals``, by index in
    ``normals``: those of a normal it has, unless a new normal lies below it."""
    if base is None or base.instance is not inst:
        return {}
    old = {a: k for k, a in enumerate(base.normals)}
    fresh = [a for a in normals if a not in old]
    reuse = {}
    for j, a in enumerate(normals):
        k = old.get(a)
        if k is not None and not any(b != a and all(x <= y for x, y in zip(b, a, strict=True))
                                     for b in fresh):
            reuse[j] = np.asarray(base.rows[k], dtype=object)
    return reuse


def _goal_costs(inst: Instance, a: Normal, scale: int) -> np.ndarray:
    """The terminal costs ``a·d(g, g^·)·scale`` at the goals, ``-1`` (no source) elsewhere."""
    init = np.full(inst.n_nodes, -1, dtype=object)
    for g in inst.goals:
        init[g] = sum(int(Fraction(inst.dist_to[t][g]) * scale) * a[t]
                      for t in range(inst.n_goals))
    return init


def _zero_one_split(sp: Split, rows: Sequence[np.ndarray | None], live: np.ndarray
                    ) -> np.ndarray:
    """The split of a 0/1 normal on the ``live`` nodes (scaled integers): its cheapest
    minimal balanced collection over the rows already computed."""
    mat = np.stack([np.asarray(rows[int(c) - 1], dtype=object)[live] for c in sp.columns],
                   axis=1)
    best = np.asarray(cheapest(mat, sp.scaled), dtype=object)
    if any(int(x) % sp.lcm for x in best):  # pragma: no cover - the coalition scale
        raise AssertionError("normal_sets: a 0/1 split is not a multiple of 1/scale")
    return best // sp.lcm


def _extra_split(normals: Sequence[Normal], a: Normal, rows: Sequence[np.ndarray | None],
                 live: np.ndarray) -> tuple[np.ndarray, int]:
    """The split of the extra normal ``a`` on the ``live`` nodes, its dominated-cover LP:
    ``(num, grow)`` with ``split = num / (scale·grow)`` (``grow > 1``: the scale must grow)."""
    idx = dominated_normals(normals, a)
    assert idx  # an extra normal is not a unit vector
    mat = np.stack([np.asarray(rows[k], dtype=object)[live] for k in idx])
    num, den = cover_values([normals[k] for k in idx], mat, a)
    g = math.gcd(den, *(int(x) for x in num))
    return np.asarray(num, dtype=object) // g, den // g


def _compact(row: np.ndarray, finite: np.ndarray) -> np.ndarray:
    """int64 when every finite entry fits comfortably, else Python integers; 0 off ``finite``."""
    out = np.asarray(row, dtype=object).copy()
    out[~finite] = 0
    top = int(np.max(np.abs(out), initial=0)) if out.size else 0
    return out.astype(np.int64) if top < 2 ** 62 else out


def _arcs(inst: Instance, finite: np.ndarray, goal: np.ndarray
          ) -> tuple[list[int], list[int], list[Fraction]]:
    """The walkable arcs ``v -> u`` (``v`` not a goal, both in ``R``), weights exact."""
    tails: list[int] = []
    heads: list[int] = []
    weights: list[Fraction] = []
    cache: dict[Any, Fraction] = {}
    for v in np.flatnonzero(finite & ~goal).tolist():
        for u, w in inst.succ[v]:
            if not finite[u]:
                continue
            tails.append(v)
            heads.append(u)
            f = cache.get(w)
            if f is None:
                f = cache[w] = Fraction(w)
            weights.append(f)
    return tails, heads, weights


def _label_setting(n: int, arcs: tuple[list[int], list[int], list[Fraction]], scale: int,
                   factor: int, init: np.ndarray) -> np.ndarray:
    """``min_x [factor·dist(v -> x) + init[x]]`` (``init < 0``: no source), scaled integers.

    One shortest-path computation on the reversed arcs from a root ``n`` with an arc
    ``n -> x`` of length ``init[x] + 1`` to every source ``x``: scipy's in float64 while every
    distance is an integer below 2**53, else the exact one of
    :func:`dppverify.game.distances.dijkstra`.
    """
    tails, heads, weights = arcs
    lengths_arc = [int(w * scale) * factor for w in weights]
    src = [x for x in range(n) if init[x] >= 0]
    out = np.full(n, 0, dtype=object)
    rows = heads + [n] * len(src)
    cols = tails + src
    lengths = lengths_arc + [int(init[x]) + 1 for x in src]
    if max(lengths, default=0) * (n + 2) < EXACT_FLOAT_LIMIT:
        from scipy.sparse import csr_matrix
        from scipy.sparse.csgraph import dijkstra as scipy_dijkstra

        r = np.asarray(rows, dtype=np.int64)
        c = np.asarray(cols, dtype=np.int64)
        w = np.asarray(lengths, dtype=np.float64)
        dist = scipy_dijkstra(csr_matrix((w, (r, c)), shape=(n + 1, n + 1)), directed=True,
                              indices=n)[:n]
        fin = np.flatnonzero(np.isfinite(dist))
        out[fin] = [int(x) - 1 for x in dist[fin].tolist()]
        return out
    adj: list[list[tuple[int, Number]]] = [[] for _ in range(n + 1)]
    for a, b, w2 in zip(rows, cols, lengths, strict=True):
        adj[a].append((b, w2))
    exact = dijkstra(adj, n)
    for v in range(n):
        if exact[v] != INF:
            out[v] = exact[v] - 1
    return out
