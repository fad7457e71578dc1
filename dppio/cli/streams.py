"""The standard streams of a ``dpp`` command: whatever they are connected to, a command
ends with one line (or, for a closed pipe, quietly), never a traceback.

- **Closed descriptors.** A command started with descriptor 0, 1 or 2 closed gets
  ``/dev/null`` there first, so a file it opens never takes the place of standard output
  (where its own or a child's output would land in the file).
- **Any encoding.** Text that the terminal's encoding cannot show (σ\\* on a Latin-1
  terminal) is written as a backslash escape (``\\u03c3``, which in a JSON document is the
  same character) instead of failing.
- **Standard output that cannot be written.** A write to standard output that fails raises
  :class:`StreamError`; :func:`stream_failure` turns it into the command's end: a closed pipe
  (the reader exited, as in ``dpp solve x.json | head -1``) ends it quietly with exit code
  141 (``128 + SIGPIPE``, like any Unix filter), any other failure (``/dev/full``: no space
  left) is one line on stderr and exit code 2, like an output file that cannot be written.
- **Standard error that cannot be written** loses its messages, never the exit code.
"""

from __future__ import annotations

import contextlib
import errno
import io
import os
import sys
from collections.abc import Iterator
from typing import Any

SIGPIPE_EXIT = 128 + 13
"""The exit code of a command whose standard output is a pipe nobody reads any more."""


class StreamError(Exception):
    """A write to standard output failed (a closed pipe, a full disk, an I/O error). Not an
    ``OSError``, so that no handler of file errors (click's own, for a closed pipe) takes it
    for another failure: the command group ends the command with its one rule.

    Attributes
    ----------
    errno : int
        The error number of the failed write.
    strerror : str
        Its description.
    """

    def __init__(self, errno_: int | None, strerror: str) -> None:
        super().__init__(strerror)
        self.errno = errno_
        self.strerror = strerror


class _GuardedOutput(io.FileIO):
    """Standard output's descriptor: a failed write raises :class:`StreamError`."""

    def write(self, data: Any) -> int:
        try:
            return super().write(data)
        except OSError as exc:
            raise StreamError(exc.errno, exc.strerror or str(exc)) from None


class _QuietOutput(io.FileIO):
    """Standard error's descriptor: a failed write is dropped (there is nowhere to report it)."""

    def write(self, data: Any) -> int:
        try:
            return super().write(data)
        except OSError:
            return len(data)


def _open_missing_descriptors() -> None:
    for fd in (0, 1, 2):
        try:
            os.fstat(fd)
        except OSError:
            null = os.open(os.devnull, os.O_RDWR)
            if null != fd:
                os.dup2(null, fd)
                os.close(null)


def _wrap(stream: Any, fd: int, raw_class: type[io.FileIO]) -> Any:
    """A text stream like ``stream`` on descriptor ``fd`` through ``raw_class``, writing
    unencodable characters as backslash escapes; None when ``stream`` is not a real file
    (e.g. a test runner's capture), which is then left alone."""
    if stream is not None and not _is_fd(stream, fd):
        return None
    encoding = getattr(stream, "encoding", None) or "utf-8"
    line_buffering = bool(getattr(stream, "line_buffering", False))
    with contextlib.suppress(Exception):
        if stream is not None:
            stream.flush()
    raw = raw_class(fd, "w", closefd=False)
    return io.TextIOWrapper(io.BufferedWriter(raw), encoding=encoding,
                            errors="backslashreplace", line_buffering=line_buffering)


@contextlib.contextmanager
def standard_streams() -> Iterator[None]:
    """Within the block, standard output and error follow this module's rules (only when
    they are the process's real descriptors 1 and 2; a test runner's capture is left alone).

    Examples
    --------
    >>> with standard_streams():
    ...     print("σ*")
    σ*
    """
    if (sys.stdout is not None and not _is_fd(sys.stdout, 1)) or \
            (sys.stderr is not None and not _is_fd(sys.stderr, 2)):
        yield  # captured (a test runner, CliRunner): nothing to guard
        return
    _open_missing_descriptors()
    old_out, old_err = sys.stdout, sys.stderr
    new_out = _wrap(old_out, 1, _GuardedOutput)  # None at start-up: descriptor 1 was closed
    new_err = _wrap(old_err, 2, _QuietOutput)
    if new_out is not None:
        sys.stdout = new_out
    if new_err is not None:
        sys.stderr = new_err
    try:
        yield
    finally:
        for new, old, name in ((new_out, old_out, "stdout"), (new_err, old_err, "stderr")):
            if new is None:
                continue
            with contextlib.suppress(Exception):
                new.flush()
            if getattr(sys, name) is new:
                setattr(sys, name, old)


def _is_fd(stream: Any, fd: int) -> bool:
    try:
        return bool(stream.fileno() == fd)
    except (AttributeError, OSError, ValueError):
        return False


def flush_stdout() -> None:
    """Flush standard output now (so that a failure is :class:`StreamError` here, inside the
    command, not at interpreter exit).

    Examples
    --------
    >>> print("data", end=""); flush_stdout()
    data
    """
    if sys.stdout is not None:
        sys.stdout.flush()


def silence_stdout(fd: int = 1) -> None:
    """Point standard output's descriptor (``fd``) at ``/dev/null`` after it failed, so that
    the interpreter's last flush at exit does not fail again.

    Examples
    --------
    >>> r, w = os.pipe(); os.close(r)  # a pipe nobody reads
    >>> silence_stdout(w); os.write(w, b"gone")  # now it takes anything
    4
    >>> os.close(w)
    """
    with contextlib.suppress(OSError, ValueError, AttributeError):
        null = os.open(os.devnull, os.O_WRONLY)
        os.dup2(null, fd)
        os.close(null)


def stream_failure(exc: StreamError) -> tuple[str | None, int]:
    """The line to print (None: quietly) and the exit code for a failed standard output.

    Examples
    --------
    >>> stream_failure(StreamError(errno.ENOSPC, "No space left on device"))
    ('error: cannot write standard output: No space left on device', 2)
    >>> stream_failure(StreamError(errno.EPIPE, "Broken pipe"))
    (None, 141)
    """
    if exc.errno == errno.EPIPE:
        return None, SIGPIPE_EXIT
    return f"error: cannot write standard output: {exc.strerror or exc}", 2
