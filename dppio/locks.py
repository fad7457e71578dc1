"""The lock discipline of the files ``dpp batch`` appends to, shared by ``dpp batch`` and
``dpp batch merge`` (docs/limits.md, "Output files").

A batch holds its CSV's exclusive lock (``flock``) while it runs; a merge takes its output's
exclusive lock before it reads a shard (:class:`OutputLocks`) and a shared lock on every shard
it reads, and keeps them until the merged file is in place. So a merge never reads a shard a
batch is still writing nor replaces a CSV a batch appends to, a batch never starts on a file a
merge reads or writes, and a new merged file never replaces one that appeared meanwhile
(:func:`dppio.files.write_files` with ``lock=``).
"""

from __future__ import annotations

import contextlib
import errno
import os
import stat
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from dppio.errors import ErrorClass, OutputError
from dppio.inputs import STDIN
from dppio.targets import is_special, resolve_target, short_path

BUSY = "another dpp batch or dpp batch merge is writing it (try again when it has finished)"
"""Why a file under the lock discipline (:func:`try_lock`) cannot be written now."""


def try_lock(fd: int, *, shared: bool = False) -> bool:
    """Take the advisory lock (``flock``) of the open file ``fd`` without waiting: exclusive
    (a writer) or ``shared`` (a reader); False when another process holds a lock that
    conflicts. The lock lasts until ``fd`` is closed.

    This is the one lock discipline of the files ``dpp batch`` appends to: a batch holds its
    CSV's exclusive lock while it runs; ``dpp batch merge`` holds its output's exclusive lock
    and a shared lock on every shard it reads, so a merge never reads a shard a batch is still
    writing, never replaces a CSV a batch is appending to, and a batch never starts on either.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     p = Path(d) / "rows.csv"
    ...     _ = p.write_text("")
    ...     a, b = os.open(p, os.O_RDONLY), os.open(p, os.O_RDONLY)
    ...     print(try_lock(a, shared=True), try_lock(b, shared=True), try_lock(b))
    ...     os.close(a); os.close(b)
    True True False
    """
    if os.name != "posix":  # pragma: no cover - Linux and macOS have flock
        return True
    import fcntl

    try:
        fcntl.flock(fd, (fcntl.LOCK_SH if shared else fcntl.LOCK_EX) | fcntl.LOCK_NB)
    except OSError as exc:
        if exc.errno in (errno.EWOULDBLOCK, errno.EAGAIN, errno.EACCES):
            return False
        raise
    return True


class OutputLocks:
    """The exclusive locks (:func:`try_lock`) of a command's output files, taken before the
    command reads its inputs and held until :func:`dppio.files.write_files` (given this
    object as ``lock``) has put every file in place: no other run can start on them meanwhile. A
    target that does not exist yet is remembered as new: it is linked into place, never
    replacing a file that appeared in between. Use as a context manager.

    Raises
    ------
    OutputError
        (or ``error``) Another process holds the lock of one of the files.

    Examples
    --------
    >>> import tempfile
    >>> from dppio.files import write_files
    >>> with tempfile.TemporaryDirectory() as d:
    ...     p = Path(d) / "all.csv"
    ...     _ = p.write_text("old")
    ...     other = os.open(p, os.O_RDONLY)  # another run's descriptor
    ...     with OutputLocks([p]) as locks:
    ...         busy = not try_lock(other, shared=True)
    ...         _ = write_files({p: "new"}, lock=locks)
    ...     print(busy, p.read_text())
    ...     os.close(other)
    True new
    """

    def __init__(self, paths: Iterable[Any], *, error: ErrorClass = OutputError) -> None:
        self.fds: dict[Path, int] = {}
        """Existing targets, locked: their descriptors."""
        self.fresh: set[Path] = set()
        """Targets that did not exist."""
        try:
            for path in paths:
                target = resolve_target(path, error)
                if str(target) == STDIN or is_special(target):
                    continue
                try:
                    fd = _locked_existing(target)
                except OSError:  # (write_files says why, in one line)
                    continue
                if fd is None:
                    self.fresh.add(target)
                elif fd < 0:
                    raise error(f"cannot write {short_path(path)}: {BUSY}")
                else:
                    self.fds[target] = fd
        except BaseException:
            self.close()
            raise

    def close(self) -> None:
        """Release the locks."""
        for fd in self.fds.values():
            with contextlib.suppress(OSError):
                os.close(fd)
        self.fds.clear()

    def __enter__(self) -> OutputLocks:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def _locked_existing(target: Path) -> int | None:
    """The exclusive lock of an existing regular ``target``: its descriptor (locked), ``-1``
    when another process holds it, None when there is no such file (a new target)."""
    try:
        fd = os.open(target, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC
                     | getattr(os, "O_NOCTTY", 0))
    except FileNotFoundError:
        return None
    if not stat.S_ISREG(os.fstat(fd).st_mode):
        os.close(fd)
        return None
    if try_lock(fd):
        return fd
    os.close(fd)
    return -1
