"""Hypothesis strategies for weighted graphs (networkx node-link dicts).

Also the helpers the package's other modules share (not exported): the argument checks
(``check_int``, ``check_bool``), the weight strategy (``weight_strategy``) and the graph
adjacency of a drawn node-link dict (``Adjacency``, ``edges_of``).
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Hashable, Iterable, Sequence
from fractions import Fraction
from numbers import Real
from typing import Any

from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument

WEIGHT_KINDS = ("units", "integers", "fractions", "floats")
"""Named edge-weight kinds: all 1; integers; exact fractions ``"p/q"``; binary floats."""

Doc = dict[str, Any]


# ----------------------------------------------------------------------------- validation
def check_int(value: object, name: str, minimum: int) -> int:
    """``value`` when it is an integer (not a bool) of at least ``minimum``, else
    hypothesis' ``InvalidArgument`` naming ``name``."""
    if isinstance(value, bool) or not isinstance(value, int):
        raise InvalidArgument(f"{name}={value!r} must be an integer")
    if value < minimum:
        raise InvalidArgument(f"{name}={value!r} must be at least {minimum}")
    return value


def check_bool(value: object, name: str, *, allow_none: bool = False) -> None:
    """Refuse a ``value`` that is not a bool (or None, with ``allow_none``)."""
    if not (isinstance(value, bool) or (allow_none and value is None)):
        what = "True, False or None" if allow_none else "True or False"
        raise InvalidArgument(f"{name}={value!r} must be {what}")


def weight_strategy(weights: object, min_weight: object, max_weight: object,
                     max_denominator: object) -> st.SearchStrategy[Any]:
    """The strategy of one JSON edge weight (int, ``"p/q"`` string or float)."""
    if isinstance(weights, st.SearchStrategy):
        return weights.map(_positive_weight)
    if weights not in WEIGHT_KINDS:
        raise InvalidArgument(f"weights={weights!r} must be one of {WEIGHT_KINDS} or a "
                              "strategy of positive numbers")
    for name, value in (("min_weight", min_weight), ("max_weight", max_weight)):
        if isinstance(value, bool) or not isinstance(value, Real) or not math.isfinite(value):
            raise InvalidArgument(f"{name}={value!r} must be a finite number")
    lo, hi = Fraction(str(min_weight)), Fraction(str(max_weight))
    if lo <= 0:
        raise InvalidArgument(f"min_weight={min_weight!r} must be positive")
    if hi < lo:
        raise InvalidArgument(f"max_weight={max_weight!r} < min_weight={min_weight!r}")
    q_max = check_int(max_denominator, "max_denominator", 1)
    if weights == "units":
        return st.just(1)
    if weights == "integers":
        i_lo, i_hi = math.ceil(lo), math.floor(hi)
        if i_lo > i_hi:
            raise InvalidArgument(f"no integer weight in [{min_weight}, {max_weight}]")
        return st.integers(i_lo, i_hi)
    if weights == "floats":
        return st.floats(float(lo), float(hi), allow_nan=False, allow_infinity=False)

    def fractions_with(q: int) -> st.SearchStrategy[Any]:
        p_lo, p_hi = math.ceil(lo * q), math.floor(hi * q)
        if p_lo > p_hi:  # no multiple of 1/q in range: fall back to the bounds themselves
            return st.sampled_from(sorted({str(lo), str(hi)}))
        return st.integers(p_lo, p_hi).map(lambda p: _fraction_json(Fraction(p, q)))

    return st.integers(1, q_max).flatmap(fractions_with)


def _fraction_json(x: Fraction) -> int | str:
    return int(x) if x.denominator == 1 else f"{x.numerator}/{x.denominator}"


def _positive_weight(w: object) -> Any:
    """Check a user-supplied weight and encode it for JSON."""
    number_like = isinstance(w, Real | str) and not isinstance(w, bool)  # w stays `object`
    if not number_like:
        raise InvalidArgument(f"weights strategy produced {w!r}, not a number")
    try:
        value = Fraction(str(w)) if not isinstance(w, Fraction) else w
    except (ValueError, ZeroDivisionError):
        raise InvalidArgument(f"weights strategy produced {w!r}, not a number") from None
    if value <= 0:
        raise InvalidArgument(f"weights strategy produced {w!r}: weights must be positive")
    if isinstance(w, float):
        return w
    if isinstance(w, str):
        return w
    return _fraction_json(value)


# ----------------------------------------------------------------------------- graphs
def weighted_graphs(
    *,
    min_nodes: int = 2,
    max_nodes: int = 8,
    directed: bool | None = None,
    weights: str | st.SearchStrategy[Any] = "integers",
    min_weight: int | float | Fraction = 1,
    max_weight: int | float | Fraction = 9,
    max_denominator: int = 6,
    max_extra_edges: int | None = None,
    strongly_connected: bool = True,
) -> st.SearchStrategy[Doc]:
    """Weighted graphs as networkx node-link dicts (the ``graph`` object of an instance).

    Nodes are the integers ``0 .. n-1``. With ``strongly_connected`` (the default) every node
    can reach every other: node ``i`` is joined to an earlier node (undirected), or gets one
    arc from and one arc to earlier nodes (directed), before up to ``max_extra_edges`` more
    edges are added. Without it the edges are arbitrary (possibly none);
    :func:`~dppverify.strategies.instances.instances`
    then chooses (or, if needed, connects) the goals so the game stays well defined.

    Parameters
    ----------
    min_nodes, max_nodes : int
        Bounds on the number of nodes (``2 <= min_nodes <= max_nodes``).
    directed : bool or None
        ``False``/``True`` for undirected/directed graphs; ``None`` draws both (shrinking to
        undirected).
    weights : {"units", "integers", "fractions", "floats"} or SearchStrategy
        Named kinds draw from ``[min_weight, max_weight]``: ``"fractions"`` are exact
        ``"p/q"`` strings with ``q <= max_denominator`` (integers written as ints),
        ``"floats"`` are binary floats (instances then say ``"numbers": "float"``). A
        strategy must produce positive ints, Fractions, floats or number strings.
    min_weight, max_weight : number
        Weight range of the named kinds (``0 < min_weight <= max_weight``).
    max_denominator : int
        Largest denominator of ``"fractions"`` weights.
    max_extra_edges : int or None
        Edges beyond the spanning scaffold (default: ``max_nodes``).
    strongly_connected : bool
        Build on a strongly connected scaffold (see above).

    Returns
    -------
    SearchStrategy of dict
        ``{"directed", "multigraph": False, "graph": {}, "nodes", "edges"}``.

    Raises
    ------
    hypothesis.errors.InvalidArgument
        For impossible arguments.

    Examples
    --------
    >>> from hypothesis import find, settings
    >>> g = find(weighted_graphs(min_nodes=3, directed=True), lambda g: True,
    ...          settings=settings(database=None))
    >>> g["directed"], [e["source"] for e in g["edges"]], [e["target"] for e in g["edges"]]
    (True, [0, 1, 0, 2], [1, 0, 2, 0])
    >>> weighted_graphs(min_nodes=1)
    Traceback (most recent call last):
    hypothesis.errors.InvalidArgument: min_nodes=1 must be at least 2
    """
    lo = check_int(min_nodes, "min_nodes", 2)
    hi = check_int(max_nodes, "max_nodes", 2)
    if hi < lo:
        raise InvalidArgument(f"max_nodes={max_nodes} < min_nodes={min_nodes}")
    check_bool(directed, "directed", allow_none=True)
    check_bool(strongly_connected, "strongly_connected")
    extra = hi if max_extra_edges is None else check_int(max_extra_edges, "max_extra_edges", 0)
    weight = weight_strategy(weights, min_weight, max_weight, max_denominator)
    directions = st.booleans() if directed is None else st.just(directed)
    return _graphs(lo, hi, directions, weight, extra, strongly_connected)


@st.composite
def _graphs(draw: st.DrawFn, lo: int, hi: int, directions: st.SearchStrategy[bool],
            weight: st.SearchStrategy[Any], extra: int, scaffold: bool) -> Doc:
    n = draw(st.integers(lo, hi))
    is_directed = draw(directions)
    arcs: dict[tuple[int, int], Any] = {}

    def add(u: int, v: int) -> None:
        key = (u, v) if is_directed else (min(u, v), max(u, v))
        if u != v and key not in arcs:
            arcs[key] = draw(weight)

    if scaffold:
        for i in range(1, n):
            add(draw(st.integers(0, i - 1)), i)
            if is_directed:
                add(i, draw(st.integers(0, i - 1)))
    pair = st.tuples(st.integers(0, n - 1), st.integers(0, n - 2)).map(
        lambda uv: (uv[0], uv[1] + (uv[1] >= uv[0])))  # u != v by construction
    for u, v in draw(st.lists(pair, max_size=extra)):
        add(u, v)
    return {"directed": is_directed, "multigraph": False, "graph": {},
            "nodes": [{"id": i} for i in range(n)],
            "edges": [{"source": u, "target": v, "weight": w} for (u, v), w in arcs.items()]}



def _key(x: Any) -> Hashable:
    return tuple(_key(y) for y in x) if isinstance(x, list) else x


class Adjacency:
    """Successor/predecessor sets of a node-link dict (node positions as indices)."""

    def __init__(self, graph: object) -> None:  # whatever a user's strategy drew
        if not (isinstance(graph, dict) and isinstance(graph.get("nodes"), list)
                and len(graph["nodes"]) >= 2):
            raise InvalidArgument("graphs must produce node-link dicts with at least 2 nodes")
        nodes = graph["nodes"]
        self.ids = [nd["id"] for nd in nodes]
        self.index = {_key(v): i for i, v in enumerate(self.ids)}
        self.directed = bool(graph.get("directed", False))
        n = len(self.ids)
        self.succ: list[set[int]] = [set() for _ in range(n)]
        self.pred: list[set[int]] = [set() for _ in range(n)]
        for e in edges_of(graph):
            self.add(self.index[_key(e["source"])], self.index[_key(e["target"])])

    def add(self, u: int, v: int) -> None:
        for a, b in ((u, v), (v, u)) if not self.directed else ((u, v),):
            self.succ[a].add(b)
            self.pred[b].add(a)

    def reach(self, source: int, *, backwards: bool = False) -> set[int]:
        return _bfs([source], self.pred if backwards else self.succ)


def edges_of(graph: Doc) -> list[Doc]:
    """A node-link graph's edges (``"edges"``, or networkx's older ``"links"``)."""
    edges = graph.get("edges", graph.get("links"))
    return list(edges) if isinstance(edges, list) else []


def _bfs(sources: Iterable[int], adj: Sequence[Iterable[int]]) -> set[int]:
    seen = set(sources)
    todo = deque(seen)
    while todo:
        u = todo.popleft()
        for v in adj[u]:
            if v not in seen:
                seen.add(v)
                todo.append(v)
    return seen
