"""``dpp experiment goal-selection`` (solver/experiments/selection.py, solver/plots/selection.py).

On a small sweep every map satisfies the two checks (V_sel <= V(b); V_sel = min(d1, d2, M/2)
with V(1/2) = M/2 from the paper's construction), the files are written together, the figure
has its two panels, and bad options write nothing.
"""

from __future__ import annotations

import csv
import json
from fractions import Fraction
from pathlib import Path

from click.testing import CliRunner

from dpp import main
from solver.experiments.density import DensityConfig
from solver.experiments.selection import selection_rows, summarize_selection
from solver.selection.mixture import minimising_choices


def test_every_map_of_a_small_sweep_passes_both_checks() -> None:
    cfg = DensityConfig(size=8, start=(7, 0), goals=((0, 7), (0, 0)), densities=(0, 20, 40),
                        samples=4)
    rows = selection_rows(cfg)
    summary = summarize_selection(rows)
    assert summary.checks_hold and summary.maps == 12
    for r in rows:
        lo, hi = minimising_choices(*(Fraction(x) for x in (r.d1, r.d2, r.M, r.V_sel)))
        assert lo <= Fraction(r.q1) <= hi
        assert Fraction(r.gain) == Fraction(r.V_prior) - Fraction(r.V_sel) >= 0


def test_the_command_writes_the_table_the_summary_and_the_figure(tmp_path: Path) -> None:
    out = tmp_path / "sel"
    r = CliRunner().invoke(main, ["experiment", "goal-selection", "--samples", "2",
                                  "--densities", "0,30", "--size", "8", "--output-dir",
                                  str(out), "--json"])
    assert r.exit_code == 0, r.output
    summary = json.loads(r.stdout)
    assert summary["checks_hold"] and summary["maps"] == 4
    rows = list(csv.DictReader((out / "selection.csv").read_text().splitlines()))
    assert len(rows) == 4 and {row["density"] for row in rows} == {"0", "30"}
    assert (out / "selection.png").read_bytes()[:4] == b"\x89PNG"
    assert (out / "selection.pdf").read_bytes()[:4] == b"%PDF"


def test_bad_options_write_nothing(tmp_path: Path) -> None:
    out = tmp_path / "none"
    r = CliRunner().invoke(main, ["experiment", "goal-selection", "--densities", "0,x",
                                  "--output-dir", str(out)])
    assert r.exit_code == 2 and "error:" in r.output and not out.exists()
