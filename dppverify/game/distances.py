"""Exact shortest distances (Dijkstra on exact numbers) and hop counts to the goals.

The checker's own implementation, independent of the solver's: pure Python on ``int`` /
``Fraction`` (or ``float`` in float mode). All game quantities use *full-graph* distances
(proofs/README.md, assumption (G); proofs/THM.md).

On big graphs the exact distances are computed by scipy's Dijkstra on the weights scaled to
integers over their common denominator, held in ``float64``, when a bound computed up front
shows every path sum stays below :data:`EXACT_FLOAT_LIMIT` (then every sum float64 forms is an
exact integer, and the result is the exact one): :class:`ArcArrays` and
:meth:`ArcArrays.scaled` are that guard, shared by :mod:`dppverify.game.instance`,
:mod:`dppverify.twogoal.progress_br` and :mod:`dppverify.twogoal.value_dp`; past it the callers use
:func:`dijkstra` on Python numbers.
"""

from __future__ import annotations

import heapq
import math
from collections import defaultdict, deque
from collections.abc import Callable, Hashable, Iterable, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from itertools import count
from typing import TYPE_CHECKING, Any, TypeVar

import numpy as np

from dppverify.exact import INF, Number

if TYPE_CHECKING:  # scipy loads where a matrix is built (`dpp --help` stays fast)
    import scipy.sparse as sp

__all__ = ["EXACT_FLOAT_LIMIT", "Adjacency", "ArcArrays", "common_denominator",
           "dijkstra", "exact_distances_to", "hops_by_arrays", "hops_to_targets",
           "multi_source_dijkstra", "scaled_distance_fields", "sparse_dijkstra", "state_dijkstra",
           "state_dijkstra_via", "uniform_hops", "unscale"]

EXACT_FLOAT_LIMIT = 2**53
"""Integer path sums below this are exact in float64."""

Adjacency = Sequence[Sequence[tuple[int, Number]]]
"""``adj[u]`` lists the arcs ``(v, w(u, v))`` leaving ``u`` (node indices)."""


def dijkstra(adj: Adjacency, source: int) -> list[Number]:
    """Exact single-source shortest distances.

    Parameters
    ----------
    adj : Adjacency
        Arcs with positive weights. Pass the *reverse* adjacency to get distances *to*
        ``source``.
    source : int
        Source node index.

    Returns
    -------
    list
        ``dist[v]``: exact distance from ``source`` to ``v``, or ``math.inf`` if unreachable.

    Examples
    --------
    >>> from fractions import Fraction
    >>> adj = [[(1, 2), (2, Fraction(7, 2))], [(2, 1)], []]
    >>> dijkstra(adj, 0)
    [0, 2, 3]
    >>> dijkstra(adj, 2)
    [inf, inf, 0]
    """
    return multi_source_dijkstra(adj, [(source, 0)])[0]


def multi_source_dijkstra(adj: Adjacency, sources: Iterable[tuple[int, Number]], *,
                          factor: Number = 1) -> tuple[list[Number], list[int]]:
    """Shortest distances from several sources, each with a starting cost, arcs ``w·factor``.

    ``dist[v] = min over sources (s, c) of c + factor·(shortest s -> v)``; ``via[v]`` is the
    node ``v`` was last reached from (``-1`` at a source or where unreachable): with the
    *reverse* adjacency, the next node of a cheapest walk from ``v`` to a source. Heap ties
    pop the smaller node first. Exact on ``int``/``Fraction`` (Python integers are fastest).

    Examples
    --------
    >>> adj = [[(1, 2)], [(2, 1)], []]            # 0 -> 1 -> 2
    >>> multi_source_dijkstra(adj, [(0, 5), (2, 0)], factor=3)
    ([5, 11, 0], [-1, 0, -1])
    """
    n = len(adj)
    if factor == 1:
        arcs: Callable[[int], Iterable[tuple[int, Number]]] = adj.__getitem__
    else:
        def arcs(u: int) -> Iterable[tuple[int, Number]]:
            return [(v, w * factor) for v, w in adj[u]]
    dist: list[Number] = [INF] * n
    via = [-1] * n
    _dijkstra(sources, arcs, dist, via, ordered=True)
    return dist, via


S = TypeVar("S", bound=Hashable)


def state_dijkstra(sources: Iterable[tuple[S, Number]],
                   arcs: Callable[[S], Iterable[tuple[S, Number]]]) -> dict[S, Number]:
    """Shortest distances on an implicit graph of hashable states, from costed sources.

    ``arcs(x)`` lists the ``(y, cost)`` arcs leaving state ``x`` (costs ``>= 0``); states
    never reached are absent from the result. The form for graphs built on the fly (the
    ``(node, running minimum)`` product graph of
    :mod:`dppverify.structured.table_br_twogoal`).

    Examples
    --------
    >>> line = {"a": [("b", 2)], "b": [("c", 1)], "c": []}
    >>> state_dijkstra([("a", 0)], lambda x: line[x])
    {'a': 0, 'b': 2, 'c': 3}
    """
    dist: defaultdict[S, Number] = defaultdict(lambda: INF)
    _dijkstra(sources, arcs, dist, {}, ordered=False)
    return {x: d for x, d in dist.items() if d != INF}  # a source of infinite cost is unreached


def state_dijkstra_via(sources: Iterable[tuple[S, Number]],
                       arcs: Callable[[S], Iterable[tuple[S, Number]]]
                       ) -> tuple[dict[S, Number], dict[S, S]]:
    """:func:`state_dijkstra` with the state each reached state was last reached from (the
    cheapest walks are read back through it).

    Examples
    --------
    >>> line = {"a": [("b", 2), ("c", 5)], "b": [("c", 1)], "c": []}
    >>> state_dijkstra_via([("a", 0)], lambda x: line[x])
    ({'a': 0, 'b': 2, 'c': 3}, {'b': 'a', 'c': 'b'})
    """
    dist: defaultdict[S, Number] = defaultdict(lambda: INF)
    via: dict[S, S] = {}
    _dijkstra(sources, arcs, dist, via, ordered=False)
    return {x: d for x, d in dist.items() if d != INF}, via


def _dijkstra(sources: Iterable[tuple[Any, Number]],
              arcs: Callable[[Any], Iterable[tuple[Any, Number]]], dist: Any, via: Any, *,
              ordered: bool) -> None:
    """The checker's one Dijkstra engine, on exact numbers: fills ``dist[x]`` with the least
    cost from the costed sources to every state ``x`` reached, and ``via[x]`` with the state
    it was last reached from.

    ``dist`` reads ``INF`` for a state not reached yet: a list over node indices, or a
    ``defaultdict``. Heap ties pop the smaller state first when ``ordered`` (node indices),
    else the one pushed first (states need not be comparable). A heap entry whose cost is
    above the state's known cost is stale and skipped (a cost is pushed only when it
    improves).

    Examples
    --------
    >>> line = [[(1, 2)], [(2, 1)], []]
    >>> dist, via = [INF] * 3, [-1] * 3
    >>> _dijkstra([(0, 0)], line.__getitem__, dist, via, ordered=True)
    >>> dist, via
    ([0, 2, 3], [-1, 0, 1])
    """
    tie = count()
    heap: list[Any] = []
    for s, c in sources:
        if c < dist[s]:
            dist[s] = c
            heap.append((c, s) if ordered else (c, next(tie), s))
    heapq.heapify(heap)
    pop, push = heapq.heappop, heapq.heappush
    while heap:
        item = pop(heap)
        d, u = item[0], item[-1]
        if d > dist[u]:
            continue
        for v, w in arcs(u):
            nd = d + w
            if nd < dist[v]:
                dist[v] = nd
                via[v] = u
                push(heap, (nd, v) if ordered else (nd, next(tie), v))


def hops_to_targets(reverse_adj: Adjacency, targets: Iterable[int]) -> list[int]:
    """Fewest steps from every node to the nearest target (``-1`` if none is reachable).

    Parameters
    ----------
    reverse_adj : Adjacency
        ``reverse_adj[v]`` lists ``(u, w)`` for every arc ``u -> v``.
    targets : iterable of int
        The target nodes (the two goals).

    Examples
    --------
    >>> rev = [[], [(0, 1)], [(1, 1)], []]   # arcs 0 -> 1 -> 2; node 3 isolated
    >>> hops_to_targets(rev, [2])
    [2, 1, 0, -1]
    """
    hops = [-1] * len(reverse_adj)
    queue: deque[int] = deque()
    for t in targets:
        if hops[t] < 0:
            hops[t] = 0
            queue.append(t)
    while queue:
        v = queue.popleft()
        for u, _ in reverse_adj[v]:
            if hops[u] < 0:
                hops[u] = hops[v] + 1
                queue.append(u)
    return hops


def common_denominator(values: Iterable[Number]) -> int:
    """The least common multiple of the denominators of the exact ``values`` (ints count 1).

    Examples
    --------
    >>> common_denominator([1, Fraction(1, 4), Fraction(5, 6)])
    12
    """
    den = 1
    for w in values:
        if type(w) is Fraction:
            den = math.lcm(den, w.denominator)
    return den


@dataclass(frozen=True, eq=False)
class ArcArrays:
    """Every arc of a graph as arrays, in adjacency order (by tail, then head).

    Attributes
    ----------
    tails, heads : numpy.ndarray
        Tail and head of every arc (``int64``).
    codes : numpy.ndarray
        ``values[codes[i]]`` is the weight of arc ``i`` (``int64``).
    values : tuple
        The distinct weights (instances have few).

    Examples
    --------
    >>> a = ArcArrays.from_adjacency([[(1, 2), (2, Fraction(1, 2))], [(2, 2)], []])
    >>> a.tails.tolist(), a.heads.tolist(), a.codes.tolist(), a.values
    ([0, 0, 1], [1, 2, 2], [0, 1, 0], (2, Fraction(1, 2)))
    >>> a.scaled(a.values), a.scaled([2**53])
    ((2, [4, 1]), None)
    """

    tails: np.ndarray
    heads: np.ndarray
    codes: np.ndarray
    values: tuple[Number, ...]
    symmetric: bool = False
    """True when every arc's reverse is an arc of the same weight (an undirected graph): the
    reversed graph is then the graph itself."""
    _rows: dict[tuple[int, bool], tuple[np.ndarray, np.ndarray, np.ndarray | None]] = field(
        default_factory=dict, repr=False, compare=False)

    @classmethod
    def from_adjacency(cls, adj: Adjacency) -> ArcArrays:
        """The arcs of ``adj`` (``adj[u]`` lists ``(v, w)``), distinct weights keyed with
        their type."""
        code: dict[tuple[type, Number], int] = {}
        tails: list[int] = []
        heads: list[int] = []
        codes: list[int] = []
        for u, arcs in enumerate(adj):
            for v, w in arcs:
                tails.append(u)
                heads.append(v)
                codes.append(code.setdefault((type(w), w), len(code)))
        return cls(tails=np.asarray(tails, dtype=np.int64), heads=np.asarray(heads, dtype=np.int64),
                   codes=np.asarray(codes, dtype=np.int64), values=tuple(w for _, w in code))

    def weights(self) -> list[Number]:
        """The weight of every arc (Python numbers)."""
        return [self.values[c] for c in self.codes.tolist()]

    def scaled(self, total_of: Sequence[Number], *, paths: int = 1,
               extra: Iterable[Number] = ()) -> tuple[int, list[int]] | None:
        """``(scale, [v * scale for v in values])`` when float64 sums of them stay exact.

        ``scale`` clears the denominators of ``values`` and ``extra``. None when a weight is
        a float, or when ``paths`` times the scaled total of ``total_of`` (one entry per arc
        counted: ``values`` weighted by how many arcs carry them, or any other list of
        numbers) reaches :data:`EXACT_FLOAT_LIMIT`: a shortest path uses every arc at most
        once, so ``paths`` path sums added up stay below the limit.
        """
        if any(type(v) is float for v in self.values):
            return None
        scale = common_denominator([*self.values, *extra])
        scaled = [int(v * scale) for v in self.values]
        if total_of is self.values:
            counts = np.bincount(self.codes, minlength=len(self.values)).tolist()
            total = sum(v * c for v, c in zip(scaled, counts, strict=True))
        else:
            total = sum(int(v * scale) for v in total_of)
        if paths * total >= EXACT_FLOAT_LIMIT:
            return None
        return scale, scaled

    def rows(self, n: int, *, reverse: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
        """The graph (``reverse``: the reversed graph) in CSR form over ``n`` nodes:
        ``(indptr, indices, order)``; the arc at CSR position ``k`` is arc ``order[k]``
        (``order`` None: the arcs' own order). Built once per graph and direction.

        Examples
        --------
        >>> a = ArcArrays.from_adjacency([[(1, 2), (2, Fraction(1, 2))], [(2, 2)], []])
        >>> indptr, indices, order = a.rows(3, reverse=True)
        >>> indptr.tolist(), indices.tolist(), order.tolist()
        ([0, 0, 1, 3], [0, 0, 1], [0, 1, 2])
        """
        if reverse and self.symmetric:  # the reversed graph is the graph
            reverse = False
        key = (n, reverse)
        if key not in self._rows:
            order = np.argsort(self.heads, kind="stable") if reverse else None
            rows = self.tails if order is None else self.heads[order]
            indptr = np.searchsorted(rows, np.arange(n + 1)).astype(np.int32)
            cols = self.heads if order is None else self.tails[order]
            self._rows[key] = (indptr, cols.astype(np.int32), order)
        return self._rows[key]

    def matrix(self, n: int, scaled: list[int], *, reverse: bool,
               keep: np.ndarray | None = None) -> sp.csr_matrix:
        """The scaled weights as a sparse matrix (``reverse``: arcs turned around), only the
        arcs whose (forward) tail is in ``keep`` when given; int32 indices, as
        ``scipy.sparse.csgraph`` works in (no conversion per run).

        Examples
        --------
        >>> a = ArcArrays.from_adjacency([[(1, 2), (2, Fraction(1, 2))], [(2, 2)], []])
        >>> a.matrix(3, [4, 1], reverse=False).toarray().tolist()[0]
        [0.0, 4.0, 1.0]
        """
        import scipy.sparse as sp

        w = np.asarray(scaled, dtype=np.float64)[self.codes]
        if keep is not None:
            rows, cols = (self.heads, self.tails) if reverse else (self.tails, self.heads)
            sel = keep[rows]
            return sp.csr_matrix((w[sel], (rows[sel], cols[sel])), shape=(n, n))
        indptr, indices, order = self.rows(n, reverse=reverse)
        return sp.csr_matrix((w if order is None else w[order], indices, indptr),
                             shape=(n, n), copy=False)


def sparse_dijkstra(matrix: sp.csr_matrix, indices: int | Sequence[int],
                    **options: Any) -> np.ndarray:
    """scipy's float64 Dijkstra on a sparse matrix (``directed=True``; ``options`` are
    :func:`scipy.sparse.csgraph.dijkstra`'s): the checker's one call of it, for the callers
    that first made sure every path sum is an integer below :data:`EXACT_FLOAT_LIMIT` (then
    its result is exact). scipy is imported here, on first use.

    Examples
    --------
    >>> import scipy.sparse as sp
    >>> m = sp.csr_matrix(([2.0, 1.0], ([0, 1], [1, 2])), shape=(3, 3))   # 0 -> 1 -> 2
    >>> sparse_dijkstra(m, 0).tolist()
    [0.0, 2.0, 3.0]
    """
    from scipy.sparse.csgraph import dijkstra as scipy_dijkstra

    return np.asarray(scipy_dijkstra(matrix, directed=True, indices=indices, **options),
                      dtype=np.float64)


def exact_distances_to(arcs: ArcArrays, n: int, targets: Sequence[int]
                       ) -> list[list[Number]] | None:
    """Exact full-graph distances to each target by scipy, or None past the float64 guard.

    Examples
    --------
    >>> a = ArcArrays.from_adjacency([[(1, 2), (2, Fraction(7, 2))], [(2, 1)], []])
    >>> exact_distances_to(a, 3, [2, 0])
    [[3, 1, 0], [0, inf, inf]]
    """
    fields = scaled_distance_fields(arcs, n, targets)
    if fields is None:
        return None
    scale, dist = fields
    return [unscale(row, scale) for row in dist]


def scaled_distance_fields(arcs: ArcArrays, n: int, targets: Sequence[int]
                           ) -> tuple[int, np.ndarray] | None:
    """:func:`exact_distances_to` before unscaling: ``(scale, rows)``, one float64 row of
    exact scaled integers per target (kept by the instance for reuse,
    :mod:`dppverify.twogoal.progress_br`).

    Examples
    --------
    >>> a = ArcArrays.from_adjacency([[(1, 2), (2, Fraction(7, 2))], [(2, 1)], []])
    >>> scale, rows = scaled_distance_fields(a, 3, [2])
    >>> scale, rows.tolist()
    (2, [[6.0, 2.0, 0.0]])
    """
    got = arcs.scaled(arcs.values)
    if got is None:
        return None
    scale, scaled = got
    dist = np.atleast_2d(sparse_dijkstra(arcs.matrix(n, scaled, reverse=True), list(targets)))
    return scale, dist


def unscale(row: np.ndarray, scale: int) -> list[Number]:
    """Scaled integer distances held in float64 as exact numbers (``inf`` stays ``inf``).

    Examples
    --------
    >>> unscale(np.array([0.0, 6.0, 3.0, np.inf]), 2)
    [0, 3, Fraction(3, 2), inf]
    """
    finite = np.isfinite(row)
    ints = np.where(finite, row, 0).astype(np.int64).tolist()
    if scale == 1:
        out: list[Number] = ints
    else:
        out = [x // scale if x % scale == 0 else Fraction(x, scale) for x in ints]
    if not finite.all():
        for v in np.flatnonzero(~finite).tolist():
            out[v] = INF
    return out


def uniform_hops(rows: np.ndarray, step: int) -> list[int]:
    """:func:`hops_to_targets` from exact scaled distance rows when every arc weighs ``step``.

    With one weight a walk of ``k`` steps costs ``k * step``, so the fewest steps to the
    nearest target is the least distance over ``step`` (``-1`` if unreachable): the BFS of
    :func:`hops_by_arrays` without another pass over the graph.

    Examples
    --------
    >>> a = ArcArrays.from_adjacency([[(1, 2)], [(2, 2)], [], []])   # 0 -> 1 -> 2; 3 isolated
    >>> scale, rows = scaled_distance_fields(a, 4, [2])
    >>> uniform_hops(rows, 2), hops_by_arrays(a, 4, [2])
    ([2, 1, 0, -1], [2, 1, 0, -1])
    """
    least = np.atleast_2d(rows).min(axis=0)
    finite = np.isfinite(least)
    hops = np.where(finite, least, 0).astype(np.int64) // step
    return np.where(finite, hops, -1).tolist()


def hops_by_arrays(arcs: ArcArrays, n: int, targets: Sequence[int]) -> list[int]:
    """:func:`hops_to_targets` by scipy (breadth-first hop counts; ``-1`` if unreachable).

    Examples
    --------
    >>> a = ArcArrays.from_adjacency([[(1, 1)], [(2, 1)], [], []])   # 0 -> 1 -> 2; 3 isolated
    >>> hops_by_arrays(a, 4, [2])
    [2, 1, 0, -1]
    """
    m = arcs.matrix(n, [1] * len(arcs.values), reverse=True)
    h = sparse_dijkstra(m, list(targets), unweighted=True, min_only=True)
    return np.where(np.isfinite(h), h, -1).astype(np.int64).tolist()
