"""Exact totals of a vertex table's covers at many nodes at once: ``values @ scaled`` by
blocks of rows, the cheapest cover per row (:func:`cover_minimum`) and the covers that attain
a given total (:func:`attaining`), in float64 only where every partial sum is provably an
integer below 2**53, else in int64 or Python integers.
"""

from __future__ import annotations

import math

import numpy as np

from solver.coalitions.vertex_tables import INT_LIMIT, VertexTable
from solver.graph.distances import EXACT_FLOAT_LIMIT

CHUNK = 8192
"""Rows per block of the cover totals (bounds the temporaries: 8192 × vertices)."""


def exact_totals(values: np.ndarray, scaled: np.ndarray) -> np.ndarray:
    """``values @ scaled`` for non-negative int64 data, exactly.

    float64 (every entry an integer below 2**53, so comparisons and ``min`` are exact) when
    every partial sum is provably such an integer, else int64 through Python integers.

    Raises
    ------
    OverflowError
        When a total leaves the int64 range used here (``2**62``).

    Examples
    --------
    >>> exact_totals(np.array([[2, 3, 4]]), np.array([[1, 0], [1, 0], [0, 1]])).tolist()
    [[5.0, 4.0]]
    """
    if values.shape[0] == 0 or scaled.shape[1] == 0:
        return np.zeros((values.shape[0], scaled.shape[1]), dtype=np.int64)
    top = int(values.max(initial=0))
    width = (top + 1) * (int(np.abs(scaled).sum(axis=0).max(initial=1)) + 1)
    if width < EXACT_FLOAT_LIMIT:
        return values.astype(np.float64) @ scaled.astype(np.float64)
    out = values.astype(object) @ scaled.astype(object)
    if max((int(x) for x in out.flat), default=0) >= INT_LIMIT:
        raise OverflowError("numbers beyond the exact int64 range")
    return out.astype(np.int64)


def cover_minimum(values: np.ndarray, lost: np.ndarray, table: VertexTable,
                  skip: tuple[int, int] | None = None
                  ) -> tuple[np.ndarray, int, np.ndarray] | None:
    """``min_c values[row] @ c`` over the table's vertices ``c`` (all parts, but ``skip``)
    whose support avoids the row's ``lost`` entries, exactly.

    Returns ``(num, den, got)``: the minimum is ``num[row] / den`` where ``got[row]`` (some
    vertex avoids the lost entries); ``num`` is int64 for a one-part table, else Python
    integers over the lcm of the parts' denominators. None when every vertex is skipped.

    Examples
    --------
    >>> from solver.coalitions.vertex_tables import vertex_table
    >>> t = vertex_table(((1, 0), (0, 1), (1, 1)), (1, 1))
    >>> num, den, got = cover_minimum(np.array([[2, 3, 4], [2, 3, 6]]),
    ...                               np.zeros((2, 3), dtype=bool), t)
    >>> num.tolist(), den, got.tolist()
    ([4, 5], 1, [True, True])
    """
    parts = [(p, sc if skip is None or skip[0] != p else np.delete(sc, skip[1], axis=1), lcm)
             for p, (sc, lcm) in enumerate(table.parts)]
    parts = [(p, sc, lcm) for p, sc, lcm in parts if sc.shape[1]]
    if not parts:
        return None
    finite = values[~lost]
    top = int(finite.max(initial=0))
    den = math.lcm(*(lcm for _, _, lcm in parts))
    best: np.ndarray | None = None
    got = np.zeros(values.shape[0], dtype=bool)
    for _, sc, lcm in parts:
        # an unreachable step: a value above every finite cover's total
        big = top * int(sc.sum(axis=0).max(initial=1)) + 1
        vals = np.where(lost, big, values)
        if big >= INT_LIMIT:
            vals = vals.astype(object)
        mins = [_row_minimum(vals[lo:lo + CHUNK], sc) for lo in range(0, values.shape[0], CHUNK)]
        low = np.concatenate(mins) if mins else np.zeros(0, dtype=np.int64)
        ok = low < big
        if len(parts) == 1:
            return np.where(ok, low, 0).astype(low.dtype), den, ok
        low = np.where(ok, low, 0).astype(object) * (den // lcm)
        best = low if best is None else np.where(ok & (~got | (low < best)), low, best)
        got |= ok
    assert best is not None
    return best, den, got


def _row_minimum(values: np.ndarray, scaled: np.ndarray) -> np.ndarray:
    """Row-wise ``min`` of ``values @ scaled`` exactly: int64 when it fits, else Python
    integers."""
    try:
        return exact_totals(values, scaled).min(axis=1).astype(np.int64)
    except OverflowError:
        return (values.astype(object) @ scaled.astype(object)).min(axis=1)


def attaining(values: np.ndarray, scaled: np.ndarray, target: np.ndarray
               ) -> tuple[np.ndarray, np.ndarray]:
    """The pairs (row, vertex) with ``values[row] @ scaled[:, vertex] == target[row]``, exactly
    (by blocks of rows: the totals of one block at a time)."""
    rows: list[np.ndarray] = []
    verts: list[np.ndarray] = []
    for lo in range(0, values.shape[0], CHUNK):
        try:
            tot = exact_totals(values[lo:lo + CHUNK], scaled)
        except OverflowError:  # totals beyond int64: Python integers
            tot = values[lo:lo + CHUNK].astype(object) @ scaled.astype(object)
        r, q = np.nonzero(tot == target[lo:lo + CHUNK, None])
        rows.append(r + lo)
        verts.append(q)
    if not rows:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    return np.concatenate(rows), np.concatenate(verts)
