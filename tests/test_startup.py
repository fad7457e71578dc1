"""Start-up stays cheap: the heavy libraries load only where they are used.

Checked by the modules a fresh interpreter has loaded, not by timing (the start-up time itself
is a benchmark: ``benchmarks/bench_startup.py``).
"""

from __future__ import annotations

import json
import os
import sys

import pytest

from solver.threads import BLAS_THREAD_VARIABLES
from tests import _guard

HEAVY = ("cvxpy", "clarabel", "scipy.stats", "matplotlib", "hypothesis", "dask")
"""Loaded only by the commands that need them (LPs, figures, audits, distributed sweeps)."""

LIGHT_CLI = (*HEAVY, "scipy", "networkx", "solver.twogoal.equilibrium")
"""Not needed to print ``dpp --help``."""


def _loaded(code: str, names: tuple[str, ...]) -> list[str]:
    probe = (f"import sys\n{code}\nimport json\n"
             f"print(json.dumps([m for m in {list(names)!r} if m in sys.modules]))")
    out = _guard.run([sys.executable, "-c", probe], capture_output=True, text=True,
                     check=True)
    return list(json.loads(out.stdout.strip().splitlines()[-1]))


@pytest.mark.parametrize("code", ["import dppverify", "import solver",
                                  "from dppverify import certify, game_value, Instance",
                                  "from solver import solve, Instance, instance_to_json",
                                  "import dppverify.cli", "import solver.cli", "import dpp"])
def test_imports_load_no_heavy_library(code: str) -> None:
    assert _loaded(code, HEAVY) == []


def test_dpp_help_loads_no_solver_or_scipy() -> None:
    code = ("from click.testing import CliRunner\nfrom dpp import main\n"
            "r = CliRunner().invoke(main, ['--help'])\nassert r.exit_code == 0, r.output")
    assert _loaded(code, LIGHT_CLI) == []


def test_public_names_still_import() -> None:
    import dppverify
    import solver

    for package in (dppverify, solver):
        for name in package.__all__:
            assert getattr(package, name) is not None, name
    from dppverify import certify

    assert callable(certify)


def test_an_lp_still_loads_cvxpy() -> None:
    code = ("from dppverify import game_value\nfrom dppverify.game.examples import triangle\n"
            "assert str(game_value(triangle(), 2).bracket.lower) == '12/5'")
    assert _loaded(code, ("cvxpy",)) == ["cvxpy"]


@pytest.mark.parametrize(("preset", "code", "want"), [
    (None, "import dpp", "1"), ("3", "import dpp", "3"),
    (None, "import dppverify, solver", None)])
def test_dpp_runs_single_threaded_blas_unless_told(preset: str | None, code: str,
                                                   want: str | None) -> None:
    env = {k: v for k, v in os.environ.items() if k not in BLAS_THREAD_VARIABLES}
    if preset is not None:
        env["OPENBLAS_NUM_THREADS"] = preset
    probe = f"{code}\nimport os\nprint(os.environ.get('OPENBLAS_NUM_THREADS'))"
    out = _guard.run([sys.executable, "-c", probe], capture_output=True, text=True,
                     check=True, env=env)
    assert out.stdout.strip() == str(want)
