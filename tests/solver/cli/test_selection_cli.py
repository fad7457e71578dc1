"""``dpp solve --goal-selection`` and ``dpp export-efg`` on the goal-selection game.

- paper10.map: the written profile has V_sel = 25/2 and q* = (1/2, 1/2); read back as JSON by
  the checker it passes every goal-selection check; the line on stderr shows V_sel beside the
  uniform prior's value; --save-instance writes a goal-selection compact instance that solves
  to the same profile;
- a goal-selection INSTANCE needs no flag; --goal-values shifts the choice;
- mistakes are one line, exit 2, nothing written.
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest
from click.testing import CliRunner, Result

from dpp import main
from dppverify.checks.selection import selection_checks
from dppverify.formats.json_reading import parse_json
from dppverify.game.instance import load_instance
from dppverify.game.selection_profile import selection_profile_from_json

ROOT = Path(__file__).resolve().parents[3]
GRID = ["--map", "paper10.map", "--start", "9,0", "--goals", "0,9", "0,0"]


@pytest.fixture
def here(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    shutil.copy(ROOT / "examples" / "paper10.map", tmp_path / "paper10.map")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def _run(*args: str) -> Result:
    return CliRunner().invoke(main, list(args))


def test_paper10_profile_is_written_and_certified(here: Path) -> None:
    r = _run("solve", "--goal-selection", *GRID, "--defender", "mixture", "-o", "p.json",
             "--save-instance", "sel.json")
    assert r.exit_code == 0, r.output
    assert "V_sel = 25/2 (at the uniform prior: 25/2), q* = (1/2, 1/2)" in r.output
    doc = parse_json((here / "p.json").read_text())
    assert doc["choice"] == ["1/2", "1/2"] and doc["value"]["V"] == "25/2"
    assert doc["defender"] == {"rule": "progress-mixture", "goal": [0, 9], "alpha": "9/20"}
    sel = load_instance(here / "sel.json")
    recs = selection_checks(sel, selection_profile_from_json(doc, sel))
    assert all(x.passed for x in recs)
    again = _run("solve", "sel.json", "--defender", "mixture", "--json")
    assert json.loads(again.output)["attacker"] == json.loads(
        (here / "p.json").read_text())["attacker"]


def test_summary_and_goal_values(here: Path) -> None:
    r = _run("solve", "--goal-selection", *GRID, "--goal-values", "-5,6")
    assert r.exit_code == 0, r.output
    assert "V_sel = 11 (at the uniform prior: 12; choosing gains 1); q* = (0, 1)" in r.output


@pytest.mark.parametrize(("args", "words"), [
    (["solve", "--goal-selection", *GRID, "--prior", "0.6,0.4"], "takes no --prior"),
    (["solve", *GRID, "--prior", "0.6,0.4", "--goal-values", "0,1"], "goal-selection game"),
    (["solve", "--goal-selection", *GRID, "--goal-values", "1"], "--goal-values takes 2"),
    (["solve", "--goal-selection", "--map", "paper10.map", "--start", "9,0", "--goals", "0,9",
      "0,0", "9,9", "--defender", "mixture"], "two-goal Defender"),
    (["solve", "--goal-selection", *GRID, "--witness", "w.json"],
     "does not decide the goal-selection game"),
    (["export-efg", "--goal-selection", *GRID, "-H", "1", "-o", "g.efg", "--goal-values", "1"],
     "--goal-values takes 2"),
])
def test_mistakes_are_one_line_and_write_nothing(here: Path, args: list[str],
                                                 words: str) -> None:
    r = _run(*args, "-o", "out.json") if args[0] == "solve" else _run(*args)
    assert r.exit_code == 2 and words in r.output, r.output
    assert r.output.count("\n") == 1
    assert not (here / "out.json").exists() and not (here / "g.efg").exists()


def test_export_efg_writes_the_attackers_root_choice(here: Path) -> None:
    doc = json.loads((ROOT / "examples" / "triangle.json").read_text())
    del doc["prior"]
    (here / "sel.json").write_text(json.dumps({**doc, "goal_selection": True}))
    r = _run("export-efg", "sel.json", "-H", "1", "-o", "g.efg")
    assert r.exit_code == 0 and "goal selection" in r.output, r.output
    lines = (here / "g.efg").read_text().splitlines()
    assert lines[3] == 'p "" 1 1 "goal" { "choose g1" "choose g2" } 0'
    assert not any(line.startswith("c ") for line in lines)
