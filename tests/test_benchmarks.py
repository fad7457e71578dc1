"""Every benchmark script runs to completion in its quick mode (issue 22).

The benchmarks report ratios (docs/benchmarks.md); here each ``benchmarks/bench_*.py`` runs with
``--quick`` (tiny sizes, one repetition) in a subprocess so that a crash like the one
``bench_ngoal.py`` had is caught by the default test run. No timing is asserted.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest

from tests import _guard

ROOT = Path(__file__).resolve().parents[1]
SCRIPTS = sorted((ROOT / "benchmarks").glob("bench_*.py"))


def test_every_script_is_listed() -> None:
    assert {p.name for p in SCRIPTS} >= {"bench_scale.py", "bench_ngoal.py", "bench_solver.py"}


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.stem)
def test_benchmark_runs_in_quick_mode(script: Path) -> None:
    env = {**os.environ, "PYTHONPATH": str(ROOT), "DPP_BENCH_QUICK": "1"}
    out = _guard.run([sys.executable, str(script), "--quick"], capture_output=True,
                     text=True, env=env, cwd=ROOT)
    assert out.returncode == 0, out.stderr[-3000:]
    assert out.stdout.strip(), "a benchmark prints its rows"
