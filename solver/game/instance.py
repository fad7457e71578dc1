"""The game instance for any number of goals: graph, start node, ``N >= 2`` goals, prior.

One type serves every construction: two goals (``N = 2``) are read under the two-goal rules
(float weights allowed, the paper's primary/secondary views :attr:`Instance.primary`,
:attr:`Instance.b1`, ...); more goals (``3 <= N <= 5``) under the N-goal rules (exact weights
only, every goal reachable from the start and from every other goal), as the checker reads them.
"""

from __future__ import annotations

from collections.abc import Hashable, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from functools import cached_property
from typing import Any

import networkx as nx
import numpy as np

from dppio.limits import common_denominator
from solver.errors import InvalidInstanceError, NotTwoGoalsError
from solver.game.instance_writing import instance_to_json
from solver.graph.distances import distances_to
from solver.graph.network import Network
from solver.numbers import parse_number

MAX_GOALS = 5
"""The most goals the solver takes: the coalition DP enumerates the minimal balanced
collections of the goals (1,291 for five goals)."""


@dataclass(frozen=True, eq=False)
class Instance:
    """A deceptive-path-planning game (paper, Section III-A) with ``N >= 2`` goals.

    Parameters
    ----------
    graph : networkx.Graph or networkx.DiGraph or Network
        The environment; edge weights must be positive. An undirected graph can be walked
        both ways. A prebuilt :class:`Network` (CSR) is accepted as is; grids use
        :meth:`from_grid`.
    start : node
        The Attacker's initial node ``s0``.
    goals : sequence of nodes
        The ``N`` candidate goals (``2 <= N <=`` :data:`MAX_GOALS`), in any order; the position
        of a goal is its *goal index* ``θ``.
    prior : sequence of numbers
        ``prior[θ]`` is the probability that ``goals[θ]`` is the true goal; exact numbers
        (``Fraction``, int, ``"3/5"``; floats are read through ``str``), each in (0, 1),
        summing to exactly 1.
    weight : str or None, keyword-only
        The edge attribute holding the weight, as in networkx (default ``"weight"``; an edge
        without it weighs 1). Any other name must be on every edge (else an error naming
        the edge); ``None`` gives unit weights.

    Notes
    -----
    Two goals are read under the two-goal rules: float weights are allowed (float mode), and
    the *primary* goal ``g1`` is the goal with the larger prior; at a tie (1/2, 1/2) it is
    ``goals[0]`` (the paper's footnote 2 leaves this choice free); reachability of the goals
    is checked when the instance is solved, where the distances are computed anyway. More
    goals are read under the N-goal rules: exact weights only, and every goal reachable from
    the start and from every other goal (the terminal costs are finite), checked here.

    Examples
    --------
    >>> g = nx.Graph()
    >>> g.add_weighted_edges_from([("s", "g2", 2), ("g2", "g1", 2), ("s", "g1", 3)])
    >>> inst = Instance(g, "s", ("g2", "g1"), ("3/10", "7/10"))
    >>> inst.primary, inst.secondary, inst.b1
    ('g1', 'g2', Fraction(7, 10))
    >>> h = nx.Graph([("s", "g2", {"cost": 2}), ("g2", "g1", {"cost": 2}),
    ...               ("s", "g1", {"cost": 3})])
    >>> inst = Instance(h, "s", ("g1", "g2"), ("7/10", "3/10"), weight="cost")
    >>> sorted(inst.network.weights.tolist())
    [2, 2, 2, 2, 3, 3]
    >>> Instance(g, "s", ("g1", "g2"), (2 / 3, 1 / 3))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    solver.errors.InvalidInstanceError: prior must sum to 1, got 0.666... + 0.333... (floats
    are read as the decimals they print); write exact fractions as strings, e.g. ("2/3", "1/3")
    >>> star = nx.Graph([("s", "a"), ("s", "b"), ("s", "c", {"weight": 2})])
    >>> inst = Instance(star, "s", ("a", "b", "c"), ("1/2", "1/3", "1/6"))
    >>> inst.n_goals, inst.label(inst.targets[2]), inst.distance(2, inst.s0)
    (3, 'c', Fraction(2, 1))
    >>> Instance(star, "s", ("a", "b", "a"), ("1/2", "1/4", "1/4"))
    Traceback (most recent call last):
    solver.errors.InvalidInstanceError: goals[2]: goal 'a' is listed twice
    """

    graph: nx.Graph | Network
    start: Hashable
    goals: tuple[Hashable, ...]
    prior: tuple[Any, ...]
    weight: str | None = field(default="weight", kw_only=True, repr=False)
    network: Network = field(init=False, repr=False)

    def __post_init__(self) -> None:
        goals = tuple(self.goals)
        if not 2 <= len(goals) <= MAX_GOALS:
            raise InvalidInstanceError(
                f"the solver takes 2 to {MAX_GOALS} goals, got {len(goals)} (the coalition DP "
                "enumerates the minimal balanced collections of the goals: 1,291 for 5 goals)")
        object.__setattr__(self, "goals", goals)
        if len(goals) == 2:
            self._two_goal_rules(tuple(self.prior))
        else:
            self._n_goal_rules(tuple(self.prior))

    def _network(self) -> Network:
        return (self.graph if isinstance(self.graph, Network) else
                Network.from_networkx(self.graph, weight=self.weight))

    def _two_goal_rules(self, prior: tuple[Any, ...]) -> None:
        goals = self.goals
        if len(prior) != 2:
            raise InvalidInstanceError(f"prior must be two numbers, got {len(prior)}")
        exact_prior = tuple(parse_number(p, where=f"prior[{i}]") for i, p in enumerate(prior))
        for i, p in enumerate(exact_prior):
            if not 0 < p < 1:
                raise InvalidInstanceError(f"prior[{i}] must lie in (0, 1), got {p}")
        if sum(exact_prior) != 1 and any(isinstance(p, float) for p in prior):
            guess = tuple(Fraction(p).limit_denominator(1000) for p in exact_prior)
            hint = (f'; write exact fractions as strings, e.g. ("{guess[0]}", "{guess[1]}")'
                    if sum(guess) == 1 else "")
            raise InvalidInstanceError(
                f"prior must sum to 1, got {prior[0]!r} + {prior[1]!r} (floats are read as "
                f"the decimals they print){hint}")
        if sum(exact_prior) != 1:
            raise InvalidInstanceError(
                f"prior must sum to 1, got {exact_prior[0]} + {exact_prior[1]} "
                f"= {sum(exact_prior)}"
            )
        net = self._network()
        for what, node in (("start", self.start), ("goal", goals[0]), ("goal", goals[1])):
            if net.index_of(node) is None:
                raise InvalidInstanceError(f"{what} node {node!r} not found in graph")
        if goals[0] == goals[1]:
            raise InvalidInstanceError(f"the two goals must differ, both are {goals[0]!r}")
        _bounded(net, exact_prior)
        object.__setattr__(self, "prior", exact_prior)
        object.__setattr__(self, "network", net)

    def _n_goal_rules(self, prior: tuple[Any, ...]) -> None:
        n = len(self.goals)
        if len(prior) != n:
            raise InvalidInstanceError(f"prior must list {n} numbers (one per goal), "
                                       f"got {len(prior)}")
        net = self._network()
        if not net.numbers.exact:
            raise InvalidInstanceError("the N-goal solver is exact only: float weights (e.g. "
                                       "--connectivity 8) are not supported for more than two "
                                       "goals")
        b = tuple(Fraction(parse_number(p, where=f"prior[{i}]")) for i, p in enumerate(prior))
        for i, p in enumerate(b):
            if not 0 < p < 1:
                raise InvalidInstanceError(f"prior[{i}] must lie in (0, 1), got {p}")
        if sum(b) != 1:
            raise InvalidInstanceError(f"prior must sum to exactly 1, got {sum(b)}")
        if net.index_of(self.start) is None:
            raise InvalidInstanceError(f"start node {self.start!r} not found in graph")
        idx: list[int] = []
        for i, g in enumerate(self.goals):
            j = net.index_of(g)
            if j is None:
                raise InvalidInstanceError(f"goals[{i}]: node {g!r} not found in graph")
            if j in idx:
                raise InvalidInstanceError(f"goals[{i}]: goal {g!r} is listed twice")
            idx.append(j)
        _bounded(net, b)
        object.__setattr__(self, "prior", b)
        object.__setattr__(self, "network", net)
        s, dist = self.s0, self.dist_to
        for t, g in enumerate(idx):
            if not np.isfinite(float(dist[t][s])):
                raise InvalidInstanceError(f"goal {net.labels[g]!r} is not reachable from the "
                                           "start")
            for g2 in idx:
                if not np.isfinite(float(dist[t][g2])):
                    raise InvalidInstanceError(f"goal {net.labels[g]!r} is not reachable from "
                                               f"goal {net.labels[g2]!r} (terminal costs must "
                                               "be finite)")

    def to_json(self) -> dict[str, Any]:
        """The instance JSON document (docs/formats.md §1), as :func:`solver.instance_to_json`.

        This is the documented protocol through which the checker takes the solver's objects
        (``dppverify.certify(inst, eq)``) without importing the solver.

        Examples
        --------
        >>> import networkx as nx
        >>> g = nx.Graph([("s", "a"), ("s", "b")])
        >>> Instance(g, "s", ("a", "b"), ("1/2", "1/2")).to_json()["goals"]
        ['a', 'b']
        """
        return instance_to_json(self)

    # ------------------------------------------------------------------ constructors
    @classmethod
    def from_grid(
        cls,
        blocked: np.ndarray,
        start: tuple[int, int],
        goals: Sequence[tuple[int, int]],
        prior: Sequence[Any],
        *,
        connectivity: int = 4,
    ) -> Instance:
        """A grid world: ``blocked[r, c]`` True marks an obstacle; cells are ``(r, c)``.

        4-connected with unit weights by default; ``connectivity=8`` adds octile diagonals
        (weight ``sqrt(2)``, float mode, no corner cutting; two goals only). A start or goal
        cell outside the grid or on an obstacle is an :class:`InvalidInstanceError` naming
        the cell and the grid's size.

        Examples
        --------
        >>> blocked = np.zeros((3, 3), dtype=bool); blocked[1, 1] = True
        >>> inst = Instance.from_grid(blocked, (0, 0), ((2, 2), (0, 2)), ("3/5", "2/5"))
        >>> inst.network.n_nodes, inst.primary   # the free cells are the nodes
        (8, (2, 2))
        >>> Instance.from_grid(blocked, (1, 1), ((2, 2), (0, 2)), ("3/5", "2/5"))
        Traceback (most recent call last):
        solver.errors.InvalidInstanceError: start cell (1, 1) is an obstacle in the 3x3 grid
        >>> Instance.from_grid(blocked, (0, 0), ((3, 0), (0, 2)), ("3/5", "2/5"))
        Traceback (most recent call last):
        solver.errors.InvalidInstanceError: goal cell (3, 0) is outside the 3x3 grid
          (rows 0-2, columns 0-2)
        >>> game = Instance.from_grid(np.zeros((3, 3), dtype=bool), (2, 0),
        ...                           [(0, 0), (0, 2), (2, 2)], ["1/2", "1/4", "1/4"])
        >>> game.n_goals, game.distance(1, game.s0)
        (3, Fraction(4, 1))
        """
        net = Network.from_grid(blocked, connectivity=connectivity)
        start_cell = _cell(start)
        _check_free(net.labels, start_cell, "start")
        cells = tuple(_cell(g) for g in goals)
        for cell in cells:
            _check_free(net.labels, cell, "goal")
        return cls(net, start_cell, cells, tuple(prior))

    # ------------------------------------------------------------------ derived
    @property
    def n_goals(self) -> int:
        """``N``, the number of goals."""
        return len(self.goals)

    def node_index(self, node: Hashable) -> int:
        """The node index of ``node`` (its position in :attr:`network`).

        Examples
        --------
        >>> triangle().node_index("g1")
        2
        """
        i = self.network.index_of(node)
        if i is None:
            raise InvalidInstanceError(f"node {node!r} not found in graph")
        return i

    def label(self, v: int) -> Hashable:
        """The node id of node index ``v``."""
        return self.network.labels[v]

    @cached_property
    def s0(self) -> int:
        """The node index of the start ``s0``."""
        return self.node_index(self.start)

    @cached_property
    def targets(self) -> tuple[int, ...]:
        """``targets[θ]``: the node index of ``goals[θ]``."""
        return tuple(self.node_index(g) for g in self.goals)

    @property
    def denominator(self) -> int:
        """The common denominator of the weights in exact mode (distances are numerators
        over it)."""
        return self.network.numbers.denominator

    @cached_property
    def dist_to(self) -> tuple[np.ndarray, ...]:
        """``dist_to[θ][v]``: ``d(v, goals[θ])`` over the whole graph, as
        :func:`~solver.graph.distances.distances_to` gives it (in exact mode an integer
        numerator over :attr:`denominator`; ``inf`` when unreachable). Computed on first use."""
        return tuple(distances_to(self.network, g) for g in self.targets)

    def distance(self, theta: int, v: int) -> Fraction:
        """``d(v, goals[θ])`` exactly (exact mode; the caller makes sure it is finite)."""
        return Fraction(int(self.dist_to[theta][v]), self.denominator)

    # --- the two-goal views (N = 2): the paper's primary and secondary goals ---

    def _two(self, view: str) -> None:
        if len(self.goals) != 2:
            raise NotTwoGoalsError(f"{view}: the (primary, secondary) labelling is for two "
                                   f"goals; this instance has {len(self.goals)}")

    @property
    def primary_goal_index(self) -> int:
        """The goal index (0 or 1) of the primary goal: its position in ``goals`` and ``prior``
        (the larger prior; ``0`` at a tie). Two goals only (:class:`NotTwoGoalsError`)."""
        self._two("primary_goal_index")
        return 0 if self.prior[0] >= self.prior[1] else 1

    @property
    def primary(self) -> Hashable:
        """The primary goal ``g1``."""
        return self.goals[self.primary_goal_index]

    @property
    def secondary(self) -> Hashable:
        """The secondary goal ``g2``."""
        return self.goals[1 - self.primary_goal_index]

    @property
    def b1(self) -> Fraction:
        """Prior of the primary goal."""
        return Fraction(self.prior[self.primary_goal_index])

    @property
    def b2(self) -> Fraction:
        """Prior of the secondary goal."""
        return Fraction(self.prior[1 - self.primary_goal_index])


def triangle() -> Instance:
    """The README's running example: ``s -> g2`` (2), ``g2 -> g1`` (2), ``s -> g1`` (3),
    goals ``g1, g2`` with the prior ``7/10, 3/10`` (``examples/triangle.json``); U* = 12/5.

    Examples
    --------
    >>> inst = triangle()
    >>> inst.start, inst.goals, str(inst.b1)
    ('s', ('g1', 'g2'), '7/10')
    """
    g = nx.Graph()
    g.add_weighted_edges_from([("s", "g2", 2), ("g2", "g1", 2), ("s", "g1", 3)])
    return Instance(g, "s", ("g1", "g2"), ("7/10", "3/10"))


def _cell(x: Any) -> tuple[int, int]:
    try:
        r, c = x
        return (int(r), int(c))
    except (TypeError, ValueError):
        raise InvalidInstanceError(f"grid cell must be a (row, col) pair, got {x!r}") from None


def _check_free(labels: Any, cell: tuple[int, int], what: str) -> None:
    height, width = labels.height, labels.width
    r, c = cell
    if not (0 <= r < height and 0 <= c < width):
        raise InvalidInstanceError(f"{what} cell ({r}, {c}) is outside the {height}x{width} grid "
                                   f"(rows 0-{height - 1}, columns 0-{width - 1})")
    if labels.blocked[r, c]:
        raise InvalidInstanceError(f"{what} cell ({r}, {c}) is an obstacle in the "
                                   f"{height}x{width} grid")


def _bounded(net: Network, prior: tuple[Any, ...]) -> None:
    """The weights' and the prior's common denominator within ``dppio.limits`` (exact mode)."""
    if net.numbers.exact:
        common_denominator([net.numbers.denominator, *(Fraction(p).denominator for p in prior)],
                           where="instance (edge weights and prior)",
                           error=InvalidInstanceError)
