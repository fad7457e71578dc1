"""Certifying N-goal profiles: the equilibrium passes, corruptions are refuted by name."""

from __future__ import annotations

import copy
import re
from pathlib import Path
from typing import Any

import pytest

from dppverify.certify import certify
from dppverify.errors import HorizonError, ProfileError
from dppverify.game.examples import star3, star3_document, star3_profile, triangle
from dppverify.game.inputs import as_profile
from dppverify.registry import check_ids, checks_of, kind_of, spec

ROOT = Path(__file__).resolve().parents[2]


def _failed(profile: dict[str, Any], **kw: Any) -> set[str]:
    kw.setdefault("horizon", 2)  # the hub profile is an equilibrium of the 2-step game only
    cert = certify(star3_document(), profile, **kw)
    return {c.id for c in cert.checks if c.status == "fail"}


def test_the_equilibrium_passes_and_a_longer_game_needs_a_longer_table() -> None:
    cert = certify(star3_document(), star3_profile(), horizon=2)
    assert cert.passed, cert.failed()
    assert [c.id for c in cert.checks] == list(check_ids("per-goal"))
    assert cert.check("game.value").numbers["V_H_lower"] == cert.check(
        "value.U").numbers["U"]
    # At H = 4 type b may loop s m s m b: the table lists only s m b, the default guards a.
    cert = certify(star3_document(), star3_profile(), horizon=4)
    rec = cert.check("pbne.attacker_br")
    assert rec.status == "fail" and "['s', 'm', 's', 'm', 'b'] costs 0" in rec.message
    assert cert.check("pbne.defender_br").status == "pass"


def test_every_n_goal_check_id_is_in_the_registry_and_the_checks_md_table() -> None:
    """One check vocabulary for any N: a shared id keeps its kind and routes, and every id of
    an N-goal certificate (tree route, structured route, both) is a registry id."""
    per_goal = checks_of("per-goal")
    shared = {c.id for c in checks_of("two-goal")} & {c.id for c in per_goal}
    assert shared == {"profile.wellformed", "value.U", "pbne.defender_br",
                      "pbne.sequential_rationality", "game.value"}
    for c in per_goal:
        if c.id in shared:
            assert (spec(c.id).kind, spec(c.id).routes) == (c.kind, c.routes), c.id
        assert kind_of(c.id) == c.kind
    for kw in ({"horizon": 2}, {}, {"horizon": 2, "route": "both"}):
        cert = certify(star3_document(), star3_profile(), **kw)
        assert {c.id for c in cert.checks} | set(cert.not_run) <= set(check_ids("per-goal")), kw
    table = (ROOT / "dppverify" / "checks.md").read_text(encoding="utf-8")
    part = table.split("## N goals", 1)[1]
    rows = re.findall(r"^\| `([^`]+)` \| ([A-Z0-9–-]+) \|", part, flags=re.M)
    assert rows == [(c.id, c.proof) for c in per_goal]


def test_a_type_with_a_cheaper_walk_is_refuted() -> None:
    p = star3_profile()
    p["attacker"][1] = [{"path": ["s", "a"], "probability": 1}]  # b: 0 + d(a, b) = 2 > 1
    rec = certify(star3_document(), p, horizon=2).check("pbne.attacker_br")
    assert rec.status == "fail" and rec.numbers["regret2"] == 1
    assert "walk ['s', 'm', 'b'] costs 1" in rec.message


def test_a_defender_off_the_belief_is_refuted() -> None:
    p = star3_profile()
    p["defender"]["entries"].append({"walk": ["s", "m"], "probabilities": ["1/2", "1/2", 0]})
    failed = _failed(p)
    assert {"pbne.sequential_rationality", "pbne.defender_br"} <= failed


def test_a_wrong_claimed_value_is_refuted() -> None:
    p = star3_profile()
    p["value"]["U"] = "7/5"
    assert _failed(p) == {"value.U"}


@pytest.mark.parametrize(("change", "message"), [
    (lambda p: p["attacker"][1][0].update(probability="1/2"), "probabilities sum to 1/2"),
    (lambda p: p["attacker"][2][0].update(path=["s", "c"]), "no edge \"s\" -> \"c\""),
    (lambda p: p["defender"].pop("default"), "no entry for walk ['s', 'm']"),
    (lambda p: p["defender"].update(default=[1, 0]), "list of 3 probabilities"),
    (lambda p: p.update(goals=["b", "a", "c"]), "instance's goals"),
    (lambda p: p.update(defender={"rule": "progress", "goal": "a"}),
     "or {\"rule\": \"guarantee\""),
    (lambda p: p.update(defender={"rule": "guarantee", "h": [1, 2]}), "list of 3 numbers"),
    (lambda p: p.update(defender={"rule": "guarantee", "h": [1, 2, "x"]}), "defender.h[2]"),
    (lambda p: p.update(defender={"rule": "guarantee", "h": [1, 2, 3], "order": [0]}),
     "unknown key(s) order"),
])
def test_ill_formed_profiles_are_refuted_not_crashed(change: Any, message: str) -> None:
    p = copy.deepcopy(star3_profile())
    change(p)
    cert = certify(star3_document(), p, horizon=2)
    rec = cert.check("profile.wellformed")
    assert rec.status == "fail" and message in rec.message
    assert cert.verdict == "fail"
    assert all(c.status == "skipped" for c in cert.checks[1:])


def test_bad_input_is_an_error() -> None:
    with pytest.raises(HorizonError, match=r"shorter than the profile.s longest walk .* or "
                                           r"none for the untruncated game"):
        certify(star3_document(), star3_profile(), horizon=1)
    with pytest.raises(ProfileError, match="dpp-ngoal-profile/1"):
        as_profile(b'{"format": "dpp-profile/1"}', star3())
    with pytest.raises(ProfileError, match="not JSON"):
        as_profile(b"{", triangle())
