"""MovingAI ``.scen`` scenario files and the seeded fake-goal rule ``dpp-batch/1``.

A ``.scen`` file (MovingAI benchmark format, version 1) has a header line ``version 1`` and
one scenario per line, nine tab-separated fields::

    bucket  map  width  height  start_x  start_y  goal_x  goal_y  optimal_length

``x`` is the column and ``y`` the row; our cells are ``(row, col)``, so the start is
``(start_y, start_x)``. The fake goal of a line (for a two-goal game) is chosen by
:func:`fake_goal_candidates` and :func:`fake_goal`: the goal cells of the other lines of the
same map, permuted by a seeded rule, the first one in the start's component taken. Both
``dpp batch`` (the solver's side) and ``dpp audit --map FILE --scen FILE`` (the checker's)
use this module, so they build the same games.
"""

from __future__ import annotations

import random
import re
from collections import deque
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from dppverify.errors import InvalidInstanceError

Cell = tuple[int, int]

BATCH_RULE = "dpp-batch/1"
"""The name of the fake-goal rule."""

MAX_SCEN_LINES = 1_000_000
"""Scenario lines accepted in one file."""

MAX_MAP_NAME = 4096
"""Longest map name of a scenario line (PATH_MAX on Linux): a longer one cannot name a file,
so its line is malformed."""

MAX_LENGTH_DIGITS = 30
"""Digits of a published optimal length on each side of its decimal point (MovingAI writes
``53.89949493``): the length is carried into ``dpp batch``'s rows as written, so it must be a
finite non-negative decimal — ``nan``, ``inf``, ``1e999999999``, ``-7`` or 5,000 digits make
the line an error row with that reason."""

_INTEGER = re.compile(r"\s*[0-9]{1,10}\s*", re.ASCII)
_LENGTH = re.compile(rf"[0-9]{{1,{MAX_LENGTH_DIGITS}}}(?:\.[0-9]{{0,{MAX_LENGTH_DIGITS}}})?"
                     rf"|\.[0-9]{{1,{MAX_LENGTH_DIGITS}}}", re.ASCII)


@dataclass(frozen=True)
class Scenario:
    """One line of a ``.scen`` file: ``line`` (1-based), the map name as written, its size
    as the line states it, the start and goal as ``(row, col)`` and MovingAI's published
    optimal length as written (``optimal``, 8-connected without corner cutting); or, for a bad
    line, ``reason``."""

    line: int
    map: str = ""
    width: int = 0
    height: int = 0
    start: Cell = (0, 0)
    goal: Cell = (0, 0)
    reason: str = ""
    optimal: str = ""


def parse_scen(text: str) -> list[Scenario]:
    """The scenario lines of a ``.scen`` file (blank lines and the ``version`` header skipped).

    A malformed line is a :class:`Scenario` with a ``reason``.

    Examples
    --------
    >>> text = "version 1\\n0\\tm.map\\t8\\t8\\t0\\t1\\t7\\t6\\t12.5\\n\\nbad line\\n"
    >>> a, b = parse_scen(text)
    >>> a.line, a.map, a.start, a.goal, a.optimal
    (2, 'm.map', (1, 0), (6, 7), '12.5')
    >>> b.line, b.reason[:45]
    (4, 'malformed scenario line: 2 fields, expected 9')
    """
    out: list[Scenario] = []
    text = text.removeprefix("\ufeff")  # a byte-order mark (Windows editors) before "version"
    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.strip()
        if not line or (number == 1 and line.lower().startswith("version")):
            continue
        if len(out) >= MAX_SCEN_LINES:
            raise InvalidInstanceError(f"more than {MAX_SCEN_LINES} scenario lines")
        parts = line.split("\t") if "\t" in line else line.split()
        if len(parts) != 9:
            out.append(Scenario(number, reason=f"malformed scenario line: {len(parts)} fields, "
                                "expected 9 (bucket, map, width, height, start_x, start_y, "
                                "goal_x, goal_y, optimal_length)"))
            continue
        fields = parts[2:8]
        if not all(_INTEGER.fullmatch(p) for p in fields):
            out.append(Scenario(number, reason="malformed scenario line: width, height and "
                                "the cells must be integers (ASCII digits)"))
            continue
        w, h, sx, sy, gx, gy = (int(p) for p in fields)
        length = parts[8].strip()
        if not _LENGTH.fullmatch(length):
            shown = repr(length[:40]) + ("…" if len(length) > 40 else "")
            out.append(Scenario(number, reason=f"malformed scenario line: the published length "
                                f"{shown} is not a finite non-negative decimal (at most "
                                f"{MAX_LENGTH_DIGITS} digits on each side of the point)"))
            continue
        name = parts[1].strip()
        if len(name) > MAX_MAP_NAME:
            out.append(Scenario(number, reason=f"malformed scenario line: a map name of "
                                f"{len(name)} characters (at most {MAX_MAP_NAME})"))
            continue
        out.append(Scenario(number, name, w, h, (sy, sx), (gy, gx), optimal=length))
    return out


def goals_by_map(scenarios: Sequence[Scenario]) -> dict[str, tuple[Cell, ...]]:
    """The goal cells of the well-formed lines of each map, in file order, without repeats:
    the table :func:`candidates_of` draws from (one pass over the file).

    Examples
    --------
    >>> sc = [Scenario(2, "m", 4, 4, (0, 0), (3, 3)), Scenario(3, "m", 4, 4, (1, 1), (0, 3)),
    ...       Scenario(4, "m", 4, 4, (2, 2), (3, 3)), Scenario(5, reason="bad")]
    >>> goals_by_map(sc)
    {'m': ((3, 3), (0, 3))}
    """
    table: dict[str, dict[Cell, None]] = {}
    for sc in scenarios:
        if not sc.reason:
            table.setdefault(sc.map, {}).setdefault(sc.goal, None)
    return {name: tuple(goals) for name, goals in table.items()}


def candidates_of(goals: Sequence[Cell], scenario: Scenario, seed: int) -> list[Cell]:
    """The fake-goal candidates of ``scenario`` from its map's goals (:func:`goals_by_map`):
    without the line's own start and goal, permuted by
    ``random.Random(f"dpp-batch:{seed}:{line}")``. Linear in the number of goals.

    Examples
    --------
    >>> me = Scenario(2, "m", 4, 4, (0, 0), (3, 3))
    >>> candidates_of([(3, 3), (0, 3), (3, 0)], me, seed=0)
    [(0, 3), (3, 0)]
    """
    own = (scenario.start, scenario.goal)
    out = [g for g in goals if g not in own]
    random.Random(f"dpp-batch:{seed}:{scenario.line}").shuffle(out)
    return out


def component(free: Callable[[int, int], bool], height: int, width: int, start: Cell,
              connectivity: int = 4) -> set[Cell]:
    """The free cells reachable from ``start`` (4- or 8-connected; 8 without corner cutting).

    Examples
    --------
    >>> rows = ["..@", "@.@", "..."]
    >>> sorted(component(lambda r, c: rows[r][c] == ".", 3, 3, (0, 0)))
    [(0, 0), (0, 1), (1, 1), (2, 0), (2, 1), (2, 2)]
    """
    seen = {start}
    queue = deque([start])
    steps = [(-1, 0), (1, 0), (0, -1), (0, 1)]
    if connectivity == 8:
        steps += [(-1, -1), (-1, 1), (1, -1), (1, 1)]
    while queue:
        r, c = queue.popleft()
        for dr, dc in steps:
            rr, cc = r + dr, c + dc
            if not (0 <= rr < height and 0 <= cc < width) or (rr, cc) in seen \
                    or not free(rr, cc):
                continue
            if dr and dc and not (free(r + dr, c) and free(r, c + dc)):
                continue
            seen.add((rr, cc))
            queue.append((rr, cc))
    return seen


def fake_goal(candidates: Sequence[Cell], reachable: Callable[[Cell], bool]) -> Cell | None:
    """The first candidate that is reachable (None when none is).

    Examples
    --------
    >>> fake_goal([(0, 3), (3, 0)], lambda cell: cell != (0, 3))
    (3, 0)
    """
    return next((g for g in candidates if reachable(g)), None)
