"""The secondary Attacker's best response ξ² to σ* without enumerating paths (proofs/XI2.md).

Against σ*, a walk ending at its first goal costs type 2
``L(walk) - (c_0 - c_T) + d(s_T, g2)`` (telescoping, proofs/TEL.md). Its minimum over all
walks is ``M - d(s0, g1)`` with ``M = min_v d(s0,v) + d(v,g1) + d(v,g2)`` over all nodes
``v`` (goals included), attained by a shortest path ``s0 -> v*`` followed by a shortest
path ``v* -> g2``, cut at the first goal it reaches (proofs/XI2.md). Three Dijkstra runs
and one vectorised scan: O(E log V).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from solver.graph.network import Network
from solver.graph.shortest_paths import path_from_source, path_to_target
from solver.numbers import NumberMode

TIE_BREAK = (
    "v* is the lowest-index minimiser of d(s0,v)+d(v,g1)+d(v,g2); the path s0->v* is traced "
    "back from v* through lowest-index tight predecessors, v*->g2 forward through "
    "lowest-index tight successors; the concatenation is cut at the first goal reached. "
    "Node index = order of the instance's node list (row-major for grids)."
)


@dataclass(frozen=True)
class SecondaryPath:
    """ξ² and the quantities that define it.

    Attributes
    ----------
    walk : tuple of int
        Node indices of ξ², from ``s0`` to the first goal reached.
    pivot : int
        ``v*``, the chosen minimiser of ``d(s0,v)+d(v,g1)+d(v,g2)`` (ξ² may be cut before it).
    m_value : object
        ``M`` as a stored numerator (int-valued) or float.
    """

    walk: tuple[int, ...]
    pivot: int
    m_value: object


def secondary_best_response(
    net: Network,
    start: int,
    goals: tuple[int, int],
    d_from_start: np.ndarray,
    d_to_g1: np.ndarray,
    d_to_g2: np.ndarray,
    numbers: NumberMode,
) -> SecondaryPath:
    """Compute ξ² from the three distance fields (all nodes ``v`` are candidates).

    Examples
    --------
    >>> from solver.graph.distances import distances_from, distances_to
    >>> from solver.game.instance import triangle
    >>> net = triangle().network   # indices: s=0, g2=1, g1=2
    >>> xi = secondary_best_response(net, 0, (2, 1), distances_from(net, 0),
    ...      distances_to(net, 2), distances_to(net, 1), net.numbers)
    >>> xi.walk, xi.pivot, int(xi.m_value)
    ((0, 1), 1, 4)
    """
    g1, g2 = goals
    total = d_from_start + d_to_g1
    total += d_to_g2
    first = int(np.argmin(total))  # the first minimum: the lowest index among exact ties
    m_value = total[first]
    pivot = first if numbers.exact else int(np.flatnonzero(numbers.is_zero(total - m_value))[0])
    head = path_from_source(net, start, pivot, d_from_start, numbers)
    tail = path_to_target(net, pivot, g2, d_to_g2, numbers)
    walk = head + tail[1:]
    cut = next(i for i, v in enumerate(walk) if v in (g1, g2))
    return SecondaryPath(tuple(walk[: cut + 1]), pivot, m_value)
