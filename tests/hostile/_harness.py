"""Running one hostile probe: the real ``dpp`` program in a subprocess of its own session,
under resource limits, in a scratch folder whose contents are compared before and after.

Bounded time and memory are enforced by the kernel (``RLIMIT_CPU``, ``RLIMIT_AS``), not by
timing assertions; a progress guard (``tests/_guard.py``: no CPU used for minutes) only turns
a hang into a failure instead of blocking the suite — never a probe that a loaded machine
makes slow. "No surviving process" is checked through the probe's session: every process the
probe started (its session id is the probe's pid) must be gone once it has exited, and the
pids that hostile solvers write into ``pids/`` must be dead too (escapees in other sessions).
"""

from __future__ import annotations

import contextlib
import os
import resource
import signal
import stat
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from dppio.procs import process_table
from tests import _guard

ROOT = Path(__file__).resolve().parents[2]
DEFAULT_MEMORY = 3 << 30
"""Address-space limit of a probe (bytes): numpy, scipy and cvxpy fit well below it."""
DEFAULT_CPU = 120
"""CPU-seconds limit of a probe."""

MAP = ["--map", "paper10.map", "--start", "9,0", "--goals", "0,9", "0,0", "--prior", "0.6,0.4"]
"""The paper's map game as ``--map`` options (paper10.map is in every probe's scratch folder)."""

Setup = Callable[[Path], None]
"""What a probe prepares in its scratch folder before it runs."""


def link(name: str, target: str) -> Setup:
    """A setup that makes ``name`` a symbolic link to ``target``."""
    def setup(d: Path) -> None:
        (d / name).symlink_to(target)
    return setup


@dataclass
class Result:
    """What a probe did."""

    code: int
    stdout: str
    stderr: str
    pid: int

    @property
    def lines(self) -> list[str]:
        """The non-empty stderr lines."""
        return [line for line in self.stderr.splitlines() if line.strip()]


def listing(root: Path) -> dict[str, tuple[str, int, int]]:
    """Every entry under ``root`` (symlinks not followed): kind, size, mtime in ns."""
    out = {}
    for p in sorted(root.rglob("*")):
        st = p.lstat()
        kind = ("link" if stat.S_ISLNK(st.st_mode) else "fifo" if stat.S_ISFIFO(st.st_mode)
                else "dir" if stat.S_ISDIR(st.st_mode) else "file")
        out[str(p.relative_to(root))] = (kind, st.st_size if kind == "file" else 0,
                                         st.st_mtime_ns if kind == "file" else 0)
    return out


def _session_members(sid: int) -> list[int]:
    return [pid for pid, fields in process_table().items()
            if len(fields) > 3 and int(fields[3]) == sid and fields[0] != "Z"]


def alive(pid: int) -> bool:
    """True when ``pid`` is a live (non-zombie) process."""
    try:
        text = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return False
    return text[text.rfind(")") + 2:].split()[0] != "Z"


@dataclass
class Probe:
    """One invocation of ``dpp`` and what it must do."""

    args: list[str]
    code: int | tuple[int, ...] = 2
    one_line: bool = True
    memory: int = DEFAULT_MEMORY
    cpu: int = DEFAULT_CPU
    changes: tuple[str, ...] = ()
    """Scratch entries the probe may create or modify (all others must stay untouched)."""
    env: dict[str, str] = field(default_factory=dict)
    contains: str = ""
    """A text the stderr line must contain (case-insensitive)."""
    fsize: int | None = None
    """``RLIMIT_FSIZE`` (bytes): a file that grows past it fails to write, as on a full disk."""
    nofile: int | None = None
    """``RLIMIT_NOFILE``: the most open files (``ulimit -n``)."""
    stdout: str = "pipe"
    """Standard output: ``pipe`` (captured), ``closed-pipe`` (a pipe whose reader is gone),
    ``full`` (``/dev/full``), ``closed`` (descriptor 1 closed)."""


def run(args: list[str], cwd: Path, *, memory: int = DEFAULT_MEMORY, cpu: int = DEFAULT_CPU,
        env: dict[str, str] | None = None,
        during: Callable[[subprocess.Popen[bytes]], None] | None = None,
        stdin: bytes | None = None, fsize: int | None = None, nofile: int | None = None,
        stdout: str = "pipe", ignore: tuple[int, ...] = (),
        survivors_seconds: float = 10, stdin_is: str = "",
        program: list[str] | None = None) -> Result:
    """Run ``python -m dpp ARGS`` in ``cwd`` under the limits; ``during`` is called
    with the running process (to send it a signal, say) before waiting for it; ``stdin``:
    bytes piped to its standard input (default: ``/dev/null``). ``fsize``, ``nofile`` and
    ``stdout`` as in :class:`Probe`; ``ignore``: signals the probe starts with ignored
    (``nohup``); ``survivors_seconds``: how long the probe's processes may take to end after
    it exited, on an idle machine (stretched by the load: ``tests/_guard.py``);
    ``stdin_is``: standard input that is ``folder`` (the scratch folder), ``closed``
    (descriptor 0 closed) or ``write-only`` (``/dev/null`` opened for writing); ``program``:
    what runs instead of ``python -m dpp`` (the installed launcher: :func:`launcher`).
    """

    def limits() -> None:  # pragma: no cover - in the child
        resource.setrlimit(resource.RLIMIT_AS, (memory, memory))
        resource.setrlimit(resource.RLIMIT_CPU, (cpu, cpu + 5))
        if fsize is not None:
            resource.setrlimit(resource.RLIMIT_FSIZE, (fsize, fsize))
        if nofile is not None:
            resource.setrlimit(resource.RLIMIT_NOFILE, (nofile, nofile))
        signal.signal(signal.SIGINT, signal.SIG_DFL)
        for s in ignore:
            signal.signal(s, signal.SIG_IGN)
        if stdout == "closed":
            os.close(1)
        if stdin_is == "closed":
            os.close(0)

    full_env = {k: v for k, v in os.environ.items() if k not in ("DPP_DEBUG",)}
    tmp = cwd.parent / "tmp"  # the probe's TMPDIR: a short link (AF_UNIX paths, < 108 bytes)
    tmp.mkdir(exist_ok=True)
    short = Path(tempfile.mkdtemp(prefix="dh", dir="/tmp"))
    short.rmdir()
    short.symlink_to(tmp)
    full_env.update({"PYTHONPATH": str(ROOT), "OPENBLAS_NUM_THREADS": "1",
                     "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1", "COLUMNS": "200",
                     "TMPDIR": str(short)})
    full_env.update(env or {})
    out_target: Any = subprocess.PIPE
    pipe_w = None
    if stdout == "closed-pipe":
        pipe_r, pipe_w = os.pipe()
        os.close(pipe_r)  # the reader is gone before the probe writes
        out_target = pipe_w
    elif stdout == "full":
        out_target = open("/dev/full", "wb")  # noqa: SIM115 - closed below
    elif stdout == "closed":
        out_target = subprocess.DEVNULL  # and closed in the child
    in_target: Any = subprocess.DEVNULL if stdin is None else subprocess.PIPE
    in_fd = None
    if stdin_is == "folder":
        in_target = in_fd = os.open(cwd, os.O_RDONLY)
    elif stdin_is == "write-only":
        in_target = in_fd = os.open(os.devnull, os.O_WRONLY)
    command = program if program is not None else [sys.executable, "-m", "dpp"]
    proc = subprocess.Popen([*command, *args], cwd=cwd, env=full_env, stdin=in_target,
                            stdout=out_target,
                            stderr=subprocess.PIPE, start_new_session=True,
                            preexec_fn=limits)
    if in_fd is not None:
        os.close(in_fd)
    if pipe_w is not None:
        os.close(pipe_w)
    if stdout == "full":
        out_target.close()
    try:
        if during is not None:
            during(proc)
        out, err = _guard.communicate(proc, stdin)  # as long as it makes progress
    finally:
        if proc.poll() is None:
            with contextlib.suppress(OSError):
                os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
        short.unlink()
    out = out or b""
    # every process of the probe's session is gone once the probe has exited
    deadline = time.monotonic() + _guard.latency(survivors_seconds)  # stretched by the load
    members = _session_members(proc.pid)
    while members and time.monotonic() < deadline:  # exit in progress: poll, never assert
        time.sleep(0.05)
        members = _session_members(proc.pid)
    assert not members, f"processes of the probe survive: {members}"
    return Result(proc.returncode, out.decode("utf-8", "replace"),
                  err.decode("utf-8", "replace"), proc.pid)


def launcher() -> list[str] | None:
    """The installed ``dpp`` program when it is this checkout's shell launcher (``bin/dpp``,
    installed next to the interpreter by ``pip install -e .``), else None: the only way to
    start ``dpp`` with standard input a folder (no Python interpreter can)."""
    installed = Path(sys.executable).with_name("dpp")
    try:
        same = installed.read_bytes() == (ROOT / "bin" / "dpp").read_bytes()
    except OSError:
        return None
    return [str(installed)] if same and installed.with_name("dpp-python").exists() else None


def wait_for(predicate: Callable[[], bool], proc: subprocess.Popen[bytes],
             what: str) -> None:
    """Poll until ``predicate()`` holds (the probe reached some state), while it runs and
    makes progress (``tests/_guard.py``)."""
    _guard.until(predicate, proc, what)


def check(result: Result, probe: Probe, before: dict[str, tuple[str, int, int]],
          after: dict[str, tuple[str, int, int]]) -> None:
    """The assertions every probe shares."""
    codes = probe.code if isinstance(probe.code, tuple) else (probe.code,)
    assert result.code in codes, (result.code, result.stderr[-2000:], result.stdout[-500:])
    assert "Traceback" not in result.stderr + result.stdout, result.stderr[-2000:]
    if probe.one_line:
        assert len(result.lines) == 1, result.stderr
    if probe.contains:
        assert probe.contains.lower() in result.stderr.lower(), result.stderr
    allowed = set(probe.changes)
    changed = {k for k in set(before) | set(after)
               if before.get(k) != after.get(k)
               and not any(k == a or k.startswith(a + "/") for a in allowed)}
    assert not changed, f"files changed: {sorted(changed)}"


def write_template(d: Path) -> Path:
    """Fill ``d`` with tri.json, its solver profile prof.json and paper10.map (the inputs
    every hostile probe starts from); return ``d``."""
    import json
    import shutil

    from solver.adapter import solve_json

    shutil.copy(ROOT / "examples" / "triangle.json", d / "tri.json")
    shutil.copy(ROOT / "examples" / "paper10.map", d / "paper10.map")
    profile = solve_json(json.loads((d / "tri.json").read_text()))
    (d / "prof.json").write_text(json.dumps(profile))
    return d


def run_probe(scratch: Path, name: str, probe: Probe,
              setup: Setup | None) -> Result:
    """Set up, run and check one probe in ``scratch`` (the ``scratch`` fixture): the shared
    assertions (:func:`check`), no recorded pid alive, no temporary file left, ``/dev/null``
    and FIFOs named ``ff`` left as they were. Probes whose target cannot exist here, or that
    would risk the machine's ``/dev/null`` as root, are skipped."""
    import pytest

    if ("/dev/full" in probe.args or probe.stdout == "full") and \
            not os.path.exists("/dev/full"):
        pytest.skip("no /dev/full here")
    if "/dev/null" in probe.args and not stat.S_ISCHR(os.stat("/dev/null").st_mode):
        pytest.skip("/dev/null is not a device here (another program replaced it)")
    writes_dev_null = ("/dev/null" in probe.args[1:] and probe.args[0] != "value") or (
        name.startswith("solve -o link to /dev/null"))
    if writes_dev_null and os.geteuid() == 0 and not os.environ.get("DPP_HOSTILE_DEV_NULL"):
        pytest.skip("as root, a regression would replace the machine's /dev/null: set "
                    "DPP_HOSTILE_DEV_NULL=1 to run it anyway (CI runs it as a normal user)")
    if setup is not None:
        setup(scratch)
    before = listing(scratch)
    null_before = stat.S_ISCHR(os.stat("/dev/null").st_mode)
    env = {"PIDS": str(scratch.parent / "pids"), **probe.env}
    result = run(probe.args, scratch, memory=probe.memory, cpu=probe.cpu, env=env,
                 fsize=probe.fsize, nofile=probe.nofile, stdout=probe.stdout)
    check(result, probe, before, listing(scratch))
    for pidfile in (scratch.parent / "pids").iterdir():  # escapees of other sessions
        pid = int(pidfile.read_text().split()[0])
        assert not alive(pid), f"{pidfile.name} ({pid}) survived the audit"
    assert list((scratch.parent / "tmp").iterdir()) == [], "temporary files left behind"
    if "/dev/null" in probe.args and null_before:  # other programs may break it: only then
        assert stat.S_ISCHR(os.stat("/dev/null").st_mode), "/dev/null was replaced"
    if "ff" in " ".join(probe.args) and (scratch / "ff").exists():
        assert stat.S_ISFIFO((scratch / "ff").lstat().st_mode)
    return result
