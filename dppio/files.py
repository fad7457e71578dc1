"""Files at the edges of both packages: bounded reading and all-or-nothing writing.

Every file the ``dpp`` commands write goes through :func:`write_files` (the output policy of
the README, "Exit codes, limits and output files"):

- a missing folder on the way to a target is created, and removed again if the command
  fails;
- all files of one command are committed together or not at all: each is first written to
  a temporary file next to its target, and only when every one is complete are they renamed
  into place; on failure every temporary file (and every folder created) is removed;
- files get the mode ``0666`` minus the umask, like any file a program creates;
- a target that exists and is not a regular file (``/dev/null``, a FIFO, a device, or a
  symlink to one) is never replaced: the content is streamed into it, after the regular
  files are complete (a FIFO without a reader is refused at once instead of blocking);
- a symlink is kept and written through: to a regular file, that file is replaced; a
  dangling one, the file it names is created (and its missing folders);
- ``-`` (:data:`~dppio.inputs.STDIN`) is standard output: the content is written there after
  the regular files are complete (a file named ``-`` is ``./-``);
- an output that names one of the command's input files — by any path, symlink or hard
  link — is refused (:func:`refuse_input_as_output`);
- a location that cannot be written — a folder that cannot be created (a file or a dangling
  symlink on the way, no permission), a full disk — raises :class:`~dppio.errors.OutputError`,
  one line naming the user's path.

Every input is read through :func:`read_input` (or :func:`open_input`), which refuses
files larger than :data:`dppio.limits.MAX_INPUT_BYTES` (``/dev/zero`` included) without
reading them whole, never blocks on a FIFO that nobody writes, reads ``-`` as standard input
and reads each input once per command (:mod:`dppio.inputs`, re-exported here).
"""

from __future__ import annotations

import contextlib
import errno
import os
import stat
import sys
import tempfile
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

from dppio.errors import ErrorClass, OutputError
from dppio.inputs import STDIN, open_input, read_input, read_text

__all__ = [
    "BUSY",
    "OutputError",
    "OutputLocks",
    "file_mode",
    "is_busy",
    "make_parents",
    "open_input",
    "read_input",
    "read_text",
    "refuse_input_as_output",
    "remove_created",
    "short_path",
    "try_lock",
    "write_atomic",
    "write_files",
]


def file_mode() -> int:
    """The mode of a newly created file under the current umask (``0o666 & ~umask``).

    Examples
    --------
    >>> old = os.umask(0o022)
    >>> oct(file_mode())
    '0o644'
    >>> _ = os.umask(old)
    """
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask


def short_path(path: str | Path, limit: int = 160) -> str:
    """``path`` for a one-line message: cut in the middle when longer than ``limit``
    characters (a path past PATH_MAX would make the line kilobytes long).

    Examples
    --------
    >>> short_path("out/p.json")
    'out/p.json'
    >>> short_path("d" * 400 + "/p.json", limit=20)
    'dddddddddd…ddd/p.json (407 characters)'
    """
    text = str(path)
    if len(text) <= limit:
        return text
    half = limit // 2
    return f"{text[:half]}…{text[-half:]} ({len(text)} characters)"


def write_files(files: Mapping[Any, str | bytes], *, remove: Iterable[str | Path] = (),
                error: ErrorClass = OutputError, lock: bool | OutputLocks = False
                ) -> tuple[Path, ...]:
    """Write several files together: all of them or none.

    Parameters
    ----------
    files : mapping
        Target path -> content (``str`` is written as UTF-8).
    remove : iterable of paths
        Files to delete once the new ones are in place (stale files of an earlier write).
    error : callable
        The error class to raise (the caller's package's), called with the message.
    lock : bool or OutputLocks
        Follow the lock discipline of the files ``dpp batch`` appends to (:func:`try_lock`):
        a target that exists is locked (exclusively) before anything is written — or was
        locked earlier, by the :class:`OutputLocks` given — and one that another process
        holds is refused; a new target is linked into place with its lock already taken and
        never replaces a file that appeared meanwhile.

    Returns
    -------
    tuple of Path
        The targets, in order.

    Raises
    ------
    OutputError
        (or ``error``) An empty path, a target that is a folder, a folder that cannot be
        created, a locked target, or any error while writing; the message names the user's
        path. Nothing is left behind.

    Examples
    --------
    >>> with tempfile.TemporaryDirectory() as d:
    ...     written = write_files({Path(d) / "new" / "a.txt": "A", Path(d) / "new" / "b.txt": "B"})
    ...     print([p.name for p in written], sorted(p.name for p in (Path(d) / "new").iterdir()))
    ['a.txt', 'b.txt'] ['a.txt', 'b.txt']
    >>> write_files({"": "x"})
    Traceback (most recent call last):
    dppio.errors.OutputError: the output path is empty
    >>> write_files({"": "x"}, error=PermissionError)
    Traceback (most recent call last):
    PermissionError: the output path is empty
    """
    targets = [(_target(p, error), c) for p, c in files.items()]
    shown = {t: short_path(p) for (t, _), p in zip(targets, files, strict=True)}  # as given
    regular = [(t, c) for t, c in targets if not _is_special(t) and str(t) != STDIN]
    special = [(t, c) for t, c in targets if _is_special(t)]
    streamed = [c for t, c in targets if str(t) == STDIN]
    created: list[Path] = []
    temps: list[tuple[str, Path]] = []
    held: list[int] = []  # (lock) our new files' descriptors, locked until all are in place
    locks = OutputLocks(files, error=error) if lock is True else lock or None
    current = targets[0][0] if targets else Path(".")
    try:
        for target, _ in regular:
            current = target
            make_parents(target.parent, created)
        mode = file_mode()
        for target, content in regular:
            current = target
            fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=_temp_prefix(target),
                                       suffix=".tmp")
            temps.append((tmp, target))
            if locks is not None:
                held.append(fd)
                try_lock(fd)  # a file of ours: nobody else can hold it yet
            with os.fdopen(fd, "wb", closefd=locks is None) as fh:
                fh.write(_encode(content))
            os.chmod(tmp, mode)
        for target, content in special:
            current = target
            _stream(target, _encode(content))
        for content in streamed:  # standard output: its failure is the stream's own error
            _to_stdout(_encode(content))
        for tmp, target in temps:
            current = target
            if locks is not None and target in locks.fresh:
                try:
                    os.link(tmp, target)  # with its lock: a batch starting now refuses it
                except FileExistsError:
                    raise error(f"cannot write {shown[target]}: it appeared while this "
                                "command ran (another program made it); nothing was written"
                                ) from None
                os.unlink(tmp)
            else:
                os.replace(tmp, target)
        temps.clear()
    except OSError as exc:
        _clean(temps, created)
        reason = exc.strerror or str(exc)
        raise error(f"cannot write {short_path(current)}: {reason}") from None
    except BaseException:
        _clean(temps, created)
        raise
    finally:
        for fd in held:
            with contextlib.suppress(OSError):
                os.close(fd)
        if lock is True and locks is not None:
            locks.close()
    for p in remove:
        Path(p).unlink(missing_ok=True)
    return tuple(t for t, _ in targets)


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
    command reads its inputs and held until :func:`write_files` (given this object as
    ``lock``) has put every file in place: no other run can start on them meanwhile. A
    target that does not exist yet is remembered as new: it is linked into place, never
    replacing a file that appeared in between. Use as a context manager.

    Raises
    ------
    OutputError
        (or ``error``) Another process holds the lock of one of the files.

    Examples
    --------
    >>> with tempfile.TemporaryDirectory() as d:
    ...     p = Path(d) / "all.csv"
    ...     _ = p.write_text("old")
    ...     with OutputLocks([p]) as locks:
    ...         busy = is_busy(p)
    ...         _ = write_files({p: "new"}, lock=locks)
    ...     print(busy, p.read_text(), is_busy(p))
    True new False
    """

    def __init__(self, paths: Iterable[Any], *, error: ErrorClass = OutputError) -> None:
        self.fds: dict[Path, int] = {}
        """Existing targets, locked: their descriptors."""
        self.fresh: set[Path] = set()
        """Targets that did not exist."""
        try:
            for path in paths:
                target = _target(path, error)
                if str(target) == STDIN or _is_special(target):
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


def is_busy(path: str | Path) -> bool:
    """True when ``path`` is a regular file whose lock another process holds
    (:func:`try_lock`): a ``dpp batch`` appending to it, a merge reading or writing it.

    Examples
    --------
    >>> with tempfile.TemporaryDirectory() as d:
    ...     p = Path(d) / "rows.csv"
    ...     _ = p.write_text("")
    ...     before = is_busy(p)
    ...     fd = os.open(p, os.O_RDONLY); _ = try_lock(fd)
    ...     print(before, is_busy(p), is_busy(Path(d) / "new.csv"))
    ...     os.close(fd)
    False True False
    """
    try:
        fd = _locked_existing(Path(path))
    except OSError:
        return False
    if fd is not None and fd >= 0:
        os.close(fd)
    return fd == -1


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


def write_atomic(path: str | Path, text: str | bytes, *, error: ErrorClass = OutputError
                 ) -> Path:
    """Write one file atomically (:func:`write_files` with one target).

    Examples
    --------
    The file is replaced, and no temporary file is left behind:

    >>> with tempfile.TemporaryDirectory() as d:
    ...     target = Path(d) / "profile.json"
    ...     _ = write_atomic(target, "old")
    ...     _ = write_atomic(target, "new")
    ...     print(target.read_text(), sorted(p.name for p in Path(d).iterdir()))
    new ['profile.json']
    """
    return write_files({Path(path): text}, error=error)[0]


def refuse_input_as_output(output: str | Path | None, inputs: Iterable[str | Path | None], *,
                           option: str = "-o", error: ErrorClass = OutputError) -> None:
    """Refuse an output path that names one of the inputs (the same file, by any path).

    Raises
    ------
    OutputError
        (or ``error``) One line naming the path.

    Examples
    --------
    >>> with tempfile.TemporaryDirectory() as d:  # doctest: +ELLIPSIS
    ...     p = Path(d) / "x.json"
    ...     _ = p.write_text("{}")
    ...     refuse_input_as_output(Path(d) / "y.json", [p])
    ...     refuse_input_as_output(Path(d) / "." / "x.json", [p])
    Traceback (most recent call last):
    dppio.errors.OutputError: ...x.json is an input of this command; refusing to overwrite it ...
    """
    if output is None or str(output) in ("", STDIN):  # (-o - is standard output)
        return
    out = Path(output)
    for path in inputs:
        if path is None or str(path) in ("", STDIN):  # standard input is not a file
            continue
        same = False
        try:
            same = os.path.samefile(out, path)
        except OSError:
            same = os.path.realpath(out) == os.path.realpath(path)
        if same and (not os.path.exists(out) or os.path.isfile(out)):
            raise error(f"{option} {short_path(out)} is an input of this command; refusing to "
                        "overwrite it (give another path)")


def _to_stdout(data: bytes) -> None:
    """Write ``data`` to standard output (``-o -``), through ``sys.stdout`` so that what the
    command printed before stays in order."""
    stream = sys.stdout
    if stream is None:  # descriptor 1 was closed: nothing can read it
        return
    stream.flush()
    buffer = getattr(stream, "buffer", None)
    if buffer is None:  # a text stream without bytes (a test runner's capture)
        stream.write(data.decode("utf-8", "backslashreplace"))
    else:
        buffer.write(data)
    stream.flush()


def _is_special(target: Path) -> bool:
    """True when ``target`` exists (through symlinks) and is neither a regular file nor a
    folder: a device, a FIFO, a socket."""
    try:
        st = os.stat(target)
    except OSError:
        return False
    return not stat.S_ISREG(st.st_mode) and not stat.S_ISDIR(st.st_mode)


def _is_socket(target: Path) -> bool:
    try:
        return stat.S_ISSOCK(os.stat(target).st_mode)
    except OSError:
        return False


def _stream(target: Path, data: bytes) -> None:
    """Write ``data`` into the existing non-regular file ``target`` without replacing it."""
    try:
        fd = os.open(target, os.O_WRONLY | os.O_NONBLOCK | getattr(os, "O_NOCTTY", 0))
    except OSError as exc:
        if exc.errno == errno.ENXIO:  # a FIFO that no process reads, or a socket
            what = "a socket, not a file" if _is_socket(target) else \
                "a FIFO that no process reads"
            raise OSError(exc.errno, f"it is {what}") from None
        raise
    try:
        os.set_blocking(fd, True)
        view = memoryview(data)
        while view:
            n = os.write(fd, view)
            view = view[n:]
    finally:
        os.close(fd)


def _encode(content: str | bytes) -> bytes:
    """UTF-8 bytes of ``content``; a character UTF-8 cannot hold (a lone surrogate: a file
    name that is not UTF-8, as Python reads it) is written as its escape ``\\udcff``, which in
    a JSON string reads back as the same character.

    Examples
    --------
    >>> name = os.fsdecode(b"b\\xff.json")  # a file name that is not UTF-8
    >>> _encode(f'{{"file": "{name}"}}')
    b'{"file": "b\\\\udcff.json"}'
    """
    if isinstance(content, bytes):
        return content
    return content.encode("utf-8", "backslashreplace")


def _temp_prefix(target: Path) -> str:
    """``.NAME.`` for the temporary file of ``target`` (``.NAME.XXXXXXXX.tmp``), or ``.dpp.``
    when that would pass the file system's limit of 255 bytes for a name (a legal name of
    250 bytes must still be writable).

    Examples
    --------
    >>> _temp_prefix(Path("out/p.json")), _temp_prefix(Path("a" * 250 + ".json"))
    ('.p.json.', '.dpp.')
    """
    if len(os.fsencode(target.name)) + len("..XXXXXXXX.tmp") > 255:
        return ".dpp."
    return f".{target.name}."


def _target(path: str | Path, error: ErrorClass) -> Path:
    if str(path) == "":
        raise error("the output path is empty")
    if str(path) == STDIN:
        return Path(STDIN)  # standard output (a file named - is ./-)
    if str(path).endswith(("/", os.sep)):  # Path() would drop the slash and write a file
        raise error(f"cannot write {short_path(path)}: it names a folder (a trailing /); give "
                    "a file name")
    p = Path(path)
    if os.path.isdir(p):  # (os.path: False, not an exception, for a name too long)
        raise error(f"cannot write {short_path(p)}: it is a folder")
    if os.path.islink(p) and (os.path.isfile(p) or not os.path.exists(p)):
        # keep the link: replace the file it points to, or create the one a dangling link names
        return Path(os.path.realpath(p))
    return p


def make_parents(folder: Path, created: list[Path]) -> None:
    """Create ``folder`` and its missing parents, appending each folder made to ``created``
    (outermost first) so that :func:`remove_created` can take them away again.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     made: list[Path] = []
    ...     make_parents(Path(d) / "a" / "b", made)
    ...     [p.name for p in made], (Path(d) / "a" / "b").is_dir()
    ...     remove_created(made)
    ...     made, (Path(d) / "a").exists()
    (['a', 'b'], True)
    ([], False)
    """
    missing = []
    f = folder if str(folder) else Path(".")
    while not f.exists():
        if f.is_symlink():  # mkdir would say "File exists"
            raise OSError(errno.ENOENT, f"{short_path(f)} is a symbolic link to a missing "
                          f"folder ({short_path(os.readlink(f))})")
        missing.append(f)
        if f.parent == f:
            break
        f = f.parent
    if not f.is_dir():
        raise OSError(errno.ENOTDIR, f"{short_path(f)} is not a folder")
    for d in reversed(missing):
        d.mkdir()
        created.append(d)


def remove_created(created: list[Path]) -> None:
    """Remove the folders :func:`make_parents` made, innermost first (a folder that is no
    longer empty stays), and forget them.

    Examples
    --------
    >>> remove_created([])  # nothing made, nothing removed
    """
    for d in reversed(created):
        with contextlib.suppress(OSError):
            d.rmdir()
    created.clear()


def _clean(temps: list[tuple[str, Path]], created: list[Path]) -> None:
    for tmp, _ in temps:
        Path(tmp).unlink(missing_ok=True)
    remove_created(created)
