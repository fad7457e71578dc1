"""Reading an instance document's graph: node ids, arcs and weights into arrays.

The graph half of the instance reader (:mod:`dppverify.game.instance_reading`): node-link
graphs (``docs/formats.md`` §1) read either by a vectorised reader for regular documents
(:func:`regular_graph`) or node by node with one-line messages naming what is wrong and where
(:func:`plain_graph`); the arcs as arrays (:func:`edge_arrays`, also used by the ``.map``
reader).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from fractions import Fraction
from itertools import chain
from typing import Any

import numpy as np

from dppverify.errors import InvalidInstanceError
from dppverify.exact import Number
from dppverify.formats.json_reading import Node, node_from_json, parse_number, show_node
from dppverify.game.arc_rows import ArcRows
from dppverify.game.distances import ArcArrays

Rows = Sequence[tuple[tuple[int, Number], ...]]
"""``succ`` or ``pred``: ``rows[u]`` = the ``(node, weight)`` pairs of ``u``'s arcs."""

Graph = tuple[list[Node], dict[Node, int], bool, Rows, Rows, ArcArrays | None]

ReadGraph = tuple[Sequence[Node], Mapping[Node, int], bool, Rows, Rows, ArcArrays | None]
"""What the game is built on: node ids, their index, ``directed``, the successor and
predecessor rows and the arcs as arrays (None: an irregular document); :data:`Graph` or a
map's arrays."""
"""Node ids, their index, ``directed``, ``succ``, ``pred`` and the arcs as arrays (or None)."""


def require(cond: bool, message: str) -> None:
    """Raise :class:`InvalidInstanceError` with ``message`` unless ``cond``.

    Examples
    --------
    >>> require(1 < 2, "never raised")
    >>> require(2 < 1, "start: unknown node")
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: start: unknown node
    """
    if not cond:
        raise InvalidInstanceError(message)


def read_graph(g: Any, exact: bool, *, fast: bool = True) -> Graph:
    """The graph of an instance document: ids, index, ``directed``, ``succ``, ``pred``, arcs.

    ``fast``: try :func:`regular_graph` first (the arcs then come as arrays); any document
    it does not take is read by :func:`plain_graph`, with its one-line messages.

    Examples
    --------
    >>> g = {"nodes": [{"id": "a"}, {"id": "b"}], "edges": [{"source": "a", "target": "b"}]}
    >>> ids, index, directed, succ, pred, arcs = read_graph(g, True)
    >>> ids, tuple(succ), tuple(pred), arcs is not None
    (['a', 'b'], (((1, 1),), ((0, 1),)), (((1, 1),), ((0, 1),)), True)
    >>> read_graph({"nodes": [], "edges": [{"source": "a"}]}, True)
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: graph.edges[0]: must be an object with "source" \
and "target"
    """
    regular = regular_graph(g, exact) if fast else None
    if regular is not None:
        return regular
    ids, index, directed, succ = plain_graph(g, exact)
    n = len(ids)
    succ_l = [tuple(sorted(s.items())) for s in succ]
    pred_l: list[list[tuple[int, Number]]] = [[] for _ in range(n)]
    for u in range(n):
        for v, w in succ_l[u]:
            pred_l[v].append((u, w))
    return ids, index, directed, _rows(n, succ_l), _rows(n, pred_l), None


def regular_graph(g: Any, exact: bool) -> Graph | None:
    """:func:`plain_graph` without a Python loop per node and edge, for regular valid documents.

    Regular: node objects are dicts whose ids are all ``[int, int]`` cells, all strings or all
    ints; edges are dicts with ``source``/``target`` ids of that kind. Returns None on anything
    else and on any invalid input (a duplicate, an unknown node, a bad weight): then
    :func:`plain_graph` reads the document and says what is wrong, with its usual message. When it
    returns, the result is the one :func:`plain_graph` and the sorting in :func:`read_graph` give
    (tests/dppverify/game/test_fast_instance.py), plus the arcs as arrays.

    Examples
    --------
    >>> g = {"nodes": [{"id": [0, 0]}, {"id": [0, 1]}],
    ...      "edges": [{"source": [0, 0], "target": [0, 1], "weight": "3/2"}]}
    >>> ids, index, directed, succ, pred, arcs = regular_graph(g, True)
    >>> ids, succ[0], arcs.values
    ([(0, 0), (0, 1)], ((1, Fraction(3, 2)),), (Fraction(3, 2),))
    >>> regular_graph({**g, "edges": g["edges"] * 2}, True) is None  # a duplicate: plain_graph
    True
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
    for key in code:  # each distinct literal once, as plain_graph parses them
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
    return succ_t, pred_t, ArcArrays(tails=tails, heads=heads, codes=codes, values=tuple(values),
                                     symmetric=not directed)


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

def plain_graph(g: Any, exact: bool) -> tuple[list[Node], dict[Node, int], bool,
                                         list[dict[int, Number]]]:
    """Node ids, their index, ``directed`` and the successor maps of ``graph``.

    Examples
    --------
    >>> plain_graph({"directed": True, "nodes": [{"id": "a"}, {"id": "b"}],
    ...              "edges": [{"source": "a", "target": "b", "weight": 2}]}, True)
    (['a', 'b'], {'a': 0, 'b': 1}, True, [{1: 2}, {}])
    >>> plain_graph({"nodes": [{"id": "a"}, {"id": "a"}], "edges": []}, True)
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: graph.nodes[1]: duplicate node id "a"
    """
    require(isinstance(g, Mapping), "graph: must be a node-link JSON object")
    require(not g.get("multigraph", False), "graph: multigraphs are not supported")
    directed = g.get("directed", False)
    require(isinstance(directed, bool), f"graph.directed: expected true/false, got {directed!r}")
    raw_nodes = g.get("nodes")
    raw_edges = g.get("edges", g.get("links"))
    require(isinstance(raw_nodes, list), "graph.nodes: must be a list of {\"id\": ...} objects")
    require(isinstance(raw_edges, list), "graph.edges: must be a list of edge objects")

    ids: list[Node] = []
    index: dict[Node, int] = {}
    for k, nd in enumerate(raw_nodes):
        require(isinstance(nd, Mapping) and "id" in nd,
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
            require(w > 0, f"graph.edges[{k}].weight: must be positive, got {w}")
            if key is not None:
                weights[key] = w
        for a, b in ((u, v),) if directed or u == v else ((u, v), (v, u)):
            sa = succ[a]
            if b in sa:
                raise InvalidInstanceError(f"graph.edges[{k}]: duplicate edge "
                                           f"{show_node(ids[a])} -> {show_node(ids[b])}")
            sa[b] = w
    return ids, index, directed, succ


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
    require(known_node(index, v), f"graph.edges[{k}].{key}: unknown node {show_node(v)}")
    return index[v]


def known_node(index: Mapping[Node, int], v: Node) -> bool:
    """True when ``v`` is a node id of ``index`` (False for unhashable ids).

    Examples
    --------
    >>> known_node({"a": 0}, "a"), known_node({"a": 0}, ("b",))
    (True, False)
    """
    try:
        return v in index
    except TypeError:
        return False
