"""The basic feasible solutions of small non-negative integer systems, exactly.

``{c >= 0 : M c = b}`` with ``M`` of full row rank ``m`` (at most 5 here): every choice of
``m`` columns with a non-zero determinant, solved by Cramer's rule, kept when non-negative and
reduced to lowest terms (:func:`basic_feasible_solutions`). The determinants are int64 —
vectorised Laplace expansion (:func:`dets`) — where Hadamard's bound proves every minor and
every partial sum below :data:`INT_SAFE`, else Python integers one basis at a time by
fraction-free (Bareiss) elimination (:func:`bareiss_det`). No object-dtype array is used and
nothing is decided in floating point.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence

import numpy as np


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


def basic_feasible_solutions(mat: list[list[int]], b: list[int]) -> set[Vertex]:
    """Every basic feasible solution of ``mat · c = b``, ``c >= 0``, as ``(numerators,
    denominator)`` in lowest terms (non-negative integer data, full row rank).

    Examples
    --------
    The covers of (2, 1) by (1, 0), (0, 1), (2, 1) and (1, 1):

    >>> sorted(basic_feasible_solutions([[1, 0, 2, 1], [0, 1, 1, 1]], [2, 1]))
    [((0, 0, 1, 0), 1), ((1, 0, 0, 1), 1), ((2, 1, 0, 0), 1)]
    """
    m = len(mat)
    vectors = [[mat[i][j] for i in range(m)] for j in range(len(mat[0]))] + [list(b)]
    if _hadamard_safe(vectors, m):
        return _vertices_int64(mat, b)
    return _vertices_exact(mat, b)
