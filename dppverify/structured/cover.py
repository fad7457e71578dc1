"""Fractional covers of goals by subsets and by integer normals: exact vertices, exact simplex.

Goal subsets are bitmasks (bit θ = goal index θ). A *fractional cover* of a weight vector ``r``
by a family of columns (subsets as 0/1 vectors, or non-negative integer *normals*) is
``c >= 0`` with ``Σ_j c_j columns[j] = r``. The one vertex enumeration and the one exact LP of
the structured route:

- :func:`basic_solutions`: every vertex of ``{c >= 0 : Σ_j c_j columns[j] = rhs}`` — every
  choice of ``|support of rhs|`` columns with a non-zero exact integer determinant, solved by
  Cramer's rule, kept when non-negative; vectorised int64 determinants (:func:`dets`: Laplace
  expansion) where Hadamard's bound keeps every minor below ``2^62``, else one basis at a time
  in Python integers (:func:`bareiss_det`); nothing is decided in floating point.
  :func:`symmetric_table` shares one table between permuted right-hand sides.
- :func:`balanced_vertices`: the vertices of ``{c >= 0 : Σ_{T ⊊ S} c_T 1_T = 1_S}`` for the
  ground set ``S = {0, …, s-1}`` — the *minimal balanced collections* of cooperative game
  theory (Shapley), 1, 5, 41 and 1291 of them for ``s = 2 … 5``.
- :func:`packing_vertices`: the vertices of the packing polytope ``{λ >= 0 : Σ_n λ_n n <= 1}``
  of a set of normals (the arc certificate of ``proofs/NGOAL.md`` NG.8).
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

__all__ = ["MAX_BALANCED", "BalancedVertices", "CoverLP", "Normal", "Table", "balanced_vertices",
           "basic_solutions", "cheapest", "dets", "members", "min_cover", "min_cover_vectors",
           "packing_directions", "packing_vertices", "popcount", "symmetric_table",
           "zero_one_normals"]

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


def dets(entries: Sequence[Sequence[np.ndarray]]) -> np.ndarray:
    """Exact integer determinants of a batch of small integer matrices.

    ``entries[r][c]`` holds entry ``(r, c)`` of every matrix (a 1-D int64 array). Laplace
    expansion bottom-up over column subsets: the minor of the last ``j`` rows on a ``j``-column
    set ``C`` is ``Σ_{c ∈ C} ± M[s-j, c] · minor(C - c)``. Where a minor could leave int64
    (``s!·max|entry|^s >= 2^62``) the arithmetic is in Python integers (an object array).

    Examples
    --------
    The determinants of ``[[2, 1], [1, 1]]`` and ``[[0, 1], [1, 0]]``:

    >>> a = np.array
    >>> dets([[a([2, 0]), a([1, 1])], [a([1, 1]), a([1, 0])]]).tolist()
    [1, -1]
    """
    s = len(entries)
    top = max((int(np.abs(e).max(initial=0)) for row in entries for e in row), default=0)
    if math.factorial(s) * max(top, 1) ** s >= 2 ** 62:  # |minor| <= j!·top^j: Python ints
        entries = [[np.asarray(e, dtype=object) for e in row] for row in entries]
    return _laplace(entries)


def _laplace(entries: Sequence[Sequence[np.ndarray]]) -> np.ndarray:
    """:func:`dets` in the arrays' own dtype (the caller bounds every minor)."""
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


INT_SAFE = 2 ** 62
"""Every integer the int64 path of :func:`basic_solutions` computes stays below this."""


def bareiss_det(mat: Sequence[Sequence[int]]) -> int:
    """The determinant of a square integer matrix by fraction-free (Bareiss) elimination.

    Every intermediate entry is a minor of ``mat``, so the integers stay as small as the
    answer allows; exact Python integers throughout.

    Examples
    --------
    >>> bareiss_det([[2, 1], [1, 1]]), bareiss_det([[0, 1], [1, 0]]), bareiss_det([[1, 2], [2, 4]])
    (1, -1, 0)
    """
    a = [list(row) for row in mat]
    n = len(a)
    sign, prev = 1, 1
    for k in range(n - 1):
        if a[k][k] == 0:
            swap = next((i for i in range(k + 1, n) if a[i][k] != 0), None)
            if swap is None:
                return 0
            a[k], a[swap] = a[swap], a[k]
            sign = -sign
        for i in range(k + 1, n):
            for j in range(k + 1, n):
                a[i][j] = (a[i][j] * a[k][k] - a[i][k] * a[k][j]) // prev
        prev = a[k][k]
    return sign * a[n - 1][n - 1] if n else 1


def _hadamard_safe(vectors: Sequence[Sequence[int]], m: int) -> bool:
    """Whether every ``m × m`` minor of the vectors (and a sum of ``m + 1`` products of one
    with an entry) stays below :data:`INT_SAFE`: Hadamard's bound ``Π ||v||`` over the ``m``
    longest vectors, times the longest once more and ``2^6`` for the sums, compared squared."""
    squares = sorted((sum(x * x for x in v) for v in vectors), reverse=True)
    return math.prod(squares[:m]) * max(squares[0], 1) * 2 ** 12 < INT_SAFE ** 2


Vertex = tuple[tuple[int, ...], int]
"""A basic solution as ``(numerators over the kept columns, denominator > 0)``, reduced."""


def _vertices_int64(mat: list[list[int]], b: list[int]) -> set[Vertex]:
    """The basic feasible solutions by vectorised int64 determinants (the caller has checked
    Hadamard's bound, so every determinant and Cramer numerator is exact)."""
    m, k = len(mat), len(mat[0])
    arr = np.array(mat, dtype=np.int64)
    found: set[Vertex] = set()
    all_combos = itertools.combinations(range(k), m)
    while True:
        chunk = np.array(list(itertools.islice(all_combos, 200_000)), dtype=np.int64)
        if chunk.size == 0:
            return found
        entries = [[np.ascontiguousarray(arr[r, chunk[:, c]]) for c in range(m)]
                   for r in range(m)]
        det = _laplace(entries)
        ok = det != 0
        if not ok.any():
            continue
        chunk, det = chunk[ok], det[ok]
        entries = [[e[ok] for e in row] for row in entries]
        numer = np.empty((chunk.shape[0], m), dtype=np.int64)
        for i in range(m):  # Cramer: column i replaced by the right-hand side
            numer[:, i] = _laplace([[np.full(chunk.shape[0], b[r], dtype=np.int64) if c == i
                                 else entries[r][c] for c in range(m)] for r in range(m)])
        sign = np.where(det > 0, 1, -1)
        numer *= sign[:, None]
        det = det * sign
        feas = np.all(numer >= 0, axis=1)
        chunk, det, numer = chunk[feas], det[feas], numer[feas]
        if not chunk.size:
            continue
        g = np.gcd.reduce(np.concatenate([numer, det[:, None]], axis=1), axis=1)
        numer //= g[:, None]
        det //= g
        dense = np.zeros((chunk.shape[0], k + 1), dtype=np.int64)
        dense[np.arange(chunk.shape[0])[:, None], chunk] = numer
        dense[:, k] = det
        for row in np.unique(dense, axis=0).tolist():  # degenerate vertices have several bases
            found.add((tuple(row[:k]), row[k]))


def _vertices_exact(mat: list[list[int]], b: list[int]) -> set[Vertex]:
    """The basic feasible solutions one basis at a time in Python integers (Bareiss
    determinants and Cramer's rule): exact for entries of any size."""
    m, k = len(mat), len(mat[0])
    found: set[Vertex] = set()
    for combo in itertools.combinations(range(k), m):
        sub = [[mat[r][c] for c in combo] for r in range(m)]
        det = bareiss_det(sub)
        if det == 0:
            continue
        numer = [bareiss_det([[b[r] if c == i else sub[r][c] for c in range(m)]
                              for r in range(m)]) for i in range(m)]
        if det < 0:
            det, numer = -det, [-x for x in numer]
        if any(x < 0 for x in numer):
            continue
        g = math.gcd(det, *numer)
        dense = [0] * k
        for pos, c in enumerate(combo):
            dense[c] = numer[pos] // g
        found.add((tuple(dense), det // g))
    return found


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
    vectors = [[columns[j][i] for i in rows] for j in keep] + [b]
    found = (_vertices_int64(mat, b) if _hadamard_safe(vectors, m)
             else _vertices_exact(mat, b))
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


@cache
def packing_vertices(normals: tuple[Normal, ...], every: bool = False
                     ) -> tuple[tuple[tuple[Fraction, ...], tuple[Fraction, ...]], ...]:
    """The vertices ``λ`` of ``{λ >= 0 : Σ_n λ_n n <= 1}`` with ``y_λ = Σ_n λ_n n`` not 0/1.

    Returned as pairs ``(λ, y_λ)``. Vertices whose ``y_λ`` is a 0/1 vector are left out unless
    ``every``: for closed support numbers the arc condition holds for them automatically
    (``proofs/NGOAL.md`` NG.8); ``λ = 0`` is always left out. Enumerated by their bases
    (:func:`_packing_bases`): a vertex whose ``y`` is not the all-ones vector has fewer than
    ``N`` basic normals, so only those bases are tried unless ``every``.

    Examples
    --------
    >>> len(packing_vertices(zero_one_normals(3)))
    0
    >>> sorted({y for _, y in packing_vertices(zero_one_normals(4))})[0]
    (Fraction(1, 2), Fraction(1, 1), Fraction(1, 1), Fraction(1, 1))
    """
    n = len(normals[0])
    out = set()
    for lam_sparse, y in _packing_bases(normals, n if every else n - 1):
        if any(x not in (0, 1) for x in y) or every:
            lam = [Fraction(0)] * len(normals)
            for j, c in lam_sparse:
                lam[j] = c
            out.add((tuple(lam), y))
    return tuple(sorted(out))


def _packing_bases(normals: tuple[Normal, ...], t_max: int
                   ) -> set[tuple[tuple[tuple[int, Fraction], ...], tuple[Fraction, ...]]]:
    """The vertices ``λ != 0`` of ``{λ >= 0 : Σ_n λ_n n <= 1}`` with at most ``t_max`` basic
    normals, as ``(((j, λ_j > 0), …), y_λ)``.

    A vertex has basic normals ``B`` and basic slacks ``S``; with ``T`` the other coordinates,
    ``y_T = 1``, ``B_T λ_B = 1_T`` (``B_T`` non-singular, ``|B| = |T|``), ``λ_B >= 0`` and
    ``y_S <= 1``: every choice of ``t = |B| = |T|`` normals and coordinates is tried, with exact
    integer determinants (vectorised; the entries are small). A degenerate vertex has several
    bases and is kept once.
    """
    n = len(normals[0])
    amat = np.array(normals, dtype=np.int64)  # K × n
    k = amat.shape[0]
    found: set[tuple[tuple[tuple[int, Fraction], ...], tuple[Fraction, ...]]] = set()
    seen: set[tuple[int, ...]] = set()
    for t in range(1, t_max + 1):
        combos_all = itertools.combinations(range(k), t)
        while True:
            combos = np.array(list(itertools.islice(combos_all, 200_000)), dtype=np.int64)
            if combos.size == 0:
                break
            cols = amat[combos]  # (C, t, n): the t normals of every combination
            for tset in itertools.combinations(range(n), t):
                entries = [[np.ascontiguousarray(cols[:, c, tset[r]]) for c in range(t)]
                           for r in range(t)]
                det = dets(entries)
                ok = det != 0
                if not ok.any():
                    continue
                sub = [[e[ok] for e in row] for row in entries]
                d = det[ok]
                ones = np.ones(d.size, dtype=np.int64)
                lam = np.stack([dets([[ones if c == i else sub[r][c] for c in range(t)]
                                      for r in range(t)]) for i in range(t)], axis=1)
                lam = lam * np.where(d > 0, 1, -1).astype(d.dtype)[:, None]  # λ·|det|
                feas = np.all(lam >= 0, axis=1)
                if not feas.any():
                    continue
                y = (lam[feas][:, :, None] * cols[ok][feas]).sum(axis=1)  # y·|det|
                ad = np.abs(d[feas])
                keep = np.all(y <= ad[:, None], axis=1)
                nums = np.concatenate([lam[feas][keep], y[keep], ad[keep][:, None]], axis=1)
                nums //= np.gcd.reduce(nums, axis=1)[:, None]  # lowest terms: one key per λ
                rows = np.concatenate([combos[ok][feas][keep], nums], axis=1)
                for row in np.unique(rows, axis=0).tolist():
                    seen.add(tuple(row))
        for row in seen:  # the same λ from another T: already in lowest terms, kept once
            den = row[-1]
            lam_row = tuple((j, Fraction(c, den)) for j, c in
                            zip(row[:t], row[t:2 * t], strict=True) if c)
            found.add((lam_row, tuple(Fraction(x, den) for x in row[2 * t:-1])))
        seen.clear()
    return found


@cache
def packing_directions(normals: tuple[Normal, ...]) -> tuple[tuple[Fraction, ...], ...]:
    """Every non-zero ``y_λ = Σ_n λ_n n`` over the vertices ``λ`` of ``{λ >= 0 : Σ_n λ_n n <= 1}``.

    Every such ``y`` has ``max y = 1`` (a vertex ``λ != 0`` has a tight row), and a vertex with
    ``N`` basic normals has ``y = 1``: so the directions are the all-ones vector and those of
    :func:`_packing_bases` with fewer than ``N`` basic normals. ``normals`` must contain the
    unit vectors.

    Examples
    --------
    >>> ys = packing_directions(zero_one_normals(4))
    >>> len(ys), sum(1 for y in ys if any(x not in (0, 1) for x in y))
    (19, 4)
    >>> len(packing_directions(zero_one_normals(5))) - 31
    45
    """
    n = len(normals[0])
    found = {y for _, y in _packing_bases(normals, n - 1)}
    found.add((Fraction(1),) * n)
    return tuple(sorted(found))


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
