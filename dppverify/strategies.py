"""Hypothesis strategies for DPP game instances, as JSON documents (``docs/formats.md`` §1).

Public strategies, in hypothesis' house style: plural names, keyword-only arguments, values
valid by construction (no filtering), :class:`hypothesis.errors.InvalidArgument` for
impossible arguments, and shrinking towards few nodes, few edges, unit weights and the
prior 1/2.

- :func:`weighted_graphs`: networkx node-link ``graph`` objects (directed or undirected;
  integer, fractional or float weights; strongly connected by default);
- :func:`priors`: ``[p, 1 - p]`` pairs of exact ``"p/q"`` strings, including exactly 1/2;
- :func:`instances`: instance documents on any graph strategy; the goals and the start are
  chosen so that ``d(s0,g1)``, ``d(s0,g2)``, ``d(g1,g2)`` and ``d(g2,g1)`` are finite;
- :func:`grid_worlds`: 4-connected grid instances with obstacles (the paper's Sec. VII), by
  default with each goal reachable from the start without passing the other goal;
- :func:`ngoal_priors` and :func:`ngoal_instances`: N-entry priors and N-goal instances
  (``N >= 2`` goals, exact weights) for :mod:`dppverify.ngoal`.

They produce plain dicts (the checker never imports the solver), ready for
``json.dumps``, :func:`dppverify.certify` or any solver reading the instance format.

Examples
--------
>>> from hypothesis import find, settings
>>> doc = find(instances(), lambda d: True, settings=settings(database=None))
>>> doc["graph"]["nodes"], doc["start"], doc["goals"], doc["prior"]
([{'id': 0}, {'id': 1}], 0, [0, 1], ['1/2', '1/2'])
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

__all__ = ["WEIGHT_KINDS", "grid_worlds", "instances", "ngoal_instances", "ngoal_priors", "priors",
           "weighted_graphs"]

WEIGHT_KINDS = ("units", "integers", "fractions", "floats")
"""Named edge-weight kinds: all 1; integers; exact fractions ``"p/q"``; binary floats."""

Doc = dict[str, Any]


# ----------------------------------------------------------------------------- validation
def _check_int(value: object, name: str, minimum: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise InvalidArgument(f"{name}={value!r} must be an integer")
    if value < minimum:
        raise InvalidArgument(f"{name}={value!r} must be at least {minimum}")
    return value


def _check_bool(value: object, name: str, *, allow_none: bool = False) -> None:
    if not (isinstance(value, bool) or (allow_none and value is None)):
        what = "True, False or None" if allow_none else "True or False"
        raise InvalidArgument(f"{name}={value!r} must be {what}")


def _weight_strategy(weights: object, min_weight: object, max_weight: object,
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
    q_max = _check_int(max_denominator, "max_denominator", 1)
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
    if isinstance(w, bool) or not isinstance(w, Real | str):
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
    edges are added. Without it the edges are arbitrary (possibly none); :func:`instances`
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
    lo = _check_int(min_nodes, "min_nodes", 2)
    hi = _check_int(max_nodes, "max_nodes", 2)
    if hi < lo:
        raise InvalidArgument(f"max_nodes={max_nodes} < min_nodes={min_nodes}")
    _check_bool(directed, "directed", allow_none=True)
    _check_bool(strongly_connected, "strongly_connected")
    extra = hi if max_extra_edges is None else _check_int(max_extra_edges, "max_extra_edges", 0)
    weight = _weight_strategy(weights, min_weight, max_weight, max_denominator)
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


# ----------------------------------------------------------------------------- priors
def priors(*, max_denominator: int = 10, allow_half: bool = True) -> st.SearchStrategy[list[str]]:
    """Prior pairs ``[p, 1 - p]`` with ``0 < p < 1``, as exact ``"p/q"`` strings.

    ``p`` has denominator at most ``max_denominator`` and shrinks towards ``1/2`` (the tie
    of the paper's footnote 2, where ``goals[0]`` is primary); either entry may be the
    larger, so both goal orders are generated.

    Parameters
    ----------
    max_denominator : int
        Largest denominator of ``p`` (at least 2; at least 3 without ``allow_half``).
    allow_half : bool
        Whether ``[1/2, 1/2]`` may be generated.

    Examples
    --------
    >>> from hypothesis import find, settings
    >>> find(priors(), lambda p: True, settings=settings(database=None))
    ['1/2', '1/2']
    >>> find(priors(allow_half=False), lambda p: True, settings=settings(database=None))
    ['1/3', '2/3']
    """
    _check_bool(allow_half, "allow_half")
    q_max = _check_int(max_denominator, "max_denominator", 2 if allow_half else 3)

    def with_denominator(q: int) -> st.SearchStrategy[list[str]]:
        half = allow_half or q % 2 == 1
        top = q - 1 if half else q - 2
        return st.integers(1, top).map(
            lambda p: _prior_pair(Fraction(p + (not half and 2 * p >= q), q)))

    return st.integers(2 if allow_half else 3, q_max).flatmap(with_denominator)


def _prior_pair(p: Fraction) -> list[str]:
    return [str(p), str(1 - p)]


_prior_pairs = priors  # the parameters named ``priors`` below shadow the function


# ----------------------------------------------------------------------------- instances
def instances(*, graphs: st.SearchStrategy[Doc] | None = None,
              priors: st.SearchStrategy[Sequence[Any]] | None = None) -> st.SearchStrategy[Doc]:
    """Instance documents: a graph, a start, two goals and a prior.

    The first goal is drawn freely; the second among the nodes that can reach it and be
    reached from it (if there is none, a direct edge between the goals is added, weighted
    like an existing edge); the start among the nodes that reach both goals, and about one
    time in five it is a goal itself (a game over at ``T = 0``). So ``d(s0,g1)``,
    ``d(s0,g2)``, ``d(g1,g2)`` and ``d(g2,g1)`` are always finite, as the game needs.
    Instances with float weights say ``"numbers": "float"``.

    Parameters
    ----------
    graphs : SearchStrategy of dict, optional
        Node-link graph objects (default :func:`weighted_graphs`), at least two nodes.
    priors : SearchStrategy, optional
        Pairs ``[prior of goals[0], prior of goals[1]]`` (default :func:`priors`).

    Returns
    -------
    SearchStrategy of dict
        ``{"graph", "start", "goals", "prior"}`` (plus ``"numbers"`` in float mode).

    Examples
    --------
    >>> from hypothesis import find, settings
    >>> doc = find(instances(graphs=weighted_graphs(min_nodes=3)),
    ...            lambda d: d["start"] not in d["goals"], settings=settings(database=None))
    >>> [(e["source"], e["target"], e["weight"]) for e in doc["graph"]["edges"]]
    [(0, 1, 1), (0, 2, 1)]
    >>> doc["start"], doc["goals"], doc["prior"]
    (2, [0, 1], ['1/2', '1/2'])
    """
    graph_strategy = weighted_graphs() if graphs is None else graphs
    prior_strategy = _prior_pairs() if priors is None else priors
    for name, value in (("graphs", graph_strategy), ("priors", prior_strategy)):
        if not isinstance(value, st.SearchStrategy):
            raise InvalidArgument(f"{name}={value!r} must be a SearchStrategy")
    return _instances(graph_strategy, prior_strategy)


def _key(x: Any) -> Hashable:
    return tuple(_key(y) for y in x) if isinstance(x, list) else x


class _Adjacency:
    """Successor/predecessor sets of a node-link dict (node positions as indices)."""

    def __init__(self, graph: Doc) -> None:
        nodes = graph.get("nodes") if isinstance(graph, dict) else None
        if not isinstance(nodes, list) or len(nodes) < 2:
            raise InvalidArgument("graphs must produce node-link dicts with at least 2 nodes")
        self.ids = [nd["id"] for nd in nodes]
        self.index = {_key(v): i for i, v in enumerate(self.ids)}
        self.directed = bool(graph.get("directed", False))
        n = len(self.ids)
        self.succ: list[set[int]] = [set() for _ in range(n)]
        self.pred: list[set[int]] = [set() for _ in range(n)]
        for e in _edges(graph):
            self.add(self.index[_key(e["source"])], self.index[_key(e["target"])])

    def add(self, u: int, v: int) -> None:
        for a, b in ((u, v), (v, u)) if not self.directed else ((u, v),):
            self.succ[a].add(b)
            self.pred[b].add(a)

    def reach(self, source: int, *, backwards: bool = False) -> set[int]:
        return _bfs([source], self.pred if backwards else self.succ)


def _edges(graph: Doc) -> list[Doc]:
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


@st.composite
def _instances(draw: st.DrawFn, graphs: st.SearchStrategy[Doc],
               prior_strategy: st.SearchStrategy[Sequence[Any]]) -> Doc:
    graph = draw(graphs)
    adj = _Adjacency(graph)
    n = len(adj.ids)
    first = draw(st.integers(0, n - 1))
    mutual = sorted((adj.reach(first) & adj.reach(first, backwards=True)) - {first})
    edges = _edges(graph)
    if mutual:
        second = draw(st.sampled_from(mutual))
    else:  # connect the goals directly, with the weight of an existing edge
        second = draw(st.integers(0, n - 2))
        second += second >= first
        weight = draw(st.sampled_from([e.get("weight", 1) for e in edges])) if edges else 1
        pairs = [(first, second), (second, first)] if adj.directed else [(first, second)]
        for u, v in pairs:
            if v not in adj.succ[u]:
                edges.append({"source": adj.ids[u], "target": adj.ids[v], "weight": weight})
                adj.add(u, v)
        graph = {**graph, "edges": edges}
        graph.pop("links", None)
    both = adj.reach(first, backwards=True) & adj.reach(second, backwards=True)
    inner = sorted(both - {first, second})
    # about one start in five is a goal (T = 0); shrinking prefers a start off the goals
    at_goal = not inner or draw(st.integers(0, 4)) == 4
    start = draw(st.sampled_from(sorted({first, second}) if at_goal else inner))
    prior = list(draw(prior_strategy))
    doc: Doc = {"graph": graph, "start": adj.ids[start],
                "goals": [adj.ids[first], adj.ids[second]], "prior": prior}
    if any(isinstance(e.get("weight"), float) for e in edges):
        doc["numbers"] = "float"
    return doc


# ----------------------------------------------------------------------------- grid worlds
def grid_worlds(
    *,
    min_size: int = 2,
    max_size: int = 6,
    max_cells: int | None = None,
    max_density: float = 0.3,
    avoid_other_goal: bool = True,
    weights: str | st.SearchStrategy[Any] = "units",
    priors: st.SearchStrategy[Sequence[Any]] | None = None,
) -> st.SearchStrategy[Doc]:
    """Grid-world instance documents: 4-connected cells ``[row, col]`` with obstacles.

    Obstacles cover at most ``floor(max_density * rows * cols)`` cells, never the start or a
    goal. With ``avoid_other_goal`` (the paper's Sec. VII-D condition) the start differs from
    both goals and each goal is reachable from the start along a path that does not pass
    through the other goal; without it, the start and both goals are merely connected (the
    start may then be a goal). When the drawn obstacles violate the condition, the fewest
    obstacles on a repair path are removed (0-1 BFS), so every example is valid by
    construction and the realised density may be lower than drawn.

    Parameters
    ----------
    min_size, max_size : int
        Bounds on the number of rows and of columns (``min_size >= 2`` with
        ``avoid_other_goal``, else ``>= 1``).
    max_cells : int or None
        Bound on ``rows * cols`` (default ``max_size ** 2``).
    max_density : float
        Largest obstacle fraction, in ``[0, 1)``.
    avoid_other_goal : bool
        Enforce the condition above.
    weights : str or SearchStrategy
        Edge weights, as in :func:`weighted_graphs` (default ``"units"``: the paper's grids;
        named kinds draw from ``[1, 9]``).
    priors : SearchStrategy, optional
        Prior pairs (default :func:`priors`).

    Examples
    --------
    >>> from hypothesis import find, settings
    >>> doc = find(grid_worlds(), lambda d: True, settings=settings(database=None))
    >>> [n["id"] for n in doc["graph"]["nodes"]], doc["start"], doc["goals"]
    ([[0, 0], [0, 1], [1, 0], [1, 1]], [1, 0], [[0, 0], [0, 1]])
    """
    _check_bool(avoid_other_goal, "avoid_other_goal")
    lo = _check_int(min_size, "min_size", 2 if avoid_other_goal else 1)
    hi = _check_int(max_size, "max_size", lo)
    cells = hi * hi if max_cells is None else _check_int(max_cells, "max_cells", 1)
    if (isinstance(max_density, bool) or not isinstance(max_density, Real)
            or not 0 <= max_density < 1):
        raise InvalidArgument(f"max_density={max_density!r} must lie in [0, 1)")
    need = 3 if avoid_other_goal else 2
    shapes = {r: (max(lo, -(-need // r)), min(hi, cells // r)) for r in range(lo, hi + 1)}
    shapes = {r: c for r, c in shapes.items() if c[0] <= c[1]}
    if not shapes:
        raise InvalidArgument(f"no grid with sides in [{min_size}, {max_size}] has at least "
                              f"{need} and at most {cells} cells")
    weight = _weight_strategy(weights, 1, 9, 6)
    prior_strategy = _prior_pairs() if priors is None else priors
    if not isinstance(prior_strategy, st.SearchStrategy):
        raise InvalidArgument(f"priors={priors!r} must be a SearchStrategy")
    return _grids(shapes, float(max_density), avoid_other_goal, weight, prior_strategy)


@st.composite
def _grids(draw: st.DrawFn, shapes: dict[int, tuple[int, int]], density: float, avoid: bool,
           weight: st.SearchStrategy[Any], prior_strategy: st.SearchStrategy[Sequence[Any]]
           ) -> Doc:
    rows = draw(st.sampled_from(sorted(shapes)))
    cols = draw(st.integers(*shapes[rows]))
    n = rows * cols
    first = draw(st.integers(0, n - 1))
    second = _skip(draw(st.integers(0, n - 2)), [first])
    start = (_skip(draw(st.integers(0, n - 3)), [first, second]) if avoid
             else draw(st.integers(0, n - 1)))
    special = {start, first, second}
    budget = min(math.floor(density * n), n - len(special))
    blocked = set(draw(st.lists(st.integers(0, n - 1), max_size=budget, unique=True))) - special
    neighbours = [_grid_neighbours(i, rows, cols) for i in range(n)]
    for goal, other in ((first, second), (second, first)):
        banned = {other} if avoid else set()
        blocked -= set(_cheapest_path(start, goal, neighbours, blocked, banned))
    free = [i for i in range(n) if i not in blocked]
    cell = [[i // cols, i % cols] for i in range(n)]
    edges = [{"source": cell[i], "target": cell[j], "weight": draw(weight)}
             for i in free for j in neighbours[i] if j > i and j not in blocked]
    doc: Doc = {"graph": {"directed": False, "multigraph": False, "graph": {},
                          "nodes": [{"id": cell[i]} for i in free], "edges": edges},
                "start": cell[start], "goals": [cell[first], cell[second]],
                "prior": list(draw(prior_strategy))}
    if any(isinstance(e["weight"], float) for e in edges):
        doc["numbers"] = "float"
    return doc


def _skip(i: int, taken: Sequence[int]) -> int:
    """The ``i``-th integer not in ``taken`` (choose among the rest without filtering)."""
    for t in sorted(taken):
        if i >= t:
            i += 1
    return i


def _grid_neighbours(i: int, rows: int, cols: int) -> list[int]:
    r, c = divmod(i, cols)
    out = []
    for dr, dc in ((-1, 0), (0, -1), (0, 1), (1, 0)):
        if 0 <= r + dr < rows and 0 <= c + dc < cols:
            out.append((r + dr) * cols + c + dc)
    return out


def _cheapest_path(source: int, target: int, neighbours: Sequence[Sequence[int]],
                   blocked: set[int], banned: set[int]) -> list[int]:
    """A path ``source -> target`` avoiding ``banned`` that crosses the fewest ``blocked``
    cells (0-1 BFS; deterministic). The grids here always have one (2-connected grids)."""
    cost = {source: 0}
    parent: dict[int, int] = {}
    todo = deque([source])
    while todo:
        u = todo.popleft()
        for v in neighbours[u]:
            if v in banned:
                continue
            step = 1 if v in blocked else 0
            if v not in cost or cost[u] + step < cost[v]:
                cost[v] = cost[u] + step
                parent[v] = u
                if step:
                    todo.append(v)
                else:
                    todo.appendleft(v)
    if target not in cost:  # unreachable only for impossible shapes, excluded by validation
        raise InvalidArgument("grid too small for the requested goal condition")
    path = [target]
    while path[-1] != source:
        path.append(parent[path[-1]])
    return path


# ----------------------------------------------------------------------------- N goals
def ngoal_priors(n_goals: int, *, max_weight: int = 6) -> st.SearchStrategy[list[str]]:
    """N-entry priors ``k_i / Σ k`` (each ``k_i`` in ``1 .. max_weight``) as ``"p/q"`` strings.

    Every entry lies in (0, 1) and they sum to exactly 1; shrinking goes to the uniform prior.

    Examples
    --------
    >>> from hypothesis import find, settings
    >>> find(ngoal_priors(3), lambda p: True, settings=settings(database=None))
    ['1/3', '1/3', '1/3']
    >>> find(ngoal_priors(3), lambda p: p[0] != p[1], settings=settings(database=None))
    ['1/4', '1/2', '1/4']
    """
    k = _check_int(n_goals, "n_goals", 2)
    top = _check_int(max_weight, "max_weight", 1)
    return st.lists(st.integers(1, top), min_size=k, max_size=k).map(
        lambda ws: [str(Fraction(w, sum(ws))) for w in ws])


def ngoal_instances(*, min_goals: int = 3, max_goals: int = 4,
                    graphs: st.SearchStrategy[Doc] | None = None,
                    max_prior_weight: int = 6) -> st.SearchStrategy[Doc]:
    """N-goal instance documents (``docs/formats.md`` §1, "N goals"), valid by construction.

    The goals are distinct nodes of one strongly connected part of the graph (when that part
    has too few nodes, a cycle of edges through the chosen goals is added, weighted like an
    existing edge), so every ``d(g^i, g^j)`` is finite; the start is a node that reaches them
    (about one time in five a goal itself). Weights must be exact (no floats).

    Parameters
    ----------
    min_goals, max_goals : int
        Bounds on ``N`` (``2 <= min_goals <= max_goals``); the graph needs at least
        ``max_goals`` nodes.
    graphs : SearchStrategy of dict, optional
        Node-link graphs (default: :func:`weighted_graphs` with ``max_goals + 1`` to
        ``max_goals + 4`` nodes and integer weights 1–4).
    max_prior_weight : int
        The prior is drawn by :func:`ngoal_priors` with this ``max_weight``.

    Examples
    --------
    >>> from hypothesis import find, settings
    >>> doc = find(ngoal_instances(), lambda d: True, settings=settings(database=None))
    >>> doc["start"], doc["goals"], doc["prior"]
    (3, [0, 1, 2], ['1/3', '1/3', '1/3'])
    >>> ngoal_instances(min_goals=4, max_goals=3)
    Traceback (most recent call last):
    hypothesis.errors.InvalidArgument: max_goals=3 < min_goals=4
    """
    lo = _check_int(min_goals, "min_goals", 2)
    hi = _check_int(max_goals, "max_goals", 2)
    if hi < lo:
        raise InvalidArgument(f"max_goals={max_goals} < min_goals={min_goals}")
    _check_int(max_prior_weight, "max_prior_weight", 1)
    graph_strategy = (weighted_graphs(min_nodes=hi + 1, max_nodes=hi + 4, max_weight=4)
                      if graphs is None else graphs)
    if not isinstance(graph_strategy, st.SearchStrategy):
        raise InvalidArgument(f"graphs={graphs!r} must be a SearchStrategy")
    return _ngoal_instances(graph_strategy, lo, hi, max_prior_weight)


@st.composite
def _ngoal_instances(draw: st.DrawFn, graphs: st.SearchStrategy[Doc], lo: int, hi: int,
                     max_prior_weight: int) -> Doc:
    graph = draw(graphs)
    adj = _Adjacency(graph)
    n = len(adj.ids)
    if n < hi:
        raise InvalidArgument(f"graphs must produce at least max_goals={hi} nodes, got {n}")
    edges = _edges(graph)
    if any(isinstance(e.get("weight"), float) for e in edges):
        raise InvalidArgument("N-goal instances are exact: graphs must not draw float weights")
    k = draw(st.integers(lo, hi))
    first = draw(st.integers(0, n - 1))
    part = sorted((adj.reach(first) & adj.reach(first, backwards=True)) - {first})
    if len(part) >= k - 1:
        others = draw(st.lists(st.sampled_from(part), min_size=k - 1, max_size=k - 1,
                               unique=True))
    else:  # join the goals by a cycle of edges
        rest = [v for v in range(n) if v != first]
        others = draw(st.lists(st.sampled_from(rest), min_size=k - 1, max_size=k - 1,
                               unique=True))
        weight = draw(st.sampled_from([e.get("weight", 1) for e in edges])) if edges else 1
        ring = [first, *others]
        for u, v in zip(ring, ring[1:] + ring[:1], strict=True):
            if v not in adj.succ[u]:
                edges.append({"source": adj.ids[u], "target": adj.ids[v], "weight": weight})
                adj.add(u, v)
        graph = {**graph, "edges": edges}
        graph.pop("links", None)
    goals = [first, *others]
    inner = sorted(adj.reach(first, backwards=True) - set(goals))
    at_goal = not inner or draw(st.integers(0, 4)) == 4
    start = draw(st.sampled_from(sorted(goals) if at_goal else inner))
    prior = draw(ngoal_priors(k, max_weight=max_prior_weight))
    return {"graph": graph, "start": adj.ids[start], "goals": [adj.ids[g] for g in goals],
            "prior": prior}
