"""Shortest distances on a :class:`~solver.graph.network.Network`, exactly: one Dijkstra engine.

In the style of networkx's ``shortest_paths.weighted``: thin public functions over one private
engine, :func:`_dijkstra`, with the flexible ``weight`` argument converted once
(:func:`_weight_function`).

- :func:`distances_from`, :func:`distances_to`: the full-graph fields ``d(source, ·)`` and
  ``d(·, target)``;
- :func:`costs_to`: ``target``'s distances under any step cost (a callable of the arc that may
  hide it), for the literature's paths.

Exact networks store integer weight numerators. ``scipy.sparse.csgraph.dijkstra`` works in
float64, which represents every integer below :data:`EXACT_FLOAT_LIMIT` (``2**53``) exactly:
when the total weight (a bound on every shortest distance) stays below it, scipy's result IS
the exact integer distance; otherwise the engine runs on Python integers.
"""

from __future__ import annotations

import heapq
import operator
from collections.abc import Callable, Iterable
from typing import Any

import numpy as np
from scipy.sparse.csgraph import dijkstra

from solver.graph.network import Network

EXACT_FLOAT_LIMIT = 2**53
"""Every integer below this is exact in float64."""

Weight = Callable[[int, int, Any], Any]
"""A step cost ``weight(u, v, w)`` of the arc ``u -> v`` stored with weight ``w``; ``None``
hides the arc (as networkx's weight functions)."""

Arcs = Callable[[int], Iterable[tuple[int, Any]]]
"""``arcs(u)``: the ``(v, w)`` pairs of the arcs leaving ``u``."""


def _weight_function(weight: Weight | None) -> Weight:
    """The step cost as a function: the stored weight itself when ``weight`` is None."""
    if weight is None:
        return lambda u, v, w: w
    return weight


def _dijkstra(arcs: Arcs, sources: Iterable[tuple[int, Any]], weight: Weight | None = None,
              less: Callable[[Any, Any], bool] = operator.lt) -> dict[int, Any]:
    """The engine: the least cost from the sources (each with a starting cost) to every node
    they reach, on Python numbers (exact on integers and ``Fraction``).

    Heap ties pop the smaller node first; a node is settled when first popped; ``less`` decides
    whether a new cost improves a known one (float mode passes a tolerance).

    Examples
    --------
    >>> line = {0: [(1, 2)], 1: [(2, 1)], 2: []}
    >>> _dijkstra(line.__getitem__, [(0, 0)])
    {0: 0, 1: 2, 2: 3}
    >>> _dijkstra(line.__getitem__, [(0, 5), (2, 0)], lambda u, v, w: 3 * w)
    {0: 5, 2: 0, 1: 11}
    """
    cost = _weight_function(weight)
    dist: dict[int, Any] = {}
    heap: list[tuple[Any, int]] = []
    for s, c in sources:
        if s not in dist or less(c, dist[s]):
            dist[s] = c
            heap.append((c, s))
    heapq.heapify(heap)
    done: set[int] = set()
    while heap:
        d, u = heapq.heappop(heap)
        if u in done:
            continue
        done.add(u)
        for v, w in arcs(u):
            if v in done:
                continue
            step = cost(u, v, w)
            if step is None:
                continue
            nd = d + step
            if v not in dist or less(nd, dist[v]):
                dist[v] = nd
                heapq.heappush(heap, (nd, v))
    return dist


def _network_arcs(net: Network) -> Arcs:
    """``arcs(u)`` of a network, weights as Python numbers (exact integers stay exact)."""
    indptr, indices, weights = net.indptr, net.indices, net.weights

    def arcs(u: int) -> Iterable[tuple[int, Any]]:
        lo, hi = int(indptr[u]), int(indptr[u + 1])
        return zip(indices[lo:hi].tolist(), weights[lo:hi].tolist(), strict=True)

    return arcs


def distances_from(net: Network, source: int) -> np.ndarray:
    """Distances ``d(source, v)`` for every node ``v`` (``inf`` when unreachable).

    In exact mode the entries are integer numerators over ``net.numbers.denominator``
    (stored as float64 when below 2**53, else as Python ints in an object array).

    Examples
    --------
    >>> import networkx as nx
    >>> net = Network.from_networkx(nx.DiGraph([(0, 1, {"weight": "1/2"}), (1, 2)]))
    >>> distances_from(net, 0).tolist(), net.numbers.denominator
    ([0.0, 1.0, 3.0], 2)
    """
    return _field(net, source)


def distances_to(net: Network, target: int) -> np.ndarray:
    """Distances ``d(v, target)`` for every node ``v`` (Dijkstra on the reversed arcs).

    Parameters
    ----------
    net : Network
        The graph.
    target : int
        Node index.

    Returns
    -------
    numpy.ndarray
        As :func:`distances_from`: exact numerators over ``net.numbers.denominator`` in
        exact mode, ``inf`` where ``target`` cannot be reached.

    Examples
    --------
    On the directed path ``0 -(1/2)-> 1 -(1)-> 2`` only node 0 reaches itself:

    >>> import networkx as nx
    >>> net = Network.from_networkx(nx.DiGraph([(0, 1, {"weight": "1/2"}), (1, 2)]))
    >>> distances_to(net, 2).tolist(), distances_to(net, 0).tolist(), net.numbers.denominator
    ([3.0, 2.0, 0.0], [0.0, inf, inf], 2)
    """
    return _field(net.reverse, target)


def _field(net: Network, source: int) -> np.ndarray:
    if not net.numbers.exact or net.weight_total < EXACT_FLOAT_LIMIT:
        return np.asarray(dijkstra(net.matrix(), directed=True, indices=source))
    dist = _dijkstra(_network_arcs(net), [(source, 0)])
    out = np.full(net.n_nodes, np.inf, dtype=object)
    for v, d in dist.items():
        out[v] = d
    return out


def costs_to(net: Network, target: int, weight: Weight,
             less: Callable[[Any, Any], bool] = operator.lt, *,
             start: Any = 0) -> dict[int, Any]:
    """The least cost from every node that reaches ``target`` to ``target``, under the step
    cost ``weight(u, v, w)`` of each arc ``u -> v`` (``None`` hides the arc); ``start`` is the
    cost at ``target`` itself. A Dijkstra from ``target`` on the reversed arcs; ``less`` is
    the comparison (float mode: a tolerance).

    Examples
    --------
    >>> import networkx as nx
    >>> net = Network.from_networkx(nx.DiGraph([(0, 1), (1, 2), (0, 2, {"weight": 5})]))
    >>> costs_to(net, 2, lambda u, v, w: w)
    {2: 0, 0: 2, 1: 1}
    >>> costs_to(net, 2, lambda u, v, w: None if u == 1 else w)   # no arc leaving node 1
    {2: 0, 0: 5}
    """
    def back(v: int, u: int, w: Any) -> Any:  # the reversed arc v <- u is the arc u -> v
        return weight(u, v, w)

    return _dijkstra(_network_arcs(net.reverse), [(target, start)], back, less)


def sources_to(net: Network, init: np.ndarray, *, stop: Iterable[int] = ()) -> np.ndarray:
    """``min over sources x of init(x) + d°(v, x)`` for every node ``v``: the sources are the
    nodes where ``init`` is finite, ``d°`` uses no arc leaving a node of ``stop`` (a walk ends
    at its first goal); ``inf`` where no source is reached. Exact networks: integer numerators
    over ``net.numbers.denominator`` in, and out (scipy on a super-source when every sum stays
    below 2**53, else Python integers).

    Examples
    --------
    >>> import networkx as nx
    >>> net = Network.from_networkx(nx.Graph([(0, 1), (1, 2), (2, 3)]))
    >>> sources_to(net, np.array([5, np.inf, np.inf, 0]), stop=[3]).tolist()
    [3.0, 2.0, 1.0, 0.0]
    """
    n = net.n_nodes
    keep = np.ones(net.indices.size, dtype=bool)
    for x in set(stop):  # the arcs leaving a stop node
        keep[net.indptr[x]:net.indptr[x + 1]] = False
    tails = np.repeat(np.arange(n, dtype=np.int64), np.diff(net.indptr))[keep]
    heads, weights = net.indices[keep].astype(np.int64), net.weights[keep]
    try:
        as_float = np.asarray(init, dtype=np.float64)
    except OverflowError:  # exact numerators past the float range: Python integers below
        as_float = np.array([np.inf if x == np.inf else 0.0 for x in init])
        as_float[np.isfinite(as_float)] = EXACT_FLOAT_LIMIT
    finite = np.isfinite(as_float)
    xs = np.flatnonzero(finite)
    top = float(np.max(as_float[finite], initial=0)) + 1
    if net.numbers.exact and net.weight_total + top < EXACT_FLOAT_LIMIT:
        import scipy.sparse as sp  # the reversed arcs, and one super-source arc per source

        cost = np.asarray(init, dtype=np.float64)[xs] + 1
        rows = np.concatenate([heads, np.full(xs.size, n, dtype=np.int64)])
        cols = np.concatenate([tails, xs])
        vals = np.concatenate([weights.astype(np.float64), cost])
        m = sp.csr_matrix((vals, (rows, cols)), shape=(n + 1, n + 1))
        return np.asarray(dijkstra(m, directed=True, indices=n))[:n] - 1
    rev: dict[int, list[tuple[int, Any]]] = {v: [] for v in range(n)}
    for t, h, w in zip(tails.tolist(), heads.tolist(), weights.tolist(), strict=True):
        rev[h].append((t, w))
    dist = _dijkstra(lambda u: rev[u], [(int(x), init[x]) for x in xs])
    out = np.full(n, np.inf, dtype=object)
    for v, d in dist.items():
        out[v] = d
    return out
