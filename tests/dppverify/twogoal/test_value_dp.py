"""The structured route's V_H (three-field DP, proofs/DP.md) against the walk tree's LP.

Evidence that the structured route is exact: structured = tree exactly on every conformance
case at several horizons and on random instances; V_H non-increasing in H and equal to the
solver's U once H covers its profile; the untruncated value; int64 / Python-int / float
arithmetic; the CLI.
"""

from __future__ import annotations

import itertools
import json
from fractions import Fraction
from pathlib import Path
from typing import Any

import pytest
from click.testing import CliRunner
from hypothesis import given, settings
from hypothesis import strategies as st

import dppverify.routes
from dppverify import count_prefixes, game_value, instance_from_json
from dppverify.cli.value import value_command
from dppverify.errors import HorizonError
from dppverify.game.examples import triangle
from dppverify.routes import resolve_route, routed_value, tree_fits
from dppverify.strategies import grid_worlds, instances, weighted_graphs
from dppverify.twogoal.value_dp import StructuredValue, structured_value, value_fields
from solver import instance_from_json as solver_instance_from_json
from solver.twogoal.equilibrium import paper_equilibrium
from tests.dppverify._helpers import make_doc, three_phase_doc

DATA = Path(__file__).resolve().parents[2] / "data" / "conformance_cases.json"
CASES = json.loads(DATA.read_text(encoding="utf-8"))
MAX_TREE = 600  # keep the tree LPs of the default run small


def _assert_tree_agrees(inst: Any, h: int, value: Fraction) -> None:
    """The tree route's exact bracket is ``value`` itself, or (rarely: the LP's rounded
    solutions miss) contains it with the LP value within its tolerance."""
    v = game_value(inst, h)
    b = v.bracket
    if b.closed:
        assert b.exact == value, (h, b.exact, value)
    else:
        assert b.lower <= value <= b.upper, (h, b, value)
        assert abs(v.value - float(value)) <= 1e-7 * max(1.0, abs(float(value)))


@pytest.mark.parametrize("case", CASES, ids=[c["name"] for c in CASES])
def test_structured_equals_tree_on_every_conformance_case(case: dict[str, Any]) -> None:
    inst = instance_from_json(case["instance"])
    expected = case["expected"]
    u = Fraction(expected["value"])
    assert structured_value(inst, None).value == u  # the untruncated game's value is U*
    h0 = inst.hops[inst.start]
    horizons = sorted({h0, expected["H"], expected["H"] + 1})
    compared = 0
    for h in horizons:
        if h < h0 or count_prefixes(inst, h) > MAX_TREE:
            continue
        _assert_tree_agrees(inst, h, Fraction(structured_value(inst, h).value))
        compared += 1
    assert compared >= 1
    assert structured_value(inst, expected["H"]).value == u  # H covers the profile


exact_instances = st.one_of(
    instances(),
    instances(graphs=weighted_graphs(max_nodes=6, weights="fractions", max_weight=4)),
    instances(graphs=weighted_graphs(max_nodes=6, directed=True, strongly_connected=False)),
    grid_worlds(max_size=3, max_cells=8),
)


@settings(deadline=None)
@given(exact_instances, st.integers(min_value=0, max_value=3))
def test_structured_equals_tree_on_random_instances(doc: dict[str, Any], extra: int) -> None:
    inst = instance_from_json(doc)
    h = inst.hops[inst.start] + extra
    if count_prefixes(inst, h) <= MAX_TREE:
        _assert_tree_agrees(inst, h, Fraction(structured_value(inst, h).value))


@settings(deadline=None)
@given(exact_instances)
def test_value_is_non_increasing_in_H_and_equals_U_once_H_covers_the_profile(
        doc: dict[str, Any]) -> None:
    eq = paper_equilibrium(solver_instance_from_json(doc))
    longest = max(len(eq.secondary_path) - 1, *(len(p.nodes) - 1 for p in eq.primary_paths))
    inst = instance_from_json(doc)
    h0 = inst.hops[inst.start]
    values = [structured_value(inst, h).value for h in range(h0, longest + 3)]
    assert all(a >= b for a, b in itertools.pairwise(values))
    assert values[longest - h0:] == [eq.U] * (len(values) - (longest - h0))
    assert structured_value(inst, None).value == eq.U


def test_the_fields_stop_at_their_fixpoint_and_agree_beyond_it() -> None:
    inst = instance_from_json(three_phase_doc())
    f = value_fields(inst, None)
    assert f.fixpoint and f.steps <= 2 * inst.n_nodes
    for h in (f.steps, f.steps + 5, 1000):
        g = value_fields(inst, h)
        assert g.fixpoint and (g.d1 == f.d1).all() and (g.m == f.m).all()
    assert structured_value(inst, 1000).value == Fraction(71, 18)


def test_unreachable_horizon_is_refused_like_the_tree() -> None:
    inst = instance_from_json(three_phase_doc())
    with pytest.raises(HorizonError, match="no walk from the start reaches a goal within H = 1"):
        structured_value(inst, 1)
    with pytest.raises(HorizonError, match="negative"):
        structured_value(inst, -1)


def _scaled(factor: int | Fraction) -> dict[str, Any]:
    edges = [(0, 1, 3), (0, 2, 4), (0, 4, 1), (0, 5, 2), (1, 2, Fraction(10, 3)), (1, 3, 1),
             (2, 5, Fraction(1, 2))]
    return make_doc([(u, v, str(w * factor)) for u, v, w in edges], 3, [4, 2], ["1/3", "2/3"],
                    nodes=[0, 1, 2, 3, 4, 5])


def test_huge_weights_fall_back_to_exact_python_integers() -> None:
    big = 10**18 + 7
    small = structured_value(instance_from_json(_scaled(1)), 6)
    huge = structured_value(instance_from_json(_scaled(big)), 6)
    assert small.arithmetic == "int64" and huge.arithmetic == "python-int"
    assert huge.value == small.value * big  # V_H is positively homogeneous in the weights
    assert small.value == Fraction(71, 18)


def test_float_mode_is_computed_in_floats_within_the_tolerance() -> None:
    doc = dict(_scaled(1), numbers="float")
    doc["graph"] = dict(doc["graph"], edges=[dict(e, weight=float(Fraction(e["weight"])))
                                              for e in doc["graph"]["edges"]])
    v = structured_value(instance_from_json(doc), None)
    assert v.arithmetic == "float64" and not v.exact and isinstance(v.value, float)
    assert abs(v.value - 71 / 18) <= 1e-9 * 71 / 18


def test_routes() -> None:
    inst = triangle()
    assert tree_fits(inst, 3, 3) and not tree_fits(inst, 3, 2)
    assert resolve_route("auto", inst, 3, 2) == "structured"
    assert resolve_route("auto", inst, None, 10**6) == "structured"
    with pytest.raises(HorizonError, match="finite horizon"):
        resolve_route("both", inst, None, 10**6)
    for h in range(1, 8):  # the saturated count agrees with the exact count
        n = count_prefixes(instance_from_json(three_phase_doc()), h)
        assert tree_fits(instance_from_json(three_phase_doc()), h, max(n, 1))
        assert n <= 1 or not tree_fits(instance_from_json(three_phase_doc()), h, n - 1)
    r = routed_value(inst, 2, route="both")
    assert r.disagreement is None and r.tree is not None and r.structured is not None


def _run(args: list[str]) -> Any:
    return CliRunner().invoke(value_command, args)


def test_value_command_routes(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    i = tmp_path / "i.json"
    i.write_text(json.dumps(three_phase_doc()), encoding="utf-8")
    r = _run([str(i), "--horizon", "inf"])
    assert r.exit_code == 0
    assert r.output.startswith("V_H (H = inf) = 71/18 (≈ 3.944) exactly; structured")
    r = _run([str(i), "-H", "4", "--route", "both", "--json"])
    doc = json.loads(r.output)
    assert r.exit_code == 0 and doc["route"] == "both" and doc["agree"]
    assert doc["value"] == doc["structured"]["value"] == "71/18"
    r = _run([str(i), "-H", "4", "--max-prefixes", "3", "--json"])  # auto: tree does not fit
    assert r.exit_code == 0 and json.loads(r.output)["route"] == "structured"
    r = _run([str(i), "-H", "4", "--route", "tree", "--max-prefixes", "3"])
    assert r.exit_code == 2 and "more than the limit" in r.output
    r = _run([str(i), "-H", "inf", "--route", "tree"])
    assert r.exit_code == 2 and r.output.count("\n") == 1 and "finite horizon" in r.output
    r = _run([str(i), "-H", "1", "--route", "structured"])
    assert r.exit_code == 2 and "no walk" in r.output
    assert _run([str(i), "-H", "-3"]).exit_code == 2

    def wrong(instance: Any, horizon: int | None) -> StructuredValue:  # a broken DP
        v = structured_value(instance, horizon)
        return StructuredValue(**{**v.__dict__, "value": v.value + Fraction(1, 10)})

    monkeypatch.setattr(dppverify.routes, "structured_value", wrong)
    r = _run([str(i), "-H", "4", "--route", "both"])
    assert r.exit_code == 1 and "the routes disagree: tree V_H = 71/18" in r.output
