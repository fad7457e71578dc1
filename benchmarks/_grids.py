"""Grids for the benchmarks, built here with numpy alone (no solver or checker code).

The baseline "one scipy Dijkstra" of the benchmarks runs on :func:`free_cell_graph`: the
4-connected graph of the free cells only, unit weights, ``int32`` CSR (what
``scipy.sparse.csgraph`` works in): the least graph any exact solver has to search, built the
same way whatever code is on ``PYTHONPATH`` (so "before" and "after" runs share it).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import scipy.sparse as sp

__all__ = ["corners", "free_cell_graph", "random_grid", "write_map"]


def random_grid(size: int, density: float, seed: int) -> np.ndarray:
    """``size`` x ``size`` obstacles, each cell blocked with probability ``density``."""
    return np.random.default_rng(seed).random((size, size)) < density


def write_map(path: Path, blocked: np.ndarray) -> None:
    """A MovingAI ``.map`` file of ``blocked`` (``@`` obstacles, ``.`` free)."""
    rows = ["".join("@" if b else "." for b in row) for row in blocked]
    path.write_text(f"type octile\nheight {blocked.shape[0]}\nwidth {blocked.shape[1]}\nmap\n"
                    + "\n".join(rows) + "\n")


def corners(blocked: np.ndarray) -> tuple[tuple[int, int], ...]:
    """The free cells nearest the bottom-left (start), top-right, top-left, bottom-right
    corners, the centre and the top middle, all in the largest 4-connected region (ties:
    row-major)."""
    from scipy import ndimage

    labels, _ = ndimage.label(~blocked)
    sizes = np.bincount(labels.ravel())
    sizes[0] = 0
    h, w = blocked.shape
    region = np.argwhere(labels == int(np.argmax(sizes)))

    def nearest(cells: np.ndarray, r: int, c: int) -> tuple[int, int]:
        d = np.abs(cells[:, 0] - r) + np.abs(cells[:, 1] - c)
        k = int(np.lexsort((cells[:, 1], cells[:, 0], d))[0])
        return (int(cells[k, 0]), int(cells[k, 1]))

    return tuple(nearest(region, r, c) for r, c in
                 ((h - 1, 0), (0, w - 1), (0, 0), (h - 1, w - 1), (h // 2, w // 2),
                  (0, w // 2)))


def free_cell_graph(blocked: np.ndarray) -> tuple[sp.csr_matrix, np.ndarray]:
    """The free cells' 4-connected graph (unit weights) and ``node[r, c]`` (-1 if blocked)."""
    h, w = blocked.shape
    free = ~blocked
    node = np.full((h, w), -1, dtype=np.int64)
    node[free] = np.arange(int(free.sum()))
    tails, heads = [], []
    for dr, dc in ((0, 1), (1, 0)):
        both = free[:h - dr, :w - dc] & free[dr:, dc:]
        u, v = node[:h - dr, :w - dc][both], node[dr:, dc:][both]
        tails += [u, v]
        heads += [v, u]
    t, hd = np.concatenate(tails), np.concatenate(heads)
    n = int(free.sum())
    mat = sp.csr_matrix((np.ones(t.size), (t, hd)), shape=(n, n))
    mat.indices = mat.indices.astype(np.int32)
    mat.indptr = mat.indptr.astype(np.int32)
    return mat, node
