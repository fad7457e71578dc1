"""Exact linear algebra by hand, shared by the proof checks and the checker's tests.

Gauss–Jordan elimination in Fractions, independent of the vertex tables of both packages
(``dppverify/structured/cover.py``, ``solver/coalitions/vertex_tables.py``): it solves one
system at a time, with no determinant, no Cramer's rule and no integer scaling.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from fractions import Fraction

__all__ = ["basic_solutions", "solve_square"]


def solve_square(mat: Sequence[Sequence[Fraction | int]], rhs: Sequence[Fraction | int]
                 ) -> list[Fraction] | None:
    """The unique solution of a square system, None when the matrix is singular.

    Examples
    --------
    >>> solve_square([[2, 1], [1, 1]], [3, 2])
    [Fraction(1, 1), Fraction(1, 1)]
    >>> solve_square([[1, 1], [2, 2]], [1, 2]) is None
    True
    """
    n = len(rhs)
    a = [[Fraction(x) for x in row] + [Fraction(b)] for row, b in zip(mat, rhs, strict=True)]
    for col in range(n):
        piv = next((r for r in range(col, n) if a[r][col] != 0), None)
        if piv is None:
            return None
        a[col], a[piv] = a[piv], a[col]
        a[col] = [x / a[col][col] for x in a[col]]
        for r in range(n):
            if r != col and a[r][col] != 0:
                f = a[r][col]
                a[r] = [x - f * y for x, y in zip(a[r], a[col], strict=True)]
    return [a[i][n] for i in range(n)]


def basic_solutions(columns: Sequence[Sequence[int]], rhs: Sequence[int]
                    ) -> set[tuple[Fraction, ...]]:
    """Every basic feasible solution of ``Σ_j c_j columns[j] = rhs, c >= 0``: each choice of
    ``len(rhs)`` columns that is non-singular, solved, kept when non-negative (the vertices of
    a standard-form polyhedron whose matrix has full row rank).

    Examples
    --------
    The covers of (1, 1) by {1}, {2} and {1, 2}:

    >>> sorted(basic_solutions([(1, 0), (0, 1), (1, 1)], (1, 1)))
    [(Fraction(0, 1), Fraction(0, 1), Fraction(1, 1)), (Fraction(1, 1), Fraction(1, 1), \
Fraction(0, 1))]
    """
    n = len(rhs)
    out: set[tuple[Fraction, ...]] = set()
    for basis in itertools.combinations(range(len(columns)), n):
        x = solve_square([[columns[j][i] for j in basis] for i in range(n)], rhs)
        if x is not None and all(v >= 0 for v in x):
            c = [Fraction(0)] * len(columns)
            for pos, j in enumerate(basis):
                c[j] = x[pos]
            out.add(tuple(c))
    return out
