"""`dpp value` and `dpp certify` dispatch on the number of goals (one entry point for any N)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

from dppverify.certificate import Certificate
from dppverify.cli.certify import certify_command
from dppverify.cli.value import value_command
from dppverify.game.examples import star3_document, star3_profile
from tests.dppverify._helpers import run_cli, write_doc


def test_value_of_an_n_goal_instance_by_each_route(tmp_path: Path) -> None:
    i = write_doc(tmp_path, "star.json", star3_document())
    r = run_cli(value_command, [i, "-H", "2"])
    assert r.exit_code == 0
    assert "V_H (H = 2, N = 3 goals) = 3/2 (≈ 1.5) exactly; LP value" in r.output
    r = run_cli(value_command, [i, "-H", "inf"])
    assert r.exit_code == 0
    assert "(H = inf, N = 3 goals) = 3/2 (≈ 1.5) exactly; coalition DP (NG.4" in r.output
    r = run_cli(value_command, [i, "-H", "3", "--route", "both", "--json"])
    doc = json.loads(r.output)
    assert r.exit_code == 0 and doc["agree"] is True and doc["value"] == "3/2"
    assert doc["tree"]["value"] == "3/2" and doc["structured"]["value"] == "3/2"
    assert doc["goals"] == 3 and doc["route"] == "both"


def test_value_errors_are_one_line_exit_2(tmp_path: Path) -> None:
    i = write_doc(tmp_path, "star.json", star3_document())
    r = run_cli(value_command, [i, "-H", "inf", "--route", "tree"])
    assert r.exit_code == 2 and "needs a finite horizon" in r.output
    r = run_cli(value_command, [i, "-H", "3", "--route", "tree", "--max-prefixes", "3"])
    assert r.exit_code == 2 and "more than the limit of 3" in r.output
    bad = dict(star3_document(), prior=["1/2", "1/2", "1/2"])
    r = run_cli(value_command, [write_doc(tmp_path, "bad.json", bad), "-H", "2"])
    assert r.exit_code == 2 and r.output.count("\n") == 1 and "must sum to exactly 1" in r.output


def test_certify_an_n_goal_profile(tmp_path: Path) -> None:
    i = write_doc(tmp_path, "star.json", star3_document())
    p = write_doc(tmp_path, "p.json", star3_profile())
    r = run_cli(certify_command, [i, p, "-H", "2"])
    assert r.exit_code == 0 and r.output.startswith(
        "verdict: PASS for the game truncated at H = 2 (6/6 checks passed; 1/1 consistency "
        "checks agree;")
    r = run_cli(certify_command, [i, p])  # the untruncated game by default
    assert r.exit_code == 1 and r.output.startswith("verdict: FAIL for the untruncated game")
    r = run_cli(certify_command, [i, p, "--json", "-H", "4"])
    cert = Certificate.from_json(r.output)
    assert r.exit_code == 1 and cert.check("pbne.attacker_br").status == "fail"
    r = run_cli(certify_command, [i, p, "-H", "inf"])  # the structured route: b loops s m s m b
    assert r.exit_code == 1 and "for the untruncated game (H = inf)" in r.output
    r = run_cli(certify_command, [i, p, "-H", "inf", "--route", "tree"])
    assert r.exit_code == 2 and "needs a finite horizon" in r.output
    two = write_doc(tmp_path, "two.json", {"format": "dpp-profile/1"})
    r = run_cli(certify_command, [i, two])
    assert r.exit_code == 2 and "dpp-ngoal-profile/1" in r.output


def test_python_m_dppverify_dispatches_too(tmp_path: Path) -> None:
    i = write_doc(tmp_path, "star.json", star3_document())
    out = subprocess.run([sys.executable, "-m", "dppverify", "value", i, "-H", "2", "--route",
                          "structured"], capture_output=True, text=True, check=False)
    assert out.returncode == 0, out.stderr
    assert "= 3/2 (≈ 1.5) exactly; coalition DP (NG.4: the value for three goals)" in out.stdout


def test_the_four_goal_counterexample_is_never_given_the_coalition_bound(tmp_path: Path) -> None:
    """proofs/NGOAL.md: the coalition DP (25/14) is only an upper bound; the value is 12/7."""
    from dppverify.game.examples import hub4_document
    for directed in (True, False):
        i = write_doc(tmp_path, f"hub{directed}.json", hub4_document(directed=directed))
        for args in (["-H", "inf"], ["-H", "5", "--route", "structured"], ["-H", "5"],
                     ["-H", "4", "--route", "both"]):
            r = run_cli(value_command, [i, *args, "--json"])
            doc = json.loads(r.output)
            assert r.exit_code == 0 and doc["value"] == "12/7", (directed, args, doc)
            if doc["structured"] is not None:
                details = doc["structured"]["details"]
                assert details["coalition_dp"]["value"] == "25/14"
                assert details["extra_normals"]
