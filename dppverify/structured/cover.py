"""Fractional covers of goals by subsets and by integer normals: exact vertices, exact simplex.

Goal subsets are bitmasks (bit θ = goal index θ). A *fractional cover* of a weight vector ``r``
by a family of columns (subsets as 0/1 vectors, or non-negative integer *normals*) is
``c >= 0`` with ``Σ_j c_j columns[j] = r``. The one vertex enumeration and the one exact LP of
the structured route:

- :func:`basic_solutions`: every vertex of ``{c >= 0 : Σ_j c_j columns[j] = rhs}`` as an
  integer table (the exact bases of :mod:`dppverify.structured.exact_bases`: int64 under
  Hadamard's bound, else Python integers; nothing is decided in floating point).
  :func:`symmetric_table` shares one table between permuted right-hand sides.
- :func:`balanced_vertices`: the vertices of ``{c >= 0 : Σ_{T ⊊ S} c_T 1_T = 1_S}`` for the
  ground set ``S = {0, …, s-1}`` — the *minimal balanced collections* of cooperative game
  theory (Shapley), 1, 5, 41 and 1291 of them for ``s = 2 … 5``.
- :func:`cheapest`: ``min`` over a table's vertices of ``values · c`` at every row, exactly.
- :func:`min_cover`: ``min Σ_T c_T m_T`` over covers of any positive ``r`` by all non-empty
  subsets, by the primal simplex method in exact rationals (Bland's rule), starting from the
  feasible basis of singletons. It returns the optimal dual ``π`` too, which certifies the
  optimum: ``π(T) <= m_T`` for every subset and ``r·π`` equals the value.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from functools import cache

import numpy as np

from dppverify.game.distances import EXACT_FLOAT_LIMIT
from dppverify.structured.exact_bases import INT_SAFE, basic_feasible_solutions

__all__ = ["MAX_BALANCED", "BalancedVertices", "CoverLP", "Normal", "Table", "balanced_vertices",
           "basic_solutions", "cheapest", "members", "min_cover", "min_cover_vectors", "popcount",
           "symmetric_table", "zero_one_normals"]

Normal = tuple[int, ...]
"""A facet normal (or cover column): a non-negative integer vector, one entry per goal index."""

MAX_BALANCED = 5
"""Largest ground set whose minimal balanced collections are enumerated (1291 at 5)."""


def popcount(mask: int) -> int:
    """Number of goals in a subset mask.

    Examples
    --------
    >>> popcount(0b1011)
    3
    """
    return bin(mask).count("1")


def members(mask: int) -> tuple[int, ...]:
    """The goals (bit positions) of a subset mask, increasing.

    Examples
    --------
    >>> members(0b1011)
    (0, 1, 3)
    """
    return tuple(i for i in range(mask.bit_length()) if mask >> i & 1)


@dataclass(frozen=True)
class BalancedVertices:
    """The vertices of the fractional partition polytope of ``{0, …, s-1}``.

    Attributes
    ----------
    size : int
        ``s``.
    columns : tuple of int
        The proper non-empty subsets (masks ``1 … 2^s - 2``), in increasing order.
    vertices : tuple of tuple of Fraction
        One vertex per entry: the coefficient ``c_T`` of every column (most are 0).
    lcm : int
        The least common multiple of all coefficients' denominators.
    scaled : numpy.ndarray of int64
        ``lcm · c``: shape ``(len(columns), len(vertices))``, exact integers.
    """

    size: int
    columns: tuple[int, ...]
    vertices: tuple[tuple[Fraction, ...], ...]
    lcm: int
    scaled: np.ndarray


@dataclass(frozen=True)
class Table:
    """The vertices of ``{c >= 0 : Σ_j c_j columns[j] = rhs}``, scaled to integers.

    Attributes
    ----------
    columns : tuple of int
        Indices of the columns (into the caller's list) that may be positive.
    scaled : numpy.ndarray
        ``lcm · c`` for every vertex: shape ``(len(columns), n_vertices)``, int64.
    lcm : int
        Common denominator of every vertex coordinate.
    """

    columns: tuple[int, ...]
    scaled: np.ndarray
    lcm: int

    @property
    def vertices(self) -> list[tuple[Fraction, ...]]:
        """The vertices as exact fractions (one entry per column)."""
        return [tuple(Fraction(int(x), self.lcm) for x in col) for col in self.scaled.T]


def basic_solutions(columns: Sequence[Sequence[int]], rhs: Sequence[int]) -> Table:
    """Every vertex of ``{c >= 0 : Σ_j c_j columns[j] = rhs}`` (non-negative integer data).

    Rows outside the support of ``rhs`` force the columns that use them to 0; on the
    support, the unit vectors must be among the columns (full row rank). The vertices are the
    basic feasible solutions: every choice of ``|support|`` columns with a non-zero exact
    integer determinant, solved by Cramer's rule, kept when non-negative, reduced to lowest
    terms and de-duplicated (a degenerate vertex has several bases). The determinants are
    int64 (vectorised) when Hadamard's bound proves every minor and every sum of the Laplace
    expansion below ``2^62``, else Python integers by fraction-free elimination; the table is
    int64 when its scaled vertices fit, else an array of Python integers (storage only).

    Examples
    --------
    The fractional covers of (1, 1, 1) by the non-empty subsets of three goals (as 0/1
    columns): the five minimal balanced collections plus the whole set itself.

    >>> t = basic_solutions(zero_one_normals(3), (1, 1, 1))
    >>> t.scaled.shape[1], t.lcm
    (6, 2)
    """
    rhs = tuple(int(x) for x in rhs)
    return _basic_solutions(tuple(tuple(int(x) for x in c) for c in columns), rhs)


@cache
def _basic_solutions(columns: tuple[Normal, ...], rhs: Normal) -> Table:
    rows = [i for i, x in enumerate(rhs) if x != 0]
    keep = [j for j, c in enumerate(columns)
            if any(c) and all(c[i] == 0 for i in range(len(rhs)) if rhs[i] == 0)]
    m = len(rows)
    if m == 0:
        return Table(columns=(), scaled=np.zeros((0, 1), dtype=np.int64), lcm=1)
    mat = [[columns[j][i] for j in keep] for i in rows]
    b = [rhs[i] for i in rows]
    found = basic_feasible_solutions(mat, b)
    ordered = sorted(found)
    lcm = math.lcm(1, *(den for _, den in ordered))
    cols = [[x * (lcm // den) for x in numer] for numer, den in ordered]
    top = max((x for col in cols for x in col), default=0)
    if top < INT_SAFE:
        scaled = np.array(cols, dtype=np.int64).reshape(len(cols), len(keep)).T.copy()
    else:  # the common denominator leaves int64: the table holds Python integers
        scaled = np.empty((len(keep), len(cols)), dtype=object)
        for v, col in enumerate(cols):
            for i, x in enumerate(col):
                scaled[i, v] = x
    return Table(columns=tuple(keep), scaled=scaled, lcm=lcm)


def symmetric_table(normals: tuple[Normal, ...], rhs: Normal) -> Table:
    """:func:`basic_solutions` by symmetry: the table of the sorted ``rhs``, columns permuted.

    When ``normals`` is not closed under permutations of the goals (the 0/1 vectors are), the
    table is enumerated directly.

    Examples
    --------
    >>> def covers(t):
    ...     return sorted(sorted(zip(t.columns, v)) for v in t.vertices)
    >>> zo = zero_one_normals(3)
    >>> covers(symmetric_table(zo, (1, 2, 1))) == covers(basic_solutions(zo, (1, 2, 1)))
    True
    """
    n = len(rhs)
    if not _permutation_closed(tuple(tuple(x) for x in normals)):
        return basic_solutions(normals, rhs)
    order = sorted(range(n), key=lambda i: (-rhs[i], i))  # srt[k] = rhs[order[k]]
    base = basic_solutions(normals, tuple(rhs[i] for i in order))
    inv = [0] * n
    for k, i in enumerate(order):
        inv[i] = k
    index = {v: j for j, v in enumerate(normals)}
    cols = tuple(index[tuple(normals[j][inv[i]] for i in range(n))] for j in base.columns)
    return Table(columns=cols, scaled=base.scaled, lcm=base.lcm)


@cache
def _permutation_closed(normals: tuple[Normal, ...]) -> bool:
    """Whether every permutation of every normal is in the set (then tables are shared)."""
    have = set(normals)
    return all(tuple(p) in have for a in normals for p in itertools.permutations(a))


def zero_one_normals(n_goals: int) -> tuple[Normal, ...]:
    """The 0/1 normals ``1_S`` in mask order (``mask = 1 … 2^N - 1``).

    Examples
    --------
    >>> zero_one_normals(2)
    ((1, 0), (0, 1), (1, 1))
    """
    return tuple(tuple((s >> i) & 1 for i in range(n_goals)) for s in range(1, 1 << n_goals))


@cache
def balanced_vertices(size: int) -> BalancedVertices:
    """The minimal balanced collections of ``{0, …, size-1}`` as exact cover vertices.

    The vertices of :func:`basic_solutions` for the proper non-empty subsets and ``1_S``.

    Parameters
    ----------
    size : int
        ``2 <= size <= 5``.

    Examples
    --------
    >>> [len(balanced_vertices(s).vertices) for s in (2, 3, 4)]
    [1, 5, 41]
    >>> bv = balanced_vertices(3)
    >>> sorted(tuple((bv.columns[i], str(c)) for i, c in enumerate(v) if c)
    ...        for v in bv.vertices)[0]
    ((1, '1'), (2, '1'), (4, '1'))
    >>> bv.lcm
    2
    """
    if not 2 <= size <= MAX_BALANCED:
        raise ValueError(f"balanced collections are tabulated for 2 to {MAX_BALANCED} goals, "
                         f"not {size}")
    proper = zero_one_normals(size)[:-1]  # masks 1 … 2^size - 2: column j is mask j + 1
    table = basic_solutions(proper, (1,) * size)
    assert table.columns == tuple(range(len(proper)))  # every proper subset may be positive
    return BalancedVertices(size=size, columns=tuple(range(1, len(proper) + 1)),
                            vertices=tuple(table.vertices), lcm=table.lcm, scaled=table.scaled)


def cheapest(values: np.ndarray, scaled: np.ndarray) -> np.ndarray:
    """Row-wise ``min`` of ``values @ scaled`` for non-negative integers, exactly.

    ``values`` holds one row per node and one column per cover column, ``scaled`` a table's
    integer vertices (:attr:`Table.scaled`): the cheapest cover at every row, times the
    table's ``lcm``. float64 BLAS when every partial sum is provably an integer below 2^53,
    else Python integers.

    Examples
    --------
    >>> t = basic_solutions(zero_one_normals(2), (1, 1))
    >>> cheapest(np.array([[2, 3, 4], [2, 3, 6]]), t.scaled).tolist()
    [4, 5]
    """
    top = int(values.max(initial=0)) if values.size else 0
    width = (top + 1) * (int(np.abs(scaled).sum(axis=0).max(initial=1)) + 1)
    if width < EXACT_FLOAT_LIMIT:
        return (values.astype(np.float64) @ scaled.astype(np.float64)).min(axis=1).astype(
            np.int64)
    return (values.astype(object) @ scaled.astype(object)).min(axis=1)


@dataclass(frozen=True)
class CoverLP:
    """The optimum of :func:`min_cover`: value, primal cover and certifying dual.

    Attributes
    ----------
    value : Fraction
        ``min Σ_T c_T m_T``.
    cover : Mapping
        Subset mask -> ``c_T > 0`` (the optimal basic solution's support).
    dual : tuple of Fraction
        ``π`` with ``π(T) <= m_T`` for every subset and ``Σ_θ r_θ π_θ = value``.
    """

    value: Fraction
    cover: Mapping[int, Fraction]
    dual: tuple[Fraction, ...]


def min_cover(costs: Mapping[int, Fraction | int], rhs: Sequence[Fraction | int]) -> CoverLP:
    """``min Σ_T c_T costs[T]`` s.t. ``Σ_T c_T 1_T = rhs``, ``c >= 0``, exactly.

    Parameters
    ----------
    costs : Mapping
        Subset mask -> cost; every singleton must be present (it gives the start basis).
        Masks absent from ``costs`` are not available.
    rhs : sequence
        Non-negative weights, one per goal (a zero: a goal no type mass is on, e.g. a goal the
        goal-selection Attacker never chooses).

    Raises
    ------
    ValueError
        If a singleton is missing or a weight is negative.

    Examples
    --------
    Three goals whose pairs each cost 2 and singletons 2: the cheapest cover of ``(1, 1, 1)``
    takes every pair with weight 1/2 (cost 3), cheaper than a pair plus a singleton (4):

    >>> costs = {1: 2, 2: 2, 4: 2, 3: 2, 5: 2, 6: 2, 7: 5}
    >>> lp = min_cover(costs, (1, 1, 1))
    >>> lp.value, sorted(lp.cover.items()), lp.dual
    (Fraction(3, 1), [(3, Fraction(1, 2)), (5, Fraction(1, 2)), (6, Fraction(1, 2))], \
(Fraction(1, 1), Fraction(1, 1), Fraction(1, 1)))
    """
    r = [Fraction(x) for x in rhs]
    if any(x < 0 for x in r):
        raise ValueError("min_cover: every weight must be non-negative")
    n = len(r)
    cols = sorted(costs)
    for i in range(n):
        if (1 << i) not in costs:
            raise ValueError(f"min_cover: the singleton of goal {i} has no cost")
    vectors = [tuple((t >> j) & 1 for j in range(n)) for t in cols]
    lp = min_cover_vectors(vectors, [costs[t] for t in cols], r)
    return CoverLP(value=lp.value, cover={cols[j]: c for j, c in lp.cover.items()},
                   dual=lp.dual)


def min_cover_vectors(columns: Sequence[Sequence[int]], costs: Sequence[Fraction | int],
                      rhs: Sequence[Fraction | int]) -> CoverLP:
    """``min Σ_j c_j costs[j]`` s.t. ``Σ_j c_j columns[j] = rhs``, ``c >= 0``, exactly.

    The primal simplex method in exact rationals (Bland's rule) from the basis of the unit
    vectors, which must be among the (non-negative integer) ``columns``. The cover is keyed
    by column index; the dual ``π`` satisfies ``π·columns[j] <= costs[j]`` for every ``j``.

    Examples
    --------
    Covering (2, 2, 2, 1) by pairs and the triple {2, 3, 4} (index 4 and up):

    >>> cols = [(1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0, 0, 0, 1), (1, 1, 0, 0),
    ...         (1, 0, 1, 0), (0, 1, 1, 1)]
    >>> lp = min_cover_vectors(cols, [2, 2, 2, 2, 2, 2, 2], (2, 2, 2, 1))
    >>> lp.value, sorted(lp.cover.items())
    (Fraction(6, 1), [(4, Fraction(1, 1)), (5, Fraction(1, 1)), (6, Fraction(1, 1))])
    """
    n = len(rhs)
    r = [Fraction(x) for x in rhs]
    if any(x < 0 for x in r):
        raise ValueError("min_cover: every weight must be non-negative")
    vecs = [tuple(int(x) for x in c) for c in columns]
    cost = [Fraction(c) for c in costs]
    basis = []
    for i in range(n):
        unit = tuple(int(i == j) for j in range(n))
        if unit not in vecs:
            raise ValueError(f"min_cover: the unit vector of goal {i} is not a column")
        basis.append(vecs.index(unit))  # basis[row] = column; B^{-1} tracked explicitly
    binv = [[Fraction(int(i == j)) for j in range(n)] for i in range(n)]
    xb = list(r)
    while True:
        # duals: π = c_B B^{-1}
        pi = [sum((cost[basis[i]] * binv[i][j] for i in range(n)), Fraction(0))
              for j in range(n)]
        entering = None
        for t, vec in enumerate(vecs):  # Bland: smallest index with negative reduced cost
            if t in basis:
                continue
            reduced = cost[t] - sum((pi[j] * vec[j] for j in range(n) if vec[j]), Fraction(0))
            if reduced < 0:
                entering = t
                break
        if entering is None:
            value = sum((cost[basis[i]] * xb[i] for i in range(n)), Fraction(0))
            cover = {basis[i]: xb[i] for i in range(n) if xb[i] != 0}
            return CoverLP(value=value, cover=cover, dual=tuple(pi))
        col = [Fraction(vecs[entering][j]) for j in range(n)]
        dcol = [sum((binv[i][j] * col[j] for j in range(n)), Fraction(0)) for i in range(n)]
        best: tuple[Fraction, int, int] | None = None
        for i in range(n):
            if dcol[i] > 0:
                ratio = xb[i] / dcol[i]
                key = (ratio, basis[i], i)
                if best is None or key[:2] < best[:2]:
                    best = key
        if best is None:  # pragma: no cover - the polytope is bounded (non-negative columns)
            raise AssertionError("min_cover: unbounded")
        _, _, leave = best
        piv = dcol[leave]
        binv[leave] = [x / piv for x in binv[leave]]
        xb[leave] = xb[leave] / piv
        for i in range(n):
            if i != leave and dcol[i] != 0:
                f = dcol[i]
                binv[i] = [a - f * b for a, b in zip(binv[i], binv[leave], strict=True)]
                xb[i] = xb[i] - f * xb[leave]
        basis[leave] = entering
