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


def _deliverable(sig: signal.Signals) -> None:
    """Skip, with the reason, when this process ignores ``sig`` (``nohup`` ignores SIGHUP):
    a probe inherits the disposition and ``dpp`` keeps ignoring the signal, as documented
    (docs/limits.md, "Signals"), so the probe could not show what the signal does. (The
    harness gives every probe SIGINT's default back: a shell's background job ignores it.)"""
    if sig != signal.SIGINT and signal.getsignal(sig) == signal.SIG_IGN:
        pytest.skip(f"{sig.name} is ignored in this process (nohup?): a probe would inherit "
                    "that, and dpp keeps ignoring it as asked")


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
    _deliverable(sig)
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
    _deliverable(sig)
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
    _deliverable(sig)
    def send(proc: subprocess.Popen[bytes]) -> None:  # the pool's workers exist
        wait_for(lambda: len(_descendants(proc.pid)) >= 3, proc, "the workers started")
        os.kill(proc.pid, sig)

    before = listing(scratch)
    result = run(["experiment", "density", "--samples", "400", "--workers", "2", "--size",
                  "30", "--output-dir", "dd"], scratch, during=send)
    check(result, Probe([], code=code), before, listing(scratch))
    assert not (scratch / "dd").exists()


# --- third round: dpp batch --- ------------------------------------------------------------
TINY_MAP = "type octile\nheight 3\nwidth 4\nmap\n....\n.@@.\n....\n"
TINY_LINES = ["0\ttiny.map\t4\t3\t0\t0\t3\t2\t5", "0\ttiny.map\t4\t3\t3\t0\t0\t2\t5",
              "0\ttiny.map\t4\t3\t0\t2\t3\t0\t3"]


def _scen(d: Path, repeat: int) -> list[str]:
    (d / "tiny.map").write_text(TINY_MAP)
    (d / "tiny.scen").write_text("version 1\n" + "\n".join(TINY_LINES * repeat) + "\n")
    return ["batch", "tiny.scen", "-o", "b.csv", "--no-progress", "--chunk", "1"]


def _room() -> list[str]:
    """A .scen of real work (130 lines on room-32-32-4, seconds each with --route auto)."""
    from dppio.standard_maps import standard_map_path

    scen = standard_map_path("room-32-32-4").with_name("room-32-32-4-even-1.scen")
    return ["batch", str(scen), "-o", "b.csv", "--no-progress", "--chunk", "1"]


@pytest.mark.parametrize("sig, code", SIGNALS, ids=[s.name for s, _ in SIGNALS])
def test_signal_to_batch_while_its_pool_starts(scratch: Path, sig: signal.Signals,
                                               code: int) -> None:
    """The signal arrives as the first helper process of the pool appears: one line, 128 + n,
    nothing written (no CSV, no temporary file), no process left, no worker traceback."""
    _deliverable(sig)
    args = _scen(scratch, 20)

    def send(proc: subprocess.Popen[bytes]) -> None:
        wait_for(lambda: len(_descendants(proc.pid)) >= 1, proc, "the pool started")
        os.kill(proc.pid, sig)

    before = listing(scratch)
    result = run([*args, "--workers", "2"], scratch, during=send)
    check(result, Probe([], code=code, contains="nothing was written"), before,
          listing(scratch))
    assert list((scratch.parent / "tmp").iterdir()) == []


@pytest.mark.parametrize("sig, code", SIGNALS, ids=[s.name for s, _ in SIGNALS])
@pytest.mark.parametrize("workers", [1, 2])
def test_signal_to_batch_after_its_first_rows(scratch: Path, sig: signal.Signals, code: int,
                                              workers: int) -> None:
    """After rows were written: one line naming how many rows the file holds; the file holds
    whole rows only and the same command continues it."""
    _deliverable(sig)
    args = _room()
    out = scratch / "b.csv"

    def send(proc: subprocess.Popen[bytes]) -> None:
        wait_for(lambda: out.exists() and out.read_bytes().count(b"\n") >= 2, proc,
                 "the first row")
        os.kill(proc.pid, sig)

    before = listing(scratch)
    result = run([*args, "--workers", str(workers), "--route", "auto"], scratch, during=send)
    check(result, Probe([], code=code, changes=("b.csv",),
                        contains="run the same command again"), before, listing(scratch))
    text = out.read_text()
    assert text.endswith("\n") and text.count("\n") >= 2
    assert list((scratch.parent / "tmp").iterdir()) == []


def test_sighup_under_nohup_is_ignored(scratch: Path) -> None:
    """Started with SIGHUP ignored (``nohup``), a batch keeps running through a SIGHUP: that
    is what nohup asks for (docs/limits.md); without nohup SIGHUP ends it (the tests above)."""
    args = _scen(scratch, 2)

    def send(proc: subprocess.Popen[bytes]) -> None:
        wait_for(lambda: (scratch / "b.csv").exists(), proc, "the first row")
        os.kill(proc.pid, signal.SIGHUP)

    before = listing(scratch)
    result = run(args, scratch, during=send, ignore=(signal.SIGHUP,))
    check(result, Probe([], code=0, one_line=False, changes=("b.csv",)), before,
          listing(scratch))


@pytest.mark.parametrize("cmd", ["batch", "density"])
def test_kill_9_leaves_no_worker(scratch: Path, cmd: str) -> None:
    """``kill -9`` of the command itself (no cleanup can run): its workers notice and end
    (PR_SET_PDEATHSIG, and a watchdog on the command's process); the harness checks that no
    process of the probe's session survives, giving them 30 s."""
    if cmd == "batch":
        args = [*_room(), "--workers", "2", "--route", "auto"]
    else:
        args = ["experiment", "density", "--samples", "400", "--workers", "2", "--size", "30",
                "--output-dir", "dd"]

    def kill(proc: subprocess.Popen[bytes]) -> None:  # the forkserver, the tracker, 2 workers
        wait_for(lambda: len(_descendants(proc.pid)) >= 4, proc, "the workers started")
        os.kill(proc.pid, signal.SIGKILL)

    result = run(args, scratch, during=kill, survivors_seconds=30)
    assert result.code == -signal.SIGKILL
