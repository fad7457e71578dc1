"""The normal-restricted DP's fixpoint by blocks of sourced shortest paths, and its ranks.

The layer map ``T`` of the normal-restricted DP (:mod:`solver.coalitions.guarantee_sets`,
proofs/NGOAL.md NG.7) is, for one normal ``a`` with the others held fixed, a shortest-path
problem with sources: a vertex cover of ``a`` that uses ``a`` at all is ``a`` itself (a
vertex with ``0 < c_a < 1`` would be the mean of ``e_a`` and another cover), so

    m_a(v) = min( init_a(v),  min_{(v,u)} [ w(v,u)·max(a) + m_a(u) ] ),
    init_a(v) = min over the other vertex covers c of Σ_n c_n s_n(v)     (s_n: the step)

with the goals' terminal values as further sources. :func:`block_fixpoint` solves these
blocks in turn (one exact Dijkstra each) until a whole round changes nothing: the same greatest
fixpoint ``m*`` as the layered DP, in a few rounds instead of ``K`` layers
(proofs/NEXACT.md NX.7). :func:`fixpoint_ranks` then recovers the layered DP's ranks (the
layer at which each ``m_a(v)`` settled) from ``m*`` alone, by a bottleneck label-setting over
the arcs and covers that attain ``m*`` (NX.7).

Everything is exact integers at a common scale ``D`` (numpy int64; scipy's float64 Dijkstra
and float64 products only when every partial sum is an integer below 2**53; the covers' totals
are :mod:`solver.coalitions.cover_totals`).
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Callable, Sequence

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import dijkstra

from solver.coalitions.arc_graph import ArcGraph
from solver.coalitions.cover_totals import attaining, cover_minimum
from solver.coalitions.normal_system import NormalSystem
from solver.coalitions.vertex_tables import INT_LIMIT, VertexTable
from solver.graph.distances import EXACT_FLOAT_LIMIT

UNSET = np.iinfo(np.int32).max
NONE = np.iinfo(np.int64).max


def _own_column(table: VertexTable, j: int) -> tuple[int, int] | None:
    """The table's vertex ``e_j`` (the step) as ``(part, vertex)``, or None when the table is
    not of that shape."""
    if j not in table.columns:
        return None
    pos = table.columns.index(j)
    found: list[tuple[int, int]] = []
    for p, (scaled, lcm) in enumerate(table.parts):
        row = scaled[pos]
        found += [(p, k) for k in np.flatnonzero(row).tolist()
                  if row[k] == lcm and not np.any(np.delete(scaled[:, k], pos))]
        if np.count_nonzero(row) != (1 if any(q == p for q, _ in found) else 0):
            return None
    return found[0] if len(found) == 1 else None


def _steps(indptr: np.ndarray, heads: np.ndarray, w_top: np.ndarray, x: np.ndarray,
           fin: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``s(v) = min_{(v,u), u finite} [w_top + x(u)]`` and whether it is finite, per node
    (arcs in CSR order by tail)."""
    n = len(indptr) - 1
    cand = np.where(fin[heads], w_top + x[heads], NONE)
    out = np.full(n, NONE, dtype=np.int64)
    starts = indptr[:-1]
    nonempty = starts < indptr[1:]
    if cand.size:
        out[nonempty] = np.minimum.reduceat(cand, starts[nonempty])
    return out, out < NONE


def _distinct(keys: np.ndarray, stamp: np.ndarray) -> np.ndarray:
    """``keys`` without repeats (first-come order not kept), in linear time; ``stamp`` is a
    scratch array indexed by key."""
    pos = np.arange(keys.size, dtype=np.int64)
    stamp[keys] = pos
    return keys[stamp[keys] == pos]


def _sourced(rev: tuple[np.ndarray, np.ndarray, np.ndarray], w: np.ndarray, init: np.ndarray,
             src: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """``min_x [dist(v -> x) + init(x)]`` over the sources ``x`` (exact), and finiteness.

    ``rev`` is the reversed graph in CSR (by head: indptr, tails, arc ids); ``w`` the arcs'
    positive integer weights.
    """
    indptr, cols, arc_ids = rev
    out = np.zeros(n, dtype=np.int64)
    fin = np.zeros(n, dtype=bool)
    if not src.size:
        return out, fin
    w_rev = w[arc_ids]
    top = int(init[src].max()) + 1 + int(w.max(initial=0)) * (n + 1)
    if top < EXACT_FLOAT_LIMIT:
        data = np.concatenate([w_rev.astype(np.float64),
                               (init[src] + 1).astype(np.float64)])
        full_cols = np.concatenate([cols, src])
        full_ptr = np.concatenate([indptr, [indptr[-1] + src.size]])
        mat = sp.csr_matrix((data, full_cols, full_ptr), shape=(n + 1, n + 1))
        d = dijkstra(mat, directed=True, indices=n)[:n]
        fin = np.isfinite(d)
        out[fin] = d[fin].astype(np.int64) - 1
        return out, fin
    best: list[int | None] = [None] * n  # Python integers: exact at any size
    heap = [(int(init[i]), int(i)) for i in src.tolist()]
    for k, i in heap:
        best[i] = k if best[i] is None else min(k, best[i])  # type: ignore[type-var]
    heapq.heapify(heap)
    ptr, cl, wl = indptr.tolist(), cols.tolist(), w_rev.tolist()
    while heap:
        k, x = heapq.heappop(heap)
        if (b := best[x]) is not None and k > b:
            continue
        for p in range(ptr[x], ptr[x + 1]):
            u, nk = cl[p], k + wl[p]
            b = best[u]
            if b is None or nk < b:
                best[u] = nk
                heapq.heappush(heap, (nk, u))
    if max((b for b in best if b is not None), default=0) >= INT_LIMIT:
        raise OverflowError("numbers beyond the exact int64 range")
    for i, b in enumerate(best):
        if b is not None:
            out[i], fin[i] = b, True
    return out, fin


def _reverse(tails: np.ndarray, heads: np.ndarray, n: int, weights: np.ndarray | None = None
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The arcs by head: CSR pointers, tails, arc ids (with ``weights``: one arc per pair
    ``(tail, head)``, a lightest one)."""
    if weights is None:
        order = np.argsort(heads, kind="stable")
    else:
        order = np.lexsort((weights, tails, heads))
        first = np.ones(order.size, dtype=bool)
        first[1:] = (heads[order][1:] != heads[order][:-1]) | (
            tails[order][1:] != tails[order][:-1])
        order = order[first]
    counts = np.bincount(heads[order], minlength=n)
    indptr = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
    return indptr, tails[order].astype(np.int64), order.astype(np.int64)


def _step_inputs(step: Callable[[int], tuple[np.ndarray, np.ndarray]], tab: VertexTable,
                 is_goal: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The steps of a table's columns at the non-goal nodes, and where they are infinite."""
    live = np.flatnonzero(~is_goal)
    vals = np.zeros((live.size, len(tab.columns)), dtype=np.int64)
    lost = np.zeros((live.size, len(tab.columns)), dtype=bool)
    for p, c in enumerate(tab.columns):
        s, has = step(c)
        vals[:, p] = s[live]
        lost[:, p] = ~has[live]
    return vals, lost


def block_fixpoint(graph: ArcGraph, system: NormalSystem, max_rounds: int
                   ) -> tuple[np.ndarray, int, np.ndarray, int] | None:
    """The greatest fixpoint of the normal-restricted DP by blocks (see the module docstring).

    The blocks are solved by increasing entry sum of their normals. Returns
    ``(m, scale, finite, rounds)`` with ``m_{a_j}(v) = m[j, v] / scale`` where ``finite[v]``,
    or None when the method does not apply (a weight that is not positive, a cover table not
    of the expected shape, numbers beyond int64) or ``max_rounds`` rounds did not settle: the
    caller then runs the layered DP.

    Examples
    --------
    Two goals one step from the start, the 0/1 normals:

    >>> from solver.coalitions.vertex_tables import zero_one_normals
    >>> graph = ArcGraph(indptr=np.array([0, 2, 2, 2]), heads=np.array([1, 2]),
    ...                  weights=np.array([1, 1]), denominator=1, goals=(1, 2),
    ...                  terminal=np.array([[0, 2], [2, 0]]), start=0)
    >>> m, scale, fin, rounds = block_fixpoint(graph, NormalSystem(zero_one_normals(2)), 10)
    >>> m[:, 0].tolist(), scale, rounds
    ([1, 1, 2], 1, 2)
    """
    if graph.weights.size and int(graph.weights.min()) <= 0:
        return None
    own = [_own_column(t, j) for j, t in enumerate(system.closures)]
    if any(k is None for k in own):
        return None
    sums = [sum(a) for a in system.normals]
    order = sorted(range(len(sums)), key=lambda j: (sums[j], j))
    blocks = _Blocks(graph, system, own)
    try:
        for rounds in range(1, max_rounds + 1):
            changed = False
            for j in order:
                if blocks.solve(j):
                    changed = True
            if not changed:
                fin = blocks.fin
                finite = np.asarray(fin.any(axis=0), dtype=bool)
                if not np.array_equal(fin, np.broadcast_to(finite, fin.shape)):
                    return None  # pragma: no cover - every normal reaches the same goals
                return blocks.x, blocks.scale, finite, rounds
    except OverflowError:  # numbers beyond int64: the layered DP, exact in Python integers
        return None
    return None


class _Blocks:
    """The state of :func:`block_fixpoint`'s rounds: every normal's values ``x`` at the common
    scale (finite where ``fin``), the steps' cache, and what each block was last solved from
    (the versions of the blocks its covers read)."""

    def __init__(self, graph: ArcGraph, system: NormalSystem,
                 own: Sequence[tuple[int, int] | None]) -> None:
        n = graph.n_nodes
        self.graph, self.system, self.own = graph, system, own
        self.heads = graph.heads.astype(np.int64)
        self.rev = _reverse(graph.tails, self.heads, n, graph.weights)
        self.goals = np.asarray(graph.goals, dtype=np.int64)
        self.scale = graph.denominator
        self.x = np.zeros((len(system.normals), n), dtype=np.int64)
        self.fin = np.zeros((len(system.normals), n), dtype=bool)
        self.x[:, self.goals] = np.array(system.normals, dtype=np.int64) @ graph.terminal.T
        self.fin[:, self.goals] = True
        self.version = [0] * len(system.normals)
        self._step_cache: dict[int, tuple[int, np.ndarray, np.ndarray]] = {}
        self._seen: dict[int, tuple[int, ...]] = {}

    def _w_top(self, j: int) -> np.ndarray:
        """The arcs' weights times ``max(a_j)`` at the common scale."""
        graph = self.graph
        return graph.weights * (int(self.system.tops[j]) * (self.scale // graph.denominator))

    def step(self, j: int) -> tuple[np.ndarray, np.ndarray]:
        """The step ``s_j(v)`` of normal ``j`` at every node, and where it is finite."""
        hit = self._step_cache.get(j)
        if hit is None or hit[0] != self.version[j]:
            s, has = _steps(self.graph.indptr, self.heads, self._w_top(j), self.x[j],
                            self.fin[j])
            hit = (self.version[j], s, has)
            self._step_cache[j] = hit
        return hit[1], hit[2]

    def solve(self, j: int) -> bool:
        """Solve block ``j`` from the others (one sourced Dijkstra): whether it changed.

        Raises OverflowError when the numbers would leave int64."""
        tab = self.system.closures[j]
        inputs = tuple(self.version[c] for c in tab.columns if c != j)
        if self._seen.get(j) == inputs:
            return False  # the same sources (up to the common scale): the same solution
        init, src = self._sources(j)
        self._seen[j] = inputs
        new, nfin = _sourced(self.rev, self._w_top(j), init, np.flatnonzero(src),
                             self.graph.n_nodes)
        if np.array_equal(nfin, self.fin[j]) and np.array_equal(new[nfin], self.x[j, nfin]):
            return False
        new[~nfin] = 0
        self.x[j], self.fin[j] = new, nfin
        self.version[j] += 1
        return True

    def _sources(self, j: int) -> tuple[np.ndarray, np.ndarray]:
        """Block ``j``'s sources: ``(init, src)``, the goals' values and ``init_a(v)`` (the
        cheapest cover other than ``a`` itself) where it is finite; the common scale grows
        first when a cover's value is not a multiple of ``1/scale``."""
        tab, is_goal = self.system.closures[j], self.graph.is_goal
        init = np.zeros(self.graph.n_nodes, dtype=np.int64)
        src = is_goal.copy()
        found = cover_minimum(*_step_inputs(self.step, tab, is_goal), tab, skip=self.own[j])
        if found is not None:
            low, lcm, got = found
            nodes = np.flatnonzero(~is_goal)[got]
            vals_live = low[got]
            grow = _growth(vals_live, lcm)
            if grow > 1:
                self.scale *= grow
                if int(self.x.max(initial=0)) * grow * 4 >= INT_LIMIT:
                    raise OverflowError("numbers beyond the exact int64 range")
                self.x *= grow
                self._step_cache.clear()
            init[nodes] = _quotients(vals_live, grow, lcm)
            src[nodes] = True
        init[self.goals] = self.x[j, self.goals]  # at the scale, grown or not
        return init, src


def _growth(vals: np.ndarray, lcm: int) -> int:
    """The least ``grow`` with every ``vals · grow / lcm`` an integer."""
    if lcm > 1 and vals.dtype != object and lcm < INT_LIMIT:
        return lcm // math.gcd(lcm, int(np.gcd.reduce(vals % lcm, initial=0)))
    if lcm > 1:
        return lcm // math.gcd(lcm, *(int(v) % lcm for v in vals))
    return 1


def _quotients(vals: np.ndarray, grow: int, lcm: int) -> np.ndarray:
    """``vals · grow / lcm`` (exact division) as int64; OverflowError past the int64 range."""
    if vals.dtype != object and int(vals.max(initial=0)) * grow < INT_LIMIT:
        return vals * grow // lcm
    quot = [int(v) * grow // lcm for v in vals]
    if quot and max(quot) >= INT_LIMIT:
        raise OverflowError("numbers beyond the exact int64 range")
    return np.asarray(quot, dtype=np.int64)


def fixpoint_ranks(graph: ArcGraph, system: NormalSystem, scale: int, m: np.ndarray,
                   finite: np.ndarray) -> np.ndarray:
    """The layered DP's ranks from its fixpoint ``m`` at ``scale`` (proofs/NEXACT.md NX.7).

    ``rank[a, v]`` is the first layer ``k`` with ``m_a^k(v) = m*_a(v)``: 0 at goals (and where
    no goal is reachable); elsewhere the least, over the vertex covers ``c`` attaining
    ``m*_a(v)``, of the largest ``ready[n, v]`` over ``n`` with ``c_n > 0``, where
    ``ready[n, v]`` is one more than the least ``rank[n, u]`` over the arcs ``(v, u)`` attaining
    the step ``s*_n(v)``.

    Examples
    --------
    >>> from solver.coalitions.vertex_tables import zero_one_normals
    >>> graph = ArcGraph(indptr=np.array([0, 2, 2, 2]), heads=np.array([1, 2]),
    ...                  weights=np.array([1, 1]), denominator=1, goals=(1, 2),
    ...                  terminal=np.array([[0, 2], [2, 0]]), start=0)
    >>> fixpoint_ranks(graph, NormalSystem(zero_one_normals(2)), 1,
    ...                np.array([[1, 0, 2], [1, 2, 0], [2, 2, 2]]),
    ...                np.array([True, True, True]))[:, 0].tolist()
    [1, 1, 1]
    """
    n, n_a = graph.n_nodes, len(system.closures)
    tails, heads = graph.tails, graph.heads.astype(np.int64)
    goals_a = np.asarray(graph.goals, dtype=np.int64)
    inner = finite & ~graph.is_goal
    s_star, opt_arc = _optimal_steps(graph, system.tops, scale, m, finite)
    e_a, e_v, e_s = _attained_covers(system.closures, s_star, m, np.flatnonzero(inner))
    # each entry waits for its support's steps: a count, and the slots by (normal, node)
    waiting = (e_s >= 0).sum(axis=1)
    slot_e, slot_n = np.nonzero(e_s >= 0)
    slot_key = e_s[slot_e, slot_n] * n + e_v[slot_e]
    by_key = np.argsort(slot_key, kind="stable")
    slot_e = slot_e[by_key]
    slot_ptr = np.concatenate([[0], np.cumsum(np.bincount(slot_key, minlength=n_a * n))]
                              ).astype(np.int64)
    slot_cnt = np.diff(slot_ptr)
    rev_ptr, _, rev_arcs = _reverse(tails, heads, n)
    rev_cnt = np.diff(rev_ptr)
    rank = np.full((n_a, n), UNSET, dtype=np.int64)
    rank[:, ~inner] = 0
    ready = np.zeros((n_a, n), dtype=bool)
    stamp = np.zeros(n_a * n, dtype=np.int64)
    fa = np.repeat(np.arange(n_a, dtype=np.int64), goals_a.size)
    fu = np.tile(goals_a, n_a)
    k = 0
    while fa.size:
        k += 1
        arcs, owner = _expand(rev_ptr, rev_cnt, fu)
        aa = fa[owner]
        sel = opt_arc[aa, rev_arcs[arcs]]
        keys = aa[sel] * n + tails[rev_arcs[arcs[sel]]]
        keys = _distinct(keys[~ready.flat[keys]], stamp)
        ready.flat[keys] = True  # ready[a, v] = k
        slots, _ = _expand(slot_ptr, slot_cnt, keys)
        ent = slot_e[slots]
        np.subtract.at(waiting, ent, 1)
        ent = ent[waiting[ent] == 0]
        key = e_a[ent] * n + e_v[ent]
        key = _distinct(key[rank.flat[key] == UNSET], stamp)
        fa, fu = key // n, key % n
        rank.flat[key] = k
    if np.any(rank == UNSET):  # pragma: no cover - NX.7: every value is attained by a cover
        raise AssertionError("fixpoint ranks: a value no ranked cover attains")
    return rank.astype(np.int32)


def _optimal_steps(graph: ArcGraph, tops: np.ndarray, scale: int, m: np.ndarray,
                   finite: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """At the fixpoint ``m``: every normal's step ``s*_a(v)`` at the inner nodes (0 elsewhere)
    and the arcs ``(v, u)`` that attain it."""
    heads = graph.heads.astype(np.int64)
    w_scaled = graph.weights * (scale // graph.denominator)
    inner = finite & ~graph.is_goal
    ok_arc = finite[heads] & inner[graph.tails]
    s_star = np.zeros((len(tops), graph.n_nodes), dtype=np.int64)
    opt_arc = np.zeros((len(tops), heads.size), dtype=bool)
    for j in range(len(tops)):
        cand = w_scaled * int(tops[j]) + m[j, heads]
        s, _ = _steps(graph.indptr, heads, w_scaled * int(tops[j]), m[j], finite)
        s_star[j] = np.where(inner, s, 0)
        opt_arc[j] = ok_arc & (cand == s[graph.tails])
    return s_star, opt_arc


def _attained_covers(closures: Sequence[VertexTable], s_star: np.ndarray, m: np.ndarray,
                     live: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The vertex covers that attain ``m*`` at the ``live`` nodes, as entries: the normal
    ``a``, the node ``v`` and the support of the vertex (normals, padded with -1)."""
    width = max(1, max(int((sc > 0).sum(axis=0).max(initial=1)) for t in closures
                       for sc, _ in t.parts))
    ent_a, ent_v, ent_s = [], [], []
    for j, tab in enumerate(closures):
        cols = np.asarray(tab.columns, dtype=np.int64)
        for sc, lcm in tab.parts:
            target = m[j, live].astype(object) * lcm if lcm * int(
                m.max(initial=0)) >= INT_LIMIT else m[j, live] * lcm
            hit_v, hit_q = attaining(s_star[cols][:, live].T, sc, target)
            supp = np.full((sc.shape[1], width), -1, dtype=np.int64)
            for q in range(sc.shape[1]):
                nz = cols[np.flatnonzero(sc[:, q])]
                supp[q, :nz.size] = nz
            ent_a.append(np.full(hit_v.size, j, dtype=np.int64))
            ent_v.append(live[hit_v])
            ent_s.append(supp[hit_q])
    return np.concatenate(ent_a), np.concatenate(ent_v), np.concatenate(ent_s)


def _expand(ptr: np.ndarray, cnt: np.ndarray, keys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The positions ``ptr[k] .. ptr[k+1]-1`` of every key (concatenated) and their key's index."""
    counts = cnt[keys]
    total = int(counts.sum())
    seg = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(np.int64)
    idx = np.arange(total, dtype=np.int64) - np.repeat(seg - ptr[keys], counts)
    return idx, np.repeat(np.arange(keys.size, dtype=np.int64), counts)
