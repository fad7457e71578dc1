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
  files are complete (a FIFO without a reader is refused at once instead of blocking); a
  symlink to a regular file keeps its link and has the file it points to replaced;
- an output that names one of the command's input files is refused
  (:func:`refuse_input_as_output`);
- a location that cannot be written raises :class:`~dppio.errors.OutputError` naming the
  user's path.

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
import tempfile
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

from dppio.errors import ErrorClass, OutputError
from dppio.inputs import STDIN, open_input, read_input, read_text

__all__ = [
    "OutputError",
    "file_mode",
    "make_parents",
    "open_input",
    "read_input",
    "read_text",
    "refuse_input_as_output",
    "remove_created",
    "short_path",
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
                error: ErrorClass = OutputError) -> tuple[Path, ...]:
    """Write several files together: all of them or none.

    Parameters
    ----------
    files : mapping
        Target path -> content (``str`` is written as UTF-8).
    remove : iterable of paths
        Files to delete once the new ones are in place (stale files of an earlier write).
    error : callable
        The error class to raise (the caller's package's), called with the message.

    Returns
    -------
    tuple of Path
        The targets, in order.

    Raises
    ------
    OutputError
        (or ``error``) An empty path, a target that is a folder, or any error while writing;
        the message names the user's path. Nothing is left behind.

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
    regular = [(t, c) for t, c in targets if not _is_special(t)]
    special = [(t, c) for t, c in targets if _is_special(t)]
    created: list[Path] = []
    temps: list[tuple[str, Path]] = []
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
            data = _encode(content)
            with os.fdopen(fd, "wb") as fh:
                fh.write(data)
            os.chmod(tmp, mode)
        for target, content in special:
            current = target
            _stream(target, _encode(content))
        for tmp, target in temps:
            current = target
            os.replace(tmp, target)
        temps.clear()
    except OSError as exc:
        _clean(temps, created)
        reason = exc.strerror or str(exc)
        raise error(f"cannot write {short_path(current)}: {reason}") from None
    except BaseException:
        _clean(temps, created)
        raise
    for p in remove:
        Path(p).unlink(missing_ok=True)
    return tuple(t for t, _ in targets)


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
    if output is None or str(output) == "":
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
    if str(path).endswith(("/", os.sep)):  # Path() would drop the slash and write a file
        raise error(f"cannot write {short_path(path)}: it names a folder (a trailing /); give "
                    "a file name")
    p = Path(path)
    if os.path.isdir(p):  # (os.path: False, not an exception, for a name too long)
        raise error(f"cannot write {short_path(p)}: it is a folder")
    if os.path.islink(p) and os.path.isfile(p):  # keep the link; replace the file it points to
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
        missing.append(f)
        if f.parent == f:
            break
        f = f.parent
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
