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
Cramer's rule, kept when non-negative. Determinants are exact integers (Laplace expansion over
numpy int64 arrays). A table whose determinants (Hadamard's bound), common denominator or
scaled vertices could reach :data:`INT_LIMIT` is refused with a ``ValueError`` instead of
being computed in int64 (the construction reports that as an unreached fixpoint with its
bracket). Nothing is decided in floating point.
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
"""Every integer a table computes or stores stays below this (int64, with room for one sum)."""


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
    """The vertices of ``{c >= 0 : Σ_j c_j columns[j] = rhs}``, scaled to integers.

    Attributes
    ----------
    columns : tuple of int
        Indices (into the caller's column list) of the columns that may be positive.
    scaled : numpy.ndarray
        ``lcm · c`` for every vertex, shape ``(len(columns), n_vertices)``, int64.
    lcm : int
        The common denominator of every vertex coordinate.
    """

    columns: tuple[int, ...]
    scaled: np.ndarray
    lcm: int

    def vertices(self) -> list[dict[int, Fraction]]:
        """Every vertex as ``{column index: c_j > 0}``.

        Examples
        --------
        >>> t = vertex_table(((1, 0), (0, 1), (1, 1)), (1, 1))
        >>> sorted(sorted(v.items()) for v in t.vertices())
        [[(0, Fraction(1, 1)), (1, Fraction(1, 1))], [(2, Fraction(1, 1))]]
        """
        out = []
        for col in self.scaled.T:
            out.append({self.columns[i]: Fraction(int(x), self.lcm)
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
    _check_hadamard([[columns[j][i] for i in rows] for j in keep] + [[rhs[i] for i in rows]], m)
    mat = np.array([[columns[j][i] for j in keep] for i in rows], dtype=np.int64)
    b = np.array([rhs[i] for i in rows], dtype=np.int64)
    found: list[np.ndarray] = []
    dens: list[int] = []
    all_combos = _combinations(len(keep), m)
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
        feas = np.all(numer * np.sign(det)[:, None] >= 0, axis=1)
        chunk, det, numer = chunk[feas], det[feas], numer[feas]
        if not chunk.size:
            continue
        common = math.lcm(1, *(int(x) for x in np.unique(np.abs(det))))
        if common * (int(np.abs(numer).max(initial=0)) + 1) >= INT_LIMIT:
            raise ValueError(f"vertex_table: the vertices' common denominator {common} leaves "
                             "int64")
        dense = np.zeros((chunk.shape[0], len(keep)), dtype=np.int64)
        idx = np.arange(chunk.shape[0])
        for i in range(m):
            dense[idx, chunk[:, i]] = numer[:, i] * (common // det)
        found.append(_unique_rows(dense))  # a degenerate vertex has several bases
        dens.append(common)
    lcm = math.lcm(1, *dens)
    if max((int(np.abs(d).max(initial=0)) * (lcm // c) for d, c in zip(found, dens, strict=True)),
           default=0) >= INT_LIMIT:
        raise ValueError(f"vertex_table: the vertices' common denominator {lcm} leaves int64")
    stacked = (np.concatenate([d * (lcm // c) for d, c in zip(found, dens, strict=True)])
               if found else np.zeros((0, len(keep)), dtype=np.int64))
    unique = _unique_rows(stacked)  # a degenerate vertex has several bases
    g = math.gcd(int(np.gcd.reduce(unique.ravel(), initial=0)), lcm)
    return VertexTable(columns=tuple(keep), scaled=np.ascontiguousarray((unique // g).T),
                       lcm=lcm // g)


def _check_hadamard(vectors: list[list[int]], m: int) -> None:
    """Refuse a system in which an integer of the determinant step could reach
    :data:`INT_LIMIT`.

    Every ``k × k`` minor of ``m`` of the vectors (the columns, or Cramer's matrices, where the
    right-hand side replaces a column) is at most ``Π ||v||`` over the ``m`` longest vectors
    (Hadamard; integer vectors have norm >= 1), a Laplace partial sum at most ``m`` such
    terms, and checking ``B·x = det·b`` multiplies one by an entry: all below
    ``2**6 · ||v||_max · Π ||v||``, compared here in exact integers (squared).
    """
    squares = sorted((sum(int(x) ** 2 for x in v) for v in vectors), reverse=True)
    if math.prod(squares[:m]) * squares[0] * 2 ** 12 >= INT_LIMIT ** 2:
        raise ValueError(f"vertex_table: a {m} × {m} determinant could leave int64 (Hadamard's "
                         "bound on these entries)")


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
