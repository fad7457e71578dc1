"""Process trees through ``/proc``: the live descendants of a process (Linux; empty elsewhere).

Both packages end what they start: the checker's audit kills every process a solver under
test left behind (``dppverify/audit/procs.py``), the density sweep kills its workers on a
signal (``solver/experiments/density.py``). Both find them here.
"""

from __future__ import annotations

import contextlib
from pathlib import Path


def process_table() -> dict[int, list[str]]:
    """Every process's ``/proc/PID/stat`` fields after its command name: the state first
    (``Z`` for a zombie), then the parent id, the process group, the session, …; empty where
    there is no ``/proc``.

    Examples
    --------
    >>> import os, sys
    >>> table = process_table()
    >>> sys.platform != "linux" or int(table[os.getpid()][1]) == os.getppid()
    True
    """
    out: dict[int, list[str]] = {}
    try:
        entries = list(Path("/proc").iterdir())
    except OSError:
        return out
    for entry in entries:
        if not entry.name.isdigit():
            continue
        try:
            text = (entry / "stat").read_text()
        except OSError:
            continue
        out[int(entry.name)] = text[text.rfind(")") + 2:].split()
    return out


def _parents() -> dict[int, int]:
    """Live (non-zombie) process id -> parent id."""
    out: dict[int, int] = {}
    for pid, fields in process_table().items():
        if fields and fields[0] != "Z":  # a zombie is already dead: nothing to end
            with contextlib.suppress(IndexError, ValueError):
                out[pid] = int(fields[1])
    return out


def descendants(pid: int) -> list[int]:
    """The process ids of every live descendant of ``pid`` (through ``/proc``; empty
    elsewhere), parents before their children.

    Examples
    --------
    >>> import os, subprocess, sys
    >>> p = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
    >>> p.pid in descendants(os.getpid())
    True
    >>> p.kill(); p.wait()
    -9
    >>> p.pid in descendants(os.getpid())
    False
    """
    children: dict[int, list[int]] = {}
    for child, parent in _parents().items():
        children.setdefault(parent, []).append(child)
    out: list[int] = []
    todo = [pid]
    while todo:
        for c in children.get(todo.pop(), []):
            out.append(c)
            todo.append(c)
    return out
