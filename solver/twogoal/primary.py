"""The primary Attacker's two branch paths and mixing (Definition 5, eq. (15)).

``ξ^{1,α} = ξ²[0..t_α] + ψ(s_{t_α}, g1)`` for α ∈ {I, II}, with ψ a full-graph shortest
path (every step of ψ has σ* = 1). ``γ*(ξ^{1,II} | g1) = b2 / b1`` and
``γ*(ξ^{1,I} | g1) = 1 - b2 / b1`` — eq. (15); the sentence before it swaps the two
(proofs/ERRATA.md). Identical paths are merged and zero-probability paths dropped.
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction

import numpy as np

from solver.game.walks import StrategyWalk
from solver.graph.network import Network
from solver.graph.shortest_paths import path_to_target
from solver.numbers import NumberMode
from solver.twogoal.phases import Phases


def branch_path(net: Network, xi2: Sequence[int], t: int, g1: int, d_to_g1: np.ndarray,
                numbers: NumberMode) -> tuple[int, ...]:
    """``ξ²[0..t]`` followed by the shortest path ψ from ``ξ²[t]`` to ``g1`` (ξ² if t = T)."""
    if t == len(xi2) - 1:
        return tuple(xi2)
    psi = path_to_target(net, xi2[t], g1, d_to_g1, numbers)
    return tuple(xi2[:t]) + tuple(psi)


def primary_mixture(net: Network, xi2: Sequence[int], phases: Phases, g1: int,
                    d_to_g1: np.ndarray, b1: Fraction, b2: Fraction,
                    numbers: NumberMode) -> tuple[StrategyWalk, ...]:
    """The primary type's equilibrium mixture over ξ^{1,I} and ξ^{1,II} (eq. (15)).

    Examples
    --------
    >>> import networkx as nx
    >>> from solver.graph.distances import distances_to
    >>> g = nx.Graph()
    >>> g.add_weighted_edges_from([("s", "g2", 2), ("g2", "g1", 2), ("s", "g1", 3)])
    >>> net = Network.from_networkx(g)   # s=0, g2=1, g1=2
    >>> mix = primary_mixture(net, [0, 1], Phases(0, 1, 1), 2, distances_to(net, 2),
    ...                       Fraction(7, 10), Fraction(3, 10), net.numbers)
    >>> [(m.nodes, str(m.probability), m.label) for m in mix]
    [(('s', 'g1'), '4/7', 'xi1_I'), (('s', 'g2'), '3/7', 'xi1_II')]
    """
    p_ii = b2 / b1
    path_i = branch_path(net, xi2, phases.t_I, g1, d_to_g1, numbers)
    path_ii = branch_path(net, xi2, phases.t_II, g1, d_to_g1, numbers)
    if path_i == path_ii:
        return (StrategyWalk.along(net, path_i, Fraction(1), "xi1"),)
    out = []
    if p_ii < 1:
        out.append(StrategyWalk.along(net, path_i, 1 - p_ii, "xi1_I"))
    out.append(StrategyWalk.along(net, path_ii, p_ii, "xi1_II"))
    return tuple(out)
