"""Running the solver under test: isolated, under a timeout, every misbehaviour contained.

Two kinds of solvers, one contract (:class:`SolverRunner`): an instance document goes in, an
:class:`Answer` comes out — the profile as JSON text, or the failure (``solver.error``,
``solver.timeout``, ``solver.output``) with one line for humans. Nothing the solver does can
end, hang or corrupt the audit:

- a Python callable (:class:`PythonRunner`) runs in a worker process of its own (forked, in a
  new session, its output discarded); an exception, ``SystemExit``, ``KeyboardInterrupt``, an
  exit of the process or a return value that is not a JSON object is that solver's failure;
- a command line (:class:`CommandRunner`) runs on files, without a shell, in a new session;

in both cases a run that exceeds the timeout has its whole process group killed, so no
child survives — not even one that started a session of its own (the worker, and the
supervisor that starts a command, are child subreapers: :mod:`dppverify.audit.procs`). A
command's output is read with a cap (its last :data:`OUTPUT_CAP` bytes are kept), and a
profile path that is not a regular file (a FIFO the solver made) is the solver's failure,
never a hang. A solver that cannot be started at all — a module that cannot be imported,
a program that does not exist — is bad input (:class:`~dppverify.errors.AuditError`).

Examples
--------
>>> with PythonRunner(lambda doc: {"format": "dpp-profile/1"}, timeout=10) as run:
...     run({"start": 0}).text
'{"format": "dpp-profile/1"}'
>>> def quitter(doc):
...     raise SystemExit(0)
>>> with PythonRunner(quitter, timeout=10) as run:
...     answer = run({})
>>> answer.check, answer.message
('solver.error', 'the solver raised SystemExit: 0')
"""

from __future__ import annotations

import contextlib
import importlib
import json
import multiprocessing
import os
import pickle
import shlex
import shutil
import signal
import stat
import subprocess
import sys
import tempfile
import threading
import traceback
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from multiprocessing.connection import Connection
from pathlib import Path
from types import TracebackType
from typing import Any

from dppio.limits import MAX_INPUT_BYTES
from dppverify.audit.config import READY_TIMEOUT
from dppverify.audit.procs import SUPERVISOR, become_subreaper, kill_tree
from dppverify.errors import AuditError
from dppverify.formats.files import read_input

Doc = dict[str, Any]
Solver = Callable[[Doc], Any]


@dataclass(frozen=True)
class Answer:
    """What one run of the solver gave.

    Attributes
    ----------
    text : str or None
        The profile as JSON text (a JSON object), None when the run failed.
    check : str
        ``""`` on success, else ``solver.error``, ``solver.timeout`` or ``solver.output``.
    message : str
        One line for humans (empty on success).
    traceback : str
        The solver's traceback when it raised (``solver.error`` from a Python solver).
    where : str
        The identity of a raised exception, ``Type@file:line`` of the frame that raised it
        (as hypothesis tells failures apart); empty otherwise.
    """

    text: str | None
    check: str = ""
    message: str = ""
    traceback: str = ""
    where: str = ""


def one_line(text: object, limit: int = 300) -> str:
    """``text`` on one line, at most ``limit`` characters.

    Examples
    --------
    >>> one_line("a\\n  b")
    'a b'
    """
    flat = " ".join(str(text).split())
    return flat if len(flat) <= limit else flat[:limit - 3] + "..."


def _number_default(x: Any) -> Any:
    if isinstance(x, Fraction):
        return f"{x.numerator}/{x.denominator}"
    raise TypeError(f"{type(x).__name__} is not JSON serializable")


def call_in_process(solver: Solver, doc: Doc) -> Answer:
    """Call ``solver`` on a copy of ``doc`` in this process and classify the result.

    Used by the worker process of :class:`PythonRunner` (and for plain callables given to
    :func:`dppverify.audit.examine`). Any ``BaseException`` the solver raises is its failure.

    Examples
    --------
    >>> call_in_process(lambda d: 1 / 0, {}).message
    'the solver raised ZeroDivisionError: division by zero'
    >>> call_in_process(lambda d: [1], {}).message
    'the solver returned list, not a JSON object'
    """
    try:
        answer = solver(json.loads(json.dumps(doc)))  # the solver gets its own copy
    except BaseException as exc:
        frames = traceback.extract_tb(exc.__traceback__)
        place = f"{frames[-1].filename}:{frames[-1].lineno}" if frames else "?"
        text = "".join(traceback.format_exception(exc))
        if len(text) > TRACEBACK_CAP:  # the end says where it was raised
            text = f"... ({len(text) - TRACEBACK_CAP} characters cut)\n" + text[-TRACEBACK_CAP:]
        return Answer(None, "solver.error",
                      f"the solver raised {type(exc).__name__}: {one_line(exc)}",
                      traceback=text, where=f"{type(exc).__name__}@{place}")
    if not isinstance(answer, dict):
        return Answer(None, "solver.output",
                      f"the solver returned {type(answer).__name__}, not a JSON object")
    try:
        text = json.dumps(answer, default=_number_default)
    except (TypeError, ValueError, RecursionError) as exc:
        return Answer(None, "solver.output", f"the solver's profile is not JSON: {one_line(exc)}")
    size = len(text) if len(text) > MAX_INPUT_BYTES or text.isascii() else len(text.encode())
    if size > MAX_INPUT_BYTES:
        return Answer(None, "solver.output", too_large(size))
    return Answer(text)


def too_large(size: int | None = None) -> str:
    """The failure of an answer beyond the input limit (every input of ``dpp`` is bounded at
    :data:`~dppio.limits.MAX_INPUT_BYTES`, a solver's profile too).

    Examples
    --------
    >>> too_large(800_000_000)
    "the solver's profile is larger than the limit of 64 MiB for every input (800000000 bytes)"
    """
    got = "" if size is None else f" ({size} bytes)"
    return (f"the solver's profile is larger than the limit of {MAX_INPUT_BYTES >> 20} MiB for "
            f"every input{got}")


TRACEBACK_CAP = 1 << 16
"""Characters of a solver's traceback kept (its end) in the answer and ``failure.json``."""

MESSAGE_CAP = MAX_INPUT_BYTES + 4 * TRACEBACK_CAP + 4096
"""Largest message the audit accepts from its worker: a profile at the input limit, a
traceback, the rest of the answer. A larger one is never read (the worker is ended)."""


class SolverRunner:
    """A solver under test, run in isolation: call it with an instance document.

    Use as a context manager (or call :meth:`close`) so that its processes end.
    """

    label = "solver"

    def __call__(self, doc: Doc) -> Answer:
        """Run the solver on ``doc``."""
        raise NotImplementedError

    def close(self) -> None:
        """End every process the runner started."""

    def __enter__(self) -> SolverRunner:
        return self

    def __exit__(self, kind: type[BaseException] | None, exc: BaseException | None,
                 _traceback: TracebackType | None) -> None:
        self.close()


def _load(spec: str) -> Solver:
    module_name, sep, attr = spec.partition(":")
    if not sep or not module_name or not attr:
        raise AuditError(f"--solver {spec!r} must look like MODULE:FUNCTION")
    try:
        obj: Any = importlib.import_module(module_name)
    except BaseException as exc:
        raise AuditError(f"cannot import module {module_name!r}: "
                         f"{type(exc).__name__}: {one_line(exc)}") from None
    for part in attr.split("."):
        if not hasattr(obj, part):
            raise AuditError(f"module {module_name!r} has no attribute {attr!r}")
        obj = getattr(obj, part)
    if not callable(obj):
        raise AuditError(f"{spec!r} is not callable")
    return obj


def _worker(target: str | Solver, conn: Connection) -> None:  # pragma: no cover - in a child
    os.setsid()  # a process group of its own: a timeout kills the solver's children too
    for s in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
        signal.signal(s, signal.SIG_DFL)  # not the audit's handlers (dppio.cli.interrupts)
    become_subreaper(signal.SIGKILL)  # the solver's escaped children stay under the worker
    devnull = os.open(os.devnull, os.O_RDWR)
    for fd in (0, 1, 2):
        os.dup2(devnull, fd)
    sys.stdout = sys.stderr = open(os.devnull, "w")  # noqa: SIM115
    try:
        solver = _load(target) if isinstance(target, str) else target
    except AuditError as exc:
        conn.send(("bad", str(exc)))
        os._exit(0)
    conn.send(("ready", ""))
    while True:
        try:
            text = conn.recv()
        except (EOFError, OSError):
            os._exit(0)
        if text is None:
            os._exit(0)
        answer = call_in_process(solver, json.loads(text))
        conn.send((answer.text, answer.check, answer.message, answer.traceback, answer.where))


class PythonRunner(SolverRunner):
    """A Python callable — or ``MODULE:FUNCTION``, imported in the worker — in a worker process.

    The worker is forked once and reused; a timed-out run kills its process group and the
    next run starts a fresh worker. ``MODULE:FUNCTION`` is imported only in the worker, so
    user code never runs in the audit's own process.

    Parameters
    ----------
    target : str or callable
        ``MODULE:FUNCTION`` (``FUNCTION`` may be dotted) or the callable itself.
    timeout : float
        Seconds per run.

    Raises
    ------
    AuditError
        If ``MODULE:FUNCTION`` is malformed, cannot be imported or is not callable.

    Examples
    --------
    >>> PythonRunner("json.dumps", timeout=5)
    Traceback (most recent call last):
    dppverify.errors.AuditError: --solver 'json.dumps' must look like MODULE:FUNCTION
    >>> with PythonRunner("json:loads", timeout=5) as run:
    ...     run({}).message
    'the solver raised TypeError: the JSON object must be str, bytes or bytearray, not dict'
    """

    def __init__(self, target: str | Solver, *, timeout: float) -> None:
        if isinstance(target, str):
            module_name, sep, attr = target.partition(":")
            if not sep or not module_name or not attr:
                raise AuditError(f"--solver {target!r} must look like MODULE:FUNCTION")
            self.label = target
        else:
            self.label = getattr(target, "__name__", "solver")
        self.target = target
        self.timeout = timeout
        self._proc: Any = None
        self._conn: Connection | None = None
        self._start()

    def _start(self) -> None:
        ctx = multiprocessing.get_context("fork")
        parent, child = ctx.Pipe()
        proc = ctx.Process(target=_worker, args=(self.target, child), daemon=True)
        proc.start()
        child.close()
        self._proc, self._conn = proc, parent
        try:
            if not parent.poll(READY_TIMEOUT):
                self.close()
                raise AuditError(f"--solver {self.label}: importing it took longer than "
                                 f"{READY_TIMEOUT:g} s")
            status, message = parent.recv()
        except (EOFError, OSError):
            self.close()
            raise AuditError(f"--solver {self.label}: the process importing it exited "
                             f"(code {proc.exitcode})") from None
        if status == "bad":
            self.close()
            raise AuditError(message)

    def __call__(self, doc: Doc) -> Answer:
        if self._proc is None:
            self._start()
        conn = self._conn
        assert conn is not None
        try:
            conn.send(json.dumps(doc))
            if not conn.poll(self.timeout):
                self.close()
                return Answer(None, "solver.timeout",
                              f"the solver timed out after {self.timeout:g} s")
            data = conn.recv_bytes(MESSAGE_CAP)  # bounded: never more than the input limit
        except OSError as exc:
            if "bad message length" in str(exc):  # (what recv_bytes says of a larger message)
                self.close()
                return Answer(None, "solver.output", too_large())
            code = self._proc.exitcode if self._proc is not None else None
            self.close()
            return Answer(None, "solver.error", f"the solver's process exited (code {code})")
        except EOFError:
            code = self._proc.exitcode if self._proc is not None else None
            self.close()
            return Answer(None, "solver.error", f"the solver's process exited (code {code})")
        text, check, message, *exc_info = pickle.loads(data)  # (our own worker's message)
        return Answer(text, check, message, *exc_info)

    def close(self) -> None:
        proc, conn = self._proc, self._conn
        self._proc = self._conn = None
        if conn is not None:
            with contextlib.suppress(OSError):
                conn.send(None)
            conn.close()
        if proc is not None:
            proc.join(0.5)
            kill_tree(proc.pid)  # the worker, its process group and every descendant
            proc.join()


class CommandRunner(SolverRunner):
    """A command line run per instance on files, in a new session, under a timeout.

    ``template`` must contain ``{instance}`` and ``{profile}``: the instance JSON is written
    to a temporary file, the command runs (no shell; arguments split like a POSIX shell) and
    must write the profile JSON to the ``{profile}`` path and exit 0. After each run the
    command's process group is killed, so children it left behind do not survive.

    Raises
    ------
    AuditError
        If the template is malformed, lacks a placeholder, or names a program that does not
        exist.

    Examples
    --------
    >>> with CommandRunner("cp {instance} {profile}", timeout=10) as solve:
    ...     solve({"start": 0}).text
    '{"start": 0}'
    >>> CommandRunner("prog {instance}", timeout=10)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.AuditError: --solver-cmd must contain {instance} and {profile}: ...
    >>> CommandRunner("no-such-program-xyz {instance} {profile}", timeout=10)
    Traceback (most recent call last):
    dppverify.errors.AuditError: --solver-cmd: program 'no-such-program-xyz' not found
    """

    def __init__(self, template: str, *, timeout: float) -> None:
        try:
            argv = shlex.split(template)
        except ValueError as exc:
            raise AuditError(f"--solver-cmd {template!r}: {exc}") from None
        if not argv or not all(any(p in a for a in argv) for p in ("{instance}", "{profile}")):
            raise AuditError(f"--solver-cmd must contain {{instance}} and {{profile}}: "
                             f"{template!r}")
        program = argv[0]
        found = shutil.which(program)
        if found is None or os.path.isdir(program):
            raise AuditError(f"--solver-cmd: program {program!r} not found")
        self.argv = argv
        self.label = template
        self.timeout = timeout

    def __call__(self, doc: Doc) -> Answer:
        with tempfile.TemporaryDirectory(prefix="dpp-audit-", ignore_cleanup_errors=True) as tmp:
            inst, prof = Path(tmp) / "instance.json", Path(tmp) / "profile.json"
            inst.write_text(json.dumps(doc))
            cmd = [a.replace("{instance}", str(inst)).replace("{profile}", str(prof))
                   for a in self.argv]
            result = self._run(cmd)
            if isinstance(result, Answer):
                return result
            code, lines = result
            if code != 0:
                last = lines[-1] if lines else "no output"
                return Answer(None, "solver.error",
                              f"the command exited {code}: {one_line(last)}")
            try:
                kind = os.stat(prof).st_mode
            except FileNotFoundError:
                return Answer(None, "solver.output", "the command exited 0 but wrote no profile")
            except OSError as exc:
                return Answer(None, "solver.output",
                              f"the command's profile: {one_line(exc.strerror or exc)}")
            if not stat.S_ISREG(kind):
                return Answer(None, "solver.output", "the command's profile path is not a "
                              "regular file (a FIFO, a device or a folder)")
            try:
                raw = read_input(prof)
            except (OSError, ValueError) as exc:
                return Answer(None, "solver.output", f"the command's profile: {one_line(exc)}")
            try:
                text = raw.decode("utf-8")
            except UnicodeDecodeError:
                return Answer(None, "solver.output", "the command's profile is not UTF-8 text")
            return Answer(text)

    def _run(self, cmd: list[str]) -> Answer | tuple[int, list[str]]:
        """Run ``cmd`` under :data:`~dppverify.audit.procs.SUPERVISOR`: its exit code and the
        last lines of its output (read with a cap of :data:`OUTPUT_CAP` bytes), or the
        timeout's :class:`Answer`. Every process it started is dead when this returns."""
        argv = [sys.executable, "-I", "-S", "-c", SUPERVISOR, str(os.getpid()), *cmd]
        try:
            proc = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                    stderr=subprocess.STDOUT, start_new_session=True)
        except OSError as exc:
            return Answer(None, "solver.error",
                          f"the command could not start: {exc.strerror or exc}")
        tail = bytearray()
        assert proc.stdout is not None
        reader = threading.Thread(target=_read_capped, args=(proc.stdout, tail), daemon=True)
        reader.start()
        try:
            try:
                code = proc.wait(self.timeout)
            except subprocess.TimeoutExpired:
                proc.terminate()  # the supervisor kills the solver's processes, then exits
                with contextlib.suppress(subprocess.TimeoutExpired):
                    proc.wait(5)
                return Answer(None, "solver.timeout",
                              f"the command timed out after {self.timeout:g} s")
        finally:
            kill_tree(proc.pid)  # whatever is left of the run, then the supervisor
            proc.wait()
            reader.join(5)
            proc.stdout.close()
        lines = bytes(tail).decode("utf-8", "replace").strip().splitlines()
        return code, lines


OUTPUT_CAP = 1 << 16
"""Bytes of a command's output kept (its tail): the rest is read and discarded."""


def _read_capped(stream: Any, tail: bytearray) -> None:
    """Read ``stream`` to its end, keeping only its last :data:`OUTPUT_CAP` bytes."""
    with contextlib.suppress(OSError, ValueError):
        while chunk := stream.read1(1 << 16):
            tail += chunk
            if len(tail) > OUTPUT_CAP:
                del tail[:len(tail) - OUTPUT_CAP]
