"""The local worker pool of the experiments (``solver.experiments.local_pool``): results of a
lazy task stream, no worker left after an error, a refusal under a small open-file limit."""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

import pytest

from dppio.procs import descendants
from solver.experiments.local_pool import completed
from tests import _guard

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
    deadline = time.monotonic() + _guard.latency(10)  # (a latency: stretched by the load)
    while set(descendants(os.getpid())) - before and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not set(descendants(os.getpid())) - before


def test_too_few_open_files_is_one_line() -> None:
    code = ("import resource; resource.setrlimit(resource.RLIMIT_NOFILE, (20, 20)); "
            "from solver.experiments.local_pool import check_open_files; check_open_files(2)")
    r = _guard.run([sys.executable, "-c", code], capture_output=True, text=True,
                   env={**os.environ, "PYTHONPATH": str(ROOT)})
    assert r.returncode == 1
    assert r.stderr.strip().splitlines()[-1].startswith(
        "solver.errors.InvalidInstanceError: --workers 2 needs about ")
    assert "the limit is 20 (ulimit -n)" in r.stderr


class _Stop(Exception):
    """Raised by a progress callback: a signal arriving between two results."""


def _live_pool(before: set[int]) -> set[int]:
    return set(descendants(os.getpid())) - before


def test_a_signal_between_two_results_ends_the_density_pool_at_once() -> None:
    """An exception raised outside the pool's generator (the progress callback, where a
    signal lands most of the time) ends every worker and the forkserver before it reaches
    the caller, not when the generator is collected after the command's exit message — the
    moment a worker still starting would find its semaphores unlinked and print a
    ``SemLock._rebuild`` traceback. The exception, with its traceback (which holds the
    generator's frame), is still alive when the pool is checked."""
    from solver.experiments.density import DensityConfig, _run_local, tasks_of

    tasks = tasks_of(DensityConfig(size=6, start=(5, 0), goals=((0, 5), (0, 0)),
                                   densities=(0, 10, 20), samples=6, chunk=1))
    before = set(descendants(os.getpid()))

    def progress(_: int) -> None:
        raise _Stop

    with pytest.raises(_Stop) as caught:
        _run_local(tasks, 2, progress)
    assert caught.value.__traceback__ is not None  # nothing collected yet
    assert not _live_pool(before), "the pool outlives the exception"


def test_a_signal_between_two_results_ends_the_batch_pool_at_once(tmp_path: Path) -> None:
    """The same for ``dpp batch --workers``: the exception leaves run_batch with no worker."""
    from solver.experiments.batch import BatchRun, run_batch
    from solver.experiments.batch_line import BatchConfig
    from tests.solver.experiments.doctest_inputs import batch_example

    checker, scen = batch_example()
    before = set(descendants(os.getpid()))

    def progress(_: int) -> None:
        raise _Stop

    with pytest.raises(_Stop) as caught:
        run_batch(scen, tmp_path / "b.csv", BatchConfig(), checker,
                  BatchRun(workers=2, chunk=1, progress=progress))
    assert caught.value.__traceback__ is not None
    assert not _live_pool(before), "the pool outlives the exception"
