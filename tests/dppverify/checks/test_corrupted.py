"""Corrupted profiles are refuted with the failing check named — never an exception.

Each corruption starts from a hand-built equilibrium (the triangle of formats.md, the
three-phase instance of ``_helpers.three_phase_doc``, or the prose-mixing instance) and
must make ``certify`` return a failing certificate whose failed checks include the expected
ids. Suboptimality claims are re-derived from the input by brute force (naive σ*, all walks).
"""

from __future__ import annotations

import copy
from collections.abc import Callable
from fractions import Fraction
from pathlib import Path
from typing import Any

import pytest

from dppverify import ProfileError, certify
from tests.dppverify._helpers import (
    all_walks,
    load_cases,
    profile_doc,
    progress_costs,
    three_phase_doc,
    three_phase_profile,
    triangle_doc,
    triangle_profile,
)

Mutation = Callable[[dict[str, Any]], None]


def _prose_case() -> tuple[dict[str, Any], dict[str, Any]]:
    case = next(c for c in load_cases() if c["name"] == "prose_mixing_exploitable")
    # g1 = 2 (7/10), g2 = 1; ξ² = 0 3 1; ξ^{1,I} = 0 2, ξ^{1,II} = 0 3 2 (eq. (15): 4/7, 3/7)
    prof = profile_doc([([0, 2], "4/7"), ([0, 3, 2], "3/7")], [([0, 3, 1], 1)], (2, 1))
    return case["instance"], prof


def _set_primary(paths: list[tuple[list[Any], str]]) -> Mutation:
    def mutate(doc: dict[str, Any]) -> None:
        doc["attacker"]["primary"] = [{"path": p, "probability": q} for p, q in paths]
    return mutate


def _set(path: tuple[Any, ...], value: Any) -> Mutation:
    def mutate(doc: dict[str, Any]) -> None:
        target = doc
        for key in path[:-1]:
            target = target[key]
        target[path[-1]] = value
    return mutate


def _delete(key: str) -> Mutation:
    return lambda doc: doc.pop(key)


TRI = (triangle_doc, triangle_profile)
PHASE3 = (three_phase_doc, three_phase_profile)

CORRUPTIONS: list[tuple[str, Any, Mutation, set[str]]] = [
    ("probabilities sum to 6/7", TRI,
     _set(("attacker", "primary", 0, "probability"), "3/7"), {"profile.wellformed"}),
    ("negative probability", TRI, _set_primary([(["s", "g1"], "8/7"), (["s", "g2"], "-1/7")]),
     {"profile.wellformed"}),
    ("probability is text", TRI, _set(("attacker", "primary", 0, "probability"), "most"),
     {"profile.wellformed"}),
    ("step that is not an edge", PHASE3, _set(("attacker", "primary", 0, "path"), [3, 2]),
     {"profile.wellformed"}),
    ("path not starting at s0", PHASE3,
     _set(("attacker", "secondary", 0, "path"), [1, 0, 4]), {"profile.wellformed"}),
    ("path not ending at a goal", PHASE3,
     _set(("attacker", "secondary", 0, "path"), [3, 1, 0]), {"profile.wellformed"}),
    ("path continuing past its first goal", PHASE3,
     _set(("attacker", "secondary", 0, "path"), [3, 1, 0, 4, 0, 4]), {"profile.wellformed"}),
    ("unknown node", PHASE3, _set(("attacker", "primary", 0, "path"), [3, 1, 99, 2]),
     {"profile.wellformed"}),
    ("node id of the wrong type", PHASE3, _set(("attacker", "primary", 0, "path"),
                                               [3, {"x": 1}, 2]), {"profile.wellformed"}),
    ("duplicate walks", PHASE3, _set_primary([([3, 1, 2], "1/2"), ([3, 1, 2], "1/2")]),
     {"profile.wellformed"}),
    ("empty path", TRI, _set(("attacker", "secondary", 0, "path"), []), {"profile.wellformed"}),
    ("missing attacker", TRI, _delete("attacker"), {"profile.wellformed"}),
    ("missing defender", TRI, _delete("defender"), {"profile.wellformed"}),
    ("unknown defender rule", TRI, _set(("defender", "rule"), "oracle"),
     {"profile.wellformed"}),
    ("defender goal not a goal", TRI, _set(("defender", "goal"), "s"), {"profile.wellformed"}),
    ("goals labelled the wrong way", TRI, _set(("goals",), {"primary": "g2",
                                                             "secondary": "g1"}),
     {"profile.wellformed"}),
    ("table without default missing walks", TRI,
     _set(("defender",), {"rule": "table", "goal": "g1",
                          "entries": [{"walk": ["s", "g1"], "probability": 1}]}),
     {"profile.wellformed"}),
    ("table probability above 1", TRI,
     _set(("defender",), {"rule": "table", "goal": "g1", "default": "progress",
                          "entries": [{"walk": ["s", "g1"], "probability": 2}]}),
     {"profile.wellformed"}),
    ("suboptimal secondary path (to the fake goal)", PHASE3,
     _set(("attacker", "secondary", 0, "path"), [3, 1, 2]), {"pbne.attacker_br.secondary"}),
    ("suboptimal secondary walk (revisits node 0)", PHASE3,
     _set(("attacker", "secondary", 0, "path"), [3, 1, 0, 5, 0, 4]),
     {"pbne.attacker_br.secondary"}),
    ("suboptimal primary path (via g2 without progress)", PHASE3,
     _set_primary([([3, 1, 0, 4], "1/2"), ([3, 1, 0, 5, 2], "1/2")]),
     {"pbne.attacker_br.primary"}),
    ("swapped mixing probabilities (triangle)", TRI,
     _set_primary([(["s", "g1"], "3/7"), (["s", "g2"], "4/7")]),
     {"pbne.defender_br", "pbne.sequential_rationality", "lemma.L5.induced_beliefs"}),
    ("primary never mixes", PHASE3, _set_primary([([3, 1, 2], "1")]),
     {"pbne.defender_br", "pbne.sequential_rationality", "lemma.L5.induced_beliefs"}),
    ("defender measures progress to g2", TRI, _set(("defender", "goal"), "g2"),
     {"pbne.attacker_br.primary"}),
    ("defender always allocates 1/2", PHASE3,
     _set(("defender",), {"rule": "table", "goal": 2, "default": "1/2"}),
     {"pbne.sequential_rationality"}),
    ("wrong claimed value", PHASE3, _set(("value", "U"), "4"), {"value.U"}),
    ("wrong claimed VoI", PHASE3, _set(("value", "VoI"), "1/8"), {"value.VoI"}),
    ("wrong claimed phases", PHASE3, _set(("phases",), {"t_I": 0, "t_II": 2, "T": 3}),
     {"profile.phases"}),
    ("wrong claimed prior", PHASE3, _set(("prior",), {"primary": "1/2",
                                                       "secondary": "1/2"}),
     {"pbne.belief_consistency"}),
]


@pytest.mark.parametrize(("name", "base", "mutate", "expected"), CORRUPTIONS,
                         ids=[c[0] for c in CORRUPTIONS])
def test_corruption_is_refuted_with_the_right_check(name: str, base: Any, mutate: Mutation,
                                                    expected: set[str]) -> None:
    make_instance, make_profile = base
    doc = copy.deepcopy(make_profile())
    mutate(doc)
    cert = certify(make_instance(), doc)
    failed = {c.id for c in cert.checks if c.status == "fail"}
    assert cert.verdict == "fail"
    assert expected <= failed, (failed, [c.message for c in cert.failed()])
    assert not any(c.status == "error" for c in cert.checks), cert.failed()
    if "profile.wellformed" in expected:
        dependent = [c for c in cert.checks if c.id.startswith(("pbne.", "value."))]
        assert all(c.status == "skipped" for c in dependent)


def test_prose_swapped_mixing_is_exploited_by_one_tenth_or_more() -> None:
    inst, prof = _prose_case()
    assert certify(inst, prof).verdict == "pass"
    prof["attacker"]["primary"][0]["probability"] = "3/7"
    prof["attacker"]["primary"][1]["probability"] = "4/7"
    cert = certify(inst, prof)
    rec = cert.check("pbne.defender_br")
    regret = rec.numbers["regret"]
    assert rec.status == "fail" and regret is not None and regret > 0
    assert cert.check("pbne.sequential_rationality").status == "fail"


def test_suboptimal_secondary_is_really_suboptimal_by_brute_force() -> None:
    inst = three_phase_doc()
    costs = {w: progress_costs(inst, w, 2, 4)[1] for w in all_walks(inst, 5)}
    best = costs[(3, 1, 0, 4)]
    assert best == min(costs.values()) == Fraction(19, 6)
    for walk in ((3, 1, 2), (3, 1, 0, 5, 0, 4)):
        assert costs[walk] > best
        doc = three_phase_profile()
        doc["attacker"]["secondary"][0]["path"] = list(walk)
        rec = certify(inst, doc).check("pbne.attacker_br.secondary")
        assert rec.numbers["regret"] == costs[walk] - best


def test_unreadable_profiles_raise_profile_error(tmp_path: Path) -> None:
    bad = tmp_path / "bad.json"
    for text in ("{oops", "[]", "{\"format\": \"dpp-profile/2\"}", "{}", "\"dpp-profile/1\""):
        bad.write_text(text)
        with pytest.raises(ProfileError) as info:
            certify(triangle_doc(), bad)
        assert "\n" not in str(info.value)
    with pytest.raises(ProfileError, match="cannot read"):
        certify(triangle_doc(), tmp_path / "missing.json")
    with pytest.raises(ProfileError):
        certify(triangle_doc(), {"format": None})


def test_garbage_everywhere_never_raises() -> None:
    """Every field replaced by junk of every JSON type: refuted, never an exception."""
    junk: list[Any] = [None, 0, -1, "x", [], {}, [None], {"a": []}, True, 1.5]
    base = three_phase_profile()
    paths: list[tuple[Any, ...]] = [("goals",), ("goals", "primary"), ("defender",),
                                    ("defender", "rule"), ("defender", "goal"), ("attacker",),
                                    ("attacker", "primary"), ("attacker", "secondary", 0),
                                    ("attacker", "primary", 1, "path"), ("value",),
                                    ("value", "U"), ("phases",), ("prior",), ("exact",),
                                    ("tolerance",)]
    for path in paths:
        for value in junk:
            doc = copy.deepcopy(base)
            _set(path, value)(doc)
            cert = certify(three_phase_doc(), doc, trials=1)
            assert cert.verdict in {"pass", "fail"}, (path, value, cert.failed())
            assert not any(c.status == "error" for c in cert.checks), (path, value)
