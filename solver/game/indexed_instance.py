"""N-goal game instances for the solver: a graph, a start, ``N >= 2`` goals and a prior.

The document is the instance JSON of ``docs/formats.md`` §1 with ``goals`` a list of ``N``
distinct nodes and ``prior`` ``N`` exact numbers in (0, 1) summing to exactly 1. Type ``θ``
(0-based) walks to ``goals[θ]``. The N-goal construction is exact only: float weights (octile
grids, ``"numbers": "float"``) are refused with one line.
"""

from __future__ import annotations

from collections.abc import Hashable, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np

from solver.errors import InstanceFormatError, InvalidInstanceError
from solver.formats.json_text import read_json
from solver.formats.map_instance import MAP_INSTANCE_FORMAT, read_map_document
from solver.formats.nodes import node_from_json, node_to_json
from solver.game.instance import _check_free
from solver.game.instance_reading import _graph_from_node_link
from solver.graph.distances import distances_to
from solver.graph.network import Network
from solver.numbers import parse_number

__all__ = ["MAX_NGOALS", "NGame", "load_ngame", "ngame_from_grid", "ngame_from_json",
           "ngame_to_json"]

MAX_NGOALS = 5
"""The coalition DP enumerates minimal balanced collections of up to five goals."""


@dataclass(frozen=True, eq=False)
class NGame:
    """A validated N-goal game on a :class:`~solver.graph.network.Network` (exact weights).

    Attributes
    ----------
    network : Network
        The arcs; weights are integer numerators over ``network.numbers.denominator``.
    start : int
        Index of ``s0``.
    goals : tuple of int
        Goal indices; type ``θ`` walks to ``goals[θ]``.
    prior : tuple of Fraction
        ``prior[θ]``.
    dist_to : tuple of numpy.ndarray
        ``dist_to[θ][v]``: ``d(v, g^θ)`` as an exact numerator (float64 integer or Python
        int) over the weight denominator, ``inf`` when unreachable.

    Examples
    --------
    >>> doc = {"graph": {"nodes": [{"id": "s"}, {"id": "a"}, {"id": "b"}, {"id": "c"}],
    ...        "edges": [{"source": "s", "target": "a"}, {"source": "s", "target": "b"},
    ...                  {"source": "s", "target": "c", "weight": 2}]},
    ...        "start": "s", "goals": ["a", "b", "c"], "prior": ["1/2", "1/3", "1/6"]}
    >>> game = ngame_from_json(doc)
    >>> game.n_goals, game.label(game.goals[2]), game.distance(2, game.goals[0])
    (3, 'c', Fraction(3, 1))
    """

    network: Network = field(repr=False)
    start: int
    goals: tuple[int, ...]
    prior: tuple[Fraction, ...]
    dist_to: tuple[np.ndarray, ...] = field(repr=False)

    @property
    def n_goals(self) -> int:
        """``N``."""
        return len(self.goals)

    @property
    def denominator(self) -> int:
        """The common denominator of the weights (distances are numerators over it)."""
        return self.network.numbers.denominator

    def label(self, v: int) -> Hashable:
        """The node id of index ``v``."""
        return self.network.labels[v]

    def distance(self, theta: int, v: int) -> Fraction:
        """``d(v, g^θ)`` exactly (the caller makes sure it is finite)."""
        return Fraction(int(self.dist_to[theta][v]), self.denominator)


def _build(net: Network, start: Hashable, goals: Sequence[Hashable], prior: Sequence[Any]
           ) -> NGame:
    n = len(goals)
    if not 2 <= n <= MAX_NGOALS:
        raise InvalidInstanceError(f"the N-goal solver takes 2 to {MAX_NGOALS} goals, got {n} "
                                   "(the coalition DP enumerates the minimal balanced "
                                   "collections of the goals: 1,291 for 5 goals)")
    if len(prior) != n:
        raise InvalidInstanceError(f"prior must list {n} numbers (one per goal), "
                                   f"got {len(prior)}")
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
    s = net.index_of(start)
    if s is None:
        raise InvalidInstanceError(f"start node {start!r} not found in graph")
    idx = []
    for i, g in enumerate(goals):
        j = net.index_of(g)
        if j is None:
            raise InvalidInstanceError(f"goals[{i}]: node {g!r} not found in graph")
        if j in idx:
            raise InvalidInstanceError(f"goals[{i}]: goal {g!r} is listed twice")
        idx.append(j)
    dist = tuple(distances_to(net, g) for g in idx)
    for t, g in enumerate(idx):
        if not np.isfinite(float(dist[t][s])):
            raise InvalidInstanceError(f"goal {net.labels[g]!r} is not reachable from the start")
        for g2 in idx:
            if not np.isfinite(float(dist[t][g2])):
                raise InvalidInstanceError(f"goal {net.labels[g]!r} is not reachable from goal "
                                           f"{net.labels[g2]!r} (terminal costs must be finite)")
    return NGame(net, s, tuple(idx), b, dist)


def ngame_from_json(data: Any, base: Path | None = None) -> NGame:
    """Build an :class:`NGame` from an instance document with ``N >= 2`` goals.

    ``data`` is the instance JSON, or a compact ``dpp-map-instance/1`` document (its map's
    sha256 checked; a relative map path is relative to ``base``).

    Raises
    ------
    InstanceFormatError, InvalidInstanceError
        One line naming what is wrong.

    Examples
    --------
    >>> ngame_from_json({"graph": {"nodes": [{"id": 1}, {"id": 2}], "edges": []},
    ...                  "start": 1, "goals": [1, 2, 1], "prior": ["1/2", "1/4", "1/4"]})
    Traceback (most recent call last):
    solver.errors.InvalidInstanceError: goals[2]: goal 1 is listed twice
    """
    if not isinstance(data, dict):
        raise InstanceFormatError(f"instance must be a JSON object, got {type(data).__name__}")
    if data.get("format") == MAP_INSTANCE_FORMAT:
        blocked, start, cells, prior, connectivity, ref = read_map_document(data, base,
                                                                            count=None)
        if connectivity != 4:
            raise InvalidInstanceError("the N-goal solver is exact only: float weights "
                                       "(connectivity 8) are not supported for more than two "
                                       "goals")
        try:
            return ngame_from_grid(blocked, start, cells, prior)
        except InvalidInstanceError as exc:
            raise InvalidInstanceError(f"{ref[:200]}: {exc}") from None
    missing = [k for k in ("graph", "start", "goals", "prior") if k not in data]
    if missing:
        raise InstanceFormatError(f"instance is missing key(s): {', '.join(missing)}")
    if data.get("numbers", "exact") != "exact":
        raise InvalidInstanceError("the N-goal solver is exact only: \"numbers\": \"float\" is "
                                   "not supported for more than two goals")
    goals, prior = data["goals"], data["prior"]
    if not isinstance(goals, list) or not isinstance(prior, list):
        raise InstanceFormatError("'goals' and 'prior' must be lists")
    graph = _graph_from_node_link(data["graph"], float_weights=False)
    net = Network.from_networkx(graph)
    return _build(net, node_from_json(data["start"]), [node_from_json(g) for g in goals], prior)


def load_ngame(path: str | Path) -> NGame:
    """Read an N-goal instance file (one-line errors prefixed by the path).

    Examples
    --------
    >>> load_ngame("/nonexistent.json")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    solver.errors.InstanceFormatError: ...
    """
    try:
        return ngame_from_json(read_json(path))
    except InstanceFormatError:
        raise
    except InvalidInstanceError as exc:
        raise InvalidInstanceError(f"{path}: {exc}") from None


def ngame_from_grid(blocked: np.ndarray, start: tuple[int, int],
                    goals: Sequence[tuple[int, int]], prior: Sequence[Any]) -> NGame:
    """A 4-connected unit-weight grid game (``blocked[r, c]`` True marks an obstacle).

    Examples
    --------
    >>> blocked = np.zeros((3, 3), dtype=bool)
    >>> game = ngame_from_grid(blocked, (2, 0), [(0, 0), (0, 2), (2, 2)], ["1/2", "1/4", "1/4"])
    >>> game.n_goals, game.distance(1, game.start)
    (3, Fraction(4, 1))
    >>> ngame_from_grid(blocked, (3, 0), [(0, 0), (0, 2)], ["1/2", "1/2"])
    Traceback (most recent call last):
    solver.errors.InvalidInstanceError: start cell (3, 0) is outside the 3x3 grid (rows 0-2, \
columns 0-2)
    """
    net = Network.from_grid(blocked, connectivity=4)
    _check_free(net.labels, (start[0], start[1]), "start")
    for g in goals:
        _check_free(net.labels, (g[0], g[1]), "goal")
    return _build(net, (start[0], start[1]), [(g[0], g[1]) for g in goals], prior)


def ngame_to_json(game: NGame) -> dict[str, Any]:
    """The instance JSON of an N-goal game (every arc listed, exact weights as strings).

    Examples
    --------
    >>> game = ngame_from_grid(np.zeros((1, 3), dtype=bool), (0, 0), [(0, 1), (0, 2)],
    ...                        ["1/2", "1/2"])
    >>> doc = ngame_to_json(game)
    >>> doc["goals"], len(doc["graph"]["edges"])
    ([[0, 1], [0, 2]], 4)
    """
    net = game.network
    den = game.denominator
    nodes = [{"id": node_to_json(net.labels[i])} for i in range(net.n_nodes)
             if net.indptr[i + 1] > net.indptr[i] or i == game.start or i in game.goals]
    edges = []
    for i in range(net.n_nodes):
        heads, ws = net.out_arcs(i)
        for j, w in zip(heads.tolist(), ws.tolist(), strict=True):
            edges.append({"source": node_to_json(net.labels[i]),
                          "target": node_to_json(net.labels[j]),
                          "weight": str(Fraction(int(w), den))})
    return {"graph": {"directed": True, "multigraph": False, "graph": {}, "nodes": nodes,
                      "edges": edges},
            "start": node_to_json(net.labels[game.start]),
            "goals": [node_to_json(net.labels[g]) for g in game.goals],
            "prior": [str(b) for b in game.prior]}
