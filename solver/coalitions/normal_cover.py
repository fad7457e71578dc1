"""The exact cover LP over integer normals: ``min Σ_n c_n cost_n`` s.t. ``Σ_n c_n n = y``.

By LP duality (``proofs/NEXACT.md`` NX.3) its value is the support function
``h_F(y) = max {y·r : r ∈ F}`` of ``F = {r : n·r <= cost_n ∀ n}``, and its optimal dual ``h``
is a point of ``F`` with ``h·y`` = the value. The solver uses it at the start (``y`` = the
prior: the value, the Attacker's first cover and the Defender's guarantee vector) and to decide
which candidate normals are facets of an exact set (a normal is redundant iff the others cover
it at no larger cost).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction

from solver.numbers import pivot, solve_exact


@dataclass(frozen=True)
class NormalCover:
    """The optimum of :func:`normal_cover_lp`.

    Attributes
    ----------
    value : Fraction
        ``min Σ_n c_n cost_n``.
    cover : dict
        Column index -> ``c_n > 0`` (an optimal basic solution).
    dual : tuple of Fraction
        ``h`` with ``h·n <= cost_n`` for every column and ``h·y`` = value.
    """

    value: Fraction
    cover: dict[int, Fraction]
    dual: tuple[Fraction, ...]


def normal_cover_lp(columns: Sequence[Sequence[int]], costs: Sequence[Fraction],
                    y: Sequence[Fraction], order: Sequence[int] = ()) -> NormalCover:
    """``min Σ_j c_j costs[j]`` s.t. ``Σ_j c_j columns[j] = y``, ``c >= 0``, exactly.

    A tableau simplex in rationals from the basis of the unit vectors (which must be among the
    non-negative integer ``columns``; ``y >= 0``), Bland's rule (finite). With ``order`` the
    right-hand side is perturbed lexicographically, ``y + ε e_{order[0]} + ε² e_{order[1]} +
    …``: the final basis is optimal for ``y`` and its dual is the lexicographically largest
    optimal dual in ``order`` (LP sensitivity).

    Raises
    ------
    ValueError
        If a unit vector is missing or ``y`` has a negative entry.

    Examples
    --------
    The N = 4 gadget's normal (2, 2, 2, 1) covered by pairs and a triple of cost 2 each:

    >>> cols = [(1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0, 0, 0, 1), (1, 1, 0, 0),
    ...         (1, 0, 1, 0), (0, 1, 1, 1)]
    >>> lp = normal_cover_lp(cols, [Fraction(2)] * 7, [Fraction(x) for x in (2, 2, 2, 1)])
    >>> lp.value, sorted(lp.cover.items())
    (Fraction(6, 1), [(4, Fraction(1, 1)), (5, Fraction(1, 1)), (6, Fraction(1, 1))])

    Two goals, the pair covering the prior (1/2, 1/2) at cost 9/2: every ``h`` with
    ``h_0 + h_1 = 9/2``, ``h_0 <= 9/2``, ``h_1 <= 3`` is an optimal dual; ``order`` picks the
    lexicographically largest one:

    >>> two = [(1, 0), (0, 1), (1, 1)], [Fraction(9, 2), Fraction(3), Fraction(9, 2)]
    >>> normal_cover_lp(*two, [Fraction(1, 2)] * 2).dual
    (Fraction(3, 2), Fraction(3, 1))
    >>> normal_cover_lp(*two, [Fraction(1, 2)] * 2, order=(0, 1)).dual
    (Fraction(9, 2), Fraction(0, 1))
    """
    n = len(y)
    vecs = [tuple(int(x) for x in c) for c in columns]
    cost = [Fraction(c) for c in costs]
    rhs = [Fraction(x) for x in y]
    if any(x < 0 for x in rhs):
        raise ValueError("normal_cover_lp: the right-hand side must be non-negative")
    basis: list[int] = []
    for i in range(n):
        unit = tuple(int(i == j) for j in range(n))
        if unit not in vecs:
            raise ValueError(f"normal_cover_lp: the unit vector of goal {i} is not a column")
        basis.append(vecs.index(unit))
    width = len(vecs)
    rows = [[Fraction(v[i]) for v in vecs] + [rhs[i]] + [Fraction(int(i == t)) for t in order]
            for i in range(n)]
    while True:
        h = solve_exact([[Fraction(vecs[basis[r]][i]) for i in range(n)] for r in range(n)],
                        [cost[basis[r]] for r in range(n)])
        if h is None:  # pragma: no cover - a basis of the simplex method is regular
            raise AssertionError("normal_cover_lp: singular basis")
        entering = None
        for j, v in enumerate(vecs):
            if j in basis:
                continue
            if cost[j] - sum((h[i] * v[i] for i in range(n) if v[i]), Fraction(0)) < 0:
                entering = j
                break
        if entering is None:
            value = sum((cost[basis[i]] * rows[i][width] for i in range(n)), Fraction(0))
            cover = {basis[i]: rows[i][width] for i in range(n) if rows[i][width]}
            return NormalCover(value, cover, tuple(h))
        best: tuple[list[Fraction], int, int] | None = None
        for i in range(n):
            a = rows[i][entering]
            if a > 0:
                key = ([x / a for x in rows[i][width:]], basis[i], i)
                if best is None or key[:2] < best[:2]:
                    best = key
        if best is None:  # pragma: no cover - c_j <= y_i / n_i keeps the LP bounded
            raise AssertionError("normal_cover_lp: unbounded")
        pivot(rows, best[2], entering)
        basis[best[2]] = entering
