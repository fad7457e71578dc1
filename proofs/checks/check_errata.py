"""ERRATA.md E1: the swapped reading of eq. (15) is exploitable; the smallest instance.

Re-derives the numbers quoted in ``proofs/ERRATA.md`` with the solver (profile) and the
checker (``dppverify.certify``), and compares them with the closed forms proved there:
``U* = b2 M + (b1 - b2) d(s0,g1)`` (XI2.md) and the Defender's exploit
``U* + sum over phase-II steps of w_t * (b1 - 2 b2) * (1 - sigma_t)`` when ``b1 > 2/3``,
``... * (2 b2 - b1) * sigma_t`` when ``b1 < 2/3`` (ERRATA.md, E1), both computed here
from the instance with networkx, independently of solver and checker.
"""

from __future__ import annotations

from fractions import Fraction

import networkx as nx
import sympy as sp

import dppverify
from proofs.checks.errata_search import (
    instance_doc,
    robust,
    search,
    swapped_outcome,
)
from solver.game.instance_reading import instance_from_json
from solver.twogoal.equilibrium import paper_equilibrium

TRIANGLE = (("s", "g1", 3), ("s", "g2", 2), ("g1", "g2", 2))
TIED = (("s", "g1", 2), ("s", "g2", 2), ("g1", "g2", 1))
P7 = (Fraction(7, 10), Fraction(3, 10))
P3 = (Fraction(3, 5), Fraction(2, 5))


def _graph(edges: tuple[tuple[str, str, int], ...]) -> nx.Graph:
    g = nx.Graph()
    g.add_weighted_edges_from(edges)
    return g


def _closed_form(edges: tuple[tuple[str, str, int], ...], xi2: tuple[str, ...],
                 t_i: int, t_ii: int, prior: tuple[Fraction, Fraction]
                 ) -> tuple[Fraction, Fraction]:
    """(U*, exploit value) from the formulas of XI2.md and ERRATA.md E1."""
    g = _graph(edges)
    b1, b2 = prior
    d = dict(nx.all_pairs_dijkstra_path_length(g))
    m = min(d["s"][v] + d[v]["g1"] + d[v]["g2"] for v in g.nodes)
    u_star = b2 * m + (b1 - b2) * d["s"]["g1"]
    c = d["s"]["g1"]
    gain = Fraction(0)
    for t in range(1, len(xi2)):
        w = g[xi2[t - 1]][xi2[t]]["weight"]
        c_new = min(c, d[xi2[t]]["g1"])
        sigma = Fraction(c - c_new, w)
        c = c_new
        if t_i < t <= t_ii:
            gain += w * ((b1 - 2 * b2) * (1 - sigma) if b1 > 2 * b2 else (2 * b2 - b1) * sigma)
    return Fraction(u_star), u_star + gain


def test_errata_E1_triangle_numbers() -> None:
    for prior, u_quoted, exploit_quoted in ((P7, "12/5", "5/2"), (P3, "11/5", "12/5")):
        out = swapped_outcome(instance_doc(TRIANGLE, False, prior))
        assert out.exploitable
        assert out.phases == (0, 1, 1) and out.secondary_path == ("s", "g2")
        assert "pbne.defender_br" in out.failing and "pbne.sequential_rationality" in out.failing
        u_star, exploit = _closed_form(TRIANGLE, ("s", "g2"), 0, 1, prior)
        assert (out.U_star, out.exploit_value) == (u_star, exploit)
        assert (str(u_star), str(exploit)) == (u_quoted, exploit_quoted)


def test_errata_E1_triangle_is_smallest() -> None:
    found = search(P7, max_edges=3, max_weight=3)
    assert found is not None
    edges, directed, _ = found
    assert not directed and sorted(edges) == sorted(TRIANGLE)
    assert robust(edges, directed, P7)


def test_errata_E1_tied_triangle_depends_on_tie_break() -> None:
    default = swapped_outcome(instance_doc(TIED, False, P7))
    assert not default.exploitable and default.secondary_path == ("s", "g1")
    other = swapped_outcome(instance_doc(TIED, False, P7, ("s", "g2", "g1")))
    assert other.exploitable and other.secondary_path == ("s", "g2")
    u_star, exploit = _closed_form(TIED, ("s", "g2"), 0, 1, P7)
    assert (other.U_star, other.exploit_value) == (u_star, exploit)
    assert (str(u_star), str(exploit)) == ("17/10", "9/5")
    assert default.U_star == u_star  # both tie-breaks give the same value


def test_errata_E1_not_exploitable_at_two_thirds() -> None:
    out = swapped_outcome(instance_doc(TRIANGLE, False, (Fraction(2, 3), Fraction(1, 3))))
    assert not out.exploitable and out.failing == ()


def test_errata_E1_exploit_gain_closed_form() -> None:
    # phase-II prefix under the swapped reading: A = b1 - b2, B = b2 (ERRATA E1)
    b2 = sp.Symbol("b2", positive=True)
    b1 = 1 - b2
    sigma = sp.Symbol("sigma", real=True)
    a_, b_ = b1 - b2, b2
    gain = sp.Max(a_, b_) - sigma * a_ - (1 - sigma) * b_
    for b2_val in (sp.Rational(3, 10), sp.Rational(2, 5), sp.Rational(1, 3), sp.Rational(1, 2)):
        g = sp.simplify(gain.subs(b2, b2_val))
        b1v = 1 - b2_val
        expected = ((b1v - 2 * b2_val) * (1 - sigma) if b1v > sp.Rational(2, 3)
                    else (2 * b2_val - b1v) * sigma)
        assert sp.simplify(g - expected) == 0
    assert sp.simplify(a_ / (a_ + b_) - (b1 - b2) / b1) == 0  # the swapped phase-II belief


def test_errata_E1_directed_four_arcs_with_weights_at_most_two() -> None:
    edges = (("s", "g1", 2), ("s", "g2", 2), ("g2", "g1", 1), ("g1", "g2", 2))
    out = swapped_outcome(instance_doc(edges, True, P7))
    assert out.exploitable and (str(out.U_star), str(out.exploit_value)) == ("17/10", "9/5")


def _progress(g: nx.Graph, walk: tuple[str, ...]) -> list[Fraction]:
    d = dict(nx.single_source_dijkstra_path_length(g, "g1"))
    c = [Fraction(d[walk[0]])]
    for v in walk[1:]:
        c.append(min(c[-1], Fraction(d[v])))
    return c


def test_errata_E2_progress_inequality_direction() -> None:
    g = _graph(TRIANGLE)
    d = dict(nx.single_source_dijkstra_path_length(g, "g1"))
    c = _progress(g, ("s", "g2"))
    assert c[0] - c[1] > 0  # new progress at the step s -> g2 ...
    assert not d["s"] < d["g2"]  # ... although the paper's formula is false there
    assert d["g2"] < d["s"]  # the corrected formula holds


def test_errata_E3_walk_to_the_fake_goal_attains_lemma_1() -> None:
    g = _graph(TRIANGLE)
    c = _progress(g, ("s", "g2"))
    j1 = c[0] - c[-1] + nx.dijkstra_path_length(g, "g2", "g1")  # TEL.3
    assert j1 == nx.dijkstra_path_length(g, "s", "g1") == 3


def test_errata_E4_primary_through_the_fake_goal_pays_more() -> None:
    doc = instance_doc((("g1", "s", 1), ("s", "g2", 1)), False, P7)
    profile = {"format": "dpp-profile/1", "goals": {"primary": "g1", "secondary": "g2"},
               "defender": {"rule": "progress", "goal": "g1"},
               "attacker": {"primary": [{"path": ["s", "g2"], "probability": "1"}],
                            "secondary": [{"path": ["s", "g2"], "probability": "1"}]}}
    g = _graph((("g1", "s", 1), ("s", "g2", 1)))
    c = _progress(g, ("s", "g2"))
    u1 = c[0] - c[-1] + nx.dijkstra_path_length(g, "g2", "g1")
    rec = dppverify.certify(doc, profile, horizon=1).check("pbne.attacker_br.primary")
    assert rec.status == "fail"  # the walk tree of the game truncated at H = 1
    assert (rec.numbers["U1"], rec.numbers["best_response"]) == (u1, 1) == (2, 1)
    rec = dppverify.certify(doc, profile).check("pbne.attacker_br.primary")
    assert rec.status == "fail"  # the untruncated game (structured route)
    assert (rec.numbers["U"], rec.numbers["min_over_walks"]) == (u1, 1)


def test_errata_E5_and_R3_one_half_and_ties() -> None:
    half = (Fraction(1, 2), Fraction(1, 2))
    eq = paper_equilibrium(instance_from_json(instance_doc(TRIANGLE, False, half)))
    assert [(p.nodes, p.probability) for p in eq.primary_paths] == [(("s", "g2"), 1)]
    values = set()
    for order, xi2 in ((("s", "g1", "g2"), ("s", "g1")), (("s", "g2", "g1"), ("s", "g2"))):
        eq = paper_equilibrium(instance_from_json(instance_doc(TIED, False, P7, order)))
        assert eq.secondary_path == xi2
        values.add(eq.U)
    assert values == {Fraction(17, 10)}
