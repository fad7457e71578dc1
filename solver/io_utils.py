"""Small I/O helpers shared by the CLI: atomic writes and JSON dumping."""

from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path
from typing import Any

__all__ = ["dumps", "write_atomic"]


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
    """Write ``text`` to ``path`` via a temporary file and ``os.replace``: readers see the old
    file or the complete new one, never a partial file.

    Parameters
    ----------
    path : str or Path
        The target; its directory must exist.
    text : str
        Written as UTF-8.

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
    p = Path(path)
    fd, tmp = tempfile.mkstemp(dir=p.parent if str(p.parent) else ".", prefix=f".{p.name}.",
                               suffix=".tmp")
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
        os.replace(tmp, p)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
