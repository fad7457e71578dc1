"""The strategies themselves: sizes, validity by construction, shrinking, bad arguments."""

from __future__ import annotations

import json
from collections import deque
from fractions import Fraction
from typing import Any

import networkx as nx
import pytest
from hypothesis import find, given, settings
from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument

from dppverify.game.instance import instance_from_json
from dppverify.strategies import WEIGHT_KINDS, grid_worlds, instances, priors, weighted_graphs
from solver import instance_from_json as solver_instance_from_json
from solver.twogoal.equilibrium import paper_equilibrium
from tests.properties._reference import INF, Game, key, number

_quiet = settings(database=None, derandomize=True)


def _nx(graph: dict[str, Any]) -> nx.Graph:
    g: nx.Graph = nx.DiGraph() if graph["directed"] else nx.Graph()
    g.add_nodes_from(key(n["id"]) for n in graph["nodes"])
    g.add_edges_from((key(e["source"]), key(e["target"])) for e in graph["edges"])
    return g


# ----------------------------------------------------------------------------- graphs
@given(st.data(), st.integers(2, 6), st.integers(0, 4), st.sampled_from(WEIGHT_KINDS),
       st.sampled_from([None, True, False]), st.booleans())
def test_weighted_graphs_respect_their_arguments(data: st.DataObject, lo: int, span: int,
                                                 kind: str, directed: bool | None,
                                                 connected: bool) -> None:
    g = data.draw(weighted_graphs(min_nodes=lo, max_nodes=lo + span, directed=directed,
                                  weights=kind, min_weight=Fraction(1, 2), max_weight=5,
                                  strongly_connected=connected))
    n = len(g["nodes"])
    assert lo <= n <= lo + span
    assert [nd["id"] for nd in g["nodes"]] == list(range(n))
    if directed is not None:
        assert g["directed"] is directed
    ends = [(e["source"], e["target"]) for e in g["edges"]]
    assert all(u != v and 0 <= u < n and 0 <= v < n for u, v in ends)
    canon = ends if g["directed"] else [tuple(sorted(uv)) for uv in ends]
    assert len(set(canon)) == len(canon), "duplicate edge"
    for e in g["edges"]:
        w = e["weight"]
        assert Fraction(1, 2) <= number(w) <= 5
        assert isinstance(w, {"units": int, "integers": int, "floats": float,
                              "fractions": int | str}[kind])
        if kind == "fractions" and isinstance(w, str):
            assert Fraction(w).denominator <= 6
    if connected:
        h = _nx(g)
        assert (nx.is_strongly_connected(h) if g["directed"] else nx.is_connected(h))
    json.dumps(g)  # plain JSON


def test_weighted_graphs_accept_a_weight_strategy() -> None:
    g = find(weighted_graphs(min_nodes=4, weights=st.sampled_from([Fraction(7, 3), 2.5, "9"])),
             lambda g: len({str(e["weight"]) for e in g["edges"]}) == 3, settings=_quiet)
    assert {str(e["weight"]) for e in g["edges"]} == {"7/3", "2.5", "9"}


def test_weighted_graphs_shrink_to_a_minimal_graph() -> None:
    g = find(weighted_graphs(max_nodes=10), lambda g: len(g["nodes"]) >= 5, settings=_quiet)
    assert g["directed"] is False
    assert len(g["nodes"]) == 5
    assert [(e["source"], e["target"], e["weight"]) for e in g["edges"]] == [
        (0, i, 1) for i in range(1, 5)]


# ----------------------------------------------------------------------------- priors
@given(priors(max_denominator=7))
def test_priors_are_exact_and_sum_to_one(prior: list[str]) -> None:
    p, q = (Fraction(x) for x in prior)
    assert 0 < p < 1 and p + q == 1
    assert p.denominator <= 7


@given(priors(allow_half=False))
def test_priors_without_half(prior: list[str]) -> None:
    assert Fraction(prior[0]) != Fraction(1, 2)


def test_priors_shrink_to_half_and_reach_both_orders() -> None:
    assert find(priors(), lambda p: True, settings=_quiet) == ["1/2", "1/2"]
    assert find(priors(), lambda p: Fraction(p[0]) < Fraction(p[1]), settings=_quiet) == [
        "1/3", "2/3"]


# ----------------------------------------------------------------------------- instances
def _reaches(game: Game, source: Any, target: Any, *, avoid: Any = None) -> bool:
    seen, todo = {source}, deque([source])
    while todo:
        u = todo.popleft()
        if u == target:
            return True
        for v, _ in game.succ[u]:
            if v not in seen and v != avoid:
                seen.add(v)
                todo.append(v)
    return False


_any_graphs = st.one_of(
    weighted_graphs(max_nodes=6),
    weighted_graphs(max_nodes=6, directed=True, strongly_connected=False, weights="fractions"),
    weighted_graphs(max_nodes=5, weights="floats", strongly_connected=False),
)


@given(instances(graphs=_any_graphs))
def test_instances_are_valid_for_both_packages(doc: dict[str, Any]) -> None:
    text = json.dumps(doc)
    game = Game.from_doc(doc)
    for a, b in ((game.start, game.g1), (game.start, game.g2), (game.g1, game.g2),
                 (game.g2, game.g1)):
        assert game.d_to(a, b) != INF
    inst = instance_from_json(text)          # the checker accepts it
    assert inst.n_nodes == len(doc["graph"]["nodes"])
    eq = paper_equilibrium(solver_instance_from_json(text))     # the solver accepts and solves it
    assert eq.secondary_path[0] == key(doc["start"])
    floats = any(isinstance(e["weight"], float) for e in doc["graph"]["edges"])
    assert doc.get("numbers", "exact") == ("float" if floats else "exact")
    assert eq.numbers.exact is not floats


def test_instances_connect_goals_of_a_disconnected_graph() -> None:
    empty = st.just({"directed": True, "multigraph": False, "graph": {},
                     "nodes": [{"id": "a"}, {"id": "b"}, {"id": "c"}], "edges": []})
    doc = find(instances(graphs=empty), lambda d: True, settings=_quiet)
    assert doc["goals"] == ["a", "b"]
    assert sorted((e["source"], e["target"]) for e in doc["graph"]["edges"]) == [
        ("a", "b"), ("b", "a")]


def test_instances_reject_tiny_graphs() -> None:
    one = st.just({"directed": False, "nodes": [{"id": 0}], "edges": []})
    with pytest.raises(InvalidArgument):
        find(instances(graphs=one), lambda d: True, settings=_quiet)


# ----------------------------------------------------------------------------- grids
@given(st.data(), st.integers(2, 4), st.integers(0, 3), st.sampled_from([0.0, 0.2, 0.5, 0.9]),
       st.booleans())
def test_grid_worlds_respect_their_arguments(data: st.DataObject, lo: int, span: int,
                                             density: float, avoid: bool) -> None:
    doc = data.draw(grid_worlds(min_size=lo, max_size=lo + span, max_density=density,
                                avoid_other_goal=avoid))
    cells = [tuple(n["id"]) for n in doc["graph"]["nodes"]]
    rows = 1 + max(r for r, _ in cells + [tuple(doc["start"])] + [tuple(g) for g in doc["goals"]])
    cols = 1 + max(c for _, c in cells + [tuple(doc["start"])] + [tuple(g) for g in doc["goals"]])
    assert rows <= lo + span and cols <= lo + span
    blocked = rows * cols - len(cells)
    assert blocked <= int(density * (lo + span) ** 2)
    game = Game.from_doc(doc)
    assert all(abs(u[0] - v[0]) + abs(u[1] - v[1]) == 1 and w == 1
               for u, arcs in game.succ.items() for v, w in arcs)
    g1, g2 = game.g1, game.g2
    if avoid:
        assert game.start not in (g1, g2)
        assert _reaches(game, game.start, g1, avoid=g2)
        assert _reaches(game, game.start, g2, avoid=g1)
    for a, b in ((game.start, g1), (game.start, g2), (g1, g2), (g2, g1)):
        assert game.d_to(a, b) != INF
    paper_equilibrium(solver_instance_from_json(json.dumps(doc)))


def test_grid_worlds_bound_the_cell_count() -> None:
    doc = find(grid_worlds(max_size=9, max_cells=12, max_density=0.0),
               lambda d: len(d["graph"]["nodes"]) >= 12, settings=_quiet)
    assert len(doc["graph"]["nodes"]) == 12


def test_grid_worlds_with_weights() -> None:
    doc = find(grid_worlds(weights="fractions"),
               lambda d: any(isinstance(e["weight"], str) for e in d["graph"]["edges"]),
               settings=_quiet)
    assert solver_instance_from_json(doc).network.numbers.exact


def test_grid_worlds_shrink_to_the_smallest_grid() -> None:
    doc = find(grid_worlds(), lambda d: True, settings=_quiet)
    assert [n["id"] for n in doc["graph"]["nodes"]] == [[0, 0], [0, 1], [1, 0], [1, 1]]


# ----------------------------------------------------------------------------- arguments
@pytest.mark.parametrize("make", [
    lambda: weighted_graphs(min_nodes=1),
    lambda: weighted_graphs(min_nodes=5, max_nodes=4),
    lambda: weighted_graphs(min_nodes=2.5),
    lambda: weighted_graphs(directed="yes"),
    lambda: weighted_graphs(weights="complex"),
    lambda: weighted_graphs(min_weight=0),
    lambda: weighted_graphs(min_weight=3, max_weight=2),
    lambda: weighted_graphs(weights="integers", min_weight="1/3", max_weight="2/3"),
    lambda: weighted_graphs(weights="integers", min_weight=Fraction(1, 3),
                            max_weight=Fraction(2, 3)),
    lambda: weighted_graphs(max_denominator=0),
    lambda: weighted_graphs(max_extra_edges=-1),
    lambda: weighted_graphs(strongly_connected=None),
    lambda: priors(max_denominator=1),
    lambda: priors(max_denominator=2, allow_half=False),
    lambda: instances(graphs=[]),
    lambda: instances(priors=["1/2", "1/2"]),
    lambda: grid_worlds(min_size=1),
    lambda: grid_worlds(min_size=4, max_size=3),
    lambda: grid_worlds(max_density=1.0),
    lambda: grid_worlds(max_density=-0.1),
    lambda: grid_worlds(max_cells=3),
    lambda: grid_worlds(min_size=1, max_size=1, avoid_other_goal=False),
    lambda: grid_worlds(weights="heavy"),
])
def test_impossible_arguments_raise_invalid_argument(make: Any) -> None:
    with pytest.raises(InvalidArgument):
        make()


def test_bad_weight_strategy_values_raise_invalid_argument() -> None:
    with pytest.raises(InvalidArgument):
        find(weighted_graphs(weights=st.just(-1)), lambda g: True, settings=_quiet)
