"""Where an output path writes: the target behind a symlink, what kind of file it is, the
folders on the way — the rule every ``dpp`` command's outputs follow (docs/limits.md, "Output
files"), shared by :mod:`dppio.files` (the writer) and :mod:`dppio.locks` (the lock
discipline).

- ``-`` (:data:`~dppio.inputs.STDIN`) is standard output; a file named ``-`` is ``./-``;
- a symlink is written through and kept: to a regular file, that file; a dangling one, the
  file it names (created with its missing folders);
- a device, a FIFO or a socket (:func:`is_special`) is written into, never replaced;
- a folder on the way that is a dangling symlink or a file cannot be created: one line.
"""

from __future__ import annotations

import contextlib
import errno
import os
import stat
from pathlib import Path

from dppio.errors import ErrorClass
from dppio.inputs import STDIN


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


def resolve_target(path: str | Path, error: ErrorClass) -> Path:
    """The file an output path writes: ``-`` for standard output, the file behind a symlink
    (a dangling one too), else the path; an empty path, a trailing ``/`` or a folder raise
    ``error`` (one line).

    Examples
    --------
    >>> resolve_target("-", ValueError), resolve_target("out/p.json", ValueError)
    (PosixPath('-'), PosixPath('out/p.json'))
    >>> resolve_target("out/", ValueError)
    Traceback (most recent call last):
    ValueError: cannot write out/: it names a folder (a trailing /); give a file name
    """
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


def is_special(target: Path) -> bool:
    """True when ``target`` exists (through symlinks) and is neither a regular file nor a
    folder: a device, a FIFO, a socket — written into, never replaced.

    Examples
    --------
    >>> is_special(Path("/dev/null")), is_special(Path("/nonexistent"))
    (True, False)
    """
    try:
        st = os.stat(target)
    except OSError:
        return False
    return not stat.S_ISREG(st.st_mode) and not stat.S_ISDIR(st.st_mode)


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
