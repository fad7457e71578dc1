"""N-goal instances: parse and validate the instance JSON with ``N >= 2`` goals.

The document is the two-goal instance format (``docs/formats.md`` §1) with ``goals`` a list of
``N >= 2`` distinct nodes and ``prior`` a list of ``N`` numbers in (0, 1) summing to exactly 1.
Validity: every goal is reachable from the start and from every other goal (the terminal
costs ``d(g^i, g^j)`` are finite). Exact numbers only (``"numbers": "float"`` is refused).
Every violation raises :class:`~dppverify.errors.InvalidInstanceError` with one line naming
what and where. The graph is read with the same primitives as the two-goal parser
(:mod:`dppverify.json_reading`).
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from types import MappingProxyType
from typing import Any

from dppverify.distances import dijkstra, hops_to_targets
from dppverify.errors import InvalidInstanceError
from dppverify.exact import INF, Number
from dppverify.json_reading import (
    JsonReadError,
    Node,
    node_from_json,
    parse_json_text,
    parse_number,
    read_json_file,
    show_node,
)

__all__ = ["NInstance", "goal_count", "load_ninstance", "ninstance_from_json",
           "read_instance_document"]


@dataclass(frozen=True, eq=False)
class NInstance:
    """A validated N-goal game instance with exact distances.

    Nodes are numbered ``0 .. n-1`` in document order.

    Attributes
    ----------
    nodes : tuple
        Node ids (JSON lists converted to tuples).
    index : Mapping
        Node id -> index.
    directed : bool
        False when every edge can be walked both ways.
    succ, pred : tuple
        ``succ[u]`` = arcs ``(v, w)`` leaving ``u``; ``pred[v]`` = arcs ``(u, w)`` entering ``v``.
    start : int
        ``s0``.
    goals : tuple of int
        The N goals in document order; type ``θ`` (0-based) walks to ``goals[θ]``.
    prior : tuple of Fraction
        ``prior[θ]``: the probability of type ``θ``.
    dist_to : tuple
        ``dist_to[θ][v]`` = full-graph ``d(v, goals[θ])`` (``math.inf`` if unreachable).
    hops : tuple of int
        Fewest steps from each node to the nearest goal (``-1`` if none).

    Examples
    --------
    >>> doc = {"graph": {"nodes": [{"id": "s"}, {"id": "a"}, {"id": "b"}, {"id": "c"}],
    ...        "edges": [{"source": "s", "target": "a"}, {"source": "s", "target": "b"},
    ...                  {"source": "s", "target": "c", "weight": 2}]},
    ...        "start": "s", "goals": ["a", "b", "c"], "prior": ["1/2", "1/3", "1/6"]}
    >>> inst = ninstance_from_json(doc)
    >>> inst.n_goals, inst.prior[2], inst.dist_to[2][inst.goals[0]]
    (3, Fraction(1, 6), 3)
    """

    nodes: tuple[Node, ...]
    index: Mapping[Node, int]
    directed: bool
    succ: tuple[tuple[tuple[int, Number], ...], ...]
    pred: tuple[tuple[tuple[int, Number], ...], ...]
    start: int
    goals: tuple[int, ...]
    prior: tuple[Fraction, ...]
    dist_to: tuple[tuple[Number, ...], ...]
    hops: tuple[int, ...]

    @property
    def n_nodes(self) -> int:
        """Number of nodes."""
        return len(self.nodes)

    @property
    def n_goals(self) -> int:
        """Number of goals ``N``."""
        return len(self.goals)

    @property
    def exact(self) -> bool:
        """Always True: N-goal instances are exact."""
        return True

    def goal_slot(self, node: int) -> int | None:
        """The type ``θ`` whose goal is ``node``, or None if ``node`` is not a goal."""
        try:
            return self.goals.index(node)
        except ValueError:
            return None

    def is_goal(self, node: int) -> bool:
        """True for the N candidate goals."""
        return node in self.goals

    def weight(self, u: int, v: int) -> Number | None:
        """Weight of the arc ``u -> v``, or None when there is no such arc."""
        for head, w in self.succ[u]:
            if head == v:
                return w
        return None

    def labels(self, walk: tuple[int, ...] | list[int]) -> tuple[Node, ...]:
        """Node ids of a walk given as indices."""
        return tuple(self.nodes[v] for v in walk)

    def terminal(self, goal: int, theta: int) -> Number:
        """Type ``θ``'s terminal cost at goal node ``goal``: ``d(goal, g^θ)``."""
        return self.dist_to[theta][goal]


def goal_count(doc: Any) -> int | None:
    """The number of goals an instance document lists (None if ``goals`` is not a list).

    Used by the command line to dispatch between the two-goal and the N-goal checker.

    Examples
    --------
    >>> goal_count({"goals": ["a", "b", "c"]}), goal_count({"goals": 3})
    (3, None)
    """
    if isinstance(doc, Mapping) and isinstance(doc.get("goals"), list):
        return len(doc["goals"])
    return None


def read_instance_document(path: str | Path) -> Any:
    """Read an instance file as a JSON document (decimals exact), one-line errors.

    Raises
    ------
    InvalidInstanceError
        ``PATH: what is wrong`` for unreadable or malformed files.

    Examples
    --------
    >>> read_instance_document("/nonexistent.json")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: /nonexistent.json: cannot read instance file ...
    """
    p = Path(path)
    try:
        return read_json_file(p, kind="instance")
    except JsonReadError as exc:
        raise InvalidInstanceError(f"{p}: {exc}") from None


def load_ninstance(path: str | Path) -> NInstance:
    """Read and validate an N-goal instance file.

    Examples
    --------
    >>> load_ninstance("/nonexistent.json")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: /nonexistent.json: cannot read instance file ...
    """
    doc = read_instance_document(path)
    try:
        return ninstance_from_json(doc)
    except InvalidInstanceError as exc:
        raise InvalidInstanceError(f"{path}: {exc}") from None


def ninstance_from_json(doc: Mapping[str, Any] | str | bytes) -> NInstance:
    """Build a validated :class:`NInstance` from an instance document (dict or JSON text).

    Raises
    ------
    InvalidInstanceError
        For malformed documents and instances violating the game's assumptions.

    Examples
    --------
    >>> ninstance_from_json('{"graph": {"nodes": [{"id": 1}, {"id": 2}], "edges": []}, '
    ...     '"start": 1, "goals": [1, 2, 1], "prior": [0.5, 0.25, 0.25]}')
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: goals[2]: goal 1 is listed twice
    """
    if isinstance(doc, str | bytes):
        try:
            doc = parse_json_text(doc)
        except JsonReadError as exc:
            raise InvalidInstanceError(str(exc)) from None
    try:
        return _build(doc)
    except InvalidInstanceError:
        raise
    except (ValueError, TypeError) as exc:
        raise InvalidInstanceError(str(exc)) from None


def _require(cond: bool, message: str) -> None:
    if not cond:
        raise InvalidInstanceError(message)


def _known(index: Mapping[Node, int], v: Node) -> bool:
    try:
        return v in index
    except TypeError:
        return False


def _node(raw: Any, index: Mapping[Node, int], where: str) -> int:
    v = node_from_json(raw, where=where)
    _require(_known(index, v), f"{where}: unknown node {show_node(v)}")
    return index[v]


def _build(doc: Any) -> NInstance:
    _require(isinstance(doc, Mapping), f"instance must be a JSON object, got {type(doc).__name__}")
    missing = [k for k in ("graph", "start", "goals", "prior") if k not in doc]
    _require(not missing, f"instance is missing key(s): {', '.join(missing)}")
    _require(doc.get("numbers", "exact") == "exact",
             "numbers: N-goal instances must be exact (\"numbers\": \"exact\")")
    g = doc["graph"]
    _require(isinstance(g, Mapping), "graph: must be a node-link JSON object")
    _require(not g.get("multigraph", False), "graph: multigraphs are not supported")
    directed = g.get("directed", False)
    _require(isinstance(directed, bool), f"graph.directed: expected true/false, got {directed!r}")
    raw_nodes = g.get("nodes")
    raw_edges = g.get("edges", g.get("links"))
    _require(isinstance(raw_nodes, list), "graph.nodes: must be a list of {\"id\": ...} objects")
    _require(isinstance(raw_edges, list), "graph.edges: must be a list of edge objects")
    ids: list[Node] = []
    index: dict[Node, int] = {}
    for k, nd in enumerate(raw_nodes):
        _require(isinstance(nd, Mapping) and "id" in nd,
                 f"graph.nodes[{k}]: must be an object with an \"id\"")
        v = node_from_json(nd["id"], where=f"graph.nodes[{k}].id")
        try:
            hash(v)
        except TypeError:
            raise InvalidInstanceError(f"graph.nodes[{k}].id: not a valid node id") from None
        _require(v not in index, f"graph.nodes[{k}]: duplicate node id {show_node(v)}")
        index[v] = len(ids)
        ids.append(v)
    n = len(ids)
    succ: list[dict[int, Number]] = [{} for _ in range(n)]
    for k, e in enumerate(raw_edges):
        _require(isinstance(e, Mapping) and "source" in e and "target" in e,
                 f"graph.edges[{k}]: must be an object with \"source\" and \"target\"")
        u = _node(e["source"], index, f"graph.edges[{k}].source")
        v = _node(e["target"], index, f"graph.edges[{k}].target")
        w = parse_number(e.get("weight", 1), where=f"graph.edges[{k}].weight")
        _require(w > 0, f"graph.edges[{k}].weight: must be positive, got {w}")
        for a, b in ([(u, v)] if directed or u == v else [(u, v), (v, u)]):
            _require(b not in succ[a], f"graph.edges[{k}]: duplicate edge {show_node(ids[a])} "
                                       f"-> {show_node(ids[b])}")
            succ[a][b] = w
    start = _node(doc["start"], index, "start")
    goals_raw = doc["goals"]
    _require(isinstance(goals_raw, list) and len(goals_raw) >= 2,
             f"goals: must be a list of at least two node ids, got "
             f"{json.dumps(goals_raw, default=str)}")
    goals: list[int] = []
    for i, raw in enumerate(goals_raw):
        gi = _node(raw, index, f"goals[{i}]")
        _require(gi not in goals, f"goals[{i}]: goal {show_node(ids[gi])} is listed twice")
        goals.append(gi)
    prior = _prior(doc["prior"], len(goals))
    succ_t = tuple(tuple(sorted(s.items())) for s in succ)
    pred_l: list[list[tuple[int, Number]]] = [[] for _ in range(n)]
    for u in range(n):
        for v, w in succ_t[u]:
            pred_l[v].append((u, w))
    pred_t = tuple(tuple(p) for p in pred_l)
    dist_to = tuple(tuple(dijkstra(pred_t, gi)) for gi in goals)
    for i, gi in enumerate(goals):
        name = show_node(ids[gi])
        _require(dist_to[i][start] != INF,
                 f"goal {name} is unreachable from start {show_node(ids[start])}")
        for gj in goals:
            other = show_node(ids[gj])
            _require(dist_to[i][gj] != INF, f"goal {name} is unreachable from goal {other}: "
                                            f"d({other}, {name}) is infinite")
    hops = tuple(hops_to_targets(pred_t, goals))
    return NInstance(nodes=tuple(ids), index=MappingProxyType(index), directed=directed,
                     succ=succ_t, pred=pred_t, start=start, goals=tuple(goals),
                     prior=prior, dist_to=dist_to, hops=hops)


def _prior(raw: Any, n: int) -> tuple[Fraction, ...]:
    _require(isinstance(raw, list) and len(raw) == n,
             f"prior: must be a list of {n} numbers (one per goal), got "
             f"{json.dumps(raw, default=str)}")
    p = [Fraction(parse_number(x, where=f"prior[{i}]")) for i, x in enumerate(raw)]
    for i, x in enumerate(p):
        _require(0 < x < 1, f"prior[{i}]: must lie strictly between 0 and 1, got {x}")
    total = sum(p, Fraction(0))
    _require(total == 1, f"prior: must sum to exactly 1, got {total}")
    return tuple(p)
