"""``dpp import-profile`` without the peers: the three forms of a behaviour profile of the
exported game come back as the same ``dpp`` profile, an equilibrium passes ``certify`` and a
perturbed one is refuted with its exact exploitability; floats are rationalised with the stated
tolerance; bad input is one line, exit 2, and writes nothing (the peers' own outputs:
tests/peers/test_import_profile.py)."""

from __future__ import annotations

import json
from fractions import Fraction
from pathlib import Path
from typing import Any

import pytest
from click.testing import CliRunner

from dppverify import certify
from dppverify.cli import main
from dppverify.game.examples import star3, star3_document, triangle, triangle_document
from dppverify.tree_route.efg_profile import exported_action_names, exported_infosets
from dppverify.tree_route.tree import build_tree

EQUILIBRIUM = {"T1 p0 h-": {"go g1": "4/7", "go g2": "3/7"},
               "T2 p0 h-": {"go g1": "0", "go g2": "1"},
               "D p1 h-": {"alloc g1": "1", "alloc g2": "0"},
               "D p2 h-": {"alloc g1": "1/2", "alloc g2": "1/2"}}
"""The paper's equilibrium of the triangle at H = 1 as a behaviour profile of its export:
the primary mixes s -> g1 (4/7) and s -> g2 (3/7), σ* puts 1 and 1/2 on g1."""


def _run(tmp_path: Path, *args: str) -> Any:
    return CliRunner().invoke(main, ["import-profile", *args])


def _files(tmp_path: Path, peer: str) -> tuple[str, str]:
    (tmp_path / "tri.json").write_text(json.dumps(triangle_document()))
    (tmp_path / "peer").write_text(peer)
    return str(tmp_path / "tri.json"), str(tmp_path / "peer")


def _line(behaviour: dict[str, dict[str, str]], inst: Any, horizon: int) -> str:
    """``behaviour`` as Gambit's profile line (its information sets' order)."""
    sets = exported_infosets(build_tree(inst, horizon))
    return "NE," + ",".join(behaviour[s.label][a] for s in sets for a in s.actions)


def _openspiel(behaviour: dict[str, dict[str, Any]], inst: Any, horizon: int) -> str:
    """``behaviour`` as OpenSpiel's ``TabularPolicy.to_dict()``: every global action id,
    illegal ones at 0, floats."""
    tree = build_tree(inst, horizon)
    names = exported_action_names(tree)
    table = {}
    for s in exported_infosets(tree):
        key = f"{s.player - 1}-{s.player - 1}-{s.number}-{s.label}"
        table[key] = [[k, float(Fraction(behaviour[s.label].get(a, 0)))]
                      for k, a in enumerate(names)]
    return json.dumps(table)


@pytest.mark.parametrize("form", ["by name", "gambit line", "openspiel"])
def test_every_form_of_the_equilibrium_imports_and_passes(tmp_path: Path, form: str) -> None:
    text = {"by name": json.dumps(EQUILIBRIUM), "gambit line": _line(EQUILIBRIUM, triangle(), 1),
            "openspiel": _openspiel(EQUILIBRIUM, triangle(), 1)}[form]
    instance, peer = _files(tmp_path, text)
    out = tmp_path / "p.json"
    result = _run(tmp_path, instance, peer, "-H", "1", "-o", str(out))
    assert result.exit_code == 0, result.output
    doc = json.loads(out.read_text())
    assert doc["format"] == "dpp-profile/1" and doc["goals"]["primary"] == "g1"
    assert doc["attacker"]["primary"] == [{"path": ["s", "g1"], "probability": "4/7"},
                                          {"path": ["s", "g2"], "probability": "3/7"}]
    assert doc["defender"]["entries"] == [{"walk": ["s", "g1"], "probability": "1"},
                                          {"walk": ["s", "g2"], "probability": "1/2"}]
    floats = doc["solver"]["rationalised"]["floats"]
    assert floats == (8 if form == "openspiel" else 0)  # 3/7 as a float comes back as 3/7
    assert "--horizon 1" in result.output and "dpp-profile/1" in result.output
    cert = certify(triangle_document(), doc, horizon=1)
    assert cert.passed and cert.exploitability.nash_conv == 0


def test_a_perturbed_profile_is_refuted_with_its_exact_exploitability(tmp_path: Path) -> None:
    wrong = dict(EQUILIBRIUM, **{"D p2 h-": {"alloc g1": "0.3", "alloc g2": "0.7"}})
    instance, peer = _files(tmp_path, json.dumps(wrong))
    out = tmp_path / "p.json"
    assert _run(tmp_path, instance, peer, "-H", "1", "-o", str(out)).exit_code == 0
    e = certify(triangle_document(), json.loads(out.read_text()), horizon=1).exploitability
    assert e.exact and e.nash_conv > 0 and isinstance(e.nash_conv, Fraction)
    # the decimal 0.3 became exactly 3/10 (the simplest rational within 1e-9)
    assert json.loads(out.read_text())["defender"]["entries"][1]["probability"] == "3/10"


def test_tolerance_zero_keeps_the_binary_value(tmp_path: Path) -> None:
    wrong = dict(EQUILIBRIUM, **{"D p2 h-": {"alloc g1": 0.3, "alloc g2": 0.7}})
    instance, peer = _files(tmp_path, json.dumps(wrong))
    out = tmp_path / "p.json"
    result = _run(tmp_path, instance, peer, "-H", "1", "-o", str(out), "--tolerance", "0")
    assert result.exit_code == 0 and "within 0," in result.output
    p = Fraction(json.loads(out.read_text())["defender"]["entries"][1]["probability"])
    assert p == Fraction(0.3) / (Fraction(0.3) + Fraction(0.7))  # scaled to sum to 1


def test_three_goals_give_an_n_goal_profile(tmp_path: Path) -> None:
    """A uniform Defender and every type straight to its goal (not an equilibrium)."""
    tree = build_tree(star3(), 2)
    beh = {}
    for s in exported_infosets(tree):
        if s.player == 2:  # the Defender: uniform
            beh[s.label] = {a: "1/3" for a in s.actions}
        else:  # type θ: s -> m -> its own goal
            target = "go m" if " p0 " in s.label else f"go {'abc'[int(s.label[1]) - 1]}"
            beh[s.label] = {a: "1" if a == target else "0" for a in s.actions}
    (tmp_path / "star.json").write_text(json.dumps(star3_document()))
    (tmp_path / "peer").write_text(json.dumps(beh))
    out = tmp_path / "p.json"
    result = _run(tmp_path, str(tmp_path / "star.json"), str(tmp_path / "peer"), "-H", "2",
                  "-o", str(out))
    assert result.exit_code == 0, result.output
    doc = json.loads(out.read_text())
    assert doc["format"] == "dpp-ngoal-profile/1" and doc["goals"] == ["a", "b", "c"]
    assert [t[0]["path"] for t in doc["attacker"]] == [["s", "m", g] for g in "abc"]
    assert all(e["probabilities"] == ["1/3"] * 3 for e in doc["defender"]["entries"])
    e = certify(star3_document(), doc, horizon=2).exploitability
    assert e.exact and e.nash_conv > 0


BAD = [
    ("not a profile", "hello", "is not a behaviour profile"),
    ("two NE lines", "NE,1\nNE,1\n", "holds 2 profiles"),
    ("wrong count", "NE,1,0", "2 probabilities, but the game has 8 actions"),
    ("unknown infoset", json.dumps({**EQUILIBRIUM, "T3 p0 h-": {"go g1": 1}}),
     "'T3 p0 h-' is not in the game"),
    ("missing infoset", json.dumps({k: v for k, v in EQUILIBRIUM.items() if k != "D p2 h-"}),
     "'D p2 h-' of the game is missing"),
    ("blind labels for the observing export",
     json.dumps({k.replace(" h-", "") if k.startswith("T") else k: v
                 for k, v in EQUILIBRIUM.items()}), "--attacker-blind"),
    ("negative", json.dumps(dict(EQUILIBRIUM, **{"D p1 h-": {"alloc g1": -1, "alloc g2": 2}})),
     "negative probability"),
    ("sum", json.dumps(dict(EQUILIBRIUM, **{"D p1 h-": {"alloc g1": "1/2", "alloc g2": "1/3"}})),
     "sum to 0.8333, not 1"),
    ("unknown action", json.dumps(dict(EQUILIBRIUM, **{"D p1 h-": {"alloc g3": 1}})),
     "has no action 'alloc g3'"),
    ("not a number", json.dumps(dict(EQUILIBRIUM, **{"D p1 h-": {"alloc g1": "x"}})),
     "is not a probability"),
    ("NaN", '{"D p1 h-": {"alloc g1": NaN}}', "not JSON"),
]


@pytest.mark.parametrize(("name", "text", "message"), BAD, ids=[b[0] for b in BAD])
def test_bad_input_is_one_line_and_writes_nothing(tmp_path: Path, name: str, text: str,
                                                  message: str) -> None:
    instance, peer = _files(tmp_path, text)
    out = tmp_path / "p.json"
    result = _run(tmp_path, instance, peer, "-H", "1", "-o", str(out))
    assert result.exit_code == 2, result.output
    lines = [line for line in result.output.splitlines() if line.strip()]
    assert len(lines) == 1 and lines[0].startswith("error:") and message in lines[0], lines
    assert not out.exists()


@pytest.mark.parametrize("args, message", [
    ([], "missing PEER_PROFILE"),
    (["peer", "-o", "peer"], "refusing to overwrite"),
    (["--map", "examples:paper10", "--start", "9,0", "--goals", "0,9", "0,0", "--prior",
      "0.6,0.4", "a", "b"], "takes only PEER_PROFILE"),
    (["peer", "--tolerance", "0.5"], "--tolerance"),
])
def test_bad_options_are_one_line(tmp_path: Path, args: list[str], message: str) -> None:
    instance, peer = _files(tmp_path, json.dumps(EQUILIBRIUM))
    full = [a if a != "peer" else peer for a in args]
    lead = [] if "--map" in args else [instance]
    result = _run(tmp_path, *lead, *full, "-H", "1", *(["-o", str(tmp_path / "p.json")]
                                                       if "-o" not in args else []))
    assert result.exit_code == 2, result.output
    lines = [line for line in result.output.splitlines() if line.strip()]
    assert len(lines) == 1 and message in lines[0], lines
