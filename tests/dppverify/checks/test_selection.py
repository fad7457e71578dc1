"""The checker's goal-selection certificate (proofs/SELECT.md SELECT.6, SELECT.7).

- The 2025 σ* played against a chosen goal is refuted on paper10.map, naming the cheap goal
  (0, 0) (c = 7 against 18) and the gain of choosing at the prior 3/5 (68/5 − 25/2 = 11/10);
- mutants of an equilibrium profile fail the check that names what is wrong: a choice that
  is not optimal, the wrong mixture weight, h off the diagonal, a claimed value, a walk that is
  not a best response, a broken document;
- the mixture's exact best response equals brute force over all short walks on tiny graphs.
"""

from __future__ import annotations

import copy
import itertools
from fractions import Fraction
from pathlib import Path
from typing import Any

import pytest

from dppverify.checks.selection import selection_checks
from dppverify.errors import ProfileError
from dppverify.game.instance import instance_from_json
from dppverify.game.mixture_rule import ProgressMixture
from dppverify.game.selection_profile import selection_profile_from_json
from dppverify.structured.mixture_br import mixture_response
from dppverify.structured.selection_value import selection_value
from solver.game.instance import Instance
from solver.selection.equilibrium import selection_equilibrium
from solver.solution import solve
from tests.solver.selection.test_equilibrium import PAPER10, paper10


def _statuses(doc: dict[str, Any], profile: dict[str, Any]) -> dict[str, Any]:
    sel = instance_from_json(doc)
    return {r.id: r for r in selection_checks(sel, selection_profile_from_json(profile, sel))}


def test_paper_sigma_star_against_a_chosen_goal_is_refuted_naming_the_cheap_goal() -> None:
    from solver.formats.movingai import map_file, read_map_bytes
    blocked, _ = read_map_bytes(map_file(str(PAPER10)))
    paper = solve(Instance.from_grid(blocked, (9, 0), [(0, 9), (0, 0)], ["3/5", "2/5"]))
    recs = _statuses(paper10(), paper.to_json())
    # an equilibrium of the game with the prior 3/5 ...
    assert all(recs[i].passed for i in ("profile.wellformed", "pbne.attacker_br",
                                        "pbne.defender_br", "game.value"))
    # ... but not of the game where the Attacker chooses
    ind = recs["selection.goal_indifference"]
    assert ind.status == "fail" and "goal (0, 0) is cheap" in ind.message
    assert (ind.numbers["c1"], ind.numbers["c2"], ind.numbers["V"]) == (18, 7, 7)
    val = recs["selection.value"]
    assert val.status == "fail"
    assert val.numbers["V_sel_lower"] == Fraction(25, 2) and val.numbers["gain"] == Fraction(11, 10)


@pytest.fixture(scope="module")
def equilibrium() -> dict[str, Any]:
    return selection_equilibrium(paper10(), rule="mixture").to_json()


def test_the_equilibrium_passes(equilibrium: dict[str, Any]) -> None:
    assert all(r.passed for r in _statuses(paper10(), equilibrium).values())


def test_a_choice_that_is_not_optimal_fails_goal_indifference(equilibrium: dict[str, Any]
                                                               ) -> None:
    bad = {**equilibrium, "choice": ["3/5", "2/5"]}
    recs = _statuses(paper10(), bad)
    # the Defender mixing at 9/20 is no longer greedy for the belief 3/5 on the shared prefix
    assert recs["pbne.defender_br"].status == "fail"


def test_the_wrong_weight_is_refuted(equilibrium: dict[str, Any]) -> None:
    bad = copy.deepcopy(equilibrium)
    bad["defender"]["alpha"] = "1/2"
    recs = _statuses(paper10(), bad)
    assert recs["selection.goal_indifference"].status == "fail"  # c = (13, 12): (0, 0) cheap
    assert "(0, 0) is cheap" in recs["selection.goal_indifference"].message


def test_h_off_the_diagonal_is_refuted() -> None:
    prof = selection_equilibrium(paper10()).to_json()
    prof["defender"]["h"] = ["13", "12"]
    recs = _statuses(paper10(), prof)
    assert not all(r.passed for r in recs.values())


def test_a_wrong_claimed_value_is_refuted(equilibrium: dict[str, Any]) -> None:
    bad = copy.deepcopy(equilibrium)
    bad["value"]["V"] = "12"
    assert _statuses(paper10(), bad)["selection.value"].status == "fail"


def test_a_walk_that_is_not_a_best_response_is_refuted(equilibrium: dict[str, Any]) -> None:
    bad = copy.deepcopy(equilibrium)
    bad["attacker"][0] = [{"path": [[9, 0], [9, 1], [9, 2], [9, 1], [9, 0], [8, 0]],
                           "probability": 1}]  # ends nowhere: not a walk of the game
    assert _statuses(paper10(), bad)["profile.wellformed"].status == "fail"
    detour = selection_equilibrium(paper10(), rule="mixture").strategies[0][0].nodes
    bad["attacker"][0] = [{"path": [list(detour[0]), [9, 1], *map(list, detour)],
                           "probability": 1}]
    recs = _statuses(paper10(), bad)
    assert recs["pbne.attacker_br"].status == "fail"


def test_broken_documents(equilibrium: dict[str, Any]) -> None:
    recs = _statuses(paper10(), {**equilibrium, "choice": ["1/2", "1/3"]})
    assert recs["profile.wellformed"].message.startswith("choice: probabilities sum to 5/6")
    assert recs["selection.value"].status == "skipped"
    three = paper10([[0, 9], [0, 0], [9, 9]])
    bad = {**equilibrium, "choice": ["1/3"] * 3, "attacker": equilibrium["attacker"] + [[]]}
    assert "two-goal Defender" in _statuses(three, bad)["profile.wellformed"].message
    with pytest.raises(ProfileError, match="dpp-selection-profile/1"):
        selection_profile_from_json({"format": "dpp-ngoal-profile/1"},
                                    instance_from_json(paper10()))
    paper = {"format": "dpp-profile/1", "goals": {"primary": [0, 9], "secondary": [0, 0]},
             "defender": {"rule": "progress", "goal": [0, 9]}, "attacker": {}}
    assert "prior" in _statuses(paper10(), paper)["profile.wellformed"].message


TINY = [
    {"graph": {"nodes": [{"id": x} for x in "sab12"],
               "edges": [{"source": "s", "target": "a", "weight": 1},
                         {"source": "s", "target": "b", "weight": 2},
                         {"source": "a", "target": "b", "weight": 1},
                         {"source": "a", "target": "1", "weight": 3},
                         {"source": "b", "target": "2", "weight": 1},
                         {"source": "a", "target": "2", "weight": "5/2"},
                         {"source": "1", "target": "2", "weight": 2}]},
     "start": "s", "goals": ["1", "2"], "prior": ["1/2", "1/2"]},
    {"graph": {"directed": True, "nodes": [{"id": x} for x in "sabc12"],
               "edges": [{"source": u, "target": v, "weight": w} for u, v, w in (
                   ("s", "a", 1), ("a", "s", 1), ("a", "b", 2), ("b", "c", 1), ("c", "a", 1),
                   ("b", "1", 2), ("c", "2", 1), ("s", "2", 4), ("1", "2", 1), ("2", "1", 3),
                   ("a", "1", 4))]},
     "start": "s", "goals": ["1", "2"], "prior": ["1/2", "1/2"]},
]


def _brute_force(inst: Any, mix: ProgressMixture, theta: int, steps: int) -> Fraction:
    best = None
    frontier = [(inst.start,)]
    for _ in range(steps + 1):
        nxt = []
        for walk in frontier:
            v = walk[-1]
            if v in inst.goals:
                cost = Fraction(inst.dist_to[theta][v]) + sum(
                    (Fraction(inst.weight(a, b)) * d[theta]
                     for (a, b), d in zip(itertools.pairwise(walk), mix.along(inst, walk),
                                          strict=True)), Fraction(0))
                best = cost if best is None or cost < best else best
                continue
            nxt += [(*walk, u) for u, _ in inst.succ[v]]
        frontier = nxt
    assert best is not None
    return best


@pytest.mark.parametrize("doc", TINY)
@pytest.mark.parametrize("alpha", [Fraction(0), Fraction(1, 3), Fraction(9, 20), Fraction(1)])
def test_the_mixture_best_response_is_the_minimum_over_walks(doc: dict[str, Any],
                                                             alpha: Fraction) -> None:
    inst = instance_from_json(doc)
    for goal in (0, 1):
        mix = ProgressMixture(goal, alpha)
        for theta in (0, 1):
            exact = mixture_response(inst, mix, theta, cost=10 ** 6)  # force the search
            assert exact.walk is not None and exact.value is not None
            assert exact.value >= exact.lower  # SELECT.7(a)
            assert exact.value == _brute_force(inst, mix, theta, 9)
            bound = mixture_response(inst, mix, theta, cost=exact.lower)
            assert bound.how.startswith("the mixture of the two progress rules")


def test_the_value_of_a_truncated_game_and_the_bracket(monkeypatch: pytest.MonkeyPatch,
                                                       tmp_path: Path) -> None:
    from tests.solver._ngoal_families import GADGET
    doc = {k: v for k, v in GADGET.items() if k != "prior"} | {"goal_selection": True}
    sel = instance_from_json(doc)
    exact = selection_value(sel)
    assert exact.value is not None and exact.normals  # needs the normals (2, 2, 2, 1)
    import dppverify.structured.proved_value as pv
    monkeypatch.setattr(pv, "MAX_ROUNDS", 0)  # no refinement: the coalition sets fail
    open_ = selection_value(sel)
    assert open_.value is None and open_.lower <= exact.value <= open_.upper
    assert "coalition DP" in open_.upper_source and open_.reason
    assert selection_value(sel, 3).upper >= selection_value(sel, 7).upper


def test_the_selection_ids_are_the_registry_and_the_checks_md_table() -> None:
    import re

    from dppverify.registry import checks_of, kind_of
    selection = checks_of("selection")
    table = (Path(__file__).resolve().parents[3] / "dppverify" / "checks.md").read_text()
    part = table.split("## Goal selection", 1)[1].split("\n## ", 1)[0]
    rows = re.findall(r"^\| `([^`]+)` \| ([A-Z0-9]+) \|", part, flags=re.M)
    assert rows == [(c.id, c.proof) for c in selection if c.id.startswith("selection.")]
    recs = _statuses(paper10(), selection_equilibrium(paper10()).to_json())
    assert list(recs) == [c.id for c in selection]
    assert all(kind_of(i) == "check" for i in recs)


def test_dppverify_certify_is_the_one_flow_for_the_goal_selection_game() -> None:
    """``dppverify.certify`` takes the goal-selection instance and profile at its door, runs the
    ``selection`` suite on the untruncated game and forms the certificate with its provenance."""
    from dppverify.certificate import Certificate
    from dppverify.certify import certify
    from dppverify.errors import HorizonError
    prof = selection_equilibrium(paper10(), rule="mixture").to_json()
    cert = certify(paper10(), prof)
    assert cert.verdict == "pass" and cert.route == "structured" and cert.horizon is None
    assert cert.info["game"] == "goal selection" and cert.provenance is not None
    assert Certificate.from_json(cert.to_json()) == cert
    with pytest.raises(HorizonError, match="untruncated game"):
        certify(paper10(), prof, horizon=40)
    with pytest.raises(ProfileError, match="dpp-selection-profile/1"):
        certify(paper10(), {"format": "dpp-ngoal-profile/1"})
