"""Single-source shortest distances on a :class:`~solver.graph.network.Network`, exactly.

Exact networks store integer weight numerators. ``scipy.sparse.csgraph.dijkstra`` works
in float64, which represents every integer below 2**53 exactly; when the total weight of
the graph (a bound on every shortest distance) stays below that, its result IS the exact
integer distance. Otherwise a pure-Python Dijkstra on Python integers is used.
"""

from __future__ import annotations

import heapq

import numpy as np
from scipy.sparse.csgraph import dijkstra

from solver.graph.network import Network

__all__ = ["EXACT_FLOAT_LIMIT", "distances_from", "distances_to"]

EXACT_FLOAT_LIMIT = 2.0**53
"""Integers below this are exact in float64."""


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
    return _engine(net, source)


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
    return _engine(net.reverse, target)


def _engine(net: Network, source: int) -> np.ndarray:
    if not net.numbers.exact or net.weight_total < EXACT_FLOAT_LIMIT:
        return np.asarray(dijkstra(net.matrix(), directed=True, indices=source))
    return _python_dijkstra(net, source)


def _python_dijkstra(net: Network, source: int) -> np.ndarray:
    """Dijkstra on arbitrary-precision integers (for huge exact weights)."""
    dist: list[int | float] = [float("inf")] * net.n_nodes
    dist[source] = 0
    heap: list[tuple[int, int]] = [(0, source)]
    indptr, indices, weights = net.indptr, net.indices, net.weights
    while heap:
        d, u = heapq.heappop(heap)
        if d > dist[u]:
            continue
        for k in range(int(indptr[u]), int(indptr[u + 1])):
            v = int(indices[k])
            nd = d + int(weights[k])
            if nd < dist[v]:
                dist[v] = nd
                heapq.heappush(heap, (nd, v))
    return np.array(dist, dtype=object)
