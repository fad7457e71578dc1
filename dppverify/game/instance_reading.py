"""Reading the instance document: the start, goals and prior checked, distances computed.

The parsing half of :mod:`dppverify.game.instance` (which builds the
:class:`~dppverify.game.instance.Instance` from what this module computes), on a graph read by
:mod:`dppverify.game.graph_reading`: the start, goal and prior checks under the two-goal or the
N-goal rules (:func:`read_goals`, :func:`read_prior`), the distances to the goals and the hops
(:func:`game_parts`), and the arrays kept per instance (:func:`arc_arrays`,
:func:`goal_distance_fields`).
"""

from __future__ import annotations

import weakref
from collections.abc import Mapping, Sequence
from fractions import Fraction
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from dppio.limits import check_float_weights
from dppio.limits import common_denominator as bounded_denominator
from dppio.text import json_shown
from dppverify.errors import InvalidInstanceError
from dppverify.exact import INF, normalize
from dppverify.formats.json_reading import Node, node_from_json, parse_number, show_node
from dppverify.game.distances import (
    ArcArrays,
    dijkstra,
    hops_by_arrays,
    hops_to_targets,
    scaled_distance_fields,
    uniform_hops,
    unscale,
)
from dppverify.game.graph_reading import ReadGraph, known_node, require
from dppverify.limits import MAX_GOALS

if TYPE_CHECKING:
    from dppverify.game.instance import Instance


FLOAT_REFUSAL = 'numbers: N-goal instances must be exact ("numbers": "exact")'
"""Why a document with more than two goals cannot be in float mode (:func:`exact_mode`)."""


def two_goal_rules(raw_goals: Any) -> bool:
    """True when a document lists exactly two goals: it is read under the two-goal rules
    (float numbers allowed, the messages say "two"); otherwise under the N-goal rules (exact
    numbers, "N numbers (one per goal)").

    Examples
    --------
    >>> two_goal_rules(["a", "b"]), two_goal_rules(["a", "b", "c"]), two_goal_rules("a")
    (True, False, False)
    """
    return isinstance(raw_goals, list) and len(raw_goals) == 2


def exact_mode(mode: Any, raw_goals: Any) -> bool:
    """Whether a document's ``numbers`` (``mode``) makes the game exact: the one place where
    float numbers are allowed, for two goals only (the paper's float maps; the N-goal
    mathematics is exact).

    Raises
    ------
    InvalidInstanceError
        ``mode`` is neither ``"exact"`` nor ``"float"``, or ``"float"`` with more goals.

    Examples
    --------
    >>> exact_mode("exact", ["a", "b", "c"]), exact_mode("float", ["a", "b"])
    (True, False)
    >>> exact_mode("float", ["a", "b", "c"])
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: numbers: N-goal instances must be exact \
("numbers": "exact")
    """
    if two_goal_rules(raw_goals):
        require(mode in ("exact", "float"),
                f"numbers: expected \"exact\" or \"float\", got {mode!r}")
    else:
        require(mode == "exact", FLOAT_REFUSAL)
    return mode == "exact"


class GameParts(NamedTuple):
    """What :func:`game_parts` computes: the instance's fields, and the float64 distance
    fields ``(scale, {goal: d(., goal) · scale})`` when it computed them (else None)."""

    fields: dict[str, Any]
    scaled: tuple[int, dict[int, np.ndarray]] | None


def game_parts(graph: ReadGraph, *, exact: bool, start: Any, goals: Any,
               prior: Any) -> GameParts:
    """The fields of the game on a read graph: start, goals and prior (JSON values) checked,
    distances to the goals, hops to the nearest goal.

    Examples
    --------
    >>> from dppverify.game.graph_reading import read_graph
    >>> g = {"nodes": [{"id": "s"}, {"id": "a"}, {"id": "b"}],
    ...      "edges": [{"source": "s", "target": "a"}, {"source": "a", "target": "b"}]}
    >>> parts = game_parts(read_graph(g, True), exact=True, start="s", goals=["a", "b"],
    ...                    prior=["1/2", "1/2"])
    >>> parts.fields["dist_to"], parts.fields["hops"], parts.scaled[0]
    (((1, 0, 1), (2, 1, 0)), (1, 0, 0), 1)
    """
    ids, index, directed, succ_t, pred_t, arcs = graph
    if not exact:  # float mode: the weight-ratio limit (dppio.limits), before any search
        try:
            check_float_weights(arcs.values if arcs is not None else
                                [w for row in succ_t for _, w in row])
        except ValueError as exc:
            raise InvalidInstanceError(str(exc)) from None
    two = two_goal_rules(goals)
    start = read_node(start, index, "start")
    goals = read_goals(goals, index, ids, two)
    prior = read_prior(prior, len(goals), two)
    if exact:  # one common denominator of bounded size, before any distance is summed
        weights = arcs.values if arcs is not None else [w for row in succ_t for _, w in row]
        bounded_denominator([*(w.denominator for w in weights if not isinstance(w, float)),
                             *(p.denominator for p in prior)],
                            where="instance (edge weights and prior)",
                            error=InvalidInstanceError)
    n = len(ids)
    fields = scaled_distance_fields(arcs, n, goals) if arcs is not None and exact else None
    if fields is not None:
        dist_to = tuple(tuple(unscale(row, fields[0])) for row in fields[1])
    else:  # float mode, an irregular document, or path sums past 2**53: exact Python numbers
        dist_to = tuple(tuple(map(normalize, dijkstra(pred_t, gi))) for gi in goals)
    for i, gi in enumerate(goals):
        name = show_node(ids[gi])
        require(dist_to[i][start] != INF,
                f"goal {name} is unreachable from start {show_node(ids[start])}")
        for gj in goals:
            other = show_node(ids[gj])
            require(dist_to[i][gj] != INF, f"goal {name} is unreachable from goal {other}: "
                                           f"d({other}, {name}) is infinite")
    if fields is not None and arcs is not None and len(arcs.values) == 1:
        hops = tuple(uniform_hops(fields[1], int(arcs.values[0] * fields[0])))
    else:
        hops = tuple(hops_to_targets(pred_t, goals) if arcs is None
                     else hops_by_arrays(arcs, n, goals))
    scaled = (fields[0], dict(zip(goals, fields[1], strict=True))) if fields is not None else None
    # a list and a dict (the JSON reader) are frozen; a grid's lazy cells and index already are
    nodes = tuple(ids) if isinstance(ids, list) else ids
    frozen = MappingProxyType(index) if isinstance(index, dict) else index
    return GameParts(dict(nodes=nodes, index=frozen, directed=directed,
                          succ=succ_t, pred=pred_t, start=start, goals=goals, prior=prior,
                          exact=exact, dist_to=dist_to, hops=hops), scaled)


_ARC_ARRAYS: weakref.WeakKeyDictionary[Instance, ArcArrays] = weakref.WeakKeyDictionary()

_GOAL_FIELDS: weakref.WeakKeyDictionary[Instance, tuple[int, dict[int, np.ndarray]]] = \
    weakref.WeakKeyDictionary()


def goal_distance_fields(game: Instance) -> tuple[int, dict[int, np.ndarray]] | None:
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


def arc_arrays(game: Instance) -> ArcArrays:
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


def remember_arrays(game: Instance, arcs: ArcArrays | None,
                    scaled: tuple[int, dict[int, np.ndarray]] | None) -> None:
    """Keep the arrays the reader built for ``game`` (:func:`arc_arrays`,
    :func:`goal_distance_fields`), for as long as ``game`` lives.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> inst = triangle()
    >>> remember_arrays(inst, None, None); goal_distance_fields(inst)[0]
    1
    """
    if arcs is not None:
        _ARC_ARRAYS[game] = arcs
    if scaled is not None:
        _GOAL_FIELDS[game] = scaled


def read_goals(raw: Any, index: Mapping[Node, int], ids: Sequence[Node], two: bool
               ) -> tuple[int, ...]:
    """The goals (node indices, document order) of the JSON list ``raw``: at least two, each
    listed once (``two``: the two-goal messages, :func:`two_goal_rules`).

    Examples
    --------
    >>> read_goals(["b", "a", "c"], {"a": 0, "b": 1, "c": 2}, ["a", "b", "c"], False)
    (1, 0, 2)
    >>> read_goals(["b", "b"], {"a": 0, "b": 1}, ["a", "b"], True)
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: goals: the two goals must differ, both are "b"
    """
    shown = json_shown(raw)
    if two:
        goals = (read_node(raw[0], index, "goals[0]"), read_node(raw[1], index, "goals[1]"))
        require(goals[0] != goals[1], f"goals: the two goals must differ, both are "
                                      f"{show_node(ids[goals[0]])}")
        return goals
    require(isinstance(raw, list) and len(raw) >= 2,
            f"goals: must be a list of at least two node ids, got {shown[:200]}")
    # distances to every goal are computed on reading: bounded before any of them
    require(len(raw) <= MAX_GOALS, f"goals: {len(raw)} goals, beyond the limit of {MAX_GOALS}")
    out: list[int] = []
    seen: set[int] = set()
    for i, x in enumerate(raw):
        gi = read_node(x, index, f"goals[{i}]")
        require(gi not in seen, f"goals[{i}]: goal {show_node(ids[gi])} is listed twice")
        seen.add(gi)
        out.append(gi)
    return tuple(out)


def read_node(raw: Any, index: Mapping[Node, int], where: str) -> int:
    """The index of the node id ``raw`` (a JSON value) found at ``where``.

    Examples
    --------
    >>> read_node("b", {"a": 0, "b": 1}, "start")
    1
    >>> read_node("z", {"a": 0}, "start")
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: start: unknown node "z"
    """
    v = node_from_json(raw, where=where)
    require(known_node(index, v), f"{where}: unknown node {show_node(v)}")
    return index[v]


def read_prior(raw: Any, n: int, two: bool) -> tuple[Fraction, ...]:
    """The exact prior of ``n`` goals: each in (0, 1), summing to exactly 1.

    ``two``: the two-goal messages ("a list of two numbers", "got p + q = s").

    Examples
    --------
    >>> read_prior(["1/2", "1/3", "1/6"], 3, False)
    (Fraction(1, 2), Fraction(1, 3), Fraction(1, 6))
    >>> read_prior(["1/2", "1/3"], 2, True)
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: prior: must sum to exactly 1, got 1/2 + 1/3 = 5/6
    """
    require(isinstance(raw, list) and len(raw) == n,
            f"prior: must be a list of two numbers, one per goal, got {json_shown(raw)}"
            if two else f"prior: must be a list of {n} numbers (one per goal), got "
                               f"{json_shown(raw)}")
    p = [Fraction(parse_number(x, where=f"prior[{i}]")) for i, x in enumerate(raw)]
    for i, x in enumerate(p):
        require(0 < x < 1, f"prior[{i}]: must lie strictly between 0 and 1, got {x}")
    total = sum(p, Fraction(0))
    require(total == 1, f"prior: must sum to exactly 1, got {p[0]} + {p[1]} = {total}"
                        if two else f"prior: must sum to exactly 1, got {total}")
    return tuple(p)
