"""No dead code: ``vulture`` at 60 % confidence finds nothing in the packages.

The configuration is ``[tool.vulture]`` in pyproject.toml: the packages and the rest of the
repository that uses them (the proof checks, the benchmarks, the figures), not the tests, so a
definition only a test uses is reported too; every name vulture cannot see used is listed
there with why.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _vulture(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "vulture", *args], cwd=ROOT,
                          capture_output=True, text=True, timeout=300)


@pytest.fixture(scope="module")
def vulture_installed() -> None:
    if shutil.which("vulture") is None and _vulture("--version").returncode != 0:
        pytest.skip("vulture is not installed (the 'test' extra)")


def test_vulture_finds_no_dead_code(vulture_installed: None) -> None:
    result = _vulture()
    assert result.returncode == 0 and not result.stdout.strip(), result.stdout + result.stderr


def test_vulture_would_report_a_dead_function(vulture_installed: None, tmp_path: Path) -> None:
    dead = tmp_path / "dead.py"
    dead.write_text("def used() -> int:\n    return 1\n\n\ndef unused() -> int:\n"
                    "    return used()\n")
    result = _vulture(str(dead), "--min-confidence", "60")
    assert "unused function 'unused'" in result.stdout
