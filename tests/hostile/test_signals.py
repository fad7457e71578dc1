"""Signals to long ``dpp`` commands: SIGINT, SIGTERM and SIGHUP end them with one line and
exit code 128 + n, no process of theirs survives (the probe's session is empty, the solver's
recorded pid is dead), no temporary file or partial output is left.

Each probe waits for a *state* (the solver has recorded its pid, the sweep has its workers)
before it sends the signal, so nothing depends on timing."""

from __future__ import annotations

import os
import signal
import subprocess
from pathlib import Path

import pytest

from tests.hostile._harness import Probe, alive, check, listing, run, wait_for

pytestmark = pytest.mark.hostile

SIGNALS = [(signal.SIGTERM, 143), (signal.SIGINT, 130), (signal.SIGHUP, 129)]


def _descendants(pid: int) -> list[int]:
    kids: dict[int, list[int]] = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                text = (entry / "stat").read_text()
            except OSError:
                continue
            parent = int(text[text.rfind(")") + 2:].split()[1])
            kids.setdefault(parent, []).append(int(entry.name))
    out, todo = [], [pid]
    while todo:
        for c in kids.get(todo.pop(), []):
            out.append(c)
            todo.append(c)
    return out


@pytest.mark.parametrize("sig, code", SIGNALS, ids=[s.name for s, _ in SIGNALS])
def test_signal_to_audit_with_a_command_solver(scratch: Path, sig: signal.Signals,
                                               code: int) -> None:
    pids = scratch.parent / "pids"

    def send(proc: subprocess.Popen[bytes]) -> None:
        wait_for(lambda: (pids / "slow").is_file() and (pids / "slow").read_text().strip()
                 != "", proc, "the solver started")
        os.kill(proc.pid, sig)

    before = listing(scratch)
    result = run(["audit", "--solver-cmd", "../bin/slow.sh {instance} {profile}",
                  "--examples", "3", "--timeout", "500", "--output-dir", "af"], scratch,
                 env={"PIDS": str(pids)}, during=send)
    check(result, Probe([], code=code, contains=signal.Signals(sig).name), before,
          listing(scratch))
    assert not alive(int((pids / "slow").read_text()))
    assert list((scratch.parent / "tmp").iterdir()) == []


@pytest.mark.parametrize("sig, code", SIGNALS[:2], ids=[s.name for s, _ in SIGNALS[:2]])
def test_signal_to_audit_with_a_python_solver(scratch: Path, sig: signal.Signals,
                                              code: int) -> None:
    def send(proc: subprocess.Popen[bytes]) -> None:  # the worker has forked
        wait_for(lambda: len(_descendants(proc.pid)) >= 1, proc, "the worker started")
        os.kill(proc.pid, sig)

    before = listing(scratch)
    result = run(["audit", "--solver", "tests.dppverify.audit.hostile_solvers:loops", "--examples",
                  "3", "--timeout", "500", "--output-dir", "af"], scratch, during=send,
                 env={"PYTHONPATH": str(Path(__file__).resolve().parents[2])})
    check(result, Probe([], code=code), before, listing(scratch))
    assert list((scratch.parent / "tmp").iterdir()) == []


@pytest.mark.parametrize("sig, code", SIGNALS[:2], ids=[s.name for s, _ in SIGNALS[:2]])
def test_signal_to_density(scratch: Path, sig: signal.Signals, code: int) -> None:
    def send(proc: subprocess.Popen[bytes]) -> None:  # the pool's workers exist
        wait_for(lambda: len(_descendants(proc.pid)) >= 3, proc, "the workers started")
        os.kill(proc.pid, sig)

    before = listing(scratch)
    result = run(["experiment", "density", "--samples", "400", "--workers", "2", "--size",
                  "30", "--output-dir", "dd"], scratch, during=send)
    check(result, Probe([], code=code), before, listing(scratch))
    assert not (scratch / "dd").exists()
