"""The checker's CLI commands: exit codes 0 / 1 / 2, tables, JSON, no tracebacks."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from dppverify.certificate import Certificate
from dppverify.cli import COMMANDS
from dppverify.cli.certify import certify_command
from dppverify.cli.value import value_command
from tests.dppverify._helpers import (
    run_cli,
    three_phase_doc,
    three_phase_profile,
    triangle_doc,
    write_doc,
)


def test_commands_are_registered() -> None:
    assert {c.name for c in COMMANDS} == {"certify", "check", "value", "export-efg",
                                           "import-profile", "audit"}


def test_certify_passes_with_exit_0_and_a_table(tmp_path: Path) -> None:
    i = write_doc(tmp_path, "i.json", three_phase_doc())
    p = write_doc(tmp_path, "p.json", three_phase_profile())
    r = run_cli(certify_command, [i, p])
    assert r.exit_code == 0
    lines = r.output.splitlines()
    assert lines[0].startswith("verdict: PASS for the untruncated game (H = inf) (11/11 checks "
                               "passed; 2/2 consistency checks agree; 4/4 facts hold;")
    assert lines[1].split()[:4] == ["check", "status", "numbers", "message"]
    r = run_cli(certify_command, [i, p, "--horizon", "4"])
    lines = r.output.splitlines()
    assert r.exit_code == 0 and lines[0].startswith(
        "verdict: PASS for the game truncated at H = 4 (11/11 checks passed; 2/2 consistency "
        "checks agree; 6/6 facts hold;")
    assert lines[1].startswith("note: this certifies the game truncated at H = 4 only")
    assert any(line.startswith("pbne.defender_br") and " pass " in line for line in lines)


def test_certify_json_is_a_certificate(tmp_path: Path) -> None:
    i = write_doc(tmp_path, "i.json", three_phase_doc())
    p = write_doc(tmp_path, "p.json", three_phase_profile())
    r = run_cli(certify_command, [i, p, "--json", "--horizon", "5", "--seed", "3"])
    assert r.exit_code == 0
    cert = Certificate.from_json(r.output)
    assert cert.passed and cert.horizon == 5 and cert.seed == 3


def test_refuted_profile_exits_1(tmp_path: Path) -> None:
    prof = three_phase_profile()
    prof["attacker"]["primary"] = [{"path": [3, 1, 2], "probability": 1}]
    r = run_cli(certify_command, [write_doc(tmp_path, "i.json", three_phase_doc()),
                               write_doc(tmp_path, "p.json", prof)])
    assert r.exit_code == 1
    assert r.output.startswith("verdict: FAIL")
    assert any(line.startswith("pbne.defender_br") and " fail " in line
               for line in r.output.splitlines())


@pytest.mark.parametrize(("instance", "profile", "needle"), [
    ("{bad", None, "malformed JSON"),
    (None, "{bad", "not JSON"),
    (None, "[1]", "must be a JSON object"),
    (None, json.dumps({"format": "x"}), "dpp-profile/1"),
    (json.dumps({"graph": {"nodes": [], "edges": []}}), None, "missing key"),
])
def test_bad_input_exits_2_with_one_line(tmp_path: Path, instance: str | None,
                                         profile: str | None, needle: str) -> None:
    i = write_doc(tmp_path, "i.json", instance if instance is not None else triangle_doc())
    p = write_doc(tmp_path, "p.json", profile if profile is not None else three_phase_profile())
    r = run_cli(certify_command, [i, p])
    assert r.exit_code == 2
    assert r.output.count("\n") == 1 and r.output.startswith("error: ") and needle in r.output


def test_missing_files_and_short_horizon_exit_2(tmp_path: Path) -> None:
    i = write_doc(tmp_path, "i.json", three_phase_doc())
    p = write_doc(tmp_path, "p.json", three_phase_profile())
    assert run_cli(certify_command, [i, str(tmp_path / "nope.json")]).exit_code == 2
    assert run_cli(certify_command, [str(tmp_path / "nope.json"), p]).exit_code == 2
    r = run_cli(certify_command, [i, p, "--horizon", "2"])
    assert r.exit_code == 2 and "shorter" in r.output
    r = run_cli(certify_command, [i, p, "--horizon", "40", "--max-prefixes", "50", "--route",
                               "tree"])
    assert r.exit_code == 2 and "--max-prefixes" in r.output
    r = run_cli(certify_command, [i, p, "--horizon", "40", "--max-prefixes", "50"])  # auto
    assert r.exit_code == 0 and "for the game truncated at H = 40" in r.output
    assert "structured route" in r.output


def test_float_mode_is_detected_from_the_instance(tmp_path: Path) -> None:
    # 8-connected maps (float mode) certify without --float; --float changes nothing
    doc = triangle_doc()
    doc["numbers"] = "float"
    i = write_doc(tmp_path, "i.json", doc)
    p = write_doc(tmp_path, "p.json", {"format": "dpp-profile/1",
                                    "goals": {"primary": "g1", "secondary": "g2"},
                                    "defender": {"rule": "progress", "goal": "g1"},
                                    "attacker": {"primary": [
                                        {"path": ["s", "g1"], "probability": "4/7"},
                                        {"path": ["s", "g2"], "probability": "3/7"}],
                                        "secondary": [{"path": ["s", "g2"],
                                                       "probability": 1}]}})
    r = run_cli(certify_command, [i, p])
    assert r.exit_code == 0 and "float mode, relative tolerance 1e-09" in r.output
    r = run_cli(certify_command, [i, p, "--float"])
    assert r.exit_code == 0 and "float mode" in r.output
    exact = run_cli(certify_command, [write_doc(tmp_path, "e.json", triangle_doc()), p])
    assert exact.exit_code == 0 and "exact" in exact.output.splitlines()[0]


def test_value_command(tmp_path: Path) -> None:
    i = write_doc(tmp_path, "i.json", three_phase_doc())
    r = run_cli(value_command, [i, "--horizon", "4"])
    assert r.exit_code == 0 and r.output.startswith("V_H (H = 4) = 71/18 (≈ 3.944) exactly")
    r = run_cli(value_command, [i, "-H", "4", "--json"])
    doc = json.loads(r.output)
    lp = doc["tree"]["details"]
    assert doc["format"] == "dpp-value/1" and doc["route"] == "tree"
    assert doc["value"] == "71/18" and doc["exact"] and abs(lp["value_lp"] - 71 / 18) < 1e-7
    assert lp["lp"]["solver"] == "CLARABEL" and lp["lp"]["status"] == "optimal"
    r = run_cli(value_command, [i, "-H", "1"])
    assert r.exit_code == 2 and "no walk" in r.output
    r = run_cli(value_command, [i])  # no horizon is the untruncated game
    assert r.exit_code == 0 and r.output.startswith("V_H (H = inf) = 71/18 (≈ 3.944) exactly")


def test_dpp_group_and_python_m_dppverify(tmp_path: Path) -> None:
    from dpp import main

    i = write_doc(tmp_path, "i.json", three_phase_doc())
    p = write_doc(tmp_path, "p.json", three_phase_profile())
    r = CliRunner().invoke(main, ["certify", i, p])
    assert r.exit_code == 0 and "Traceback" not in r.output
    r = CliRunner().invoke(main, ["value", i, "-H", "4"])
    assert r.exit_code == 0 and "71/18" in r.output
    proc = subprocess.run([sys.executable, "-m", "dppverify", "certify", i, p],
                          capture_output=True, text=True, check=False)
    assert proc.returncode == 0 and proc.stdout.startswith("verdict: PASS")
    proc = subprocess.run([sys.executable, "-m", "dppverify", "certify", i, i],
                          capture_output=True, text=True, check=False)
    assert proc.returncode == 2 and "Traceback" not in proc.stderr + proc.stdout
    assert proc.stderr.startswith("error: ") and proc.stderr.count("\n") == 1


def test_an_error_verdict_is_could_not_decide_not_a_refutation(tmp_path: Path) -> None:
    """The triangle with weights scaled by 10**12 on the walk tree: the LP cross-checks fail
    numerically (verdict ERROR), which decides nothing: exit 3, never exit 1 (refuted). The
    same profile passes on the untruncated game (structured route, no LP)."""
    from dppverify.game.examples import triangle_document, triangle_profile

    doc = triangle_document()
    for e in doc["graph"]["edges"]:
        e["weight"] = e["weight"] * 10**12
    prof = triangle_profile()
    for key in ("value",):  # stated values of the unscaled game would not match: drop them
        prof.pop(key, None)
    i, p = tmp_path / "tri12.json", tmp_path / "p.json"
    i.write_text(json.dumps(doc))
    p.write_text(json.dumps(prof))
    untruncated = run_cli(certify_command, [str(i), str(p)])
    assert untruncated.exit_code == 0, untruncated.output
    tree = run_cli(certify_command, [str(i), str(p), "-H", "1"])
    verdict = tree.output.splitlines()[0]
    assert verdict.startswith(("verdict: ERROR", "verdict: INCOMPLETE", "verdict: PASS")), verdict
    assert tree.exit_code == (0 if verdict.startswith("verdict: PASS") else 3), tree.output
