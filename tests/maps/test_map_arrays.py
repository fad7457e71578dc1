"""``.map`` straight to arrays (``grid_game``) gives the very instance the JSON route gives.

The JSON route is the checker's reference: ``grid_document`` then the instance reader.
Compared field by field (nodes, arcs, weights, distances, hops, priors) on the bundled paper
map and all twelve standard maps, 4- and 8-connected.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from dppio.standard_maps import standard_map_path
from dppverify.errors import InvalidInstanceError
from dppverify.formats.movingai import GridMap, grid_document, parse_map, read_map
from dppverify.game.grids import grid_game
from dppverify.game.instance import Instance, arc_arrays, instance_from_json
from tests.maps._maps import PAPER10, STANDARD, corner_cells


def _blocked(grid: GridMap) -> np.ndarray:
    return np.array([[ch not in ".GS" for ch in row] for row in grid.rows], dtype=bool)


def _same(a: Instance, b: Instance) -> None:
    for field in ("nodes", "directed", "succ", "pred", "start", "goals", "prior", "exact",
                  "dist_to", "hops"):
        assert getattr(a, field) == getattr(b, field), field
    assert dict(a.index) == dict(b.index)
    x, y = arc_arrays(a), arc_arrays(b)
    assert np.array_equal(x.tails, y.tails) and np.array_equal(x.heads, y.heads)
    assert [x.values[k] for k in x.codes.tolist()] == [y.values[k] for k in y.codes.tolist()]
    assert type(a) is type(b)


def _case(name: str) -> GridMap:
    return read_map(PAPER10 if name == "paper10" else standard_map_path(name))


SMALL = [m for m in STANDARD if not m.startswith(("Berlin", "maze-128"))]


@pytest.mark.parametrize("name", ["paper10", *STANDARD])
def test_same_instance_4_connected(name: str) -> None:
    grid = _case(name)
    start, g1, g2 = corner_cells(_blocked(grid))
    prior = ("3/5", "2/5")
    _same(grid_game(grid, start, (g1, g2), prior),
          instance_from_json(grid_document(grid, start, (g1, g2), prior)))


@pytest.mark.parametrize("name", ["paper10", *SMALL])
def test_same_instance_8_connected(name: str) -> None:
    grid = _case(name)
    start, g1, g2 = corner_cells(_blocked(grid))
    prior = ("0.5", "0.5")
    _same(grid_game(grid, start, (g1, g2), prior, connectivity=8),
          instance_from_json(grid_document(grid, start, (g1, g2), prior, connectivity=8)))


def test_same_n_goal_instance() -> None:
    grid = _case("room-32-32-4")
    start, g1, g2 = corner_cells(_blocked(grid))
    r, c = corner_cells(_blocked(grid)[:, ::-1])[0]  # bottom-right, same region
    goals = (g1, g2, (r, grid.width - 1 - c))
    assert len(set(goals)) == 3
    prior = ("1/2", "1/3", "1/6")
    _same(grid_game(grid, start, goals, prior),
          instance_from_json(grid_document(grid, start, goals, prior)))


@pytest.mark.parametrize(("text", "start", "goals", "prior"), [
    ("type octile\nheight 2\nwidth 3\nmap\n...\n.@.\n", (1, 1), ((0, 0), (1, 2)), ("1/2",) * 2),
    ("type octile\nheight 2\nwidth 3\nmap\n...\n.@.\n", (1, 0), ((0, 0), (5, 2)), ("1/2",) * 2),
    ("type octile\nheight 2\nwidth 3\nmap\n...\n.@.\n", (1, 0), ((0, 0), (1, 2)), ("1", "0")),
    ("type octile\nheight 2\nwidth 3\nmap\n...\n.@.\n", (1, 0), ((0, 0), (0, 0)), ("1/2",) * 2),
    ("type octile\nheight 1\nwidth 3\nmap\n.@.\n", (0, 0), ((0, 2), (0, 0)), ("1/2",) * 2),
])
def test_same_messages(text: str, start: tuple[int, int], goals: tuple, prior: tuple) -> None:
    grid = parse_map(text)
    with pytest.raises(InvalidInstanceError) as direct:
        grid_game(grid, start, goals, prior)
    with pytest.raises(InvalidInstanceError) as via_json:
        instance_from_json(grid_document(grid, start, goals, prior))
    assert str(direct.value) == str(via_json.value)


def test_float_mode_weights_are_the_octile_floats() -> None:
    grid = parse_map("type octile\nheight 2\nwidth 2\nmap\n..\n..\n")
    inst = grid_game(grid, (1, 0), ((0, 1), (0, 0)), ("1/2", "1/2"), connectivity=8)
    assert not inst.exact and inst.prior == (Fraction(1, 2), Fraction(1, 2))
    assert sorted({w for arcs in inst.succ for _, w in arcs}) == [1.0, 2.0 ** 0.5]
