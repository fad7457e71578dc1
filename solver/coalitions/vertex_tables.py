"""Exact vertex tables of small integer systems (the solver's own; N <= 5 rows).

Two polytopes carry the N-goal mathematics of ``proofs/NEXACT.md``:

- the *covers* of a non-negative integer vector ``a`` by a set of normals ``A``,
  ``{c >= 0 : Σ_n c_n n = a}`` (:func:`vertex_table` of ``A`` and ``a``): the support
  function of a set ``F = {r : n·r <= m_n ∀ n ∈ A}`` at ``a`` is ``min_c Σ_n c_n m_n`` over
  its vertices (LP duality; NEXACT.3);
- the *packing* polytope ``P_A = {λ >= 0 : Σ_n λ_n n <= 1}`` (:func:`packing_directions`):
  ``F_u + wΔ = {r : y_λ·r <= w + λ·m(u) for every vertex λ}``, ``y_λ = Σ_n λ_n n`` (Farkas;
  proofs/NGOAL.md NG.8(c)).

Vertices are basic feasible solutions: every choice of as many columns as the system has rows
(on the support of the right-hand side) with a non-zero exact integer determinant, solved by
Cramer's rule, kept when non-negative, reduced to lowest terms. Determinants are exact
integers: Laplace expansion over numpy int64 arrays where Hadamard's bound keeps every integer
of the step below :data:`INT_LIMIT`, else fraction-free (Bareiss) elimination in Python
integers, one basis at a time. A table is stored in *parts* (:class:`VertexTable`), each with
its own common denominator, so that no table is refused because the denominators of all its
vertices together leave int64. Nothing is decided in floating point.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from functools import cache

import numpy as np

Normal = tuple[int, ...]
"""A facet normal: a non-negative integer vector with one entry per goal, not all zero."""

CHUNK = 100_000

INT_LIMIT = 2 ** 62
"""Every integer the int64 determinant path computes stays below this (room for one sum)."""

PART_LIMIT = 2 ** 40
"""Every scaled coordinate of a table's part stays below this (a part's products with DP
values stay in int64 or exact float64 far longer than the whole table's would)."""


def zero_one_normals(n_goals: int) -> tuple[Normal, ...]:
    """The ``2^N - 1`` non-zero 0/1 vectors, in mask order (bit θ is goal θ).

    Examples
    --------
    >>> zero_one_normals(2)
    ((1, 0), (0, 1), (1, 1))
    """
    return tuple(tuple((s >> i) & 1 for i in range(n_goals)) for s in range(1, 1 << n_goals))


def primitive(y: Sequence[Fraction | int]) -> Normal:
    """The primitive integer vector along a non-negative rational direction ``y``.

    Examples
    --------
    >>> primitive([Fraction(1), Fraction(1), Fraction(1), Fraction(1, 2)])
    (2, 2, 2, 1)
    """
    den = math.lcm(*(Fraction(x).denominator for x in y))
    ints = [int(Fraction(x) * den) for x in y]
    g = math.gcd(*ints)
    if g == 0:
        raise ValueError("primitive: the zero vector has no direction")
    return tuple(x // g for x in ints)


@dataclass(frozen=True)
class VertexTable:
    """The vertices of ``{c >= 0 : Σ_j c_j columns[j] = rhs}``, scaled to integers by parts.

    The vertices are split into *parts*, each with its own common denominator small enough
    that every scaled coordinate stays below :data:`PART_LIMIT` (int64 arithmetic over a part
    stays exact); one part when the whole table's denominator is small, which is the rule.

    Attributes
    ----------
    columns : tuple of int
        Indices (into the caller's column list) of the columns that may be positive.
    scaled : numpy.ndarray
        The first part: ``lcm · c`` for its vertices, shape ``(len(columns), n_vertices)``,
        int64.
    lcm : int
        The first part's common denominator.
    more : tuple of (numpy.ndarray, int)
        The other parts, ``(scaled, lcm)`` each.
    """

    columns: tuple[int, ...]
    scaled: np.ndarray
    lcm: int
    more: tuple[tuple[np.ndarray, int], ...] = ()

    @property
    def parts(self) -> tuple[tuple[np.ndarray, int], ...]:
        """Every part as ``(scaled, lcm)``, the first one first."""
        return ((self.scaled, self.lcm), *self.more)

    @property
    def n_vertices(self) -> int:
        """The number of vertices over every part."""
        return sum(sc.shape[1] for sc, _ in self.parts)

    def vertices(self) -> list[dict[int, Fraction]]:
        """Every vertex as ``{column index: c_j > 0}``.

        Examples
        --------
        >>> t = vertex_table(((1, 0), (0, 1), (1, 1)), (1, 1))
        >>> sorted(sorted(v.items()) for v in t.vertices())
        [[(0, Fraction(1, 1)), (1, Fraction(1, 1))], [(2, Fraction(1, 1))]]
        """
        out = []
        for scaled, lcm in self.parts:
            for col in scaled.T:
                out.append({self.columns[i]: Fraction(int(x), lcm)
                            for i, x in enumerate(col) if x})
        return out


def _dets(entries: list[list[np.ndarray]]) -> np.ndarray:
    """Exact determinants of a batch of ``s × s`` integer matrices (``entries[r][c]``: entry
    ``(r, c)`` of every matrix), by Laplace expansion along the rows, bottom-up."""
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


def _combinations(n: int, k: int) -> np.ndarray:
    """All ``k``-subsets of ``range(n)`` as rows of increasing indices (numpy, no loop over
    subsets)."""
    out = np.arange(n, dtype=np.int64)[:, None]
    for _ in range(1, k):
        last = out[:, -1]
        counts = n - 1 - last
        rep = np.repeat(out, counts, axis=0)
        starts = np.repeat(last + 1 - np.cumsum(counts) + counts, counts)
        nxt = np.arange(rep.shape[0], dtype=np.int64) + starts
        out = np.concatenate([rep, nxt[:, None]], axis=1)
    return out if k > 0 else np.zeros((1, 0), dtype=np.int64)


def vertex_table(columns: Sequence[Sequence[int]], rhs: Sequence[int],
                 max_bases: int = 20_000_000) -> VertexTable:
    """Every vertex of ``{c >= 0 : Σ_j c_j columns[j] = rhs}`` (non-negative integer data).

    Rows outside the support of ``rhs`` force the columns that use them to 0. On the support
    the columns must have full row rank (the unit vectors among them suffice).

    Raises
    ------
    ValueError
        If more than ``max_bases`` bases would have to be tried.

    Examples
    --------
    The covers of (2, 2, 2, 1) by the 0/1 vectors of four goals include the three sets
    {1, 2}, {1, 3}, {2, 3, 4} of the N = 4 gadget (proofs/NGOAL.md):

    >>> zo = zero_one_normals(4)
    >>> t = vertex_table(zo, (2, 2, 2, 1))
    >>> {zo.index((1, 1, 0, 0)): 1, zo.index((1, 0, 1, 0)): 1,
    ...  zo.index((0, 1, 1, 1)): 1} in [{k: int(x) for k, x in v.items()} for v in t.vertices()]
    True
    """
    cols = tuple(tuple(int(x) for x in c) for c in columns)
    return _vertex_table(cols, tuple(int(x) for x in rhs), max_bases)


@cache
def _vertex_table(columns: tuple[Normal, ...], rhs: Normal, max_bases: int) -> VertexTable:
    rows = [i for i, x in enumerate(rhs) if x != 0]
    keep = [j for j, c in enumerate(columns)
            if any(c) and all(c[i] == 0 for i in range(len(rhs)) if rhs[i] == 0)]
    m = len(rows)
    if m == 0:
        return VertexTable(columns=(), scaled=np.zeros((0, 1), dtype=np.int64), lcm=1)
    if math.comb(len(keep), m) > max_bases:
        raise ValueError(f"vertex_table: {math.comb(len(keep), m):,} bases exceed the limit "
                         f"of {max_bases:,}")
    mat = [[columns[j][i] for j in keep] for i in rows]
    b = [rhs[i] for i in rows]
    if _hadamard_ok([[columns[j][i] for i in rows] for j in keep] + [b], m):
        found = _bases_int64(np.array(mat, dtype=np.int64), np.array(b, dtype=np.int64))
    else:  # entries too large for int64 determinants: one basis at a time, Python integers
        found = _bases_python(mat, b)
    return _in_parts(tuple(keep), sorted(found, key=lambda v: (v[1], v[0])))


def _bases_int64(mat: np.ndarray, b: np.ndarray) -> set[tuple[tuple[int, ...], int]]:
    """The basic feasible solutions ``(numerators over the columns, denominator)`` in lowest
    terms, by int64 determinants (the caller checked Hadamard's bound)."""
    m, k = mat.shape
    found: set[tuple[tuple[int, ...], int]] = set()
    all_combos = _combinations(k, m)
    for lo in range(0, all_combos.shape[0], CHUNK):
        chunk = all_combos[lo:lo + CHUNK]
        entries = [[np.ascontiguousarray(mat[r, chunk[:, c]]) for c in range(m)]
                   for r in range(m)]
        det = _dets(entries)  # exact
        ok = det != 0
        if not ok.any():
            continue
        chunk, det = chunk[ok], det[ok]
        bases = np.transpose(mat[:, chunk], (1, 0, 2))  # (k, m, m): columns = chosen normals
        approx = np.linalg.solve(bases.astype(np.float64),
                                 np.broadcast_to(b.astype(np.float64), (len(chunk), m))[..., None]
                                 )[..., 0]
        numer = np.rint(approx * det[:, None]).astype(np.int64)
        # exact: B·numer = det·b; Cramer's rule where the rounded guess is wrong
        wrong = np.any(np.einsum("kij,kj->ki", bases, numer) != det[:, None] * b[None, :],
                       axis=1)
        if wrong.any():
            sub = [[np.ascontiguousarray(mat[r, chunk[wrong][:, c]]) for c in range(m)]
                   for r in range(m)]
            n_w = int(wrong.sum())
            for i in range(m):
                numer[wrong, i] = _dets([[np.full(n_w, b[r]) if c == i else sub[r][c]
                                          for c in range(m)] for r in range(m)])
        sign = np.sign(det)
        numer *= sign[:, None]
        det = det * sign
        feas = np.all(numer >= 0, axis=1)
        chunk, det, numer = chunk[feas], det[feas], numer[feas]
        if not chunk.size:
            continue
        g = np.gcd.reduce(np.concatenate([numer, det[:, None]], axis=1), axis=1)
        dense = np.zeros((chunk.shape[0], k + 1), dtype=np.int64)
        dense[np.arange(chunk.shape[0])[:, None], chunk] = numer // g[:, None]
        dense[:, k] = det // g
        for row in _unique_rows(dense).tolist():  # a degenerate vertex has several bases
            found.add((tuple(row[:k]), row[k]))
    return found


def _bases_python(mat: list[list[int]], b: list[int]) -> set[tuple[tuple[int, ...], int]]:
    """:func:`_bases_int64` for any integers: fraction-free (Bareiss) determinants and Cramer's
    rule in Python integers, one basis at a time."""
    m, k = len(mat), len(mat[0])
    found: set[tuple[tuple[int, ...], int]] = set()
    for combo in itertools.combinations(range(k), m):
        sub = [[mat[r][c] for c in combo] for r in range(m)]
        det = _bareiss(sub)
        if det == 0:
            continue
        numer = [_bareiss([[b[r] if c == i else sub[r][c] for c in range(m)]
                           for r in range(m)]) for i in range(m)]
        if det < 0:
            det, numer = -det, [-x for x in numer]
        if min(numer) < 0:
            continue
        g = math.gcd(det, *numer)
        dense = [0] * k
        for pos, c in enumerate(combo):
            dense[c] = numer[pos] // g
        found.add((tuple(dense), det // g))
    return found


def _bareiss(mat: list[list[int]]) -> int:
    """The determinant of a square integer matrix, fraction-free (every intermediate entry is a
    minor, so exact division)."""
    a = [row[:] for row in mat]
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


def _in_parts(columns: tuple[int, ...], found: Sequence[tuple[tuple[int, ...], int]]
              ) -> VertexTable:
    """The vertices (sorted by denominator) in consecutive parts, each part's common
    denominator times its largest coordinate below :data:`PART_LIMIT` (a vertex that alone
    exceeds it is a part of its own, in Python integers past int64)."""
    parts: list[tuple[np.ndarray, int]] = []
    cur: list[tuple[tuple[int, ...], int]] = []
    cur_lcm, cur_top = 1, Fraction(0)

    def close() -> None:
        if cur:
            rows = [[x * (cur_lcm // den) for x in numer] for numer, den in cur]
            top = max((x for row in rows for x in row), default=0)
            arr = np.array(rows, dtype=np.int64 if top < INT_LIMIT else object).reshape(
                len(cur), len(columns))  # a lone vertex past int64: Python integers
            g = math.gcd(cur_lcm, *(int(x) for x in arr.ravel()))
            parts.append((np.ascontiguousarray((arr // g).T), cur_lcm // g))

    for numer, den in found:
        top = max(Fraction(max(numer, default=0), den), cur_top)
        lcm = math.lcm(cur_lcm, den)
        if cur and (lcm * top >= PART_LIMIT):
            close()
            cur, cur_lcm, cur_top = [], 1, Fraction(0)
            top, lcm = Fraction(max(numer, default=0), den), den
        cur.append((numer, den))
        cur_lcm, cur_top = lcm, top
    close()
    if not parts:
        return VertexTable(columns=columns, scaled=np.zeros((len(columns), 0), dtype=np.int64),
                           lcm=1)
    (first, lcm0), *rest = parts
    return VertexTable(columns=columns, scaled=first, lcm=lcm0, more=tuple(rest))


def _hadamard_ok(vectors: list[list[int]], m: int) -> bool:
    """Whether every integer of the int64 determinant step stays below :data:`INT_LIMIT`.

    Every ``k × k`` minor of ``m`` of the vectors (the columns, or Cramer's matrices, where the
    right-hand side replaces a column) is at most ``Π ||v||`` over the ``m`` longest vectors
    (Hadamard; integer vectors have norm >= 1), a Laplace partial sum at most ``m`` such
    terms, and checking ``B·x = det·b`` multiplies one by an entry: all below
    ``2**6 · ||v||_max · Π ||v||``, compared here in exact integers (squared).
    """
    squares = sorted((sum(int(x) ** 2 for x in v) for v in vectors), reverse=True)
    return math.prod(squares[:m]) * squares[0] * 2 ** 12 < INT_LIMIT ** 2


def _unique_rows(arr: np.ndarray) -> np.ndarray:
    """The distinct rows of an int64 array (hashing the rows' bytes)."""
    if arr.shape[0] == 0:
        return arr
    arr = np.ascontiguousarray(arr)
    seen: dict[bytes, int] = {}
    for i, row in enumerate(arr.view(np.dtype((np.void, arr.dtype.itemsize * arr.shape[1]))
                                     ).ravel()):
        seen.setdefault(row.tobytes(), i)
    return arr[sorted(seen.values())]


@dataclass(frozen=True)
class Direction:
    """One direction ``y`` of the packing polytope's vertices that is not a 0/1 vector.

    Attributes
    ----------
    y : tuple of Fraction
        ``y_λ = Σ_n λ_n n`` (entries in [0, 1]).
    scale : int
        ``s``: ``s·y`` is an integer vector.
    cover : VertexTable
        The covers of ``s·y`` by the normals.
    lams : numpy.ndarray
        ``lam_lcm · λ`` for every vertex ``λ`` with ``y_λ = y``: shape ``(n_λ, |A|)``.
    lam_lcm : int
        The common denominator of those ``λ``.
    """

    y: tuple[Fraction, ...]
    scale: int
    cover: VertexTable
    lams: np.ndarray
    lam_lcm: int


def packing_vertices(normals: tuple[Normal, ...]) -> list[tuple[Fraction, ...]]:
    """Every vertex ``λ`` of ``P_A = {λ >= 0 : Σ_n λ_n n <= 1}`` (``λ = 0`` included).

    Examples
    --------
    >>> sorted(packing_vertices(((1, 0), (0, 1), (1, 1))))
    [(Fraction(0, 1), Fraction(0, 1), Fraction(0, 1)), (Fraction(0, 1), Fraction(0, 1), \
Fraction(1, 1)), (Fraction(0, 1), Fraction(1, 1), Fraction(0, 1)), (Fraction(1, 1), \
Fraction(0, 1), Fraction(0, 1)), (Fraction(1, 1), Fraction(1, 1), Fraction(0, 1))]
    """
    n = len(normals[0])
    slack = tuple(tuple(int(i == j) for i in range(n)) for j in range(n))
    table = vertex_table(normals + slack, (1,) * n)
    out = set()
    for v in table.vertices():
        out.add(tuple(v.get(j, Fraction(0)) for j in range(len(normals))))
    return sorted(out)


@cache
def packing_directions(normals: tuple[Normal, ...]) -> tuple[Direction, ...]:
    """The directions ``y_λ`` of the vertices of ``P_A`` that are not 0/1 vectors.

    For these alone the arc test ``h_{F_v}(y_λ) <= w + λ·m(u)`` can fail at a fixpoint of the
    normal-restricted DP; the 0/1 ones hold by the step and the closure (proofs/NGOAL.md
    NG.8(c)).

    Examples
    --------
    >>> len(packing_directions(zero_one_normals(3)))
    0
    >>> [str(x) for x in packing_directions(zero_one_normals(4))[0].y]
    ['1/2', '1', '1', '1']
    """
    n = len(normals[0])
    groups: dict[tuple[Fraction, ...], list[tuple[Fraction, ...]]] = {}
    for lam in packing_vertices(normals):
        y = tuple(sum((lam[j] * normals[j][i] for j in range(len(normals)) if lam[j]),
                      Fraction(0)) for i in range(n))
        if all(x in (0, 1) for x in y):
            continue
        groups.setdefault(y, []).append(lam)
    out = []
    for y, lams in sorted(groups.items()):
        s = math.lcm(*(x.denominator for x in y))
        cover = vertex_table(normals, tuple(int(x * s) for x in y))
        lcm = math.lcm(*(x.denominator for lam in lams for x in lam))
        arr = np.array([[int(x * lcm) for x in lam] for lam in lams], dtype=np.int64)
        out.append(Direction(y, s, cover, arr, lcm))
    return tuple(out)
