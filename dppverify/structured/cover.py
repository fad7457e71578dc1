"""Fractional covers of a set of goals by subsets: exact vertices and an exact simplex.

Goal subsets are bitmasks (bit θ = type θ). A *fractional cover* of a weight vector ``r`` by a
family of subsets is ``c >= 0`` with ``Σ_T c_T 1_T = r``. Two exact tools:

- :func:`balanced_vertices`: the vertices of ``{c >= 0 : Σ_{T ⊊ S} c_T 1_T = 1_S}`` for the
  ground set ``S = {0, …, s-1}`` — the *minimal balanced collections* of cooperative game
  theory (Shapley), 1, 5, 41 and 1291 of them for ``s = 2 … 5``. Computed once per ``s``
  by enumerating all ``s``-column bases with exact integer determinants (Leibniz formula,
  vectorised) and Cramer's rule; nothing is decided in floating point.
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

__all__ = ["BalancedVertices", "CoverLP", "balanced_vertices", "members", "min_cover",
           "min_cover_vectors", "popcount"]

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


def _dets(entries: Sequence[Sequence[np.ndarray]]) -> np.ndarray:
    """Exact integer determinants of a batch of small integer matrices.

    ``entries[r][c]`` holds entry ``(r, c)`` of every matrix (a 1-D int64 array). Laplace
    expansion bottom-up over column subsets: the minor of the last ``j`` rows on a ``j``-column
    set ``C`` is ``Σ_{c ∈ C} ± M[s-j, c] · minor(C - c)``.
    """
    s = len(entries)
    minors: dict[int, np.ndarray] = {0: np.ones_like(entries[0][0])}
    for j in range(1, s + 1):
        row = s - j
        nxt: dict[int, np.ndarray] = {}
        for cols in itertools.combinations(range(s), j):
            mask = sum(1 << c for c in cols)
            acc = np.zeros_like(entries[0][0])
            for pos, c in enumerate(cols):
                term = entries[row][c] * minors[mask & ~(1 << c)]
                acc = acc - term if pos % 2 else acc + term
            nxt[mask] = acc
        minors = nxt
    return minors[(1 << s) - 1]


@cache
def balanced_vertices(size: int) -> BalancedVertices:
    """The minimal balanced collections of ``{0, …, size-1}`` as exact cover vertices.

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
    full = (1 << size) - 1
    columns = tuple(range(1, full))
    incidence = np.array([[(t >> i) & 1 for t in columns] for i in range(size)], dtype=np.int64)
    combos = np.array(list(itertools.combinations(range(len(columns)), size)), dtype=np.int64)
    entries = [[np.ascontiguousarray(incidence[r, combos[:, c]]) for c in range(size)]
               for r in range(size)]
    det = _dets(entries)
    keep = det != 0
    combos, det = combos[keep], det[keep]
    entries = [[e[keep] for e in row] for row in entries]
    ones = np.ones(combos.shape[0], dtype=np.int64)
    numer = np.empty((combos.shape[0], size), dtype=np.int64)
    for i in range(size):  # Cramer: column i replaced by the right-hand side 1_S
        numer[:, i] = _dets([[ones if c == i else row[c] for c in range(size)]
                             for row in entries])
    sign = np.sign(det)[:, None]
    feasible = np.all(numer * sign >= 0, axis=1)
    combos, det, numer = combos[feasible], det[feasible], numer[feasible]
    common = int(np.lcm.reduce(np.abs(det)))  # every c = numer/det is a multiple of 1/common
    dense = np.zeros((combos.shape[0], len(columns)), dtype=np.int64)
    rows = np.arange(combos.shape[0])
    for i in range(size):
        dense[rows, combos[:, i]] = numer[:, i] * (common // det)
    unique = np.unique(dense, axis=0)  # degenerate vertices have several bases
    vertices = [tuple(Fraction(int(x), common) for x in row) for row in unique.tolist()]
    lcm = math.lcm(*(c.denominator for v in vertices for c in v))
    scaled = np.array([[int(v[j] * lcm) for v in vertices] for j in range(len(columns))],
                      dtype=np.int64)
    return BalancedVertices(size=size, columns=columns, vertices=tuple(vertices), lcm=lcm,
                            scaled=scaled)


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
        Positive weights, one per goal.

    Raises
    ------
    ValueError
        If a singleton is missing or a weight is not positive.

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
    if any(x <= 0 for x in r):
        raise ValueError("min_cover: every weight must be positive")
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
