"""The checker's own MovingAI ``.map`` reader and grid-document builder (no solver code).

A ``.map`` file (https://movingai.com/benchmarks/formats.html) is read strictly: the header
is exactly the four lines ``type octile``, ``height H``, ``width W``, ``map`` (in that
order; ``H`` and ``W`` positive decimal integers), followed by exactly ``H`` rows of exactly
``W`` characters and nothing else but empty lines. ``.``, ``G`` and ``S`` are passable;
``@``, ``O``, ``T`` and ``W`` are obstacles; any other character is an error. Lines may end
in ``\\n`` or ``\\r\\n``.

:func:`grid_document` turns a map, a start, the goals and a prior into the instance JSON of
``docs/formats.md`` §1 — node ids ``[row, col]`` for the free cells in row-major order,
undirected edges between free neighbours — the same document the solver's
``instance_to_json`` writes for its grid instances: 4-connected moves have exact unit weights;
8-connected (octile) grids add diagonals of weight ``sqrt(2)`` without corner cutting (a
diagonal move needs both orthogonal neighbours free) and are float-mode documents
(``"numbers": "float"``, every weight a binary float). :func:`grid_arcs` gives that
document's edges as arrays, with numpy and no JSON: :func:`dppverify.game.grids.grid_game`
builds the very instance from them (what ``--map`` and the compact map-instance files of
:mod:`dppverify.formats.map_instance` use). This module does not import the game model.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np

from dppio.errors import InputError
from dppio.inputs import read_input
from dppio.limits import MAX_MAP_CELLS
from dppverify.errors import InvalidInstanceError
from dppverify.formats.json_reading import parse_number

PASSABLE = frozenset(".GS")
"""Map characters of free cells (ground, ground, swamp)."""

BLOCKED = frozenset("@OTW")
"""Map characters of obstacles (out of bounds, out of bounds, trees, water)."""

SQRT2 = math.sqrt(2.0)

Cell = tuple[int, int]


@dataclass(frozen=True)
class GridMap:
    """A parsed ``.map`` grid.

    Attributes
    ----------
    height, width : int
        Rows and columns.
    rows : tuple of str
        The map rows as written (``rows[r][c]`` is the character of cell ``(r, c)``).

    Examples
    --------
    >>> grid = parse_map("type octile\\nheight 2\\nwidth 3\\nmap\\n..@\\nT.G\\n")
    >>> grid.height, grid.width, grid.free(0, 1), grid.free(1, 0), grid.free(2, 0)
    (2, 3, True, False, False)
    """

    height: int
    width: int
    rows: tuple[str, ...]

    def free(self, r: int, c: int) -> bool:
        """True when ``(r, c)`` lies on the map and is passable."""
        return 0 <= r < self.height and 0 <= c < self.width and self.rows[r][c] in PASSABLE

    def check_cell(self, cell: Cell, what: str) -> None:
        """Raise a one-line :class:`InvalidInstanceError` unless ``cell`` is a free cell.

        Examples
        --------
        >>> grid = parse_map("type octile\\nheight 2\\nwidth 3\\nmap\\n..@\\nT.G\\n")
        >>> grid.check_cell((0, 2), "start")
        Traceback (most recent call last):
        dppverify.errors.InvalidInstanceError: start cell (0, 2) is an obstacle ('@' at row 0,
          column 2 of the 2x3 map)
        >>> grid.check_cell((2, 0), "goal")
        Traceback (most recent call last):
        dppverify.errors.InvalidInstanceError: goal cell (2, 0) is outside the 2x3 map
          (rows 0-1, columns 0-2)
        """
        r, c = cell
        if not (0 <= r < self.height and 0 <= c < self.width):
            raise InvalidInstanceError(
                f"{what} cell ({r}, {c}) is outside the {self.height}x{self.width} map "
                f"(rows 0-{self.height - 1}, columns 0-{self.width - 1})")
        if self.rows[r][c] not in PASSABLE:
            raise InvalidInstanceError(
                f"{what} cell ({r}, {c}) is an obstacle ({self.rows[r][c]!r} at row {r}, "
                f"column {c} of the {self.height}x{self.width} map)")


def read_map(path: str | Path) -> GridMap:
    """Read a ``.map`` file strictly; errors name the file and the line
    (:func:`read_map_file` without the bytes).

    Examples
    --------
    >>> read_map("/nonexistent.map")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: /nonexistent.map: cannot read map file (...)
    """
    return read_map_file(path)[0]


def read_map_file(path: str | Path) -> tuple[GridMap, bytes]:
    """Read a ``.map`` file strictly, with the bytes it was parsed from (what a compact map
    instance's ``map_sha256`` hashes); errors name the file and the line.

    Parameters
    ----------
    path : str or Path
        The ``.map`` file (ASCII).

    Returns
    -------
    (GridMap, bytes)

    Raises
    ------
    InvalidInstanceError
        One line ``PATH: line N: what is wrong`` (or ``PATH: cannot read map file``).

    Examples
    --------
    >>> from dppio.standard_maps import standard_map_path
    >>> grid, data = read_map_file(standard_map_path("empty-8-8"))
    >>> grid.height, data[:11]
    (8, b'type octile')
    """
    p = Path(path)
    try:  # bounded, and read once per command: the bytes hashed are the bytes parsed
        data = read_input(path)
        text = data.decode("ascii")
    except OSError as exc:
        raise InvalidInstanceError(f"{p}: cannot read map file ({exc.strerror})") from None
    except InputError as exc:
        raise InvalidInstanceError(f"{p}: cannot read map file ({exc})") from None
    except UnicodeDecodeError as exc:
        raise InvalidInstanceError(f"{p}: not an ASCII map file (byte {exc.start})") from None
    try:
        return parse_map(text), data
    except InvalidInstanceError as exc:
        raise InvalidInstanceError(f"{p}: {exc}") from None


def _header_int(line: str, key: str, number: int) -> int:
    parts = line.split(" ")
    if len(parts) != 2 or parts[0] != key:
        raise InvalidInstanceError(f"line {number}: expected '{key} N', got {line[:40]!r}")
    value = parts[1]
    if not (value.isascii() and value.isdigit()) or len(value) > 9 or int(value) == 0:
        raise InvalidInstanceError(
            f"line {number}: {key} must be a positive integer below 10**9, got {value[:40]!r}")
    return int(value)


def parse_map(text: str) -> GridMap:
    """Parse the text of a ``.map`` file (see the module docstring for the rules).

    Examples
    --------
    >>> parse_map("type octile\\nheight 1\\nwidth 2\\nmap\\n.@\\n").rows
    ('.@',)
    >>> parse_map("type octile\\nheight 1\\nwidth 2\\nmap\\n.@\\n..\\n")
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: line 6: more map rows than height 1
    >>> parse_map("type octile\\nheight 1\\nwidth 2\\nmap\\n.x\\n")
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: line 5: unknown map character 'x' at column 1
    """
    lines = text.split("\n")
    lines = [line[:-1] if line.endswith("\r") else line for line in lines]
    if len(lines) < 4:
        raise InvalidInstanceError("truncated header: expected the four lines 'type octile', "
                                   "'height H', 'width W', 'map'")
    if lines[0] != "type octile":
        raise InvalidInstanceError(f"line 1: expected 'type octile', got {lines[0][:40]!r}")
    height = _header_int(lines[1], "height", 2)
    width = _header_int(lines[2], "width", 3)
    if height * width > MAX_MAP_CELLS:  # refused before the rows are read
        raise InvalidInstanceError(f"a {height}x{width} map has {height * width} cells, beyond "
                                   f"the limit of {MAX_MAP_CELLS} (the memory budget)")
    if lines[3] != "map":
        raise InvalidInstanceError(f"line 4: expected 'map', got {lines[3][:40]!r}")
    body = lines[4:]
    if body and body[-1] == "":  # the newline that ends the last row
        body.pop()
    rows = body[:height]
    if len(rows) < height:
        raise InvalidInstanceError(f"expected {height} map rows, found {len(rows)}")
    known = PASSABLE | BLOCKED
    for r, row in enumerate(rows):
        if len(row) != width:
            raise InvalidInstanceError(f"line {5 + r}: expected {width} characters, "
                                       f"found {len(row)}")
        bad = set(row) - known
        if bad:
            c = min(row.index(ch) for ch in bad)
            raise InvalidInstanceError(f"line {5 + r}: unknown map character {row[c]!r} "
                                       f"at column {c}")
    for k, extra in enumerate(body[height:]):
        if extra.strip():
            raise InvalidInstanceError(f"line {5 + height + k}: more map rows than height "
                                       f"{height}")
    return GridMap(height, width, tuple(rows))


def _octile(grid: GridMap, start: Cell, goals: Sequence[Cell], connectivity: int) -> bool:
    """Check the start, the goals and ``connectivity`` (4 or 8); True for 8 (octile)."""
    if connectivity not in (4, 8):
        raise InvalidInstanceError(f"connectivity must be 4 or 8, got {connectivity}")
    grid.check_cell(start, "start")
    for goal in goals:
        grid.check_cell(goal, "goal")
    return connectivity == 8


def grid_document(grid: GridMap, start: Cell, goals: Sequence[Cell], prior: Sequence[Any],
                  *, connectivity: int = 4) -> dict[str, Any]:
    """The instance JSON document of a grid game (``docs/formats.md`` §1).

    Parameters
    ----------
    grid : GridMap
        The map.
    start : (int, int)
        The start cell ``(row, col)``.
    goals : sequence of (int, int)
        The goal cells (two, or N for an N-goal instance, ``docs/formats.md`` §1 "N goals");
        ``prior[i]`` belongs to ``goals[i]``.
    prior : sequence
        The priors as instance JSON numbers (e.g. ``"3/5"``, ``"0.6"``), one per goal;
        validated by the instance parser.
    connectivity : {4, 8}
        4: unit-weight moves up/down/left/right (exact). 8: also diagonal moves of weight
        ``sqrt(2)`` where both orthogonal neighbours are free (float mode).

    Returns
    -------
    dict
        Free cells ``[r, c]`` in row-major order; each undirected edge once, from the lower
        row-major cell, in row-major order of its lower cell and then of its other cell.

    Raises
    ------
    InvalidInstanceError
        ``start`` or a goal is outside the map or an obstacle; ``connectivity`` not 4 or 8.

    Examples
    --------
    >>> grid = parse_map("type octile\\nheight 2\\nwidth 2\\nmap\\n..\\n@.\\n")
    >>> doc = grid_document(grid, (0, 0), ((1, 1), (0, 1)), ("3/5", "2/5"))
    >>> [n["id"] for n in doc["graph"]["nodes"]]
    [[0, 0], [0, 1], [1, 1]]
    >>> [(e["source"], e["target"], e["weight"]) for e in doc["graph"]["edges"]]
    [([0, 0], [0, 1], '1'), ([0, 1], [1, 1], '1')]
    >>> doc8 = grid_document(grid, (0, 0), ((1, 1), (0, 1)), ("3/5", "2/5"), connectivity=8)
    >>> doc8["numbers"], len(doc8["graph"]["edges"])  # no diagonal past the obstacle corner
    ('float', 2)
    """
    octile = _octile(grid, start, goals, connectivity)
    # neighbours later in row-major order: right, then (diagonals) down-left, down, down-right
    steps = [(0, 1), (1, -1), (1, 0), (1, 1)] if octile else [(0, 1), (1, 0)]
    unit: str | float = 1.0 if octile else "1"
    free = grid.free
    nodes: list[dict[str, Any]] = []
    edges: list[dict[str, Any]] = []
    for r in range(grid.height):
        for c in range(grid.width):
            if not free(r, c):
                continue
            nodes.append({"id": [r, c]})
            for dr, dc in steps:
                if not free(r + dr, c + dc):
                    continue
                if dr and dc:
                    if not (free(r + dr, c) and free(r, c + dc)):
                        continue
                    w: str | float = SQRT2
                else:
                    w = unit
                edges.append({"source": [r, c], "target": [r + dr, c + dc], "weight": w})
    doc: dict[str, Any] = {
        "graph": {"directed": False, "multigraph": False, "graph": {}, "nodes": nodes,
                  "edges": edges},
        "start": list(start), "goals": [list(g) for g in goals], "prior": list(prior)}
    if octile:
        doc["numbers"] = "float"
    return doc


class GridArcs(NamedTuple):
    """A grid's graph as arrays: the arcs of :func:`grid_document`'s edges, both ways, in
    adjacency (CSR) order.

    The nodes are the free cells, row-major: node ``k`` is the cell at ``framed[k]`` of the map
    with a one-cell frame (``(row + 1) * stride + col + 1``, ``stride = width + 2``);
    ``node_at`` is the inverse (-1 at blocked cells and the frame). The arcs leaving node ``u``
    are ``indptr[u]:indptr[u + 1]``, by increasing head: arc ``j`` goes ``tails[j] ->
    heads[j]`` with weight ``values[codes[j]]`` (the weights numbered in the order the JSON
    reader meets them in the document); every arc's reverse is an arc of the same weight.
    ``exact`` is False for octile grids (float weights).
    """

    framed: np.ndarray
    node_at: np.ndarray
    stride: int
    indptr: np.ndarray
    tails: np.ndarray
    heads: np.ndarray
    codes: np.ndarray
    values: list[Any]
    exact: bool


def grid_arcs(grid: GridMap, start: Cell, goals: Sequence[Cell], *,
              connectivity: int = 4) -> GridArcs:
    """The arcs of :func:`grid_document`'s edges as CSR arrays, from numpy shifts of the
    free-cell mask (no sort: the neighbours of a cell in increasing row-major order are up,
    left, right, down, with the diagonals in between for 8-connected grids).

    Same checks and messages as :func:`grid_document` for the connectivity and the cells.

    Examples
    --------
    >>> grid = parse_map("type octile\\nheight 2\\nwidth 3\\nmap\\n...\\n.@.\\n")
    >>> a = grid_arcs(grid, (1, 0), ((1, 2), (0, 0)))
    >>> a.framed.tolist(), a.indptr.tolist(), a.heads.tolist(), a.values
    ([6, 7, 8, 11, 13], [0, 2, 4, 6, 7, 8], [1, 3, 0, 2, 1, 4, 0, 2], [1])
    >>> b = grid_arcs(parse_map("type octile\\nheight 2\\nwidth 2\\nmap\\n..\\n..\\n"),
    ...               (1, 0), ((0, 1), (0, 0)), connectivity=8)
    >>> b.heads.tolist(), b.codes.tolist(), b.values
    ([1, 2, 3, 0, 2, 3, 0, 1, 3, 0, 1, 2], [0, 0, 1, 0, 1, 0, 0, 1, 0, 1, 0, 0], \
[1.0, 1.4142135623730951])
    >>> grid_arcs(grid, (1, 1), ((1, 2), (0, 0)))
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: start cell (1, 1) is an obstacle ('@' at row 1,
      column 1 of the 2x3 map)
    """
    octile = _octile(grid, start, goals, connectivity)
    h, w = grid.height, grid.width
    chars = np.frombuffer("".join(grid.rows).encode("ascii"), dtype=np.uint8).reshape(h, w)
    free = np.isin(chars, np.frombuffer("".join(sorted(PASSABLE)).encode("ascii"),
                                        dtype=np.uint8))
    stride = w + 2  # cells are indexed in the map with a one-cell frame: no bounds checks
    framed = np.flatnonzero(np.pad(free, 1))  # row-major: the node order of grid_document
    n = int(framed.size)
    node_at = np.full((h + 2) * stride, -1, dtype=np.int64)
    node_at[framed] = np.arange(n, dtype=np.int64)
    steps = ([(-1, -1), (-1, 0), (-1, 1), (0, -1), (0, 1), (1, -1), (1, 0), (1, 1)] if octile
             else [(-1, 0), (0, -1), (0, 1), (1, 0)])  # increasing head index
    k = len(steps)
    heads2 = np.empty((n, k), dtype=np.int64)  # heads2[u, j]: the neighbour by step j, or -1
    for j, (dr, dc) in enumerate(steps):
        heads2[:, j] = node_at[framed + (dr * stride + dc)]
        if dr and dc:  # a diagonal needs both orthogonal neighbours free
            cut = (node_at[framed + dr * stride] < 0) | (node_at[framed + dc] < 0)
            heads2[cut, j] = -1
    arc = heads2 >= 0
    heads = heads2[arc]
    degree = np.zeros(n, dtype=np.int64)
    for j in range(k):
        degree += arc[:, j]
    indptr = np.zeros(n + 1, dtype=np.int64)
    np.cumsum(degree, out=indptr[1:])
    tails = np.repeat(np.arange(n, dtype=np.int64), degree)
    if octile:  # weight codes in order of first appearance, as the JSON reader numbers them
        diagonal = np.broadcast_to(np.array([bool(dr and dc) for dr, dc in steps]), (n, k))[arc]
        first_diagonal = _first_edge_diagonal(heads2, arc, steps)
        literals: list[Any] = [SQRT2, 1.0] if first_diagonal else [1.0, SQRT2]
        codes = (diagonal != first_diagonal).astype(np.int64)
        if not diagonal.any() or diagonal.all():
            literals = literals[:1]
    else:
        literals, codes = ["1"], np.zeros(heads.size, dtype=np.int64)
    values = [parse_number(x, where="weight", allow_float=octile) for x in literals]
    return GridArcs(framed, node_at, stride, indptr, tails, heads, codes, values, not octile)


def _first_edge_diagonal(heads2: np.ndarray, arc: np.ndarray,
                         steps: list[tuple[int, int]]) -> bool:
    """Whether :func:`grid_document`'s first edge is a diagonal: the first cell with a
    neighbour later in row-major order, its first such step (right, down-left, down,
    down-right)."""
    later = [j for j, (dr, dc) in enumerate(steps) if dr > 0 or (dr == 0 and dc > 0)]
    has = arc[:, later]
    rows = np.flatnonzero(has.any(axis=1))
    if rows.size == 0:
        return False
    j = later[int(np.argmax(has[rows[0]]))]
    return bool(steps[j][0] and steps[j][1])
