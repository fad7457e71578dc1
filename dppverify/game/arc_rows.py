"""An instance's adjacency rows held as arrays: :class:`ArcRows` reads like the tuple of
``(head, weight)`` tuples per node that ``Instance.succ`` and ``Instance.pred`` stand for, in
memory linear in the arcs (the arrays of :class:`dppverify.game.distances.ArcArrays`).
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from typing import Any

import numpy as np

from dppverify.exact import Number

_SHORT_ROW = 32
"""Rows longer than this are searched by bisection (their heads are sorted)."""


class ArcRows(Sequence[tuple[tuple[int, Number], ...]]):
    """An instance's ``succ`` (or ``pred``): ``rows[u]`` = the ``(head, weight)`` pairs of
    ``u``'s arcs, built on access from arrays (arcs sorted by tail, then head).

    It reads like the tuple of tuples it stands for (indexing, iteration, ``len``, equality
    with any sequence of rows), in memory linear in the arcs as numpy arrays: a grid of a
    million cells holds no Python object per arc.

    Examples
    --------
    >>> from fractions import Fraction
    >>> rows = ArcRows(3, np.array([0, 0, 2]), np.array([1, 2, 0]), np.array([0, 1, 0]),
    ...                (1, Fraction(3, 2)))
    >>> rows[0], rows[1], len(rows), rows == ((( 1, 1), (2, Fraction(3, 2))), (), ((0, 1),))
    (((1, 1), (2, Fraction(3, 2))), (), 3, True)
    """

    __slots__ = ("_bounds", "_codes", "_heads", "_keys", "_n", "_order", "_values")

    def __init__(self, n: int, tails: np.ndarray, heads: np.ndarray, codes: np.ndarray,
                 values: tuple[Number, ...], *, bounds: np.ndarray | None = None) -> None:
        self._n = n
        # bounds: the CSR row pointer when the caller has it (rows u are bounds[u]:bounds[u+1])
        self._bounds = np.searchsorted(tails, np.arange(n + 1)) if bounds is None else bounds
        self._heads = heads
        self._codes = codes
        self._values = values
        self._keys: np.ndarray | None = None  # tail·n + head per arc, sorted (built on use)
        self._order: np.ndarray | None = None  # arc positions in key order, when not arc order

    def __len__(self) -> int:
        return self._n

    def _row(self, u: int) -> tuple[tuple[int, Number], ...]:
        a, b = int(self._bounds[u]), int(self._bounds[u + 1])
        heads = self._heads[a:b].tolist()
        if len(self._values) == 1:
            w = self._values[0]
            return tuple([(h, w) for h in heads])
        values = self._values
        return tuple(zip(heads, [values[c] for c in self._codes[a:b].tolist()], strict=True))

    def __getitem__(self, u: Any) -> Any:
        if isinstance(u, slice):
            return tuple(self._row(i) for i in range(*u.indices(self._n)))
        i = u.__index__()
        if i < 0:
            i += self._n
        if not 0 <= i < self._n:
            raise IndexError(u)
        return self._row(i)

    def __iter__(self) -> Iterator[tuple[tuple[int, Number], ...]]:
        for u in range(self._n):
            yield self._row(u)

    def find(self, u: int, v: int) -> Number | None:
        """The weight of the arc ``u -> v`` (None when there is none), by binary search.

        Examples
        --------
        >>> from fractions import Fraction
        >>> rows = ArcRows(2, np.array([0]), np.array([1]), np.array([0]), (Fraction(1, 2),))
        >>> rows.find(0, 1), rows.find(1, 0)
        (Fraction(1, 2), None)
        """
        a, b = int(self._bounds[u]), int(self._bounds[u + 1])
        if b - a > _SHORT_ROW:  # a hub: a binary search
            found = self._positions(np.array([u], dtype=np.int64), np.array([v], dtype=np.int64))
            if found[0] < 0:
                return None
            i = int(found[0])
        else:
            try:  # a short row: a list search beats numpy's per-call overhead
                i = a + self._heads[a:b].tolist().index(v)
            except ValueError:
                return None
        return self._values[int(self._codes[i])] if len(self._values) > 1 else self._values[0]

    def find_many(self, tails: Sequence[int], heads: Sequence[int]) -> list[Number | None]:
        """:meth:`find` for many arcs at once (one binary search per arc, in one numpy call).

        Examples
        --------
        >>> from fractions import Fraction
        >>> rows = ArcRows(3, np.array([0, 0, 1]), np.array([1, 2, 2]), np.array([0, 1, 0]),
        ...                (Fraction(1, 2), 3))
        >>> rows.find_many([0, 0, 1, 2], [2, 1, 2, 0])
        [3, Fraction(1, 2), Fraction(1, 2), None]
        """
        u = np.asarray(tails, dtype=np.int64)
        v = np.asarray(heads, dtype=np.int64)
        if u.size == 0 or self._heads.size == 0:
            return [None] * int(u.size)
        pos = self._positions(u, v)
        found = (pos >= 0).tolist()
        if len(self._values) == 1:
            w = self._values[0]
            return [w if ok else None for ok in found]
        values = self._values
        codes = self._codes[np.maximum(pos, 0)].tolist()
        return [values[c] if ok else None for c, ok in zip(codes, found, strict=True)]

    def _positions(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        """The position of the first arc ``u[k] -> v[k]`` for each ``k`` (-1: none), by one
        binary search each in the arcs' ``tail·n + head`` keys (built once, sorted once)."""
        if self._keys is None:
            tails = np.repeat(np.arange(self._n, dtype=np.int64), np.diff(self._bounds))
            keys = tails * self._n + self._heads.astype(np.int64)
            if keys.size and bool(np.any(keys[1:] < keys[:-1])):
                self._order = np.argsort(keys, kind="stable")
                keys = keys[self._order]
            self._keys = keys
        keys, query = self._keys, u * self._n + v
        pos = np.searchsorted(keys, query)
        hit = pos < keys.size
        hit[hit] = keys[pos[hit]] == query[hit]
        if self._order is not None:
            pos[hit] = self._order[pos[hit]]
        return np.where(hit, pos, -1)

    def degree(self, u: int) -> int:
        """The number of arcs of ``u`` (without building its row)."""
        return int(self._bounds[u + 1] - self._bounds[u])

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Sequence):
            return NotImplemented
        return len(self) == len(other) and all(
            tuple(a) == tuple(b) for a, b in zip(self, other, strict=True))

    # defining __eq__ makes the class unhashable (Python sets __hash__ to None), like a list

    def __repr__(self) -> str:
        return f"ArcRows({self._n} nodes, {self._heads.size} arcs)"
