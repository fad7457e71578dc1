"""Deterministic shortest paths from distance fields (the documented tie-break).

Given exact distances, a shortest path is traced along *tight* arcs
(``w(u, v) + d(v, t) == d(u, t)``). Among tight arcs the lowest node index wins — the
node order of the instance (insertion order of the networkx graph / the JSON node list;
row-major for grids). Only nodes on the traced path are touched: each step reads the arcs
of one node, as Python numbers through memoryviews of the CSR and distance arrays (no numpy
call per step; a path of L steps costs O(L) scalar reads, never a pass over the graph).
Stored values that are not machine numbers (Python integers past int64) use numpy per step.
"""

from __future__ import annotations

import numpy as np

from solver.graph.network import Network
from solver.numbers import NumberMode


def path_to_target(net: Network, start: int, target: int, dist_to: np.ndarray,
                   numbers: NumberMode) -> list[int]:
    """A shortest path ``start -> target``: from each node, the lowest-index tight successor.

    ``dist_to[v] = d(v, target)`` must be finite at ``start``.

    Examples
    --------
    >>> import networkx as nx
    >>> from solver.graph.distances import distances_to
    >>> net = Network.from_networkx(nx.cycle_graph(4))
    >>> path_to_target(net, 0, 2, distances_to(net, 2), net.numbers)
    [0, 1, 2]
    """
    views = _views(net, dist_to)
    if views is not None:
        return _trace(*views, start, target, numbers.abs_tol)
    path = [start]
    u = start
    while u != target:
        heads, ws = net.out_arcs(u)
        slack = ws + dist_to[heads] - dist_to[u]
        u = int(heads[_first_tight(slack, numbers, dist_to[heads] < dist_to[u])])
        path.append(u)
    return path


def path_from_source(net: Network, source: int, end: int, dist_from: np.ndarray,
                     numbers: NumberMode) -> list[int]:
    """A shortest path ``source -> end``: traced back from ``end`` through the lowest-index
    tight predecessor. ``dist_from[v] = d(source, v)`` must be finite at ``end``.

    Examples
    --------
    On the README's triangle (``s = 0``, ``g2 = 1``, ``g1 = 2``) ``s -> g1`` directly (3)
    beats ``s -> g2 -> g1`` (4):

    >>> from solver.graph.distances import distances_from
    >>> from solver.game.instance import triangle
    >>> net = triangle().network
    >>> path_from_source(net, 0, 2, distances_from(net, 0), net.numbers), net.labels[2]
    ([0, 2], 'g1')
    """
    rev = net.reverse
    views = _views(rev, dist_from)
    if views is not None:
        path = _trace(*views, end, source, numbers.abs_tol)
    else:
        path = [end]
        v = end
        while v != source:
            tails, ws = rev.out_arcs(v)
            slack = dist_from[tails] + ws - dist_from[v]
            v = int(tails[_first_tight(slack, numbers, dist_from[tails] < dist_from[v])])
            path.append(v)
    path.reverse()
    return path


def _views(net: Network, dist: np.ndarray
           ) -> tuple[memoryview, memoryview, memoryview, memoryview] | None:
    """Memoryviews of the CSR arrays and a distance field (Python numbers on indexing), or
    None when some array holds Python objects (exact numerators past int64)."""
    arrays = (net.indptr, net.indices, net.weights, dist)
    if any(a.dtype.kind not in "iuf" or a.ndim != 1 for a in arrays):
        return None
    indptr, indices, weights, d = (memoryview(np.ascontiguousarray(a).data) for a in arrays)
    return indptr, indices, weights, d


def _trace(indptr: memoryview, heads: memoryview, weights: memoryview, dist: memoryview,
           u: int, stop: int, tol: float | None) -> list[int]:
    """From ``u`` to ``stop``: at each node the first arc (lowest head index) ``u -> v`` with
    ``w + d(v) == d(u)`` (within ``tol`` in float mode) that gets strictly closer — the rule
    of :func:`_first_tight`, on scalars."""
    path = [u]
    while u != stop:
        du = dist[u]
        for k in range(indptr[u], indptr[u + 1]):
            v = heads[k]
            dv = dist[v]
            if dv < du and (weights[k] + dv == du if tol is None
                            else abs(weights[k] + dv - du) <= tol):
                break
        else:  # cannot happen with consistent distances
            raise RuntimeError("no tight arc: distance field inconsistent with the graph")
        u = v
        path.append(u)
    return path


def _first_tight(slack: np.ndarray, numbers: NumberMode, closer: np.ndarray) -> int:
    """The first tight arc that also gets strictly closer (positive weights: every tight arc
    does in exact arithmetic; in float mode this keeps the trace from cycling, so it ends
    within n steps)."""
    hits = np.flatnonzero(numbers.is_zero(slack) & closer)
    if hits.size == 0:  # cannot happen with consistent distances
        raise RuntimeError("no tight arc: distance field inconsistent with the graph")
    return int(hits[0])
