"""The field's path metrics (:mod:`solver.literature.path_metrics`) of the game's walks.

A type θ's walk ends at the first goal it reaches, where the type pays the terminal cost
``d(end, g^θ)``: its **route** is the walk followed, when it ended at the other goal, by the
shortest path from there to ``g^θ`` (the solver's tie rule, :mod:`solver.graph.shortest_paths`), the
path that terminal cost pays for. This is the path Masters & Sardina's reference script
measures (π_d1's route goes to the bogus goal and on to the real one). The real goal of type
θ is ``g^θ`` and its bogus goal the other goal; truthfulness is
:func:`solver.literature.masters_sardina.truthful` on the game's distances.

Examples
--------
>>> from solver.game.instance import triangle
>>> meter = RouteMeter.of(triangle())
>>> m = meter.walk_metrics((0, 1), 1)  # the primary type walks s -> g2, then g2 -> g1
>>> meter.route((0, 1), 1), str(m.cost), str(m.cost_ratio), str(m.ldp)
((0, 1, 2), '4', '4/3', '1/2')
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from solver.game.instance import Instance
from solver.game.walks import StrategyWalk
from solver.graph.distances import distances_to
from solver.graph.network import Network
from solver.graph.shortest_paths import path_to_target
from solver.literature.masters_sardina import truthful
from solver.literature.path_metrics import PathMetrics, expectation, route_metrics


@dataclass(frozen=True)
class WalkMetrics:
    """The metrics of one walk of a type's strategy.

    Attributes
    ----------
    theta : int
        1 (primary type, true goal ``g1``) or 2 (secondary, ``g2``).
    label : str
        The walk's name (``xi1_I``, ``xi2_am``, ``xi1_pi_d4``, …).
    probability : Fraction
        Its probability within the type's strategy.
    steps : int
        Steps of its route.
    metrics : PathMetrics
    """

    theta: int
    label: str
    probability: Fraction
    steps: int
    metrics: PathMetrics


@dataclass(frozen=True, eq=False)
class RouteMeter:
    """Measures walks of a two-goal instance: the start, both goals and their distance
    fields, once.

    Attributes
    ----------
    net : Network
    start, g1, g2 : int
        Node indices of the start, the primary and the secondary goal.
    d_to_g1, d_to_g2 : numpy.ndarray
        Stored distances to each goal.
    b1, b2 : Fraction
        The priors of the primary and the secondary type.
    """

    net: Network
    start: int
    g1: int
    g2: int
    d_to_g1: np.ndarray
    d_to_g2: np.ndarray
    b1: Fraction
    b2: Fraction

    @classmethod
    def of(cls, instance: Instance, d_to_g1: np.ndarray | None = None,
           d_to_g2: np.ndarray | None = None) -> RouteMeter:
        """The meter of an instance (distance fields computed unless given)."""
        net = instance.network
        idx = [net.index_of(x) for x in (instance.start, instance.primary, instance.secondary)]
        s0, g1, g2 = (int(i) for i in idx if i is not None)
        return cls(net, s0, g1, g2,
                   distances_to(net, g1) if d_to_g1 is None else d_to_g1,
                   distances_to(net, g2) if d_to_g2 is None else d_to_g2,
                   instance.b1, instance.b2)

    def _goals(self, theta: int) -> tuple[int, int, np.ndarray, np.ndarray]:
        if theta == 1:
            return self.g1, self.g2, self.d_to_g1, self.d_to_g2
        if theta == 2:
            return self.g2, self.g1, self.d_to_g2, self.d_to_g1
        raise ValueError(f"theta must be 1 or 2, got {theta!r}")

    def route(self, walk: Sequence[int], theta: int) -> tuple[int, ...]:
        """Type θ's route of ``walk``: the walk, then a shortest path on to ``g^θ`` if it
        stopped elsewhere."""
        real, _, d_real, _ = self._goals(theta)
        out = [int(v) for v in walk]
        if out[-1] != real:
            out += path_to_target(self.net, out[-1], real, d_real, self.net.numbers)[1:]
        return tuple(out)

    def walk_metrics(self, walk: Sequence[int], theta: int) -> PathMetrics:
        """The metrics of type θ's ``walk`` (through its route)."""
        real, bogus, d_real, d_bogus = self._goals(theta)
        net = self.net
        route = self.route(walk, theta)
        flags = [truthful(net, v, self.start, real, bogus, d_real, d_bogus) for v in route]
        mode = net.numbers
        cost = mode.convert(net.path_weights(route).sum())
        return route_metrics(flags, cost=cost, optimal=mode.convert(d_real[self.start]))

    def strategy(self, primary: Sequence[StrategyWalk],
                 secondary: Sequence[StrategyWalk]) -> tuple[WalkMetrics, ...]:
        """Every walk of a mixed Attacker (primary type's walks first) with its metrics.

        Examples
        --------
        >>> from solver.game.instance import triangle
        >>> from solver.twogoal.equilibrium import paper_equilibrium
        >>> eq = paper_equilibrium(triangle())
        >>> rows = RouteMeter.of(triangle()).strategy(eq.primary_paths, (eq.secondary,))
        >>> [(r.theta, r.label, str(r.probability), r.steps) for r in rows]
        [(1, 'xi1_I', '4/7', 1), (1, 'xi1_II', '3/7', 2), (2, 'xi2', '1', 1)]
        """
        out = []
        for theta, paths in ((1, primary), (2, secondary)):
            for p in paths:
                if p.probability == 0:
                    continue
                out.append(WalkMetrics(theta, p.label, p.probability,
                                       len(self.route(p.walk, theta)) - 1,
                                       self.walk_metrics(p.walk, theta)))
        return tuple(out)

    def expectation(self, walks: Sequence[WalkMetrics]) -> PathMetrics:
        """The expectation over both types (by the prior) and their walks: the mixture's
        expected metrics.

        Examples
        --------
        >>> from solver.game.instance import triangle
        >>> from solver.twogoal.equilibrium import paper_equilibrium
        >>> eq = paper_equilibrium(triangle())
        >>> meter = RouteMeter.of(triangle())
        >>> e = meter.expectation(meter.strategy(eq.primary_paths, (eq.secondary,)))
        >>> str(e.cost), str(e.cost_ratio), str(e.ldp)
        ('3', '11/10', '3/20')
        """
        return expectation([(b * w.probability, w.metrics)
                            for b, theta in ((self.b1, 1), (self.b2, 2))
                            for w in walks if w.theta == theta])
