"""Exact shortest distances (Dijkstra on exact numbers) and hop counts to the goals.

The checker's own implementation, independent of the solver's: pure Python on ``int`` /
``Fraction`` (or ``float`` in float mode). It is meant for the small graphs a truncated game
tree can be built on. All game quantities use *full-graph* distances (proofs/README.md,
assumption (G); proofs/THM.md).
"""

from __future__ import annotations

import heapq
from collections import deque
from collections.abc import Iterable, Sequence

from dppverify.exact import INF, Number

__all__ = ["Adjacency", "dijkstra", "hops_to_targets"]

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
    dist: list[Number] = [INF] * len(adj)
    dist[source] = 0
    heap: list[tuple[Number, int]] = [(0, source)]
    done = [False] * len(adj)
    while heap:
        d, u = heapq.heappop(heap)
        if done[u]:
            continue
        done[u] = True
        for v, w in adj[u]:
            nd = d + w
            if nd < dist[v]:
                dist[v] = nd
                heapq.heappush(heap, (nd, v))
    return dist


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
