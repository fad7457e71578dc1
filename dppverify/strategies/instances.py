"""Hypothesis strategies for priors and instance documents (two goals and N goals)."""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction
from typing import Any

from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument

from dppverify.strategies.graphs import (
    Adjacency,
    Doc,
    check_bool,
    check_int,
    edges_of,
    weighted_graphs,
)

__all__ = ["goal_priors", "instances", "many_goal_instances", "priors", "selection_instances"]

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

    Returns
    -------
    SearchStrategy of list of str
        ``[p, 1 - p]`` as ``"p/q"`` strings.

    Examples
    --------
    >>> from hypothesis import find, settings
    >>> find(priors(), lambda p: True, settings=settings(database=None))
    ['1/2', '1/2']
    >>> find(priors(allow_half=False), lambda p: True, settings=settings(database=None))
    ['1/3', '2/3']
    """
    check_bool(allow_half, "allow_half")
    q_max = check_int(max_denominator, "max_denominator", 2 if allow_half else 3)

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

    Raises
    ------
    hypothesis.errors.InvalidArgument
        A graph strategy that draws fewer than two nodes (when the example is drawn).

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

@st.composite
def _instances(draw: st.DrawFn, graphs: st.SearchStrategy[Doc],
               prior_strategy: st.SearchStrategy[Sequence[Any]]) -> Doc:
    graph = draw(graphs)
    adj = Adjacency(graph)
    n = len(adj.ids)
    first = draw(st.integers(0, n - 1))
    mutual = sorted((adj.reach(first) & adj.reach(first, backwards=True)) - {first})
    edges = edges_of(graph)
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


# ----------------------------------------------------------------------------- N goals
def goal_priors(n_goals: int, *, max_weight: int = 6) -> st.SearchStrategy[list[str]]:
    """N-entry priors ``k_i / Σ k`` (each ``k_i`` in ``1 .. max_weight``) as ``"p/q"`` strings.

    Every entry lies in (0, 1) and they sum to exactly 1; shrinking goes to the uniform prior.

    Parameters
    ----------
    n_goals : int
        ``N``, at least 2.
    max_weight : int
        Largest ``k_i``.

    Returns
    -------
    SearchStrategy of list of str
        ``N`` exact priors, summing to 1.

    Examples
    --------
    >>> from hypothesis import find, settings
    >>> find(goal_priors(3), lambda p: True, settings=settings(database=None))
    ['1/3', '1/3', '1/3']
    >>> find(goal_priors(3), lambda p: p[0] != p[1], settings=settings(database=None))
    ['1/4', '1/2', '1/4']
    """
    k = check_int(n_goals, "n_goals", 2)
    top = check_int(max_weight, "max_weight", 1)
    return st.lists(st.integers(1, top), min_size=k, max_size=k).map(
        lambda ws: [str(Fraction(w, sum(ws))) for w in ws])


def many_goal_instances(*, min_goals: int = 3, max_goals: int = 4,
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
        The prior is drawn by :func:`goal_priors` with this ``max_weight``.

    Returns
    -------
    SearchStrategy of dict
        ``{"graph", "start", "goals", "prior"}`` with ``N`` goals.

    Raises
    ------
    hypothesis.errors.InvalidArgument
        Bounds out of range or inconsistent (when the strategy is built).

    Examples
    --------
    >>> from hypothesis import find, settings
    >>> doc = find(many_goal_instances(), lambda d: True, settings=settings(database=None))
    >>> doc["start"], doc["goals"], doc["prior"]
    (3, [0, 1, 2], ['1/3', '1/3', '1/3'])
    >>> many_goal_instances(min_goals=4, max_goals=3)
    Traceback (most recent call last):
    hypothesis.errors.InvalidArgument: max_goals=3 < min_goals=4
    """
    lo = check_int(min_goals, "min_goals", 2)
    hi = check_int(max_goals, "max_goals", 2)
    if hi < lo:
        raise InvalidArgument(f"max_goals={max_goals} < min_goals={min_goals}")
    check_int(max_prior_weight, "max_prior_weight", 1)
    graph_strategy = (weighted_graphs(min_nodes=hi + 1, max_nodes=hi + 4, max_weight=4)
                      if graphs is None else graphs)
    if not isinstance(graph_strategy, st.SearchStrategy):
        raise InvalidArgument(f"graphs={graphs!r} must be a SearchStrategy")
    return _many_goal_instances(graph_strategy, lo, hi, max_prior_weight)


@st.composite
def _many_goal_instances(draw: st.DrawFn, graphs: st.SearchStrategy[Doc], lo: int, hi: int,
                     max_prior_weight: int) -> Doc:
    graph = draw(graphs)
    adj = Adjacency(graph)
    n = len(adj.ids)
    if n < hi:
        raise InvalidArgument(f"graphs must produce at least max_goals={hi} nodes, got {n}")
    edges = edges_of(graph)
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
    prior = draw(goal_priors(k, max_weight=max_prior_weight))
    return {"graph": graph, "start": adj.ids[start], "goals": [adj.ids[g] for g in goals],
            "prior": prior}


def selection_instances(*, min_goals: int = 2, max_goals: int = 4,
                        graphs: st.SearchStrategy[Doc] | None = None,
                        values: bool = True) -> st.SearchStrategy[Doc]:
    """Goal-selection instance documents (``docs/formats.md`` §1, "Goal selection"): the
    instances of :func:`many_goal_instances` without their prior, marked ``"goal_selection":
    true``, and with ``values`` sometimes ``"goal_values"`` (halves in ``-2 .. 2``).

    Parameters
    ----------
    min_goals, max_goals : int
        The number of goals, as for :func:`many_goal_instances`.
    graphs : hypothesis strategy of dict, optional
        The graphs (node-link documents), as for :func:`many_goal_instances`.
    values : bool, default True
        Whether documents may carry ``"goal_values"``.

    Returns
    -------
    hypothesis strategy of dict
        Goal-selection instance documents, valid by construction.

    Examples
    --------
    >>> from hypothesis import find, settings
    >>> doc = find(selection_instances(), lambda d: True, settings=settings(database=None))
    >>> doc["goal_selection"], "prior" in doc, len(doc["goals"])
    (True, False, 2)
    """
    base = many_goal_instances(min_goals=min_goals, max_goals=max_goals, graphs=graphs)
    return _selection_instances(base, values)


@st.composite
def _selection_instances(draw: st.DrawFn, base: st.SearchStrategy[Doc], values: bool) -> Doc:
    doc = {k: v for k, v in draw(base).items() if k != "prior"}
    doc["goal_selection"] = True
    if values and draw(st.booleans()):
        doc["goal_values"] = [str(Fraction(draw(st.integers(-4, 4)), 2)) for _ in doc["goals"]]
    return doc
