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
and float64 products only when every partial sum is an integer below 2**53).
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Callable, Sequence

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import dijkstra

from solver.coalitions.vertex_tables import VertexTable
from solver.graph.distances import EXACT_FLOAT_LIMIT

INT_LIMIT = 2 ** 62
UNSET = np.iinfo(np.int32).max
NONE = np.iinfo(np.int64).max
CHUNK = 8192
"""Rows per block of the cover totals (bounds the temporaries: 8192 × vertices)."""


def exact_totals(values: np.ndarray, scaled: np.ndarray) -> np.ndarray:
    """``values @ scaled`` for non-negative int64 data, exactly.

    float64 (every entry an integer below 2**53, so comparisons and ``min`` are exact) when
    every partial sum is provably such an integer, else int64 through Python integers.

    Raises
    ------
    OverflowError
        When a total leaves the int64 range used here (``2**62``).

    Examples
    --------
    >>> exact_totals(np.array([[2, 3, 4]]), np.array([[1, 0], [1, 0], [0, 1]])).tolist()
    [[5.0, 4.0]]
    """
    if values.shape[0] == 0 or scaled.shape[1] == 0:
        return np.zeros((values.shape[0], scaled.shape[1]), dtype=np.int64)
    top = int(values.max(initial=0))
    width = (top + 1) * (int(np.abs(scaled).sum(axis=0).max(initial=1)) + 1)
    if width < EXACT_FLOAT_LIMIT:
        return values.astype(np.float64) @ scaled.astype(np.float64)
    out = values.astype(object) @ scaled.astype(object)
    if max((int(x) for x in out.flat), default=0) >= INT_LIMIT:
        raise OverflowError("numbers beyond the exact int64 range")
    return out.astype(np.int64)


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


def cover_minimum(values: np.ndarray, lost: np.ndarray, table: VertexTable,
                  skip: tuple[int, int] | None = None
                  ) -> tuple[np.ndarray, int, np.ndarray] | None:
    """``min_c values[row] @ c`` over the table's vertices ``c`` (all parts, but ``skip``)
    whose support avoids the row's ``lost`` entries, exactly.

    Returns ``(num, den, got)``: the minimum is ``num[row] / den`` where ``got[row]`` (some
    vertex avoids the lost entries); ``num`` is int64 for a one-part table, else Python
    integers over the lcm of the parts' denominators. None when every vertex is skipped.

    Examples
    --------
    >>> from solver.coalitions.vertex_tables import vertex_table
    >>> t = vertex_table(((1, 0), (0, 1), (1, 1)), (1, 1))
    >>> num, den, got = cover_minimum(np.array([[2, 3, 4], [2, 3, 6]]),
    ...                               np.zeros((2, 3), dtype=bool), t)
    >>> num.tolist(), den, got.tolist()
    ([4, 5], 1, [True, True])
    """
    parts = [(p, sc if skip is None or skip[0] != p else np.delete(sc, skip[1], axis=1), lcm)
             for p, (sc, lcm) in enumerate(table.parts)]
    parts = [(p, sc, lcm) for p, sc, lcm in parts if sc.shape[1]]
    if not parts:
        return None
    finite = values[~lost]
    top = int(finite.max(initial=0))
    den = math.lcm(*(lcm for _, _, lcm in parts))
    best: np.ndarray | None = None
    got = np.zeros(values.shape[0], dtype=bool)
    for _, sc, lcm in parts:
        # an unreachable step: a value above every finite cover's total
        big = top * int(sc.sum(axis=0).max(initial=1)) + 1
        vals = np.where(lost, big, values)
        if big >= INT_LIMIT:
            vals = vals.astype(object)
        mins = [_row_minimum(vals[lo:lo + CHUNK], sc) for lo in range(0, values.shape[0], CHUNK)]
        low = np.concatenate(mins) if mins else np.zeros(0, dtype=np.int64)
        ok = low < big
        if len(parts) == 1:
            return np.where(ok, low, 0).astype(low.dtype), den, ok
        low = np.where(ok, low, 0).astype(object) * (den // lcm)
        best = low if best is None else np.where(ok & (~got | (low < best)), low, best)
        got |= ok
    assert best is not None
    return best, den, got


def _row_minimum(values: np.ndarray, scaled: np.ndarray) -> np.ndarray:
    """Row-wise ``min`` of ``values @ scaled`` exactly: int64 when it fits, else Python
    integers."""
    try:
        return exact_totals(values, scaled).min(axis=1).astype(np.int64)
    except OverflowError:
        return (values.astype(object) @ scaled.astype(object)).min(axis=1)


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


def block_fixpoint(indptr: np.ndarray, heads: np.ndarray, weights: np.ndarray, den: int,
                   goals: Sequence[int], goal_values: np.ndarray, tops: np.ndarray,
                   closures: Sequence[VertexTable], sums: Sequence[int], max_rounds: int
                   ) -> tuple[np.ndarray, int, np.ndarray, int] | None:
    """The greatest fixpoint of the normal-restricted DP by blocks (see the module docstring).

    ``goal_values[j, i]`` is ``m_{a_j}(goals[i])`` over ``den``; ``sums[j]`` orders the blocks
    (smallest first). Returns ``(m, scale, finite, rounds)`` with ``m_{a_j}(v) = m[j, v] /
    scale`` where ``finite[v]``, or None when the method does not apply (a weight that is not
    positive, a cover table not of the expected shape, numbers beyond int64) or ``max_rounds``
    rounds did not settle: the caller then runs the layered DP.

    Examples
    --------
    Two goals one step from the start, the 0/1 normals:

    >>> from solver.coalitions.vertex_tables import vertex_table, zero_one_normals
    >>> zo = zero_one_normals(2)
    >>> tabs = [vertex_table(zo, a) for a in zo]
    >>> m, scale, fin, rounds = block_fixpoint(
    ...     np.array([0, 2, 2, 2]), np.array([1, 2]), np.array([1, 1]), 1, (1, 2),
    ...     np.array([[0, 2], [2, 0], [2, 2]]), np.array([1, 1, 1]), tabs, [1, 1, 2], 10)
    >>> m[:, 0].tolist(), scale, rounds
    ([1, 1, 2], 1, 2)
    """
    n = len(indptr) - 1
    n_a = len(closures)
    if weights.size and int(weights.min()) <= 0:
        return None
    own = [_own_column(t, j) for j, t in enumerate(closures)]
    if any(k is None for k in own):
        return None
    tails = np.repeat(np.arange(n, dtype=np.int64), np.diff(indptr))
    heads = heads.astype(np.int64)
    rev = _reverse(tails, heads, n, weights)
    goals_a = np.asarray(goals, dtype=np.int64)
    is_goal = np.zeros(n, dtype=bool)
    is_goal[goals_a] = True
    scale = den
    x = np.zeros((n_a, n), dtype=np.int64)
    fin = np.zeros((n_a, n), dtype=bool)
    x[:, goals_a] = goal_values
    fin[:, goals_a] = True
    order = sorted(range(n_a), key=lambda j: (sums[j], j))
    step_cache: dict[int, tuple[int, np.ndarray, np.ndarray]] = {}
    version = [0] * n_a
    seen: dict[int, tuple[int, ...]] = {}

    def step(j: int) -> tuple[np.ndarray, np.ndarray]:
        hit = step_cache.get(j)
        if hit is None or hit[0] != version[j]:
            w_top = weights * (int(tops[j]) * (scale // den))
            s, has = _steps(indptr, heads, w_top, x[j], fin[j])
            hit = (version[j], s, has)
            step_cache[j] = hit
        return hit[1], hit[2]

    try:
        for rounds in range(1, max_rounds + 1):
            changed = False
            for j in order:
                tab = closures[j]
                inputs = tuple(version[c] for c in tab.columns if c != j)
                if seen.get(j) == inputs:
                    continue  # the same sources (up to the common scale): the same solution
                init = np.zeros(n, dtype=np.int64)
                src = is_goal.copy()
                init[goals_a] = x[j, goals_a]
                found = cover_minimum(*_step_inputs(step, tab, is_goal), tab, skip=own[j])
                if found is not None:
                    low, lcm, got = found
                    nodes = np.flatnonzero(~is_goal)[got]
                    vals_live = low[got]
                    grow = 1
                    if lcm > 1 and vals_live.dtype != object and lcm < INT_LIMIT:
                        grow = lcm // math.gcd(lcm, int(np.gcd.reduce(vals_live % lcm,
                                                                      initial=0)))
                    elif lcm > 1:
                        grow = lcm // math.gcd(lcm, *(int(v) % lcm for v in vals_live))
                    if grow > 1:
                        scale *= grow
                        if int(x.max(initial=0)) * grow * 4 >= INT_LIMIT:
                            return None
                        x *= grow
                        goal_values = goal_values * grow
                        step_cache.clear()
                        init[goals_a] = x[j, goals_a]
                    if vals_live.dtype != object and int(
                            vals_live.max(initial=0)) * grow < INT_LIMIT:
                        init[nodes] = vals_live * grow // lcm
                    else:
                        quot = [int(v) * grow // lcm for v in vals_live]
                        if quot and max(quot) >= INT_LIMIT:
                            return None
                        init[nodes] = np.asarray(quot, dtype=np.int64)
                    src[nodes] = True
                seen[j] = inputs
                w_top = weights * (int(tops[j]) * (scale // den))
                new, nfin = _sourced(rev, w_top, init, np.flatnonzero(src), n)
                if not (np.array_equal(nfin, fin[j]) and np.array_equal(new[nfin], x[j, nfin])):
                    changed = True
                    new[~nfin] = 0
                    x[j], fin[j] = new, nfin
                    version[j] += 1
            if not changed:
                finite = np.asarray(fin.any(axis=0), dtype=bool)
                if not np.array_equal(fin, np.broadcast_to(finite, fin.shape)):
                    return None  # pragma: no cover - every normal reaches the same goals
                return x, scale, finite, rounds
    except OverflowError:
        return None
    return None


def fixpoint_ranks(indptr: np.ndarray, heads: np.ndarray, w_scaled: np.ndarray,
                   goals: Sequence[int], tops: np.ndarray, closures: Sequence[VertexTable],
                   m: np.ndarray, finite: np.ndarray) -> np.ndarray:
    """The layered DP's ranks from its fixpoint ``m`` (proofs/NEXACT.md NX.7).

    ``rank[a, v]`` is the first layer ``k`` with ``m_a^k(v) = m*_a(v)``: 0 at goals (and where
    no goal is reachable); elsewhere the least, over the vertex covers ``c`` attaining
    ``m*_a(v)``, of the largest ``ready[n, v]`` over ``n`` with ``c_n > 0``, where
    ``ready[n, v]`` is one more than the least ``rank[n, u]`` over the arcs ``(v, u)`` attaining
    the step ``s*_n(v)``. ``w_scaled`` are the weights at ``m``'s scale.

    Examples
    --------
    >>> from solver.coalitions.vertex_tables import vertex_table, zero_one_normals
    >>> zo = zero_one_normals(2)
    >>> tabs = [vertex_table(zo, a) for a in zo]
    >>> fixpoint_ranks(np.array([0, 2, 2, 2]), np.array([1, 2]), np.array([1, 1]), (1, 2),
    ...                np.array([1, 1, 1]), tabs, np.array([[1, 0, 2], [1, 2, 0], [2, 2, 2]]),
    ...                np.array([True, True, True]))[:, 0].tolist()
    [1, 1, 1]
    """
    n = len(indptr) - 1
    n_a = len(closures)
    tails = np.repeat(np.arange(n, dtype=np.int64), np.diff(indptr))
    heads = heads.astype(np.int64)
    goals_a = np.asarray(goals, dtype=np.int64)
    is_goal = np.zeros(n, dtype=bool)
    is_goal[goals_a] = True
    inner = finite & ~is_goal
    ok_arc = finite[heads] & inner[tails]
    s_star = np.zeros((n_a, n), dtype=np.int64)
    opt_arc = np.zeros((n_a, heads.size), dtype=bool)
    for j in range(n_a):
        cand = w_scaled * int(tops[j]) + m[j, heads]
        s, _ = _steps(indptr, heads, w_scaled * int(tops[j]), m[j], finite)
        s_star[j] = np.where(inner, s, 0)
        opt_arc[j] = ok_arc & (cand == s[tails])
    # the attained covers: entries (normal a, node v, support of the vertex), by node
    live = np.flatnonzero(inner)
    width = max(1, max(int((sc > 0).sum(axis=0).max(initial=1)) for t in closures
                       for sc, _ in t.parts))
    ent_a, ent_v, ent_s = [], [], []
    for j, tab in enumerate(closures):
        cols = np.asarray(tab.columns, dtype=np.int64)
        for sc, lcm in tab.parts:
            target = m[j, live].astype(object) * lcm if lcm * int(
                m.max(initial=0)) >= INT_LIMIT else m[j, live] * lcm
            hit_v, hit_q = _attaining(s_star[cols][:, live].T, sc, target)
            supp = np.full((sc.shape[1], width), -1, dtype=np.int64)
            for q in range(sc.shape[1]):
                nz = cols[np.flatnonzero(sc[:, q])]
                supp[q, :nz.size] = nz
            ent_a.append(np.full(hit_v.size, j, dtype=np.int64))
            ent_v.append(live[hit_v])
            ent_s.append(supp[hit_q])
    e_a = np.concatenate(ent_a)
    e_v = np.concatenate(ent_v)
    e_s = np.concatenate(ent_s)
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


def _attaining(values: np.ndarray, scaled: np.ndarray, target: np.ndarray
               ) -> tuple[np.ndarray, np.ndarray]:
    """The pairs (row, vertex) with ``values[row] @ scaled[:, vertex] == target[row]``, exactly
    (by blocks of rows: the totals of one block at a time)."""
    rows: list[np.ndarray] = []
    verts: list[np.ndarray] = []
    for lo in range(0, values.shape[0], CHUNK):
        try:
            tot = exact_totals(values[lo:lo + CHUNK], scaled)
        except OverflowError:  # totals beyond int64: Python integers
            tot = values[lo:lo + CHUNK].astype(object) @ scaled.astype(object)
        r, q = np.nonzero(tot == target[lo:lo + CHUNK, None])
        rows.append(r + lo)
        verts.append(q)
    if not rows:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    return np.concatenate(rows), np.concatenate(verts)


def _expand(ptr: np.ndarray, cnt: np.ndarray, keys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The positions ``ptr[k] .. ptr[k+1]-1`` of every key (concatenated) and their key's index."""
    counts = cnt[keys]
    total = int(counts.sum())
    seg = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(np.int64)
    idx = np.arange(total, dtype=np.int64) - np.repeat(seg - ptr[keys], counts)
    return idx, np.repeat(np.arange(keys.size, dtype=np.int64), counts)
