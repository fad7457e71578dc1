"""Small I/O helpers of the solver's CLI: all-or-nothing writes and JSON dumping (the
checker has its own copy of the rules, ``dppverify/formats/files.py``)."""

from __future__ import annotations

import contextlib
import errno
import json
import os
import stat
import tempfile
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

from solver.errors import OutputError
from solver.limits import open_input

__all__ = ["dumps", "open_input", "refuse_input_as_output", "write_atomic", "write_files"]


def dumps(doc: Any) -> str:
    """JSON text with a trailing newline (2-space indent).

    Parameters
    ----------
    doc : object
        Anything :func:`json.dumps` accepts.

    Returns
    -------
    str

    Examples
    --------
    >>> print(dumps({"U": "12/5", "path": ["s", "g1"]}), end="")
    {
      "U": "12/5",
      "path": [
        "s",
        "g1"
      ]
    }
    """
    return json.dumps(doc, indent=2) + "\n"


def write_atomic(path: str | Path, text: str) -> None:
    """Write ``text`` to ``path`` atomically (one file of :func:`write_files`).

    Examples
    --------
    The file is replaced, and no temporary file is left behind:

    >>> with tempfile.TemporaryDirectory() as d:
    ...     target = Path(d) / "profile.json"
    ...     write_atomic(target, "old")
    ...     write_atomic(target, dumps({"U": "12/5"}))
    ...     print(target.read_text(), end="")
    ...     print(sorted(p.name for p in Path(d).iterdir()))
    {
      "U": "12/5"
    }
    ['profile.json']
    """
    write_files({Path(path): text})


def write_files(files: Mapping[Any, str | bytes]) -> tuple[Path, ...]:
    """Write several files together: all of them or none (the README's output policy).

    Missing folders on the way are created (and removed again on failure); each file is
    written to a temporary file next to its target, with mode ``0666`` minus the umask, and
    all are renamed into place only when every one is complete. A target that exists and
    is not a regular file (``/dev/null``, a FIFO, a device, or a symlink to one) is never
    replaced: the content is streamed into it (a FIFO without a reader is refused at once);
    a symlink to a regular file keeps its link and the file it points to is replaced.

    Raises
    ------
    OutputError
        An empty path, a target that is a folder, or any error while writing; the message
        names the user's path, and nothing is left behind.

    Examples
    --------
    >>> with tempfile.TemporaryDirectory() as d:
    ...     out = write_files({Path(d) / "new" / "a.csv": "A", Path(d) / "new" / "b.txt": "B"})
    ...     print(sorted(p.name for p in (Path(d) / "new").iterdir()))
    ['a.csv', 'b.txt']
    >>> write_files({"": "x"})
    Traceback (most recent call last):
    solver.errors.OutputError: the output path is empty
    """
    targets: list[tuple[Path, str | bytes]] = []
    for path, content in files.items():
        if str(path) == "":
            raise OutputError("the output path is empty")
        p = Path(path)
        if p.is_dir():
            raise OutputError(f"cannot write {p}: it is a folder")
        if p.is_symlink() and p.is_file():
            p = Path(os.path.realpath(p))
        targets.append((p, content))
    regular = [(t, c) for t, c in targets if not _is_special(t)]
    special = [(t, c) for t, c in targets if _is_special(t)]
    created: list[Path] = []
    temps: list[tuple[str, Path]] = []
    current = targets[0][0] if targets else Path(".")
    try:
        for target, _ in regular:
            current = target
            missing = []
            f = target.parent
            while not f.exists() and f != f.parent:
                missing.append(f)
                f = f.parent
            for folder in reversed(missing):
                folder.mkdir()
                created.append(folder)
        mask = os.umask(0)
        os.umask(mask)
        for target, content in regular:
            current = target
            fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.",
                                       suffix=".tmp")
            temps.append((tmp, target))
            with os.fdopen(fd, "wb") as fh:
                fh.write(content.encode("utf-8") if isinstance(content, str) else content)
            os.chmod(tmp, 0o666 & ~mask)
        for target, content in special:
            current = target
            _stream(target, content.encode("utf-8") if isinstance(content, str) else content)
        for tmp, target in temps:
            current = target
            os.replace(tmp, target)
        temps.clear()
    except BaseException as exc:
        for tmp, _ in temps:
            Path(tmp).unlink(missing_ok=True)
        for folder in reversed(created):
            with contextlib.suppress(OSError):
                folder.rmdir()
        if isinstance(exc, OSError):
            raise OutputError(f"cannot write {current}: {exc.strerror or exc}") from None
        raise
    return tuple(t for t, _ in targets)


def refuse_input_as_output(output: str | Path | None, inputs: Iterable[str | Path | None], *,
                           option: str = "-o") -> None:
    """Refuse an output path that names one of the inputs (the same file, by any path).

    Examples
    --------
    >>> with tempfile.TemporaryDirectory() as d:  # doctest: +ELLIPSIS
    ...     p = Path(d) / "x.json"
    ...     _ = p.write_text("{}")
    ...     refuse_input_as_output(Path(d) / "y.json", [p])
    ...     refuse_input_as_output(Path(d) / "." / "x.json", [p])
    Traceback (most recent call last):
    solver.errors.OutputError: ...x.json is an input of this command; refusing to overwrite it ...
    """
    if output is None or str(output) == "":
        return
    out = Path(output)
    for path in inputs:
        if path is None or str(path) == "":
            continue
        try:
            same = os.path.samefile(out, path)
        except OSError:
            same = os.path.realpath(out) == os.path.realpath(path)
        if same and (not out.exists() or out.is_file()):
            raise OutputError(f"{option} {out} is an input of this command; refusing to "
                              "overwrite it (give another path)")


def _is_special(target: Path) -> bool:
    try:
        st = os.stat(target)
    except OSError:
        return False
    return not stat.S_ISREG(st.st_mode) and not stat.S_ISDIR(st.st_mode)


def _stream(target: Path, data: bytes) -> None:
    try:
        fd = os.open(target, os.O_WRONLY | os.O_NONBLOCK | getattr(os, "O_NOCTTY", 0))
    except OSError as exc:
        if exc.errno == errno.ENXIO:
            raise OSError(exc.errno, "it is a FIFO that no process reads") from None
        raise
    try:
        os.set_blocking(fd, True)
        view = memoryview(data)
        while view:
            view = view[os.write(fd, view):]
    finally:
        os.close(fd)
