"""A set of facet normals with its tables: the closures (cover tables of every normal), the
packing polytope's directions and their cover tables, shared between permuted right-hand sides.

The normals are closed under permutations of the goals (:func:`symmetric_closure`), so the
table of a right-hand side is that of its sorted permutation with the columns permuted
(:func:`symmetric_table`). With ``dominated`` the closure of ``a`` uses only the normals
``n <= a`` (the reading of ``docs/formats.md`` §2b by which the checker judges a written rule).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from functools import cache, cached_property

import numpy as np

from solver.coalitions.vertex_tables import (
    Direction,
    Normal,
    VertexTable,
    packing_vertices,
    vertex_table,
    zero_one_normals,
)


def symmetric_closure(normals: Sequence[Normal]) -> tuple[Normal, ...]:
    """The normals with every permutation of each, 0/1 vectors first (mask order), the others
    sorted decreasingly.

    Examples
    --------
    >>> symmetric_closure([(2, 2, 1)])
    ((1, 0, 0), (0, 1, 0), (1, 1, 0), (0, 0, 1), (1, 0, 1), (0, 1, 1), (1, 1, 1), (2, 2, 1), \
(2, 1, 2), (1, 2, 2))
    """
    n = len(normals[0])
    zo = zero_one_normals(n)
    extra = {p for a in normals for p in itertools.permutations(a)} - set(zo)
    return zo + tuple(sorted(extra, reverse=True))


@dataclass(frozen=True, eq=False)
class NormalSystem:
    """A normal set ``A`` with its tables: closures, packing directions, packing vertices.

    ``normals`` must be closed under permutations (:func:`symmetric_closure`); tables of
    permuted right-hand sides are shared. With ``dominated`` the closure of ``a`` uses only the
    normals ``n <= a`` (componentwise): the reading of ``docs/formats.md`` §2b by which the
    checker judges a written rule; its values need not be closed, so every direction of the
    packing polytope is tested, the 0/1 ones included.
    """

    normals: tuple[Normal, ...]
    dominated: bool = False
    tops: np.ndarray = field(init=False, repr=False)
    closures: tuple[VertexTable, ...] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "tops", np.array([max(a) for a in self.normals],
                                                  dtype=np.int64))
        if self.dominated:
            closures = tuple(_dominated_table(self.normals, a) for a in self.normals)
        else:
            closures = tuple(symmetric_table(self.normals, a) for a in self.normals)
        object.__setattr__(self, "closures", closures)

    @cached_property
    def by_vertices(self) -> bool:
        """Whether the arc test goes by the vertices of the sets (:mod:`~solver.coalitions.
        arc_vertices`): with extra normals whose packing polytope has more than
        :data:`DIRECTION_BASES` bases to enumerate (the direction test's tables would be
        large), or whose direction tables would not fit a part."""
        n = self.n_goals
        if len(self.normals) == 2 ** n - 1:
            return False
        if math.comb(len(self.normals) + n, n) > DIRECTION_BASES:
            return True
        try:
            _ = self.directions
        except (ValueError, OverflowError):
            return True
        return False

    @cached_property
    def directions(self) -> tuple[Direction, ...]:
        """The packing polytope's directions with their cover tables (every one with
        ``dominated``, else the non-0/1 ones)."""
        return packing_directions_symmetric(self.normals, self.dominated)

    @property
    def n_goals(self) -> int:
        """``N``."""
        return len(self.normals[0])

    @property
    def lcm(self) -> int:
        """The lcm of the closure tables' denominators (over every part)."""
        return math.lcm(1, *(lcm for t in self.closures for _, lcm in t.parts))


DIRECTION_BASES = 200_000
"""Above this many bases of the packing polytope (``C(|A| + N, N)``) a system with extra
normals is tested by the vertices of its sets instead of the packing directions."""


def symmetric_table(normals: tuple[Normal, ...], rhs: Normal) -> VertexTable:
    """The cover table of ``rhs`` from that of its sorted permutation (normals closed under
    permutations).

    Examples
    --------
    >>> zo = zero_one_normals(3)
    >>> a = symmetric_table(zo, (1, 0, 1)).vertices()
    >>> b = vertex_table(zo, (1, 0, 1)).vertices()
    >>> sorted(sorted(v.items()) for v in a) == sorted(sorted(v.items()) for v in b)
    True
    """
    n = len(rhs)
    order = sorted(range(n), key=lambda i: (-rhs[i], i))  # sorted[k] = rhs[order[k]]
    base = vertex_table(normals, tuple(rhs[i] for i in order))
    inv = [0] * n
    for k, i in enumerate(order):
        inv[i] = k
    index = {v: j for j, v in enumerate(normals)}
    cols = tuple(index[tuple(normals[j][inv[i]] for i in range(n))] for j in base.columns)
    return VertexTable(columns=cols, scaled=base.scaled, lcm=base.lcm, more=base.more)


def _dominated_table(normals: tuple[Normal, ...], a: Normal) -> VertexTable:
    """The covers of ``a`` by the normals ``n <= a`` (``a`` itself included: the step)."""
    keep = [j for j, n in enumerate(normals) if all(x <= y for x, y in zip(n, a, strict=True))]
    sub = vertex_table(tuple(normals[j] for j in keep), a)
    return VertexTable(columns=tuple(keep[c] for c in sub.columns), scaled=sub.scaled,
                       lcm=sub.lcm, more=sub.more)


@cache
def packing_directions_symmetric(normals: tuple[Normal, ...], every: bool = False
                                 ) -> tuple[Direction, ...]:
    """:func:`solver.coalitions.vertex_tables.packing_directions` with the cover tables shared
    by symmetry (``every``: the 0/1 directions too)."""
    out = []
    for d in packing_directions_raw(normals, every):
        s, y, lams, lcm = d
        cover = symmetric_table(normals, tuple(int(x * s) for x in y))
        out.append(Direction(y, s, cover, lams, lcm))
    return tuple(out)


@cache
def packing_directions_raw(normals: tuple[Normal, ...], every: bool = False
                           ) -> tuple[tuple[int, tuple[Fraction, ...], np.ndarray, int], ...]:
    """``(s, y, lam_lcm · λs, lam_lcm)`` per non-0/1 direction of the packing vertices (every
    non-zero direction with ``every``)."""
    n = len(normals[0])
    groups: dict[tuple[Fraction, ...], list[tuple[Fraction, ...]]] = {}
    for lam in packing_vertices(normals):
        y = tuple(sum((lam[j] * normals[j][i] for j in range(len(normals)) if lam[j]),
                      Fraction(0)) for i in range(n))
        if not any(y) or (not every and all(x in (0, 1) for x in y)):
            continue
        groups.setdefault(y, []).append(lam)
    out = []
    for y, lams in sorted(groups.items()):
        s = math.lcm(*(x.denominator for x in y))
        lcm = math.lcm(*(x.denominator for lam in lams for x in lam))
        arr = np.array([[int(x * lcm) for x in lam] for lam in lams], dtype=np.int64)
        out.append((s, y, arr, lcm))
    return tuple(out)
