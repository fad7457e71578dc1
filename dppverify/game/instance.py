"""The game instance: parse and validate the ``dpp`` instance JSON, exact distances.

The checker reads instances itself (``docs/formats.md`` §1) and validates the paper's
assumptions (Section III-A): positive weights, two distinct goals, a prior in (0, 1) summing
to 1, and finite full-graph distances ``d(s0, g1)``, ``d(s0, g2)``, ``d(g1, g2)``,
``d(g2, g1)`` (assumption (R) of proofs/README.md). Every violation raises
:class:`InvalidInstanceError` with a one-line message naming what and where.
"""

from __future__ import annotations

import json
import weakref
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from itertools import chain
from pathlib import Path
from types import MappingProxyType
from typing import Any, TypeVar

import numpy as np

from dppio.limits import check_float_weights
from dppverify.errors import InvalidInstanceError
from dppverify.exact import INF, Number, normalize
from dppverify.formats.json_reading import (
    JsonReadError,
    Node,
    node_from_json,
    node_to_json,
    parse_json_text,
    parse_number,
    read_json_file,
    show_node,
)
from dppverify.game.distances import (
    ArcArrays,
    ArcRows,
    dijkstra,
    hops_by_arrays,
    hops_to_targets,
    scaled_distance_fields,
    uniform_hops,
    unscale,
)
from dppverify.numbers import NumberMode, number_mode

__all__ = ["GameInstance", "Instance", "Node", "Roles", "arc_arrays", "as_instance",
           "goal_distance_fields",
           "instance_from_json",
           "load_game", "load_instance", "node_from_json", "node_to_json", "read_game",
           "show_node"]

NGOAL_REFUSAL = ("goals: this instance lists {n} goals; the two-goal checker reads exactly two. "
                 "N-goal instances are read by dppverify.ngoal (`dpp value` and `dpp certify` "
                 "dispatch on the number of goals)")
"""The two-goal parser's message for an instance with more than two goals."""


@dataclass(frozen=True)
class Roles:
    """Which goal plays ``g1`` (primary) and which ``g2`` (secondary), with priors/distances.

    Attributes
    ----------
    g1, g2 : int
        Node indices of the primary and secondary goals.
    b1, b2 : Fraction
        Their priors (``b1 >= b2``, except when a profile labels a 1/2-1/2 tie the other way,
        which the paper's footnote 2 allows).
    d1, d2 : tuple
        Full-graph distances from every node to ``g1`` / ``g2`` (``math.inf`` if unreachable).
    """

    g1: int
    g2: int
    b1: Fraction
    b2: Fraction
    d1: tuple[Number, ...]
    d2: tuple[Number, ...]

    def dist(self, theta: int) -> tuple[Number, ...]:
        """Distances to the true goal of type ``theta`` (1 = primary, 2 = secondary)."""
        return self.d1 if theta == 1 else self.d2

    def prior(self, theta: int) -> Fraction:
        """Prior of type ``theta`` (1 = primary, 2 = secondary)."""
        return self.b1 if theta == 1 else self.b2


@dataclass(frozen=True, eq=False)
class GameInstance:
    """A validated game instance with ``N >= 2`` goals: graph, start, goals, prior, distances.

    What the two-goal :class:`Instance` and the N-goal
    :class:`~dppverify.ngoal.instance.NInstance` share; both are read by :func:`read_game`.
    Nodes are numbered ``0 .. n-1`` in document order; ``nodes[i]`` is the id of node ``i``.

    Attributes
    ----------
    nodes : tuple
        Node ids (JSON lists converted to tuples).
    index : Mapping
        Node id -> index.
    directed : bool
        False when every edge can be walked both ways.
    succ, pred : ArcRows
        ``succ[u]`` = arcs ``(v, w)`` leaving ``u``; ``pred[v]`` = arcs ``(u, w)`` entering ``v``
        (tuples built on access from arrays, :class:`~dppverify.game.distances.ArcRows`).
    start : int
        ``s0``.
    goals : tuple of int
        The goals in document order; ``prior[i]`` belongs to ``goals[i]``.
    prior : tuple of Fraction
        Exact priors (always exact, also in float mode).
    exact : bool
        False in float mode (``"numbers": "float"``, two goals only): weights are binary floats.
    dist_to : tuple
        ``dist_to[i][v]`` = full-graph ``d(v, goals[i])`` (``math.inf`` if unreachable).
    hops : tuple of int
        Fewest steps from each node to the nearest goal (``-1`` if none): tree pruning.
    """

    nodes: tuple[Node, ...]
    index: Mapping[Node, int]
    directed: bool
    succ: Sequence[tuple[tuple[int, Number], ...]]
    pred: Sequence[tuple[tuple[int, Number], ...]]
    start: int
    goals: tuple[int, ...]
    prior: tuple[Fraction, ...]
    exact: bool
    dist_to: tuple[tuple[Number, ...], ...]
    hops: tuple[int, ...]

    @property
    def numbers(self) -> NumberMode:
        """The number mode (:mod:`dppverify.numbers`): exact, or float within a relative
        tolerance."""
        return number_mode(self.exact)

    @property
    def n_nodes(self) -> int:
        """Number of nodes."""
        return len(self.nodes)

    def is_goal(self, node: int) -> bool:
        """True for the candidate goals."""
        return node in self.goals

    def weight(self, u: int, v: int) -> Number | None:
        """Weight of the arc ``u -> v``, or None when there is no such arc."""
        if isinstance(self.succ, ArcRows):
            return self.succ.find(u, v)
        for head, w in self.succ[u]:
            if head == v:
                return w
        return None

    def weights_along(self, walk: Sequence[int]) -> list[Number | None]:
        """``weight(walk[t-1], walk[t])`` for ``t = 1 .. len(walk) - 1`` (None: no such arc).

        Examples
        --------
        >>> from dppverify.game.examples import triangle
        >>> triangle().weights_along([0, 2, 1, 1])
        [2, 2, None]
        """
        if isinstance(self.succ, ArcRows) and len(walk) > 8:
            return self.succ.find_many(walk[:-1], walk[1:])
        return [self.weight(walk[t - 1], walk[t]) for t in range(1, len(walk))]

    def label(self, v: int) -> Node:
        """The node id of index ``v``."""
        return self.nodes[v]

    def labels(self, walk: tuple[int, ...] | list[int]) -> tuple[Node, ...]:
        """Node ids of a walk given as indices."""
        return tuple(self.nodes[v] for v in walk)


@dataclass(frozen=True, eq=False)
class Instance(GameInstance):
    """A validated DPP game instance (paper, Section III-A) with exact distances.

    A :class:`GameInstance` with exactly two goals, plus the paper's (primary, secondary)
    labelling (:meth:`roles`). Every attribute is that of :class:`GameInstance`; these hold
    two entries:

    Attributes
    ----------
    goals : tuple of int
        The two goals in document order; ``prior[i]`` belongs to ``goals[i]``.
    prior : tuple of Fraction
        Exact priors (always exact, also in float mode).
    dist_to : tuple
        ``dist_to[i][v]`` = full-graph ``d(v, goals[i])`` (``math.inf`` if unreachable).

    Examples
    --------
    >>> doc = {"graph": {"directed": False, "nodes": [{"id": "s"}, {"id": "g1"}, {"id": "g2"}],
    ...        "edges": [{"source": "s", "target": "g2", "weight": 2},
    ...                  {"source": "g2", "target": "g1", "weight": 2},
    ...                  {"source": "s", "target": "g1", "weight": 3}]},
    ...        "start": "s", "goals": ["g1", "g2"], "prior": ["7/10", "3/10"]}
    >>> inst = instance_from_json(doc)
    >>> r = inst.roles()
    >>> inst.nodes[r.g1], r.b1, r.d1[inst.start], r.d2[r.g1]
    ('g1', Fraction(7, 10), 3, 2)
    """

    goals: tuple[int, int]
    prior: tuple[Fraction, Fraction]
    dist_to: tuple[tuple[Number, ...], tuple[Number, ...]]

    @property
    def primary_slot(self) -> int:
        """Document position (0 or 1) of the primary goal: larger prior, ``goals[0]`` at a tie."""
        return 1 if self.prior[1] > self.prior[0] else 0

    @property
    def tied(self) -> bool:
        """True at prior 1/2 - 1/2, where either goal may be called primary (footnote 2)."""
        return self.prior[0] == self.prior[1]

    def slot(self, node: int) -> int | None:
        """Document position of goal ``node``, or None if it is not a goal."""
        if node == self.goals[0]:
            return 0
        if node == self.goals[1]:
            return 1
        return None

    def is_goal(self, node: int) -> bool:
        """True for the two candidate goals."""
        return node == self.goals[0] or node == self.goals[1]

    def roles(self, primary_slot: int | None = None) -> Roles:
        """The (primary, secondary) labelling; default: the instance's primary goal."""
        i = self.primary_slot if primary_slot is None else primary_slot
        j = 1 - i
        return Roles(g1=self.goals[i], g2=self.goals[j], b1=self.prior[i], b2=self.prior[j],
                     d1=self.dist_to[i], d2=self.dist_to[j])


def as_instance(instance: Any) -> Instance:
    """An :class:`Instance` from any of the forms the public API accepts (duck typing).

    Parameters
    ----------
    instance : Instance, Mapping, str, Path, or an object with ``to_json()``
        Returned as is; parsed (a document); loaded (a file path); or, for any object with a
        ``to_json()`` method returning a document (e.g. the solver's ``Instance``), parsed
        from that document. ``dppverify`` never imports the solver: only the JSON is used.

    Returns
    -------
    Instance

    Raises
    ------
    InvalidInstanceError
        The input is none of these, or not a valid instance.

    Examples
    --------
    >>> from dppverify.game.examples import triangle_document
    >>> class Foreign:  # any object that can write the instance JSON
    ...     def to_json(self):
    ...         return triangle_document()
    >>> as_instance(Foreign()).prior
    (Fraction(7, 10), Fraction(3, 10))
    >>> as_instance(42)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    dppverify.errors.InvalidInstanceError: an instance must be ... with to_json(); got int ...
    """
    if isinstance(instance, Instance):
        return instance
    if isinstance(instance, Mapping):
        return instance_from_json(instance)
    if isinstance(instance, str | Path):
        return load_instance(instance)
    to_json = getattr(instance, "to_json", None)
    if callable(to_json):
        doc = to_json()
        if isinstance(doc, Mapping | str | bytes):
            return instance_from_json(doc)
    raise InvalidInstanceError(
        "an instance must be an Instance, a JSON document (dict), a file path or an object "
        f"with to_json(); got {type(instance).__name__} (the solver's Instance and "
        "Equilibrium have to_json())")


def load_instance(path: str | Path) -> Instance:
    """Read and validate an instance JSON file.

    Raises
    ------
    InvalidInstanceError
        One line ``PATH: what is wrong`` for unreadable, malformed or invalid instances.

    Examples
    --------
    >>> load_instance("/nonexistent.json")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: /nonexistent.json: cannot read instance file ...
    """
    return load_game(path, Instance, two_goals=True)


def instance_from_json(doc: Mapping[str, Any] | str | bytes) -> Instance:
    """Build a validated :class:`Instance` from the instance document (dict or JSON text).

    Raises
    ------
    InvalidInstanceError
        For malformed documents and for instances violating the game's assumptions.

    Examples
    --------
    >>> instance_from_json('{"graph": {"nodes": [{"id": 1}], "edges": []}, "start": 1, '
    ...                    '"goals": [1, 1], "prior": [0.5, 0.5]}')
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: goals: the two goals must differ, both are 1
    """
    return read_game(doc, Instance, two_goals=True)


def _require(cond: bool, message: str) -> None:
    if not cond:
        raise InvalidInstanceError(message)


G = TypeVar("G", bound=GameInstance)


def load_game(path: str | Path, cls: type[G], *, two_goals: bool) -> G:
    """Read and validate an instance file into ``cls`` (:func:`read_game` on its document).

    Raises
    ------
    InvalidInstanceError
        One line ``PATH: what is wrong`` for unreadable, malformed or invalid instances.

    Examples
    --------
    >>> load_game("/nonexistent.json", GameInstance, two_goals=False)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: /nonexistent.json: cannot read instance file ...
    """
    p = Path(path)
    try:
        doc = read_json_file(p, kind="instance")
    except JsonReadError as exc:
        raise InvalidInstanceError(f"{p}: {exc}") from None
    try:
        return read_game(doc, cls, two_goals=two_goals, base=p.parent)
    except InvalidInstanceError as exc:
        raise InvalidInstanceError(f"{p}: {exc}") from None


def read_game(doc: Any, cls: type[G], *, two_goals: bool, base: Path | None = None) -> G:
    """Read and validate an instance document (parsed JSON, or JSON text) into ``cls``.

    The one graph/instance parser of the checker: the two-goal :class:`Instance`
    (``two_goals=True``: exactly two goals, float mode allowed, the two-goal messages) and the
    N-goal :class:`~dppverify.ngoal.instance.NInstance` (``two_goals=False``: ``N >= 2``
    goals, exact numbers only). A compact map instance (``"format": "dpp-map-instance/1"``,
    :mod:`dppverify.formats.map_instance`) is read from its map; a relative map path is relative to
    ``base`` (the instance file's directory; the working directory when None).

    Raises
    ------
    InvalidInstanceError
        One line naming what is wrong and where.

    Examples
    --------
    >>> from dppverify.game.examples import triangle_document
    >>> g = read_game(triangle_document(), GameInstance, two_goals=False)
    >>> g.labels(g.goals), g.prior
    (('g1', 'g2'), (Fraction(7, 10), Fraction(3, 10)))
    >>> read_game({**triangle_document(), "numbers": "float"}, GameInstance, two_goals=False)
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: numbers: N-goal instances must be exact \
("numbers": "exact")
    """
    if isinstance(doc, str | bytes):
        try:
            doc = parse_json_text(doc)
        except JsonReadError as exc:
            raise InvalidInstanceError(str(exc)) from None
    if isinstance(doc, Mapping) and "format" in doc:
        from dppverify.formats.map_instance import is_map_document, map_game

        if is_map_document(doc):
            return map_game(doc, cls, two_goals=two_goals, base=base)
    try:
        return _read_game(doc, cls, two_goals)
    except InvalidInstanceError:
        raise
    except (ValueError, TypeError) as exc:  # parse_number / node_from_json messages
        raise InvalidInstanceError(str(exc)) from None


def _read_game(doc: Any, cls: type[G], two_goals: bool, *, fast: bool = True) -> G:
    _require(isinstance(doc, Mapping), f"instance must be a JSON object, got {type(doc).__name__}")
    missing = [k for k in ("graph", "start", "goals", "prior") if k not in doc]
    _require(not missing, f"instance is missing key(s): {', '.join(missing)}")
    mode = doc.get("numbers", "exact")
    if two_goals:
        _require(mode in ("exact", "float"),
                 f"numbers: expected \"exact\" or \"float\", got {mode!r}")
    else:
        _require(mode == "exact",
                 "numbers: N-goal instances must be exact (\"numbers\": \"exact\")")
    exact = mode == "exact"
    regular = _regular_graph(doc["graph"], exact) if fast else None
    arcs: ArcArrays | None = None
    if regular is not None:
        ids, index, directed, succ_t, pred_t, arcs = regular
    else:
        ids, index, directed, succ = _graph(doc["graph"], exact)
        n = len(ids)
        succ_l = [tuple(sorted(s.items())) for s in succ]
        pred_l: list[list[tuple[int, Number]]] = [[] for _ in range(n)]
        for u in range(n):
            for v, w in succ_l[u]:
                pred_l[v].append((u, w))
        succ_t, pred_t = _rows(n, succ_l), _rows(n, pred_l)
    return finish_game(cls, ids, index, directed, succ_t, pred_t, arcs, exact=exact,
                       start=doc["start"], goals=doc["goals"], prior=doc["prior"],
                       two_goals=two_goals)


def finish_game(cls: type[G], ids: list[Node], index: dict[Node, int], directed: bool,
                succ_t: Sequence[tuple[tuple[int, Number], ...]],
                pred_t: Sequence[tuple[tuple[int, Number], ...]], arcs: ArcArrays | None,
                *, exact: bool, start: Any, goals: Any, prior: Any, two_goals: bool) -> G:
    """The game on a read graph: start, goals and prior (as JSON values) checked, distances.

    Shared by the JSON reader and the ``.map`` reader (:mod:`dppverify.formats.movingai`), so that a
    map read straight into arrays gives the very instance its JSON document gives.
    """
    if not exact:  # float mode: the weight-ratio limit (dppio.limits), before any search
        try:
            check_float_weights(arcs.values if arcs is not None else
                                [w for row in succ_t for _, w in row])
        except ValueError as exc:
            raise InvalidInstanceError(str(exc)) from None
    start = _node(start, index, "start")
    goals = _goals(goals, index, ids, two_goals)
    prior = _prior(prior, len(goals), two_goals)
    n = len(ids)
    fields = scaled_distance_fields(arcs, n, goals) if arcs is not None and exact else None
    if fields is not None:
        dist_to = tuple(tuple(unscale(row, fields[0])) for row in fields[1])
    else:  # float mode, an irregular document, or path sums past 2**53: exact Python numbers
        dist_to = tuple(tuple(map(normalize, dijkstra(pred_t, gi))) for gi in goals)
    for i, gi in enumerate(goals):
        name = show_node(ids[gi])
        _require(dist_to[i][start] != INF,
                 f"goal {name} is unreachable from start {show_node(ids[start])}")
        for gj in goals:
            other = show_node(ids[gj])
            _require(dist_to[i][gj] != INF, f"goal {name} is unreachable from goal {other}: "
                                            f"d({other}, {name}) is infinite")
    if fields is not None and arcs is not None and len(arcs.values) == 1:
        hops = tuple(uniform_hops(fields[1], int(arcs.values[0] * fields[0])))
    else:
        hops = tuple(hops_to_targets(pred_t, goals) if arcs is None
                     else hops_by_arrays(arcs, n, goals))
    game = cls(nodes=tuple(ids), index=MappingProxyType(index), directed=directed,
               succ=succ_t, pred=pred_t, start=start, goals=goals, prior=prior,
               exact=exact, dist_to=dist_to, hops=hops)
    if arcs is not None:
        _ARC_ARRAYS[game] = arcs
    if fields is not None:
        _GOAL_FIELDS[game] = (fields[0], dict(zip(goals, fields[1], strict=True)))
    return game


_ARC_ARRAYS: weakref.WeakKeyDictionary[GameInstance, ArcArrays] = weakref.WeakKeyDictionary()

_GOAL_FIELDS: weakref.WeakKeyDictionary[GameInstance, tuple[int, dict[int, np.ndarray]]] = \
    weakref.WeakKeyDictionary()


def goal_distance_fields(game: GameInstance) -> tuple[int, dict[int, np.ndarray]] | None:
    """``(scale, {goal: d(., goal) · scale})``: the float64 fields the reader computed
    ``dist_to`` from (exact integers), shared with later computations on the same graph; None
    when the reader used the exact Python Dijkstra.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> scale, rows = goal_distance_fields(triangle())
    >>> scale, rows[1].tolist()
    (1, [3.0, 0.0, 2.0])
    """
    return _GOAL_FIELDS.get(game)


def arc_arrays(game: GameInstance) -> ArcArrays:
    """The arcs of ``game`` as arrays in ``succ`` order (built once per instance).

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> a = arc_arrays(triangle())
    >>> a.tails.tolist(), a.heads.tolist(), [a.values[c] for c in a.codes]
    ([0, 0, 1, 1, 2, 2], [1, 2, 0, 2, 0, 1], [3, 2, 3, 2, 2, 2])
    """
    arcs = _ARC_ARRAYS.get(game)
    if arcs is None:
        arcs = _ARC_ARRAYS[game] = ArcArrays.from_adjacency(game.succ)
    return arcs


_Regular = tuple[list[Node], dict[Node, int], bool,
                 ArcRows, ArcRows, ArcArrays]


def _regular_graph(g: Any, exact: bool) -> _Regular | None:
    """:func:`_graph` without a Python loop per node and edge, for regular valid documents.

    Regular: node objects are dicts whose ids are all ``[int, int]`` cells, all strings or all
    ints; edges are dicts with ``source``/``target`` ids of that kind. Returns None on anything
    else and on any invalid input (a duplicate, an unknown node, a bad weight): then
    :func:`_graph` reads the document and says what is wrong, with its usual message. When it
    returns, the result is the one :func:`_graph` and the sorting in :func:`_read_game` give
    (tests/checker/test_fast_instance.py), plus the arcs as arrays.
    """
    if not isinstance(g, Mapping) or g.get("multigraph", False):
        return None
    directed = g.get("directed", False)
    raw_nodes = g.get("nodes")
    raw_edges = g.get("edges", g.get("links"))
    if not (type(directed) is bool and type(raw_nodes) is list and type(raw_edges) is list
            and _all_type(raw_nodes, dict) and _all_type(raw_edges, dict)):
        return None
    try:
        raw_ids = [nd["id"] for nd in raw_nodes]
        src = [e["source"] for e in raw_edges]
        dst = [e["target"] for e in raw_edges]
    except KeyError:
        return None
    ids: list[Node]
    if raw_ids and _cells(raw_ids):
        if not (_cells(src) and _cells(dst)):
            return None
        ids = list(map(tuple, raw_ids))
        src, dst = list(map(tuple, src)), list(map(tuple, dst))
    elif _all_type(raw_ids, str) or _all_type(raw_ids, int):
        kind = type(raw_ids[0]) if raw_ids else str
        if not (_all_type(src, kind) and _all_type(dst, kind)):
            return None
        ids = raw_ids
    else:
        return None
    n, m = len(ids), len(raw_edges)
    index = dict(zip(ids, range(n), strict=True))
    if len(index) != n:
        return None
    us, vs = list(map(index.get, src)), list(map(index.get, dst))
    if None in us or None in vs:
        return None
    raw_w = [e.get("weight", 1) for e in raw_edges]
    if not set(map(type, raw_w)) <= set(_SCALARS):
        return None
    keys = list(zip(map(type, raw_w), raw_w, strict=True))
    code = dict.fromkeys(keys)
    values: list[Number] = []
    for key in code:  # each distinct literal once, as _graph parses them
        try:
            w = parse_number(key[1], where="weight", allow_float=not exact)
        except (ValueError, TypeError):
            return None
        if not w > 0:
            return None
        code[key] = len(values)
        values.append(w)
    u = np.fromiter(us, dtype=np.int64, count=m)
    v = np.fromiter(vs, dtype=np.int64, count=m)
    c = (np.zeros(m, dtype=np.int64) if len(values) == 1
         else np.fromiter(map(code.__getitem__, keys), dtype=np.int64, count=m))
    built = edge_arrays(n, u, v, c, values, directed)
    if built is None:
        return None  # a duplicate arc
    return (ids, index, directed, *built)


def edge_arrays(n: int, u: np.ndarray, v: np.ndarray, c: np.ndarray, values: list[Number],
                directed: bool) -> tuple[ArcRows, ArcRows, ArcArrays] | None:
    """``succ``, ``pred`` and the arc arrays of the edges ``u[k] - v[k]`` of weight
    ``values[c[k]]`` (both ways unless ``directed``); None when an arc repeats.

    Examples
    --------
    >>> a = np.array([0, 1]); b = np.array([1, 2]); c = np.array([0, 0])
    >>> succ, pred, arcs = edge_arrays(3, a, b, c, [1], False)
    >>> tuple(succ), arcs.tails.tolist()
    ((((1, 1),), ((0, 1), (2, 1)), ((1, 1),)), [0, 1, 1, 2])
    >>> edge_arrays(2, np.array([0, 1]), np.array([1, 0]), c, [1], False) is None
    True
    """
    if not directed:
        back = u != v  # a self-loop is one arc
        u, v, c = (np.concatenate([u, v[back]]), np.concatenate([v, u[back]]),
                   np.concatenate([c, c[back]]))
    fwd = np.argsort(u * n + v, kind="stable")
    key_sorted = (u * n + v)[fwd]
    if key_sorted.size > 1 and bool((key_sorted[1:] == key_sorted[:-1]).any()):
        return None  # a duplicate arc
    tails, heads, codes = u[fwd], v[fwd], c[fwd]
    succ_t = _adjacency(n, tails, heads, codes, values)
    rev = np.argsort(heads * n + tails, kind="stable")
    pred_t = _adjacency(n, heads[rev], tails[rev], codes[rev], values)
    return succ_t, pred_t, ArcArrays(tails=tails, heads=heads, codes=codes, values=tuple(values))


def _rows(n: int, adj: Sequence[Sequence[tuple[int, Number]]]) -> ArcRows:
    """``adj`` (sorted rows) as :class:`ArcRows`."""
    a = ArcArrays.from_adjacency(adj)
    return ArcRows(n, a.tails, a.heads, a.codes, a.values)


def _all_type(xs: list[Any], t: type) -> bool:
    """Every item of ``xs`` has exactly type ``t`` (``bool`` is not ``int``)."""
    return not xs or set(map(type, xs)) == {t}


def _cells(xs: list[Any]) -> bool:
    """Every item is a list of two ints (a grid cell)."""
    return (_all_type(xs, list) and set(map(len, xs)) <= {2}
            and _all_type(list(chain.from_iterable(xs)), int))


def _adjacency(n: int, tails: np.ndarray, heads: np.ndarray, codes: np.ndarray,
               values: list[Number]) -> ArcRows:
    """``adj[u]`` = the ``(head, weight)`` pairs of the arcs out of ``u`` (arcs sorted by
    tail, then head)."""
    return ArcRows(n, tails, heads, codes, tuple(values))


def _graph(g: Any, exact: bool) -> tuple[list[Node], dict[Node, int], bool,
                                         list[dict[int, Number]]]:
    """Node ids, their index, ``directed`` and the successor maps of ``graph``."""
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
        raw = nd["id"]
        if type(raw) is list and len(raw) == 2 and type(raw[0]) is int and type(raw[1]) is int:
            v: Node = (raw[0], raw[1])  # a grid cell, the common case
        else:
            v = node_from_json(raw, where=f"graph.nodes[{k}].id")
        try:
            hash(v)
        except TypeError:
            raise InvalidInstanceError(f"graph.nodes[{k}].id: not a valid node id") from None
        if v in index:
            raise InvalidInstanceError(f"graph.nodes[{k}]: duplicate node id {show_node(v)}")
        index[v] = len(ids)
        ids.append(v)

    succ: list[dict[int, Number]] = [{} for _ in ids]
    weights: dict[tuple[type, Any], Number] = {}
    for k, e in enumerate(raw_edges):
        if not (isinstance(e, Mapping) and "source" in e and "target" in e):
            raise InvalidInstanceError(
                f"graph.edges[{k}]: must be an object with \"source\" and \"target\"")
        u = _edge_end(e["source"], index, k, "source")
        v = _edge_end(e["target"], index, k, "target")
        raw_w = e.get("weight", 1)
        key = (type(raw_w), raw_w) if type(raw_w) in _SCALARS else None
        w = weights.get(key) if key is not None else None
        if w is None:  # each distinct weight literal is parsed and checked once
            w = parse_number(raw_w, where=f"graph.edges[{k}].weight", allow_float=not exact)
            _require(w > 0, f"graph.edges[{k}].weight: must be positive, got {w}")
            if key is not None:
                weights[key] = w
        for a, b in ((u, v),) if directed or u == v else ((u, v), (v, u)):
            sa = succ[a]
            if b in sa:
                raise InvalidInstanceError(f"graph.edges[{k}]: duplicate edge "
                                           f"{show_node(ids[a])} -> {show_node(ids[b])}")
            sa[b] = w
    return ids, index, directed, succ


def _goals(raw: Any, index: Mapping[Node, int], ids: list[Node], two_goals: bool
           ) -> tuple[int, ...]:
    shown = json.dumps(raw, default=str)
    if two_goals:
        # --- N-goal hook: more than two goals belong to dppverify.ngoal (docs/formats.md §1) ---
        _require(not (isinstance(raw, list) and len(raw) > 2),
                 NGOAL_REFUSAL.format(n=len(raw) if isinstance(raw, list) else 0))
        _require(isinstance(raw, list) and len(raw) == 2,
                 f"goals: must be a list of two node ids, got {shown}")
        goals = (_node(raw[0], index, "goals[0]"), _node(raw[1], index, "goals[1]"))
        _require(goals[0] != goals[1], f"goals: the two goals must differ, both are "
                                       f"{show_node(ids[goals[0]])}")
        return goals
    _require(isinstance(raw, list) and len(raw) >= 2,
             f"goals: must be a list of at least two node ids, got {shown}")
    out: list[int] = []
    for i, x in enumerate(raw):
        gi = _node(x, index, f"goals[{i}]")
        _require(gi not in out, f"goals[{i}]: goal {show_node(ids[gi])} is listed twice")
        out.append(gi)
    return tuple(out)


_SCALARS = (str, int, Fraction, float)
"""Weight literals of these types are parsed once per distinct value (keyed with the type)."""


def _edge_end(raw: Any, index: Mapping[Node, int], k: int, key: str) -> int:
    """The index of an edge's end; the common ids (``[r, c]``, ints, strings) without copies."""
    if type(raw) is list and len(raw) == 2 and type(raw[0]) is int and type(raw[1]) is int:
        i = index.get((raw[0], raw[1]))
    elif type(raw) is str or type(raw) is int:
        i = index.get(raw)
    else:
        i = None
    if i is not None:
        return i
    v = node_from_json(raw, where=f"graph.edges[{k}].{key}")
    _require(_known(index, v), f"graph.edges[{k}].{key}: unknown node {show_node(v)}")
    return index[v]


def _known(index: Mapping[Node, int], v: Node) -> bool:
    try:
        return v in index
    except TypeError:
        return False


def _node(raw: Any, index: Mapping[Node, int], where: str) -> int:
    v = node_from_json(raw, where=where)
    _require(_known(index, v), f"{where}: unknown node {show_node(v)}")
    return index[v]


def _prior(raw: Any, n: int, two_goals: bool) -> tuple[Fraction, ...]:
    _require(isinstance(raw, list) and len(raw) == n,
             f"prior: must be a list of two numbers, got {json.dumps(raw, default=str)}"
             if two_goals else f"prior: must be a list of {n} numbers (one per goal), got "
                               f"{json.dumps(raw, default=str)}")
    p = [Fraction(parse_number(x, where=f"prior[{i}]")) for i, x in enumerate(raw)]
    for i, x in enumerate(p):
        _require(0 < x < 1, f"prior[{i}]: must lie strictly between 0 and 1, got {x}")
    total = sum(p, Fraction(0))
    _require(total == 1, f"prior: must sum to exactly 1, got {p[0]} + {p[1]} = {total}"
                         if two_goals else f"prior: must sum to exactly 1, got {total}")
    return tuple(p)
