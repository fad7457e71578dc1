"""The N-goal experiment (dppverify.ngoal.experiment): exact rows, N = 2 against the two-goal
structured route, and the command line."""

from __future__ import annotations

from fractions import Fraction
from pathlib import Path

import pytest

from dppverify.instance import instance_from_json
from dppverify.ngoal.experiment import goal_series, grid_document, main, read_map
from dppverify.value_dp import structured_value

MAP = Path(__file__).resolve().parents[2] / "examples" / "paper10.map"
ROWS = read_map(MAP.read_text(encoding="utf-8"))


def test_two_goal_rows_equal_the_two_goal_value() -> None:
    goals = [(0, 9), (0, 0), (0, 5)]
    series = goal_series(ROWS, (9, 0), goals)
    assert [(r.n_goals, r.prior_kind) for r in series] == [
        (2, "equal"), (2, "skewed"), (3, "equal"), (3, "skewed")]
    for r in series[:2]:
        two = instance_from_json(grid_document(ROWS, (9, 0), goals[:2], r.prior))
        assert r.value == structured_value(two, None).value
    for r in series:
        assert r.voi == (r.complete - r.value) / r.complete
        assert 0 <= r.voi < 1 and isinstance(r.value, int | Fraction)


def test_command_line_writes_the_csv_and_figure(tmp_path: Path,
                                                capsys: pytest.CaptureFixture[str]) -> None:
    csv_path, fig = tmp_path / "out.csv", tmp_path / "fig.png"
    assert main(["--map", str(MAP), "--goals", "0,9", "0,0", "0,5", "--csv", str(csv_path),
                 "--figure", str(fig)]) == 0
    assert csv_path.read_text().splitlines()[1].startswith("2,equal,1/2 1/2,25/2,35/2,2/7")
    assert fig.stat().st_size > 1000
    assert main(["--map", str(tmp_path / "missing.map")]) == 2
    assert "error:" in capsys.readouterr().err
