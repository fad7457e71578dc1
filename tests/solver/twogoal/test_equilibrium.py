"""Hand-computed equilibria and the edge cases of proofs/README.md."""

from __future__ import annotations

from fractions import Fraction as F
from typing import Any

import networkx as nx
import pytest

from solver import Instance, InvalidInstanceError, instance_from_json
from solver.twogoal.equilibrium import paper_equilibrium
from solver.twogoal.phases import Phases
from tests.solver.twogoal._cases import load_cases

NAMED: dict[str, dict[str, Any]] = {}
for _case in load_cases():  # the first case of each edge-case name
    NAMED.setdefault(_case["name"], _case)


def _solve_named(name: str) -> Any:
    return paper_equilibrium(instance_from_json(NAMED[name]["instance"]))


def test_triangle_by_hand(triangle: Instance) -> None:
    # M = min_v d(s,v)+d(v,g1)+d(v,g2): v=s 0+3+2, v=g2 2+2+0, v=g1 3+0+2 -> M = 4 at g2
    eq = paper_equilibrium(triangle)
    assert eq.secondary_path == ("s", "g2")
    assert eq.schedule == (F(1, 2),)  # c0 = 3, c1 = d(g2, g1) = 2, progress 1 over weight 2
    assert eq.phases == Phases(0, 1, 1)
    paths = {p.label: (p.nodes, p.probability) for p in eq.primary_paths}
    assert paths == {"xi1_I": (("s", "g1"), F(4, 7)), "xi1_II": (("s", "g2"), F(3, 7))}
    assert (eq.U1, eq.U2) == (3, 1)  # U2 = 2*(1 - 1/2) + d(g2, g2) = 1 = M - d1
    assert eq.U == F(7, 10) * 3 + F(3, 10) * 1 == F(12, 5)
    assert eq.U_bar == F(7, 10) * 3 + F(3, 10) * 2
    assert eq.VoI == (eq.U_bar - eq.U) / eq.U_bar == F(1, 9)


def test_beliefs_along_triangle_paths(triangle: Instance) -> None:
    eq = paper_equilibrium(triangle)
    by_label = {t.label: t for t in eq.trajectories}
    # xi2 = xi1_II: phase II belief exactly 1/2 (eq. (15) mixing), branch xi1_I belief 1
    assert by_label["xi2"].belief_g1 == (F(7, 10), F(1, 2))
    assert by_label["xi1_II"].belief_g1 == (F(7, 10), F(1, 2))
    assert by_label["xi1_I"].belief_g1 == (F(7, 10), F(1))
    # cumulative expected allocation to the true goal
    assert by_label["xi2"].allocation == (0, 1)
    assert by_label["xi1_I"].allocation == (0, 3)
    assert by_label["xi1_II"].allocation == (0, 1) and by_label["xi1_II"].terminal == 2


def test_paper_figure3_progress_example() -> None:
    # c0 = 3.5: the red step makes progress 1.5 (to a node at distance 2), the purple one 0.5
    g = nx.DiGraph()
    g.add_weighted_edges_from([("s", "r", F(3, 2)), ("r", "g1", 2), ("s", "p", 1),
                               ("p", "g1", 3), ("s", "g2", 5), ("g2", "g1", 9), ("g1", "g2", 9)])
    eq = paper_equilibrium(Instance(g, "s", ("g1", "g2"), ("3/5", "2/5")))
    idx = eq.instance.network.index_of
    red = eq.defender.schedule([idx("s"), idx("r"), idx("g1")])
    purple = eq.defender.schedule([idx("s"), idx("p"), idx("g1")])
    assert red[0] * F(3, 2) == F(3, 2) and purple[0] * 1 == F(1, 2)
    # Fig. 3(b): both paths cost the primary exactly d(s0, g1) = 3.5
    assert F(3, 2) * red[0] + 2 * red[1] == F(7, 2)
    assert 1 * purple[0] + 3 * purple[1] == F(7, 2)


def test_mixing_follows_eq15_not_the_swapped_sentence() -> None:
    eq = _solve_named("phases_I_II")
    probs = {p.label: p.probability for p in eq.primary_paths}
    b1, b2 = eq.instance.b1, eq.instance.b2
    assert probs == {"xi1_I": 1 - b2 / b1, "xi1_II": b2 / b1}


@pytest.mark.parametrize("name", ["s0_is_g1", "s0_is_g2", "s0_is_goal"])
def test_start_at_a_goal_ends_immediately(name: str) -> None:
    eq = _solve_named(name)
    inst = eq.instance
    assert eq.phases.T == 0 and eq.secondary_path == (inst.start,)
    assert [p.nodes for p in eq.primary_paths] == [(inst.start,)]
    # only terminal costs: U^θ = d(s0, g^θ)
    assert eq.U == eq.U_bar and eq.VoI == 0


def test_xi2_ending_at_g1_is_cut_there() -> None:
    eq = _solve_named("xi2_ends_at_g1")
    assert eq.secondary_path[-1] == eq.instance.primary
    xi2 = next(t for t in eq.trajectories if t.label == "xi2")
    assert xi2.terminal > 0  # the secondary pays d(g1, g2) after revealing itself


def test_g1_reachable_only_through_g2() -> None:
    eq = _solve_named("g1_only_through_g2")
    # every walk to g1 passes g2 first: both types end at g2; the primary still pays d(s0,g1)
    assert all(p.nodes[-1] == eq.instance.secondary for p in eq.primary_paths)
    assert eq.U1 == F(NAMED["g1_only_through_g2"]["expected"]["d1"])


def test_phase_II_with_sigma_one_and_sigma_zero_steps() -> None:
    eq1 = _solve_named("phase_II_has_sigma1")
    assert eq1.phases.t_I < eq1.phases.t_II and 1 in eq1.schedule[eq1.phases.t_I:eq1.phases.t_II]
    eq0 = _solve_named("phases_I_II")
    assert 0 in eq0.schedule[eq0.phases.t_I:eq0.phases.t_II]


def test_one_half_prior_puts_all_primary_weight_on_xi1_II() -> None:
    eq = _solve_named("phase_II_has_sigma1")
    assert eq.instance.b1 == eq.instance.b2
    assert [(p.label, p.probability) for p in eq.primary_paths] == [("xi1_II", 1)]


@pytest.mark.parametrize("name,phases", [
    ("phases=I+II+III", (True, True, True)), ("phases=II", (False, True, False)),
    ("phases=I", (True, False, False)), ("phases=III", (False, False, True)),
    ("phases=I+III", (True, False, True)), ("phases=II+III", (False, True, True)),
    ("phases=I+II", (True, True, False)),
])
def test_each_phase_combination(name: str, phases: tuple[bool, bool, bool]) -> None:
    ph = _solve_named(name).phases
    assert (ph.t_I > 0, ph.t_II > ph.t_I, ph.T > ph.t_II) == phases


def test_unreachable_goal_is_a_clear_error() -> None:
    g = nx.DiGraph()
    g.add_weighted_edges_from([("s", "g1", 1), ("s", "g2", 1), ("g1", "g2", 1)])
    with pytest.raises(InvalidInstanceError, match="unreachable from goal"):
        paper_equilibrium(Instance(g, "s", ("g1", "g2"), ("1/2", "1/2")))
    g.add_node("x")
    with pytest.raises(InvalidInstanceError, match="'x' is unreachable from start 's'"):
        paper_equilibrium(Instance(g, "s", ("g1", "x"), ("1/2", "1/2")))


def test_float_weights_agree_with_exact_weights() -> None:
    g = nx.Graph()
    g.add_weighted_edges_from([("s", "a", F(1, 3)), ("a", "g1", F(2, 3)), ("a", "g2", F(5, 7)),
                               ("s", "g2", F(8, 7)), ("g1", "g2", F(1, 2))])
    gf = nx.Graph()
    gf.add_weighted_edges_from((u, v, float(d["weight"])) for u, v, d in g.edges(data=True))
    exact = paper_equilibrium(Instance(g, "s", ("g1", "g2"), ("3/5", "2/5")))
    approx = paper_equilibrium(Instance(gf, "s", ("g1", "g2"), ("3/5", "2/5")))
    assert exact.numbers.exact and not approx.numbers.exact and approx.numbers.abs_tol is not None
    assert exact.secondary_path == approx.secondary_path and exact.phases == approx.phases
    assert abs(float(exact.U) - approx.U) <= 1e-9  # type: ignore[operator]


@pytest.mark.parametrize("big", [2**55 + 1, 2**63 + 5])  # beyond float64 / beyond int64
@pytest.mark.parametrize("directed", [False, True])
def test_huge_integer_weights_stay_exact(big: int, directed: bool) -> None:
    """Distances beyond 2**53 use the integer Dijkstra, on the forward AND reversed arcs."""
    g: nx.Graph = nx.DiGraph() if directed else nx.Graph()
    arcs = [("s", "g2", 0), ("g2", "g1", 2), ("s", "g1", 1), ("g1", "g2", 3), ("g2", "s", 0),
            ("g1", "s", 1), ("s", "a", 5), ("a", "g2", 1)]
    for u, v, extra in arcs:
        if directed or not g.has_edge(u, v):
            g.add_edge(u, v, weight=big + extra)
    eq = paper_equilibrium(Instance(g, "s", ("g1", "g2"), ("7/10", "3/10")))
    d = dict(nx.all_pairs_dijkstra_path_length(g))  # Python ints: exact
    m = min(d["s"][v] + d[v]["g1"] + d[v]["g2"] for v in g if "g1" in d[v] and "g2" in d[v])
    assert eq.U1 == d["s"]["g1"]
    assert eq.U2 == m - d["s"]["g1"]
    assert eq.U == F(7, 10) * eq.U1 + F(3, 10) * eq.U2
