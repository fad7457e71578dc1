"""The kernel's two graph representations and the one operation its inequalities need.

Every arc inequality of proofs/KERNEL.md has the form ``X(v) <= k·w(v, u) + Y(u)`` for all arcs
``(v, u)``; :meth:`Graph.relax` gives ``min`` over the arcs of ``v`` of the right-hand side, so
each check is a comparison of two lists (Python integers over the witness's denominator, with
``float("inf")`` for +∞, which compares exactly with every integer and fraction).
:class:`Graph` holds adjacency lists; :class:`Grid` is a 4-connected unit-weight MovingAI map,
each direction one list of neighbour indices (no Python object per arc).
"""

from __future__ import annotations

import re
from fractions import Fraction
from itertools import compress, repeat
from operator import add
from typing import Any

from dppverify.kernel.verdict import BadInput


def exact(x: Fraction) -> int | Fraction:
    """``x`` as an ``int`` when it is integral (integers compare fastest).

    Examples
    --------
    >>> exact(Fraction(4, 2)), exact(Fraction(1, 2))
    (2, Fraction(1, 2))
    """
    return x.numerator if x.denominator == 1 else x


class Graph:
    """A digraph as adjacency lists: ``adj[v]`` = the ``(u, w(v, u))`` arcs of ``v``."""

    def __init__(self, adj: list[list[tuple[int, Fraction]]]) -> None:
        self.adj = adj
        self.n = len(adj)
        self._big = {v: dict(row) for v, row in enumerate(adj) if len(row) > 8}  # weight()

    def arcs(self, v: int) -> list[tuple[int, Fraction]]:
        """The arcs ``(u, w)`` leaving ``v``."""
        return self.adj[v]

    def weight(self, v: int, u: int) -> Fraction | None:
        """The weight of the arc ``v -> u`` (None when there is none): a scan of a short
        row, a dictionary for a node of many arcs (a hub of thousands of walks stays linear).

        Examples
        --------
        >>> g = Graph([[(u, Fraction(u)) for u in range(1, 20)]] + [[]] * 19)
        >>> g.weight(0, 7), g.weight(0, 0), g.weight(1, 0)
        (Fraction(7, 1), None, None)
        """
        big = self._big.get(v)
        return big.get(u) if big is not None else next((w for x, w in self.adj[v] if x == u), None)

    def relax(self, y: list[Any], k: Fraction, inf: float) -> list[Any]:
        """``M(v) = min over arcs (v, u) of k·w(v, u) + y(u)`` (``inf`` without arcs).

        Examples
        --------
        >>> Graph([[(1, Fraction(2))], []]).relax([5, 1], Fraction(1), float("inf"))
        [3, inf]
        """
        cost = {w: exact(k * w) for row in self.adj for _, w in row}
        out = []
        for row in self.adj:
            best = inf
            for u, w in row:
                t = cost[w] + y[u]
                if t < best:
                    best = t
            out.append(best)
        return out


class Grid:
    """A 4-connected MovingAI map with unit weights: free cells in row-major order.

    Cell ``(r, c)`` sits at position ``(r + 1)·W + c`` of a padded row-major list of width
    ``W = cols + 1`` with one blocked row above and below, so that the four neighbours of every
    free cell are the positions ``±1`` and ``±W``; ``nbr[k][v]`` is node ``v``'s neighbour in
    direction ``k`` (up, left, right, down), ``n`` where there is none.
    """

    def __init__(self, rows: int, cols: int, pos: list[int]) -> None:
        self.rows, self.cols, self.W = rows, cols, cols + 1
        self.pos, self.n = pos, len(pos)
        self.idx = idx = dict(zip(pos, range(self.n), strict=True))  # padded position -> node
        self.nbr = [list(map(idx.get, map(add, pos, repeat(d)), repeat(self.n)))
                    for d in (-self.W, -1, 1, self.W)]

    @classmethod
    def from_map(cls, data: bytes) -> Grid:
        """Read a ``.map`` file strictly (``docs/formats.md`` §1c; lines end in LF or CRLF).

        Examples
        --------
        >>> g = Grid.from_map(b"type octile\\nheight 2\\nwidth 3\\nmap\\n..@\\nT.G\\n")
        >>> g.n, g.cell(3), g.index_of((1, 1)), [u for u, _ in g.arcs(1)]
        (4, (1, 2), 2, [0, 2])
        """
        lines = [ln[:-1] if ln.endswith(b"\r") else ln for ln in data.split(b"\n")]
        head = re.fullmatch(rb"type octile\nheight (\d{1,9})\nwidth (\d{1,9})\nmap",
                            b"\n".join(lines[:4]))
        rows, cols = (int(head[1]), int(head[2])) if head else (0, 0)
        if not 0 < rows * cols <= 4_000_000:
            raise BadInput("map: not a MovingAI .map file the kernel reads (header)")
        body = lines[4:]
        while len(body) > rows and not body[-1].strip():
            body.pop()
        free = bytes.maketrans(b".GS@OTW", b"\1\1\1\0\0\0\0")
        pos: list[int] = []
        W = cols + 1
        for r, row in enumerate(body):
            if len(row) != cols or len(row.translate(None, b".GS@OTW")) or r >= rows:
                raise BadInput(f"map: line {5 + r} is not a row of {cols} map characters")
            pos.extend(compress(range((r + 1) * W, (r + 1) * W + cols), row.translate(free)))
        if len(body) != rows:
            raise BadInput(f"map: expected {rows} rows, found {len(body)}")
        return cls(rows, cols, pos)

    def index_of(self, cell: Any) -> int | None:
        """The node index of the cell ``(r, c)``, or None."""
        if not (type(cell) is tuple and len(cell) == 2 and all(type(x) is int for x in cell)):
            return None
        r, c = cell
        return self.idx.get((r + 1) * self.W + c) if 0 <= r < self.rows and 0 <= c < self.cols \
            else None

    def cell(self, v: int) -> tuple[int, int]:
        """The cell ``(r, c)`` of node ``v``."""
        r, c = divmod(self.pos[v], self.W)
        return (r - 1, c)

    def arcs(self, v: int) -> list[tuple[int, Fraction]]:
        """The arcs ``(u, 1)`` leaving ``v`` (its free neighbours, in node order)."""
        return [(d[v], Fraction(1)) for d in self.nbr if d[v] < self.n]

    def weight(self, v: int, u: int) -> Fraction | None:
        """The weight of the arc ``v -> u``: 1 between neighbours, else None."""
        return Fraction(1) if abs(self.pos[u] - self.pos[v]) in (1, self.W) else None

    def relax(self, y: list[Any], k: Fraction, inf: float) -> list[Any]:
        """:meth:`Graph.relax` on the grid: one shifted list per direction.

        Examples
        --------
        >>> g = Grid.from_map(b"type octile\\nheight 1\\nwidth 3\\nmap\\n.@.\\n")
        >>> g.relax([0, 5], Fraction(2), float("inf"))
        [inf, inf]
        """
        yy = [*y, inf]
        m = map(min, *(map(yy.__getitem__, d) for d in self.nbr))
        return list(map(add, m, repeat(exact(k))))
