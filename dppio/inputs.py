"""Reading inputs at the edges of both packages: bounded, never blocking, each read once.

Every input of the ``dpp`` commands is read through :func:`read_input` (or :func:`read_text`):

- a file larger than :data:`dppio.limits.MAX_INPUT_BYTES` (``/dev/zero`` included) is refused
  without being read whole;
- a FIFO that nobody writes reads as empty instead of blocking (:func:`open_input`);
- ``-`` (:data:`STDIN`) is standard input. It is read at most once per process: a second
  read of ``-`` returns the same bytes (a stream cannot be read twice). A file literally named
  ``-`` is ``./-``;
- inside :func:`reading_once` (every ``dpp`` command and every :func:`dppverify.certify` call
  runs in one) each path is read once: a later read of the same path — to hash it for a
  certificate's provenance, to look at it for a hint — returns the bytes read the first time.
  So what is hashed is exactly what was parsed, whether the input is a file, a pipe
  (``/dev/stdin``, ``<(...)``), a FIFO or standard input, and even if the file changes
  meanwhile. Non-regular inputs are always kept (they cannot be read again); regular files
  while the session holds less than :data:`MEMO_BYTES`, after that they are read again.

Examples
--------
>>> import tempfile
>>> from pathlib import Path
>>> d = Path(tempfile.mkdtemp())
>>> _ = (d / "a.json").write_text("{}")
>>> with reading_once():
...     first = read_input(d / "a.json")
...     _ = (d / "a.json").write_text('{"changed": 1}')
...     again = read_input(d / "a.json")
>>> first == again == b"{}", read_input(d / "a.json")
(True, b'{"changed": 1}')
"""

from __future__ import annotations

import contextlib
import errno
import os
import stat
import sys
from collections.abc import Iterator
from contextvars import ContextVar
from typing import BinaryIO

from dppio.errors import InputError, LimitError
from dppio.limits import MAX_INPUT_BYTES

STDIN = "-"
"""The input name that means standard input."""

MEMO_BYTES = 2 * MAX_INPUT_BYTES
"""Regular files kept by one :func:`reading_once` session, in bytes: an instance and a profile
of the largest size (non-regular inputs and standard input are always kept). A command that
reads many files (``batch`` its maps, ``audit --instances`` its folder) keeps no more."""


class _Session:
    """The bytes read so far in one :func:`reading_once` block."""

    def __init__(self) -> None:
        self.data: dict[str, bytes] = {}
        self.kept = 0

    def remember(self, key: str, data: bytes, regular: bool) -> None:
        if regular and self.kept + len(data) > MEMO_BYTES:
            return
        self.data[key] = data
        self.kept += len(data) if regular else 0


_SESSION: ContextVar[_Session | None] = ContextVar("dppio_inputs_session", default=None)
_STDIN_READ: list[tuple[object, bytes]] = []
"""``(sys.stdin object, its bytes)`` once standard input has been read in this process."""


def is_stdin(path: str | os.PathLike[str] | None) -> bool:
    """True when ``path`` names standard input (``-``).

    Examples
    --------
    >>> is_stdin("-"), is_stdin("./-"), is_stdin(None)
    (True, False, False)
    """
    return path is not None and os.fspath(path) == STDIN


@contextlib.contextmanager
def reading_once() -> Iterator[None]:
    """Within this block every input path is read once (see the module docstring); nested
    blocks share the outermost one.

    Examples
    --------
    >>> with reading_once(), reading_once():
    ...     _SESSION.get() is not None
    True
    >>> _SESSION.get() is None
    True
    """
    if _SESSION.get() is not None:
        yield
        return
    token = _SESSION.set(_Session())
    try:
        yield
    finally:
        _SESSION.reset(token)


class StdinError(OSError):
    """Standard input cannot be read: it is closed, a folder, or a stream that refuses to be
    read. Its text is the one sentence (``str()`` and ``strerror`` alike), so every reader's
    message names the reason the same way.

    Examples
    --------
    >>> exc = StdinError("standard input is a folder")
    >>> str(exc), exc.strerror
    ('standard input is a folder', 'standard input is a folder')
    """

    def __init__(self, sentence: str) -> None:
        super().__init__(errno.EBADF, sentence)

    def __str__(self) -> str:
        return str(self.strerror)


FOLDER_MARK = "DPP_STDIN_IS_FOLDER"
"""Set (to ``1``) by the ``dpp`` launcher when it found standard input to be a folder, which
no Python interpreter can start with: it gave the command ``/dev/null`` instead, and ``-``
is refused. Consumed when this module is imported, so the command's children do not see it."""

_STDIN_FOLDER = os.environ.pop(FOLDER_MARK, "") == "1"
_STDIN_NAMES = frozenset({"/dev/stdin", "/dev/fd/0", "/proc/self/fd/0"})


def stdin_problem() -> str | None:
    """Why standard input cannot be read, known without reading it (it is closed, a folder),
    or None.

    Examples
    --------
    >>> stdin_problem() in (None, "standard input is closed")
    True
    """
    if _STDIN_FOLDER:
        return "standard input is a folder"
    try:
        st = os.fstat(0)
    except OSError:
        return "standard input is closed"
    if stat.S_ISDIR(st.st_mode):
        return "standard input is a folder"
    if sys.stdin is None:  # descriptor 0 was closed when the interpreter started
        return "standard input is closed"
    return None


def _stdin_bytes(limit: int) -> bytes:
    """Standard input's bytes (at most ``max(limit, MAX_INPUT_BYTES) + 1``), read once."""
    stream = sys.stdin
    for owner, data in _STDIN_READ:
        if owner is stream:
            return data
    problem = stdin_problem()
    if problem is not None or stream is None:
        raise StdinError(problem or "standard input is closed")
    raw = getattr(stream, "buffer", stream)
    try:
        got = raw.read(max(limit, MAX_INPUT_BYTES) + 1)
    except ValueError:  # a closed stream
        raise StdinError("standard input is closed") from None
    except OSError as exc:  # opened for writing only, a socket that resets, an I/O error
        raise StdinError("standard input is not open for reading" if exc.errno == errno.EBADF
                         else f"standard input cannot be read: {exc.strerror or exc}") from None
    data = got.encode("utf-8") if isinstance(got, str) else bytes(got)
    _STDIN_READ[:] = [(stream, data)]
    return data


def read_input(path: str | os.PathLike[str], *, limit: int = MAX_INPUT_BYTES) -> bytes:
    """The bytes of an input: a file, a pipe, a FIFO, a device, or ``-`` (standard input);
    larger than ``limit`` is refused.

    Reads at most ``limit + 1`` bytes, so ``/dev/zero`` or a huge file is refused quickly.

    Raises
    ------
    OSError
        The file cannot be read (the callers name it in their own error class).
    LimitError
        (a ``ValueError``) The input is larger than ``limit`` bytes.

    Examples
    --------
    >>> read_input("/dev/zero", limit=10)
    Traceback (most recent call last):
    dppio.errors.LimitError: larger than the limit of 10 bytes
    """
    key = os.fspath(path)
    session = _SESSION.get()
    if session is not None and key in session.data:
        data = session.data[key]
    elif key == STDIN:
        data = _stdin_bytes(limit)
        if session is not None:
            session.remember(key, data, regular=False)
    else:
        if _STDIN_FOLDER and key in _STDIN_NAMES:  # the launcher gave /dev/null for a folder
            raise StdinError("standard input is a folder")
        with open_input(path) as fh:
            regular = stat.S_ISREG(os.fstat(fh.fileno()).st_mode)
            data = fh.read(max(limit, MAX_INPUT_BYTES if session is not None else limit) + 1)
        if session is not None:
            session.remember(key, data, regular)
    if len(data) > limit:
        raise LimitError(f"larger than the limit of {limit} bytes")
    return data


def read_text(path: str | os.PathLike[str], *, limit: int = MAX_INPUT_BYTES) -> str:
    """The UTF-8 text of an input (:func:`read_input`: larger than ``limit`` refused).

    Raises
    ------
    OSError
        The file cannot be read (the callers name it in their own error class).
    InputError
        (a ``ValueError``) Larger than ``limit`` bytes (:class:`~dppio.errors.LimitError`),
        or not UTF-8 text.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> d = Path(tempfile.mkdtemp())
    >>> _ = (d / "a.txt").write_text("café", encoding="utf-8")
    >>> _ = (d / "b.txt").write_text("café", encoding="latin-1")
    >>> read_text(d / "a.txt")
    'café'
    >>> read_text(d / "b.txt")
    Traceback (most recent call last):
    dppio.errors.InputError: not UTF-8 text
    """
    try:
        return read_input(path, limit=limit).decode("utf-8")
    except UnicodeDecodeError:
        raise InputError("not UTF-8 text") from None


def peek_input(path: str | os.PathLike[str], size: int) -> bytes:
    """The first ``size`` bytes of an input, to guess what it is, without ever blocking: the
    bytes already read (standard input, or any input of the current :func:`reading_once`
    session), else the start of a regular file; b"" for anything else or on any error.

    Examples
    --------
    >>> peek_input("/nonexistent", 10), peek_input("/dev/zero", 10)
    (b'', b'')
    """
    key = os.fspath(path)
    session = _SESSION.get()
    try:
        if (session is not None and key in session.data) or key == STDIN:
            return read_input(path)[:size]
        if not stat.S_ISREG(os.stat(path).st_mode):
            return b""
        with open(path, "rb") as fh:
            return fh.read(size)
    except (OSError, ValueError):
        return b""


def open_input(path: str | os.PathLike[str]) -> BinaryIO:
    """Open an input file for reading without ever blocking on a FIFO that nobody writes.

    The file is opened non-blocking (a FIFO without a writer then reads as empty instead of
    hanging), then switched back to blocking reads (a pipe with a writer, e.g. bash's
    ``<(...)``, is read to its end). ``-`` is a copy of standard input's descriptor.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> with tempfile.TemporaryDirectory() as d:
    ...     os.mkfifo(Path(d) / "fifo")
    ...     with open_input(Path(d) / "fifo") as fh:
    ...         fh.read()
    b''
    """
    if os.fspath(path) == STDIN:
        problem = stdin_problem()
        if problem is not None:
            raise StdinError(problem)
        return os.fdopen(os.dup(0), "rb")
    fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_NOCTTY", 0))
    try:
        os.set_blocking(fd, True)
        return os.fdopen(fd, "rb")
    except BaseException:
        os.close(fd)
        raise
