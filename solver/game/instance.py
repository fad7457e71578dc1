"""The game instance: graph, start node, two candidate goals and the prior over them."""

from __future__ import annotations

from collections.abc import Hashable
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import networkx as nx
import numpy as np

from solver.errors import InvalidInstanceError
from solver.game.instance_writing import instance_to_json
from solver.graph.network import Network
from solver.numbers import parse_number

__all__ = ["Instance", "triangle"]


@dataclass(frozen=True, eq=False)
class Instance:
    """A deceptive-path-planning game (paper, Section III-A).

    Parameters
    ----------
    graph : networkx.Graph or networkx.DiGraph or Network
        The environment; edge weights must be positive. An undirected graph can be walked
        both ways. A prebuilt :class:`Network` (CSR) is accepted as is; grids use
        :meth:`from_grid`.
    start : node
        The Attacker's initial node ``s0``.
    goals : pair of nodes
        The two candidate goals, in any order.
    prior : pair of numbers
        ``prior[i]`` is the probability that ``goals[i]`` is the true goal; exact numbers
        (``Fraction``, int, ``"3/5"``; floats are read through ``str``), each in (0, 1),
        summing to exactly 1.
    weight : str or None, keyword-only
        The edge attribute holding the weight, as in networkx (default ``"weight"``; an edge
        without it weighs 1). Any other name must be on every edge (else an error naming
        the edge); ``None`` gives unit weights.

    Notes
    -----
    The *primary* goal ``g1`` is the goal with the larger prior; at a tie (1/2, 1/2) it is
    ``goals[0]`` (the paper's footnote 2 leaves this choice free). Reachability of the goals
    is checked when the instance is solved, where the distances are computed anyway.

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
    """

    graph: nx.Graph | Network
    start: Hashable
    goals: tuple[Hashable, Hashable]
    prior: tuple[Any, Any]
    weight: str | None = field(default="weight", kw_only=True, repr=False)
    network: Network = field(init=False, repr=False)

    def __post_init__(self) -> None:
        goals = tuple(self.goals)
        if len(goals) != 2:
            raise InvalidInstanceError(f"goals must be two nodes, got {len(goals)}")
        prior = tuple(self.prior)
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
        net = (self.graph if isinstance(self.graph, Network) else
               Network.from_networkx(self.graph, weight=self.weight))
        for what, node in (("start", self.start), ("goal", goals[0]), ("goal", goals[1])):
            if net.index_of(node) is None:
                raise InvalidInstanceError(f"{what} node {node!r} not found in graph")
        if goals[0] == goals[1]:
            raise InvalidInstanceError(f"the two goals must differ, both are {goals[0]!r}")
        object.__setattr__(self, "goals", goals)
        object.__setattr__(self, "prior", exact_prior)
        object.__setattr__(self, "network", net)

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
        goals: tuple[tuple[int, int], tuple[int, int]],
        prior: tuple[Any, Any],
        *,
        connectivity: int = 4,
    ) -> Instance:
        """A grid world: ``blocked[r, c]`` True marks an obstacle; cells are ``(r, c)``.

        4-connected with unit weights by default; ``connectivity=8`` adds octile diagonals
        (weight ``sqrt(2)``, float mode, no corner cutting). A start or goal cell outside the
        grid or on an obstacle is an :class:`InvalidInstanceError` naming the cell and the
        grid's size.

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
        """
        net = Network.from_grid(blocked, connectivity=connectivity)
        cells = (_cell(start), _cell(goals[0]), _cell(goals[1]))
        for what, cell in zip(("start", "goal", "goal"), cells, strict=True):
            _check_free(net.labels, cell, what)
        return cls(net, cells[0], (cells[1], cells[2]), prior)

    # ------------------------------------------------------------------ derived
    @property
    def primary_index(self) -> int:
        """The goal index (0 or 1) of the primary goal: its position in ``goals`` and ``prior``
        (the larger prior; ``0`` at a tie)."""
        return 0 if self.prior[0] >= self.prior[1] else 1

    @property
    def primary(self) -> Hashable:
        """The primary goal ``g1``."""
        return self.goals[self.primary_index]

    @property
    def secondary(self) -> Hashable:
        """The secondary goal ``g2``."""
        return self.goals[1 - self.primary_index]

    @property
    def b1(self) -> Fraction:
        """Prior of the primary goal."""
        return Fraction(self.prior[self.primary_index])

    @property
    def b2(self) -> Fraction:
        """Prior of the secondary goal."""
        return Fraction(self.prior[1 - self.primary_index])


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
