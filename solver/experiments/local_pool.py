"""Local worker processes of the experiments (``dpp batch --workers``, ``dpp experiment
density --workers``): started within the limits, ended with the run, whatever ends it.

- **Open files.** A pool needs file descriptors (pipes, the forkserver's socket, two per
  worker). Before it starts, :func:`check_open_files` raises the soft ``RLIMIT_NOFILE`` up to
  the hard limit if that is enough, else refuses in one line naming the limit, instead of
  failing half-way with tracebacks from the workers.
- **Children die with the run.** Each worker runs in a process group of its own with the
  default signal handlers (a terminal's Ctrl-C reaches only the run, which then ends its
  workers) and ends itself when the run's process is gone, even after ``kill -9``: Linux's
  ``PR_SET_PDEATHSIG`` (through ``ctypes``) kills it when its parent (the forkserver, which
  exits when the run does) dies, and a watchdog thread checks the run's process twice a
  second (other systems, and a worker that started after its parent was gone).
- **On any error or signal** every worker, its process group, the forkserver and any process
  it was starting are killed (SIGKILL) before the exception goes on, so none outlives the run
  or prints a traceback after it — also when the signal lands in the caller's loop between
  two results: the callers close the results' generator on the way out
  (``contextlib.closing``).
- **Bounded work in flight.** :func:`completed` submits at most ``2 * workers`` tasks at a
  time, so ``tasks`` may be a lazy iterator of any length.
"""

from __future__ import annotations

import contextlib
import os
import signal
import threading
import time
from collections.abc import Callable, Generator, Iterable
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from pathlib import Path
from typing import TypeVar, cast

from dppio.procs import descendants
from solver.errors import InvalidInstanceError

T = TypeVar("T")
R = TypeVar("R")

FILES_BASE = 32
"""Open files a run needs beside its pool (its own, the pool's queues, the forkserver)."""

FILES_PER_WORKER = 4
"""Open files the run holds per worker (measured: 2; twice that for margin)."""


def check_open_files(workers: int, *, option: str = "--workers") -> None:
    """Make sure the open-file limit holds a pool of ``workers``: raise the soft limit up to
    the hard one if needed, else refuse in one line.

    Raises
    ------
    InvalidInstanceError
        Even the hard limit (``ulimit -n``) is too small.

    Examples
    --------
    >>> check_open_files(2)  # (tests/solver/experiments/test_local_pool.py: under ulimit -n 20)
    """
    try:
        import resource
    except ImportError:  # pragma: no cover - not POSIX
        return
    try:
        open_now = len(os.listdir("/proc/self/fd"))
    except OSError:  # pragma: no cover - no /proc: a guess
        open_now = 16
    need = open_now + FILES_BASE + FILES_PER_WORKER * workers
    soft, hard = resource.getrlimit(resource.RLIMIT_NOFILE)
    infinite = resource.RLIM_INFINITY
    if soft == infinite or soft >= need:
        return
    if hard == infinite or hard >= need:
        resource.setrlimit(resource.RLIMIT_NOFILE, (need, hard))
        return
    raise InvalidInstanceError(f"{option} {workers} needs about {need} open files; the limit "
                               f"is {hard} (ulimit -n): give fewer {option} or raise the limit")


def completed(fn: Callable[[T], R], tasks: Iterable[T], workers: int, *,
              option: str = "--workers") -> Generator[tuple[T, R], None, None]:
    """``(task, fn(task))`` in completion order, computed by ``workers`` local processes
    (this module's rules); at most ``2 * workers`` tasks in flight.

    ``fn`` and the tasks must be picklable (module-level). When the iteration ends early, or
    raises (a worker's error, a signal), every process of the pool is killed. Iterate it
    under ``contextlib.closing``: an exception raised in the caller's loop (a signal between
    two results) then ends the pool at once, not when the generator is collected — after
    the command's last line, when a worker still starting could print a traceback.

    Examples
    --------
    >>> sorted(r for _, r in completed(abs, iter([-3, 1, -2]), 2))
    [1, 2, 3]
    """
    import multiprocessing

    check_open_files(workers, option=option)
    ctx = multiprocessing.get_context("forkserver" if os.name == "posix" else "spawn")
    run = os.getpid()
    pool = ProcessPoolExecutor(max_workers=workers, mp_context=ctx, initializer=_worker_start,
                               initargs=(run, _start_time(run)))
    todo = iter(tasks)
    running: dict[Future[R], T] = {}
    try:
        while True:
            while len(running) < 2 * workers:
                item = next(todo, _END)
                if item is _END:
                    break
                running[pool.submit(fn, cast(T, item))] = cast(T, item)
            if not running:
                break
            finished, _ = wait(running, return_when=FIRST_COMPLETED)
            for fut in finished:
                task = running.pop(fut)
                yield task, fut.result()
    except BaseException:  # an error, a signal, or the caller stopped: no worker outlives it
        kill_pool(pool)
        raise
    pool.shutdown()


_END = object()


def _stat(pid: int) -> list[str]:
    """The fields of ``/proc/PID/stat`` after the command name (empty when unreadable)."""
    try:
        text = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return []
    return text[text.rfind(")") + 2:].split()


def _start_time(pid: int) -> str:
    """The start time of process ``pid`` (``/proc``; '' elsewhere): with the pid, it names
    the process even after its pid is reused."""
    fields = _stat(pid)
    return fields[19] if len(fields) > 19 else ""


def _alive(pid: int, started: str) -> bool:
    """True while the run's process lives: not gone, not a zombie (killed, not yet reaped),
    not another process with its pid."""
    if started:
        fields = _stat(pid)
        return len(fields) > 19 and fields[19] == started and fields[0] not in ("Z", "X")
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:
        return True
    return True


def _worker_start(run: int, started: str) -> None:  # pragma: no cover - runs in a worker
    """Worker initializer: a process group of its own, default signal handlers, and death
    with the run (``PR_SET_PDEATHSIG`` and a watchdog thread)."""
    if os.name == "posix":
        os.setpgid(0, 0)
        for s in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
            signal.signal(s, signal.SIG_DFL)
    parent = os.getppid()
    with contextlib.suppress(Exception):  # Linux: die with the parent (the forkserver)
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, int(signal.SIGKILL), 0, 0, 0)  # PR_SET_PDEATHSIG
    if os.getppid() != parent or not _alive(run, started):  # gone before the prctl
        os._exit(1)

    def watch() -> None:
        while os.getppid() == parent and _alive(run, started):
            time.sleep(0.5)
        os.kill(os.getpid(), signal.SIGKILL)

    threading.Thread(target=watch, name="dpp-run-watchdog", daemon=True).start()


def kill_pool(pool: ProcessPoolExecutor) -> None:
    """Kill every worker process of ``pool`` and its process group, the forkserver and what
    it was starting, then shut the pool down (without waiting for a task).

    Examples
    --------
    >>> import multiprocessing
    >>> pool = ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("forkserver"))
    >>> pool.submit(abs, -1).result()
    1
    >>> workers = list(pool._processes.values())
    >>> kill_pool(pool)
    >>> [p.is_alive() for p in workers]
    [False]
    """
    procs = list((getattr(pool, "_processes", None) or {}).values())  # no public accessor
    for proc in procs:
        with contextlib.suppress(OSError, ValueError):
            if os.name == "posix" and proc.pid:
                os.killpg(proc.pid, signal.SIGKILL)
        with contextlib.suppress(OSError, ValueError):
            proc.kill()
    import multiprocessing.forkserver

    server: int = getattr(getattr(multiprocessing.forkserver, "_forkserver", None),
                          "_forkserver_pid", None) or 0  # no public accessor either
    if server > 0:  # frozen first: it forks nothing more while its children are killed
        with contextlib.suppress(OSError):
            os.kill(server, signal.SIGSTOP)
        for _ in range(20):
            found = descendants(server)
            for pid in found:
                with contextlib.suppress(OSError):
                    os.kill(pid, signal.SIGKILL)
            if not found:
                break
        with contextlib.suppress(OSError):
            os.kill(server, signal.SIGKILL)
    manager = getattr(pool, "_executor_manager_thread", None)  # no public accessor
    pool.shutdown(wait=False, cancel_futures=True)
    for proc in procs:
        with contextlib.suppress(Exception):
            proc.join(5)
    if manager is not None:  # let it close its wake-up pipe before the interpreter exits:
        manager.join(5)      # else concurrent.futures' exit hook may write to it as it closes
