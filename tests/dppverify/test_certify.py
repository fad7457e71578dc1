"""certify(): hand-built equilibria certify; labellings, tables, horizons, float mode."""

from __future__ import annotations

import copy
import json
from fractions import Fraction
from pathlib import Path
from typing import Any

import pytest

from dppverify import (
    HorizonError,
    InvalidInstanceError,
    TreeTooLargeError,
    certify,
    instance_from_json,
)
from dppverify.formats.json_reading import parse_json
from dppverify.registry import checks_of
from dppverify.tree_route.tree import build_tree
from solver import instance_from_json as solver_instance_from_json
from solver import instance_to_json
from tests.dppverify._helpers import (
    grid_doc,
    load_cases,
    make_doc,
    profile_doc,
    three_phase_doc,
    three_phase_profile,
    tree_horizon,
    triangle_doc,
    triangle_profile,
)


def _assert_certified(instance: Any, profile: Any, **kw: Any) -> None:
    cert = certify(instance, profile, **kw)
    assert cert.verdict == "pass", [(c.id, c.status, c.message) for c in cert.failed()]
    route = "structured" if cert.route == "structured" else "tree"
    assert tuple(c.id for c in cert.checks) == tuple(c.id for c in checks_of("two-goal")
                                                     if route in c.routes)


def test_triangle_of_formats_md_certifies_with_the_documented_numbers() -> None:
    cert = certify(triangle_doc(), triangle_profile(), horizon=1)
    assert cert.passed and cert.horizon == 1 and cert.prefixes == 3
    u = cert.check("value.U").numbers
    assert u["U"] == Fraction(12, 5) and u["U_profile"] == Fraction(12, 5)
    assert abs(float(u["U_lp"] or 0) - 2.4) < 1e-7
    assert cert.check("value.VoI").numbers["VoI"] == Fraction(1, 9)
    assert cert.check("game.value").numbers["V_H"] == Fraction(12, 5)
    assert cert.check("pbne.defender_br").numbers["regret"] == 0
    assert cert.check("lemma.L3.greedy").proof == "L3"


def test_three_phase_equilibrium_written_by_hand_certifies() -> None:
    cert = certify(three_phase_doc(), three_phase_profile())
    assert cert.passed
    l5 = cert.check("lemma.L5.induced_beliefs").numbers
    assert (l5["t_I"], l5["t_II"], l5["T"]) == (1, 2, 3)
    assert cert.check("value.U").numbers["U"] == Fraction(71, 18)
    # a longer horizon covers deviations with more steps: still an equilibrium
    _assert_certified(three_phase_doc(), three_phase_profile(), horizon=6)


def test_equilibrium_through_the_fake_goal_certifies() -> None:
    """g1 reachable only through g2: both types walk to g2 (proofs/README.md, edge cases)."""
    doc = make_doc([("s", "b", 1), ("b", "g2", 1), ("g2", "g1", 1), ("g1", "g2", 1)], "s",
                   ["g2", "g1"], ["2/5", "3/5"], directed=True)
    prof = profile_doc([(["s", "b", "g2"], 1)], [(["s", "b", "g2"], 1)], ("g1", "g2"),
                       value={"U1": "3", "U2": "0", "U": "9/5"})
    _assert_certified(doc, prof, horizon=4)


def test_start_at_a_goal() -> None:
    doc = make_doc([("g1", "a", 1), ("a", "g2", 1)], "g1", ["g1", "g2"], ["3/4", "1/4"])
    prof = profile_doc([(["g1"], 1)], [(["g1"], 1)], ("g1", "g2"),
                       value={"U1": "0", "U2": "2", "U": "1/2"})
    cert = certify(doc, prof)
    assert cert.passed and cert.horizon is None and cert.route == "structured"
    cert = certify(doc, prof, horizon=0)
    assert cert.passed and cert.horizon == 0 and cert.prefixes == 1


def test_table_defender_equal_to_sigma_star_certifies() -> None:
    """The same σ* written as an explicit table of allocations (to g2, the other goal)."""
    inst = instance_from_json(three_phase_doc())
    tree = build_tree(inst, 4)
    from dppverify.game.profile import ProgressRule
    from dppverify.tree_route.tree_defender import tree_defender

    r = inst.roles()
    td = tree_defender(tree, r, ProgressRule(r.g1))
    entries = [{"walk": list(inst.labels(tree.walk(p))), "probability": str(1 - td.sigma1[p])}
               for p in range(1, tree.n_prefixes)]
    prof = three_phase_profile()
    prof["defender"] = {"rule": "table", "goal": 4, "entries": entries}
    _assert_certified(three_phase_doc(), prof, horizon=4)
    prof["defender"] = {"rule": "table", "goal": 2, "entries": [], "default": "progress"}
    _assert_certified(three_phase_doc(), prof)


def test_either_labelling_at_prior_one_half() -> None:
    from solver.twogoal.equilibrium import paper_equilibrium

    case = next(c for c in load_cases() if c["name"] == "b_half")
    doc = case["instance"]
    swapped = dict(doc, goals=doc["goals"][::-1])
    for d in (doc, swapped):
        prof = paper_equilibrium(solver_instance_from_json(d)).to_json()
        _assert_certified(doc, prof)
    bad = copy.deepcopy(triangle_profile())
    bad["goals"] = {"primary": "g2", "secondary": "g1"}
    assert certify(triangle_doc(), bad).check("profile.wellformed").status == "fail"


@pytest.mark.parametrize("case", load_cases(), ids=lambda c: c["name"])
def test_solver_profiles_of_all_conformance_cases_certify(case: dict[str, Any]) -> None:
    from solver.twogoal.equilibrium import paper_equilibrium

    prof = paper_equilibrium(solver_instance_from_json(case["instance"])).to_json()
    cert = certify(case["instance"], parse_json(json.dumps(prof)), trials=2)
    assert cert.passed, [(c.id, c.message) for c in cert.failed()]
    assert cert.check("value.U").numbers["U"] == Fraction(case["expected"]["value"])
    assert cert.check("value.VoI").numbers["VoI"] == Fraction(case["expected"]["voi"])


def test_horizon_shorter_than_the_profile_is_an_error() -> None:
    with pytest.raises(HorizonError, match=r"shorter than the profile.s longest path .*: give "
                                           r"a horizon of at least .*, or none for the "
                                           r"untruncated game"):
        certify(three_phase_doc(), three_phase_profile(), horizon=3)
    with pytest.raises(TreeTooLargeError):
        certify(three_phase_doc(), three_phase_profile(), horizon=30, max_prefixes=1000,
                route="tree")
    # auto: a tree that does not fit goes to the structured route at the same horizon
    cert = certify(three_phase_doc(), three_phase_profile(), horizon=30, max_prefixes=1000)
    assert cert.route == "structured" and cert.horizon == 30 and cert.passed


def test_files_and_paths(tmp_path: Path) -> None:
    inst, prof = tmp_path / "i.json", tmp_path / "p.json"
    inst.write_text(json.dumps(three_phase_doc()))
    prof.write_text(json.dumps(three_phase_profile()))
    assert certify(inst, prof).passed
    assert certify(str(inst), str(prof)).passed
    assert certify(instance_from_json(three_phase_doc()), prof.read_bytes()).passed


def test_float_mode_is_refused_unless_asked_for() -> None:
    doc = grid_doc(2, 3, (0, 0), [(1, 2), (0, 2)], ["3/5", "2/5"])
    doc["numbers"] = "float"
    prof = profile_doc([([[0, 0], [0, 1], [0, 2]], "1/3"), ([[0, 0], [1, 0], [1, 1], [1, 2]],
                                                           "2/3")],
                       [([[0, 0], [0, 1], [0, 2]], 1)], ([1, 2], [0, 2]))
    with pytest.raises(InvalidInstanceError, match="cannot be certified exactly"):
        certify(doc, prof)
    cert = certify(doc, prof, exact=False)
    assert not cert.exact and cert.tolerance == 1e-9
    assert cert.to_json()["tolerance"] == 1e-9


def test_octile_grid_from_the_solver_certifies_in_float_mode() -> None:
    import numpy as np

    from solver import Instance
    from solver.twogoal.equilibrium import paper_equilibrium

    blocked = np.zeros((3, 4), dtype=bool)
    blocked[1, 1] = True
    inst = Instance.from_grid(blocked, (2, 0), ((0, 3), (0, 0)), ("3/5", "2/5"),
                              connectivity=8)
    idoc = parse_json(json.dumps(instance_to_json(inst)))
    assert idoc["numbers"] == "float"
    pdoc = parse_json(json.dumps(paper_equilibrium(inst).to_json()))
    cert = certify(idoc, pdoc, exact=False)
    assert cert.passed, [(c.id, c.message) for c in cert.failed()]


def test_seed_is_recorded_and_results_are_reproducible() -> None:
    h = tree_horizon(three_phase_doc(), three_phase_profile())
    a = certify(three_phase_doc(), three_phase_profile(), seed=7, trials=3, horizon=h)
    b = certify(three_phase_doc(), three_phase_profile(), seed=7, trials=3, horizon=h)
    assert a.seed == 7 and a.check("lemma.L3.greedy").numbers["seed"] == 7
    assert a.check("lemma.L4.monotonicity").to_json() == b.check("lemma.L4.monotonicity").to_json()
