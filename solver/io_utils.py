"""Small I/O helpers of the solver's CLI: all-or-nothing writes and JSON dumping (the
checker has its own copy of the rules, ``dppverify/files.py``)."""

from __future__ import annotations

import contextlib
import json
import os
import tempfile
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from solver.errors import OutputError

__all__ = ["dumps", "write_atomic", "write_files"]


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
    all are renamed into place only when every one is complete.

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
        targets.append((p, content))
    created: list[Path] = []
    temps: list[str] = []
    current = targets[0][0] if targets else Path(".")
    try:
        for target, _ in targets:
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
        for target, content in targets:
            current = target
            fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.",
                                       suffix=".tmp")
            temps.append(tmp)
            with os.fdopen(fd, "wb") as fh:
                fh.write(content.encode("utf-8") if isinstance(content, str) else content)
            os.chmod(tmp, 0o666 & ~mask)
        for tmp, (target, _) in zip(temps, targets, strict=True):
            current = target
            os.replace(tmp, target)
        temps.clear()
    except BaseException as exc:
        for tmp in temps:
            Path(tmp).unlink(missing_ok=True)
        for folder in reversed(created):
            with contextlib.suppress(OSError):
                folder.rmdir()
        if isinstance(exc, OSError):
            raise OutputError(f"cannot write {current}: {exc.strerror or exc}") from None
        raise
    return tuple(t for t, _ in targets)
