"""``solver.solve`` takes a ``networkx`` graph with ``start=``, ``goals=``, ``prior=`` and
``weight=`` (the keywords of ``dppverify.certify``), converted once at the door (``as_instance``,
by ``Instance`` itself): the same game as its instance document, bad input one line."""

from __future__ import annotations

from fractions import Fraction

import networkx as nx
import pytest

import solver
from solver.errors import DPPError


def _triangle(attr: str = "weight", factor: object = 1) -> nx.Graph:
    g = nx.Graph()
    for u, v, w in (("s", "g2", 2), ("g2", "g1", 2), ("s", "g1", 3)):
        g.add_edge(u, v, **{attr: w * factor})  # type: ignore[operator]
    return g


def test_a_graph_solves_as_its_document() -> None:
    from solver.game.instance import triangle

    doc = triangle().to_json()
    by_doc = solver.solve(doc).to_json()
    by_graph = solver.solve(_triangle(), start="s", goals=["g1", "g2"],
                            prior=["7/10", "3/10"]).to_json()
    assert by_graph["value"] == by_doc["value"] and by_graph["value"]["U"] == "12/5"
    assert by_graph["attacker"] == by_doc["attacker"]


def test_weights_fractions_directed_graphs_and_n_goals() -> None:
    frac = solver.solve(_triangle("w", Fraction(1, 3)), start="s", goals=["g1", "g2"],
                        prior=[Fraction(7, 10), Fraction(3, 10)], weight="w")
    assert frac.U == Fraction(12, 5) / 3  # exact: the Fractions stayed exact
    both_ways = nx.DiGraph(_triangle()).to_directed()  # every edge as two arcs
    assert solver.solve(both_ways, start="s", goals=["g1", "g2"], prior=["7/10", "3/10"]).U \
        == Fraction(12, 5)
    star = nx.Graph([("s", "m"), ("m", "a"), ("m", "b"), ("m", "c")])
    star.add_edge("s", "a", weight=2)
    sol = solver.solve(star, start="s", goals=["a", "b", "c"], prior=["1/2", "1/3", "1/6"])
    assert str(sol.U) == "3/2"
    grid = nx.grid_2d_graph(3, 3)  # tuple node ids, as the grid instances have them
    assert solver.solve(grid, start=(2, 0), goals=[(0, 2), (0, 0)], prior=["3/5", "2/5"]).U > 0


@pytest.mark.parametrize("call, message", [
    (lambda: solver.solve(_triangle(), start="s", goals=["g1", "g2"]), "needs prior="),
    (lambda: solver.solve(nx.MultiGraph([(0, 1), (1, 2)]), start=0, goals=[1, 2],
                          prior=[0.5, 0.5]),
     "multigraph"),
    (lambda: solver.solve(_triangle("weight", "x"), start="s", goals=["g1", "g2"],
                          prior=[0.5, 0.5]), "weight"),
    (lambda: solver.solve(_triangle(), start="z", goals=["g1", "g2"], prior=[0.5, 0.5]), "z"),
    (lambda: solver.solve({"graph": {}}, start="s"), "go with a networkx graph"),
])
def test_bad_graph_input_is_one_line(call: object, message: str) -> None:
    with pytest.raises(DPPError) as info:
        call()  # type: ignore[operator]
    assert message in str(info.value) and "\n" not in str(info.value)
