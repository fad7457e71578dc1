"""Grids: the CSR fast path agrees with networkx graphs; MovingAI maps parse strictly."""

from __future__ import annotations

from pathlib import Path

import networkx as nx
import numpy as np
import pytest

from solver import Instance, InstanceFormatError
from solver.formats.movingai import parse_map, read_map
from solver.twogoal.equilibrium import paper_equilibrium

MAP = """type octile
height 4
width 5
map
.....
.@@T.
...W.
G....
"""


def test_grid_solves_like_the_same_graph_built_with_networkx() -> None:
    rng = np.random.default_rng(7)
    for _ in range(20):
        blocked = rng.random((6, 7)) < 0.25
        blocked[0, 0] = blocked[5, 6] = blocked[0, 6] = False
        g = nx.grid_2d_graph(6, 7)
        g.remove_nodes_from([(int(r), int(c)) for r, c in zip(*np.nonzero(blocked), strict=True)])
        if not (nx.has_path(g, (0, 0), (5, 6)) and nx.has_path(g, (0, 0), (0, 6))):
            continue
        goals = ((5, 6), (0, 6))
        fast = paper_equilibrium(Instance.from_grid(blocked, (0, 0), goals, ("3/5", "2/5")))
        slow = paper_equilibrium(Instance(g, (0, 0), goals, ("3/5", "2/5")))
        assert (fast.U, fast.VoI, fast.U2) == (slow.U, slow.VoI, slow.U2)


def test_octile_grid_is_float_mode_with_sqrt2_diagonals() -> None:
    blocked = np.zeros((3, 3), dtype=bool)
    eq = paper_equilibrium(Instance.from_grid(blocked, (0, 0), ((2, 2), (0, 2)), ("3/5", "2/5"),
                                  connectivity=8))
    assert not eq.numbers.exact and eq.numbers.abs_tol is not None
    assert eq.U1 == pytest.approx(2 * np.sqrt(2))


def test_corner_cutting_is_forbidden() -> None:
    blocked = np.array([[False, True], [False, False]])
    inst = Instance.from_grid(blocked, (0, 0), ((1, 1), (1, 0)), ("3/5", "2/5"), connectivity=8)
    assert inst.network.arc_weight(0, 3) is None  # (0,0) -> (1,1) would cut the corner (0,1)


def test_parse_map() -> None:
    grid = parse_map(MAP)
    assert grid.shape == (4, 5)
    assert grid.sum() == 4 and grid[1, 3] and grid[2, 3] and not grid[3, 0]


@pytest.mark.parametrize("text,message", [
    ("type octile\nheight 2\nwidth 2\nmap\n..\n", "expected 2 map rows .*, found 1"),
    ("type octile\nheight 1\nwidth 2\nmap\n...\n", "line 5: expected 2 characters, found 3"),
    ("type octile\nheight 1\nwidth 2\nmap\n.x\n", "unknown map character"),
    ("type octile\nwidth 2\nmap\n..\n", "header lacks 'height'"),
    ("type octile\nheight 1\nwidth 2\n..\n", "line 4: expected 'key value' header"),
    ("type octile\nheight a\nwidth 2\nmap\n..\n", "must be integers"),
])
def test_malformed_maps(text: str, message: str) -> None:
    with pytest.raises(InstanceFormatError, match=message):
        parse_map(text)


def test_read_map_names_the_file(tmp_path: Path) -> None:
    p = tmp_path / "m.map"
    p.write_text("type octile\nheight 1\nwidth 2\nmap\n.\n")
    with pytest.raises(InstanceFormatError, match=r"m\.map: line 5"):
        read_map(p)
