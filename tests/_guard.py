"""Waiting for what a test started, with no wall-clock budget that a loaded machine could
exceed.

A test must never fail because the machine is busy (two other CPU-bound jobs, ``-n 2``, a CI
runner shared with others), yet a hang must fail rather than block the suite. So the guards
here measure *progress*, not time:

- a process (and its children) that keeps using CPU is waited for however long the load makes
  it take; one that uses **no CPU at all for** :data:`IDLE_SECONDS` — blocked on a pipe, a
  lock, a read that never ends — is a hang: it is killed and the test fails;
- what a process may spend is bounded by the kernel where a test needs a bound
  (``RLIMIT_CPU``: CPU seconds, which load does not stretch), never by the clock;
- in-process work (:func:`progress_guard`) is bounded the same way: a CPU-time budget (the
  profiling timer counts this process's CPU, not the wall) and an idle watchdog.

``DPP_TEST_IDLE_SECONDS`` overrides :data:`IDLE_SECONDS` (a slower machine, a debugger).
"""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import threading
import time
from collections.abc import Iterator, Sequence
from typing import Any

from dppio.procs import descendants, process_table

IDLE_SECONDS = float(os.environ.get("DPP_TEST_IDLE_SECONDS", "300"))
"""Seconds without any CPU progress after which a process the test waits for is a hang."""

POLL_SECONDS = 0.5
"""How often progress is looked at."""

_TICKS = os.sysconf("SC_CLK_TCK") if hasattr(os, "sysconf") else 100


def tree_cpu(pid: int) -> float:
    """CPU seconds used so far by ``pid``, its live descendants and the children they reaped
    (``/proc``: user and system time, with the children's): it only grows while any of them
    runs. 0 where there is no ``/proc``."""
    table = process_table()
    total = 0
    for p in (pid, *descendants(pid)):
        fields = table.get(p)
        if fields is not None and len(fields) > 14:
            with contextlib.suppress(ValueError):
                total += sum(int(x) for x in fields[11:15])  # utime stime cutime cstime
    return total / _TICKS


class Progress:
    """The progress of one process tree: :meth:`stalled` is True once it has used no CPU for
    ``idle`` seconds (a hang)."""

    def __init__(self, pid: int, idle: float = IDLE_SECONDS) -> None:
        self.pid = pid
        self.idle = idle
        self.cpu = tree_cpu(pid)
        self.since = time.monotonic()

    def stalled(self) -> bool:
        """True when no CPU was used for ``idle`` seconds (looked at now)."""
        now, cpu = time.monotonic(), tree_cpu(self.pid)
        if cpu > self.cpu:
            self.cpu, self.since = cpu, now
        return now - self.since > self.idle


def _kill(proc: subprocess.Popen[Any]) -> None:
    with contextlib.suppress(OSError):
        if os.getpgid(proc.pid) == proc.pid:  # its own process group (start_new_session)
            os.killpg(proc.pid, signal.SIGKILL)
    with contextlib.suppress(OSError):
        proc.kill()


def communicate(proc: subprocess.Popen[Any], input: Any = None, *,
                idle: float = IDLE_SECONDS) -> tuple[Any, Any]:
    """``proc.communicate(input)``, waiting as long as ``proc`` makes progress; a hang (no
    CPU for ``idle`` seconds) kills it and raises ``AssertionError``."""
    progress = Progress(proc.pid, idle)
    while True:
        try:
            return proc.communicate(input, timeout=POLL_SECONDS)
        except subprocess.TimeoutExpired:
            input = None  # sent (or being sent): a retry must not pass it again
            if progress.stalled():
                _kill(proc)
                proc.communicate()
                raise AssertionError(f"{proc.args!r} made no progress for {idle:g} s "
                                     "(no CPU used): a hang") from None


def wait(proc: subprocess.Popen[Any], *, idle: float = IDLE_SECONDS) -> int:
    """``proc.wait()``, as long as it makes progress (:func:`communicate`'s rule)."""
    progress = Progress(proc.pid, idle)
    while True:
        try:
            return proc.wait(timeout=POLL_SECONDS)
        except subprocess.TimeoutExpired:
            if progress.stalled():
                _kill(proc)
                proc.wait()
                raise AssertionError(f"{proc.args!r} made no progress for {idle:g} s "
                                     "(no CPU used): a hang") from None


def run(cmd: Sequence[str], *, input: Any = None, capture_output: bool = False,
        text: bool = False, check: bool = False, idle: float = IDLE_SECONDS,
        **kwargs: Any) -> subprocess.CompletedProcess[Any]:
    """``subprocess.run`` without ``timeout``: the process is waited for as long as it makes
    progress (:func:`communicate`)."""
    if capture_output:
        kwargs["stdout"] = kwargs["stderr"] = subprocess.PIPE
    if input is not None:
        kwargs["stdin"] = subprocess.PIPE
    with subprocess.Popen(cmd, text=text, **kwargs) as proc:
        out, err = communicate(proc, input, idle=idle)
    result = subprocess.CompletedProcess(proc.args, proc.returncode, out, err)
    if check:
        result.check_returncode()
    return result


def until(predicate: Any, proc: subprocess.Popen[Any], what: str, *,
          idle: float = IDLE_SECONDS) -> None:
    """Poll ``predicate()`` until it holds while ``proc`` runs and makes progress; fail if
    ``proc`` exits first or hangs (no CPU for ``idle`` seconds)."""
    progress = Progress(proc.pid, idle)
    while not predicate():
        assert proc.poll() is None, f"the process exited before {what}"
        assert not progress.stalled(), f"no progress for {idle:g} s before {what}: a hang"
        time.sleep(0.05)


def load_factor() -> float:
    """How much the machine's load stretches a latency now: the run queue per CPU over the
    last minute, at least 1 — for the few waits that are latencies, not work (how long a
    killed process takes to be gone), scaled by it instead of fixed."""
    try:
        return max(1.0, os.getloadavg()[0] / (os.cpu_count() or 1))
    except OSError:  # pragma: no cover - no load average
        return 1.0


def latency(seconds: float) -> float:
    """``seconds`` of an idle machine as a wait on this one (:func:`load_factor`; at least
    doubled, so that a sudden burst of load is covered too)."""
    return seconds * 2 * load_factor()


class GuardTimeout(Exception):
    """In-process work exceeded its CPU budget or made no progress (:func:`progress_guard`)."""


@contextlib.contextmanager
def progress_guard(cpu_seconds: float, *, idle: float = IDLE_SECONDS) -> Iterator[None]:
    """Bound in-process work by CPU time, not the clock: :class:`GuardTimeout` is raised in
    the block once this process has spent ``cpu_seconds`` of CPU in it (the profiling
    timer), or has used no CPU at all for ``idle`` seconds (a blocked read). Main thread only.
    """
    if threading.current_thread() is not threading.main_thread():  # pragma: no cover
        yield
        return
    stop = threading.Event()
    why: list[str] = []

    def interrupt(signum: int, frame: Any) -> None:
        raise GuardTimeout(why[0] if why else f"more than {cpu_seconds:g} CPU seconds")

    def watch() -> None:
        last, since = time.process_time(), time.monotonic()
        while not stop.wait(POLL_SECONDS):
            now, cpu = time.monotonic(), time.process_time()
            if cpu > last + 0.01:
                last, since = cpu, now
            elif now - since > idle:
                why.append(f"no CPU used for {idle:g} s: a hang")
                signal.pthread_kill(threading.main_thread().ident or 0, signal.SIGPROF)
                return

    previous = signal.signal(signal.SIGPROF, interrupt)
    signal.setitimer(signal.ITIMER_PROF, cpu_seconds)
    watcher = threading.Thread(target=watch, name="progress-guard", daemon=True)
    watcher.start()
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_PROF, 0)
        stop.set()
        watcher.join()
        signal.signal(signal.SIGPROF, previous)
