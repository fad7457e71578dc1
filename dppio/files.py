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
from dppio.inputs import STDIN
from dppio.locks import OutputLocks, try_lock
from dppio.targets import is_special, make_parents, remove_created, resolve_target, short_path


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
    targets = [(resolve_target(p, error), c) for p, c in files.items()]
    locks = OutputLocks(files, error=error) if lock is True else lock or None
    job = _Write(targets, [short_path(p) for p in files], locks)
    try:
        job.run()
    except OSError as exc:
        job.clean()
        raise error(f"cannot write {short_path(job.current)}: {exc.strerror or exc}") from None
    except BaseException:
        job.clean()
        raise
    finally:
        job.release()
        if lock is True and locks is not None:
            locks.close()
    for p in remove:
        Path(p).unlink(missing_ok=True)
    return tuple(t for t, _ in targets)


class _Write:
    """One :func:`write_files` call: the temporary files, the folders made, the descriptors
    held (under a lock), the target being written (for the message)."""

    def __init__(self, targets: list[tuple[Path, str | bytes]], shown: list[str],
                 locks: OutputLocks | None) -> None:
        self.regular = [(t, c) for t, c in targets if not is_special(t) and str(t) != STDIN]
        self.special = [(t, c) for t, c in targets if is_special(t)]
        self.streamed = [c for t, c in targets if str(t) == STDIN]
        self.shown = {t: s for (t, _), s in zip(targets, shown, strict=True)}  # as given
        self.locks = locks
        self.created: list[Path] = []
        self.temps: list[tuple[str, Path]] = []
        self.held: list[int] = []  # (locks) our new files' descriptors, until all are in place
        self.current = targets[0][0] if targets else Path(".")

    def run(self) -> None:
        for target, _ in self.regular:
            self.current = target
            make_parents(target.parent, self.created)
        mode = file_mode()
        for target, content in self.regular:
            self.current = target
            fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=_temp_prefix(target),
                                       suffix=".tmp")
            self.temps.append((tmp, target))
            if self.locks is not None:
                self.held.append(fd)
                try_lock(fd)  # a file of ours: nobody else can hold it yet
            with os.fdopen(fd, "wb", closefd=self.locks is None) as fh:
                fh.write(_encode(content))
            os.chmod(tmp, mode)
        for target, content in self.special:
            self.current = target
            _stream(target, _encode(content))
        for content in self.streamed:  # standard output: its failure is the stream's own error
            _to_stdout(_encode(content))
        for tmp, target in self.temps:
            self.current = target
            self._commit(tmp, target)
        self.temps.clear()

    def _commit(self, tmp: str, target: Path) -> None:
        if self.locks is None or target not in self.locks.fresh:
            os.replace(tmp, target)
            return
        try:
            os.link(tmp, target)  # with its lock: a batch starting now refuses it
        except FileExistsError:
            raise OSError(errno.EEXIST, "it appeared while this command ran (another program "
                          "made it); nothing was written") from None
        os.unlink(tmp)

    def clean(self) -> None:
        _clean(self.temps, self.created)

    def release(self) -> None:
        for fd in self.held:
            with contextlib.suppress(OSError):
                os.close(fd)
        self.held.clear()


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


def _clean(temps: list[tuple[str, Path]], created: list[Path]) -> None:
    for tmp, _ in temps:
        Path(tmp).unlink(missing_ok=True)
    remove_created(created)
