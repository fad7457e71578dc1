"""`dpp experiment ngoal`: solved and certified N-goal equilibria as goals are added."""

from __future__ import annotations

import csv
import io
from fractions import Fraction
from pathlib import Path

import numpy as np
from click.testing import CliRunner

from solver import Instance, solve
from solver.cli import main
from solver.experiments.ngoal import corner_cells, ngoal_series

MAP = "type octile\nheight 4\nwidth 5\nmap\n.....\n.@@..\n...@.\n.....\n"


def test_the_command_writes_csv_and_figure_with_certified_rows(tmp_path: Path) -> None:
    m = tmp_path / "m.map"
    m.write_text(MAP)
    out = tmp_path / "out"
    r = CliRunner().invoke(main, ["experiment", "ngoal", "--map", str(m), "--max-goals", "4",
                                  "--output-dir", str(out)])
    assert r.exit_code == 0, r.output
    rows = list(csv.DictReader(io.StringIO((out / "ngoal.csv").read_text())))
    assert [(int(x["n_goals"]), x["prior_kind"]) for x in rows] == [
        (n, k) for n in (2, 3, 4) for k in ("equal", "skewed")]
    assert all(x["certified"] == "pass" for x in rows)  # N <= 3 always; N = 4 here too
    for x in rows:
        u, ubar, voi = Fraction(x["U"]), Fraction(x["U_bar"]), Fraction(x["VoI"])
        assert voi == (ubar - u) / ubar and 0 <= Fraction(x["deception"]) <= 1
    assert (out / "ngoal.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_two_goal_rows_are_the_papers_value() -> None:
    blocked = np.zeros((5, 6), dtype=bool)
    blocked[1:3, 2] = True
    start, goals = corner_cells(blocked, 3)
    rows = ngoal_series(blocked, start, goals, map_name="g", max_goals=2)
    for row in rows:
        two = solve(Instance.from_grid(blocked, start, (goals[0], goals[1]), row.prior))
        assert two.U == row.U


def test_bad_output_dir_is_one_line(tmp_path: Path) -> None:
    target = tmp_path / "file"
    target.write_text("x")
    m = tmp_path / "m.map"
    m.write_text(MAP)
    r = CliRunner().invoke(main, ["experiment", "ngoal", "--map", str(m), "--max-goals", "2",
                                  "--output-dir", str(target)])
    assert r.exit_code == 2
    assert len(r.stderr.strip().splitlines()) == 1 and r.stderr.startswith("error: ")
