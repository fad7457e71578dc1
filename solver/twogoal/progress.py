"""The Defender's equilibrium strategy σ*: allocation proportional to new progress (eq. (7)).

``c_t = min(c_{t-1}, d(s_t, g1))`` with ``c_0 = d(s0, g1)`` (Definition 3) and
``σ*(g1 | c_{t-1}, e_t) = (c_{t-1} - c_t) / w(e_t)``. Along any walk the allocations to
``g1`` telescope: ``Σ_t w(e_t) σ*(g1) = c_0 - c_T`` (proofs/TEL.md).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from solver.graph.network import Network
from solver.numbers import Number, NumberMode


@dataclass(frozen=True, eq=False)
class ProgressDefender:
    """σ*: allocates to ``g1`` with probability (new progress toward ``g1``) / (step weight).

    Parameters
    ----------
    network : Network
        The game graph.
    goal : int
        Index of the primary goal ``g1``.
    dist_to_goal : numpy.ndarray
        ``d(v, g1)`` for every node (stored numerators; ``inf`` where ``g1`` is unreachable).
    numbers : NumberMode
        Exact, or float with a tolerance (float mode snaps σ* to 0 or 1 within it).

    Examples
    --------
    The paper's Fig. 3: ``c0 = 3.5``; a step of weight 1.5 to a node at distance 2 makes
    progress 1.5 (σ* = 1), a step of weight 1 to a node at distance 3 makes 0.5.

    >>> import networkx as nx
    >>> from solver.graph.distances import distances_to
    >>> g = nx.DiGraph()
    >>> g.add_weighted_edges_from([("s", "r", "3/2"), ("r", "g1", 2), ("s", "p", 1),
    ...                            ("p", "g1", 3)])
    >>> net = Network.from_networkx(g)
    >>> net.labels    # indices 0..3
    ['s', 'r', 'g1', 'p']
    >>> sigma = ProgressDefender(net, 2, distances_to(net, 2), net.numbers)
    >>> [str(x) for x in sigma.schedule([0, 1, 2])], [str(x) for x in sigma.schedule([0, 3])]
    (['1', '1'], ['1/2'])
    """

    network: Network
    goal: int
    dist_to_goal: np.ndarray = field(repr=False)
    numbers: NumberMode

    def schedule(self, walk: Sequence[int]) -> list[Number]:
        """σ*(g1) at each step ``t = 1..T`` of ``walk`` (node indices starting at ``s0``)."""
        weights = self.network.path_weights(walk).tolist()
        ratio = self.numbers.ratio
        return [ratio(p, w) for p, w in zip(self.progress(walk).tolist(), weights, strict=True)]

    def progress(self, walk: Sequence[int]) -> np.ndarray:
        """New progress ``c_{t-1} - c_t`` at each step (stored numerators), vectorised:
        ``c`` is the running minimum of ``d(s_t, g1)`` along the walk."""
        c = np.minimum.accumulate(self.dist_to_goal[np.asarray(walk, dtype=np.int64)])
        return c[:-1] - c[1:]
