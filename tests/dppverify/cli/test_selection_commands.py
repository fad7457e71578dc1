"""`dpp value` and `dpp certify` on the goal-selection game (docs/cli.md, "Goal selection").

The profiles are written by hand or by the solver's JSON; the checker's commands read them
with their own readers, and the certificate round-trips with its provenance.
"""

from __future__ import annotations

import json
from pathlib import Path

from dppverify.certificate import Certificate
from dppverify.cli.certify import certify_command
from dppverify.cli.value import value_command
from dppverify.game.examples import star3_document, triangle_document
from tests.dppverify._helpers import run_cli, write_doc

TRIANGLE = {k: v for k, v in triangle_document().items() if k != "prior"} | {
    "goal_selection": True}
PROFILE = {"format": "dpp-selection-profile/1", "choice": ["1/4", "3/4"],
           "attacker": [[{"path": ["s", "g2"], "probability": 1}],
                        [{"path": ["s", "g2"], "probability": 1}]],
           "defender": {"rule": "guarantee", "h": [2, 2]}, "value": {"V": 2}}


def test_value_gives_v_sel_the_choice_and_the_uniform_prior(tmp_path: Path) -> None:
    i = write_doc(tmp_path, "sel.json", TRIANGLE)
    r = run_cli(value_command, [i])
    assert r.exit_code == 0, r.output
    assert "V_sel (H = inf, N = 2 goals, the Attacker chooses its goal) = 2 exactly at q* = " \
           "(1/4, 3/4)" in r.output
    assert "at the uniform prior: V = 2 exactly; choosing gains the Attacker 0" in r.output
    valued = write_doc(tmp_path, "valued.json", {**TRIANGLE, "goal_values": [0, 1]})
    doc = json.loads(run_cli(value_command, [valued, "--json"]).output)
    assert doc["format"] == "dpp-selection-value/1" and doc["value"] == "1"
    assert doc["goal_values"] == ["0", "1"] and doc["choice"] == ["0", "1"]  # g2 worth 1 more
    three = {k: v for k, v in star3_document().items() if k != "prior"} | {
        "goal_selection": True}
    doc = json.loads(run_cli(value_command, [write_doc(tmp_path, "s3.json", three), "-H", "2",
                                             "--json"]).output)
    assert (doc["value"], doc["horizon"], doc["truncated"]) == ("4/3", 2, True)


def test_certify_passes_the_equilibrium_and_refutes_sigma_star(tmp_path: Path) -> None:
    i = write_doc(tmp_path, "sel.json", TRIANGLE)
    p = write_doc(tmp_path, "p.json", PROFILE)
    r = run_cli(certify_command, [i, p, "--json"])
    assert r.exit_code == 0, r.output
    cert = Certificate.from_json(json.loads(r.output))
    assert cert.info["game"] == "goal selection" and cert.provenance is not None
    assert cert.check("selection.value").passed
    assert cert.info["kernel"]["status"] == "not applicable"  # the kernel reads prior games only
    assert "goal-selection" in cert.info["kernel"]["message"]
    paper = {"format": "dpp-profile/1", "goals": {"primary": "g1", "secondary": "g2"},
             "prior": {"primary": "7/10", "secondary": "3/10"},
             "defender": {"rule": "progress", "goal": "g1"},
             "attacker": {"primary": [{"path": ["s", "g1"], "probability": "4/7"},
                                      {"path": ["s", "g2"], "probability": "3/7"}],
                          "secondary": [{"path": ["s", "g2"], "probability": 1}]}}
    r = run_cli(certify_command, [i, write_doc(tmp_path, "paper.json", paper)])
    assert r.exit_code == 1 and "goal 'g2' is cheap" in r.output


def test_mistakes_are_one_line_exit_2(tmp_path: Path) -> None:
    i = write_doc(tmp_path, "sel.json", TRIANGLE)
    p = write_doc(tmp_path, "p.json", PROFILE)
    for cmd, args, words in (
            (certify_command, [i, p, "-H", "3"], "untruncated game"),
            (value_command, [i, "--route", "both"], "structured route"),
            (value_command, [i, "--goal-values", "0,1"], "go with --map FILE"),
            (value_command, [i, "--goal-selection"], "go with --map FILE"),
            (certify_command, [i, p, "--witness", str(tmp_path / "w.json")],
             "does not decide the goal-selection game"),
            (certify_command, [i, write_doc(tmp_path, "n.json", {"format": "x"})],
             "dpp-selection-profile/1")):
        r = run_cli(cmd, args)
        assert r.exit_code == 2 and words in r.output and r.output.count("\n") == 1, r.output
