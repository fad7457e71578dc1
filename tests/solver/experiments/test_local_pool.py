"""The local worker pool of the experiments (``solver.experiments.local_pool``): results of a
lazy task stream, no worker left after an error, a refusal under a small open-file limit."""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

from dppio.procs import descendants
from solver.experiments.local_pool import completed

ROOT = Path(__file__).resolve().parents[3]


def _fail_on_three(x: int) -> int:
    if x == 3:
        raise ValueError("three")
    time.sleep(0.05)
    return x


def test_a_lazy_stream_of_tasks_gives_every_result() -> None:
    pulled: list[int] = []

    def tasks() -> object:
        for k in range(40):
            pulled.append(k)
            yield k

    results = sorted(r for _, r in completed(abs, tasks(), 2))  # type: ignore[arg-type]
    assert results == list(range(40)) and pulled == list(range(40))


def test_an_error_in_a_worker_kills_the_pool() -> None:
    before = set(descendants(os.getpid()))
    with pytest.raises(ValueError, match="three"):
        for _ in completed(_fail_on_three, iter(range(10)), 2):
            pass
    deadline = time.monotonic() + 10
    while set(descendants(os.getpid())) - before and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not set(descendants(os.getpid())) - before


def test_too_few_open_files_is_one_line() -> None:
    code = ("import resource; resource.setrlimit(resource.RLIMIT_NOFILE, (20, 20)); "
            "from solver.experiments.local_pool import check_open_files; check_open_files(2)")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       env={**os.environ, "PYTHONPATH": str(ROOT)}, timeout=120)
    assert r.returncode == 1
    assert r.stderr.strip().splitlines()[-1].startswith(
        "solver.errors.InvalidInstanceError: --workers 2 needs about ")
    assert "the limit is 20 (ulimit -n)" in r.stderr
