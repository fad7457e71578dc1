"""Process containment for the audit's solver runs: nothing a solver starts outlives its run.

A solver under test may start children, and those may leave its process group (``setsid``)
or be orphaned. Two mechanisms together end all of them:

- every run has a *reaper*: the worker process of a Python solver, or the small
  :data:`SUPERVISOR` program that starts a command-line solver. It runs in a session of its
  own and is a Linux *child subreaper* (``prctl(PR_SET_CHILD_SUBREAPER)``), so every
  descendant of the solver — even one that started its own session, even after its parent
  exited — stays among the reaper's descendants;
- :func:`kill_tree` kills the reaper's descendants (found through ``/proc``) and its process
  group with SIGKILL, repeatedly until none is left.

The supervisor also dies with the audit (``PR_SET_PDEATHSIG``), taking the solver's processes
along. On systems without ``/proc`` or ``prctl`` only the process group is killed.

Examples
--------
>>> import os, subprocess, sys
>>> p = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"],
...                      start_new_session=True)
>>> kill_tree(p.pid); p.wait()
-9
"""

from __future__ import annotations

import contextlib
import os
import signal

from dppio.procs import descendants

PR_SET_PDEATHSIG = 1
PR_SET_CHILD_SUBREAPER = 36


def _prctl(option: int, value: int) -> bool:
    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        return bool(libc.prctl(option, value, 0, 0, 0) == 0)
    except (OSError, AttributeError):  # not Linux
        return False


def become_subreaper(parent_death_signal: int | None = None) -> bool:
    """Make this process a child subreaper (orphaned descendants are re-parented to it); with
    ``parent_death_signal``, also have that signal sent to it when its parent exits.

    Returns
    -------
    bool
        True on Linux, where it worked.

    Examples
    --------
    >>> import subprocess, sys
    >>> code = "from dppverify.audit.procs import become_subreaper; print(become_subreaper())"
    >>> out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    >>> out.stdout.strip() in ("True", "False")
    True
    """
    if parent_death_signal is not None:
        _prctl(PR_SET_PDEATHSIG, int(parent_death_signal))
    return _prctl(PR_SET_CHILD_SUBREAPER, 1)


def kill_tree(pid: int, *, include_self: bool = True, rounds: int = 20) -> None:
    """SIGKILL every descendant of ``pid`` and the process group ``pid`` (and ``pid``).

    Repeated until no descendant is left (a process may fork while the others die); a
    process that is already gone is skipped.

    Examples
    --------
    >>> import subprocess, sys
    >>> p = subprocess.Popen(["sh", "-c", "sleep 60 & sleep 60"], start_new_session=True)
    >>> kill_tree(p.pid); p.wait() in (-9, 128 + 9), descendants(p.pid)
    (True, [])

    (``sh`` itself is killed, or, if its child dies first, exits with 128 + 9.)
    """
    for _ in range(rounds):
        found = descendants(pid)
        for p in found:
            with contextlib.suppress(ProcessLookupError, PermissionError):
                os.kill(p, signal.SIGKILL)
        if not found:
            break
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(pid, signal.SIGKILL)
    if include_self:
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.kill(pid, signal.SIGKILL)


SUPERVISOR = r'''
import ctypes, os, signal, sys
audit = int(sys.argv[1]); argv = sys.argv[2:]
try:
    libc = ctypes.CDLL(None, use_errno=True)
    libc.prctl(36, 1, 0, 0, 0)                       # PR_SET_CHILD_SUBREAPER
    libc.prctl(1, int(signal.SIGTERM), 0, 0, 0)      # PR_SET_PDEATHSIG
except (OSError, AttributeError):
    pass
def tree():
    kids = {}
    for e in os.listdir("/proc") if os.path.isdir("/proc") else ():
        if e.isdigit():
            try:
                t = open("/proc/%s/stat" % e).read()
            except OSError:
                continue
            kids.setdefault(int(t[t.rfind(")") + 2:].split()[1]), []).append(int(e))
    out, todo = [], [os.getpid()]
    while todo:
        for c in kids.get(todo.pop(), []):
            out.append(c); todo.append(c)
    return out
def clean():
    for _ in range(50):
        found = tree()
        for p in found:
            try: os.kill(p, signal.SIGKILL)
            except OSError: pass
        try:
            while os.waitpid(-1, os.WNOHANG)[0]: pass
        except ChildProcessError:
            pass
        if not found: break
def stop(signum, frame):
    clean(); os._exit(128 + signum)
for s in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
    signal.signal(s, stop)
if os.getppid() != audit:
    stop(signal.SIGTERM, None)
pid = os.fork()
if pid == 0:
    for s in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
        signal.signal(s, signal.SIG_DFL)
    try:
        os.execvp(argv[0], argv)
    except OSError as exc:
        os.write(2, ("cannot start %s: %s\n" % (argv[0], exc.strerror)).encode())
    os._exit(127)
while True:
    try:
        p, status = os.wait()
    except ChildProcessError:
        status = 127 << 8; break
    if p == pid: break
code = os.waitstatus_to_exitcode(status)
clean()
os._exit(code if code >= 0 else 128 - code)
'''
"""The program that starts a ``--solver-cmd`` solver: ``python -I -S -c SUPERVISOR AUDIT_PID
ARGV...``. It is a subreaper, forwards the solver's exit code (``128 + n`` for a signal),
and kills every descendant when the solver exits, when it receives SIGTERM/SIGINT/SIGHUP,
or when the audit (``AUDIT_PID``) dies."""
