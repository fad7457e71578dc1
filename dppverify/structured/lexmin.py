"""The guarantee rule's step distribution: an exact lexicographic minimum over a small polytope.

The rule (``docs/formats.md`` §2b) plays, on a step into ``u`` of weight ``w`` from state
``r``, the lexicographic minimum in the priority order of

    F = { σ ∈ Δ^N : a·σ >= (a·r - m_a(u)) / w  for every normal a }.

Rows with a non-positive right-hand side hold for every ``σ >= 0`` (the normals are
non-negative) and are dropped; a row implied by another (a smaller normal with a larger
bound) too. :func:`lexmin` minimises the coordinates one after the other, each by the exact
simplex method (:func:`simplex_min`: two phases, Bland's rule, rationals), fixing each
minimum before the next.
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction

Row = tuple[tuple[int, ...], Fraction]


def reduce_rows(rows: Sequence[Row]) -> list[Row]:
    """Drop rows ``a·σ >= q`` with ``q <= 0`` and rows implied by another one.

    ``(a, q)`` is implied by ``(a', q')`` when ``a' <= a`` componentwise and ``q' >= q``
    (then ``a·σ >= a'·σ >= q' >= q`` for ``σ >= 0``).

    Examples
    --------
    >>> reduce_rows([((1, 0), Fraction(1, 2)), ((1, 1), Fraction(1, 3)),
    ...              ((0, 1), Fraction(-1))])
    [((1, 0), Fraction(1, 2))]
    """
    pos = [(tuple(a), Fraction(q)) for a, q in rows if q > 0]
    out: list[Row] = []
    for i, (a, q) in enumerate(pos):
        implied = False
        for k, (b, p) in enumerate(pos):
            if k == i or p < q or not all(x <= y for x, y in zip(b, a, strict=True)):
                continue
            if (b, p) != (a, q) or k < i:  # equal rows: keep the first
                implied = True
                break
        if not implied:
            out.append((a, q))
    return out


def simplex_min(cost: Sequence[Fraction], eq_rows: Sequence[Sequence[Fraction]],
                eq_rhs: Sequence[Fraction]) -> list[Fraction] | None:
    """``argmin cost·x`` s.t. ``x >= 0``, ``eq_rows x = eq_rhs``; None if infeasible.

    :func:`simplex_basis` with the basis left out.

    Exact two-phase simplex with Bland's rule (the feasible set must be bounded: here it
    always lies in a simplex). Negative right-hand sides are negated first.

    Examples
    --------
    >>> simplex_min([Fraction(1), Fraction(0)], [[Fraction(1), Fraction(1)]], [Fraction(1)])
    [Fraction(0, 1), Fraction(1, 1)]
    >>> simplex_min([Fraction(1)], [[Fraction(1)], [Fraction(2)]], [Fraction(1), Fraction(1)])
    """
    out = simplex_basis(cost, eq_rows, eq_rhs)
    return None if out is None else out[0]


def simplex_basis(cost: Sequence[Fraction], eq_rows: Sequence[Sequence[Fraction]],
                  eq_rhs: Sequence[Fraction]) -> tuple[list[Fraction], list[int]] | None:
    """:func:`simplex_min` and its optimal basis (one column per row; a row whose artificial
    could not leave the basis is redundant and gets ``-1``).

    Examples
    --------
    >>> simplex_basis([Fraction(2), Fraction(1)], [[Fraction(1), Fraction(1)]], [Fraction(3)])
    ([Fraction(0, 1), Fraction(3, 1)], [1])
    """
    m = len(eq_rows)
    nv = len(cost)
    rows = [[Fraction(x) for x in r] for r in eq_rows]
    rhs = [Fraction(x) for x in eq_rhs]
    for i in range(m):
        if rhs[i] < 0:
            rows[i] = [-x for x in rows[i]]
            rhs[i] = -rhs[i]
    # tableau with artificials nv .. nv+m-1
    tab = [rows[i] + [Fraction(int(i == k)) for k in range(m)] + [rhs[i]] for i in range(m)]
    basis = list(range(nv, nv + m))
    total = nv + m

    def pivot(row: int, col: int) -> None:
        """Column ``col`` enters the basis in row ``row`` (exact Gauss-Jordan step)."""
        piv = tab[row][col]
        tab[row] = [x / piv for x in tab[row]]
        for i in range(m):
            if i != row and tab[i][col]:
                f = tab[i][col]
                tab[i] = [x - f * y for x, y in zip(tab[i], tab[row], strict=True)]
        basis[row] = col

    def run(obj: list[Fraction], allowed: int) -> None:
        while True:
            # reduced costs: obj_j - Σ_i obj_{basis_i} tab[i][j]
            enter = None
            for j in range(allowed):
                if j in basis:
                    continue
                rc = obj[j] - sum((obj[basis[i]] * tab[i][j] for i in range(m) if tab[i][j]),
                                  Fraction(0))
                if rc < 0:
                    enter = j
                    break
            if enter is None:
                return
            leave = None
            best: tuple[Fraction, int] | None = None
            for i in range(m):
                if tab[i][enter] > 0:
                    key = (tab[i][total] / tab[i][enter], basis[i])
                    if best is None or key < best:
                        best, leave = key, i
            if leave is None:  # pragma: no cover - bounded feasible sets only
                raise AssertionError("simplex_min: unbounded")
            pivot(leave, enter)

    phase1 = [Fraction(0)] * nv + [Fraction(1)] * m
    run(phase1, total)
    if any(basis[i] >= nv and tab[i][total] != 0 for i in range(m)):
        return None
    # drive artificials at zero out of the basis where possible (else their rows are redundant)
    for i in range(m):
        if basis[i] >= nv:
            j = next((j for j in range(nv) if tab[i][j] != 0 and j not in basis), None)
            if j is None:
                continue
            pivot(i, j)
    obj = [Fraction(x) for x in cost] + [Fraction(0)] * m
    # artificials still basic sit at 0 on redundant rows: forbid them from entering again
    run(obj, nv)
    x = [Fraction(0)] * nv
    for i in range(m):
        if basis[i] < nv:
            x[basis[i]] = tab[i][total]
    return x, [b if b < nv else -1 for b in basis]


def lexmin(rows: Sequence[Row], n: int, order: Sequence[int]) -> tuple[Fraction, ...] | None:
    """The lexicographic minimum in ``order`` of ``{σ ∈ Δ^n : a·σ >= q for (a, q) ∈ rows}``.

    None when the set is empty.

    Examples
    --------
    Three types in the order (0, 1, 2); the pair {0, 1} needs 1/2 and type 0 alone 1/4:

    >>> rows = [((1, 1, 0), Fraction(1, 2)), ((1, 0, 0), Fraction(1, 4))]
    >>> [str(x) for x in lexmin(rows, 3, (0, 1, 2))]
    ['1/4', '1/4', '1/2']
    >>> lexmin([((1, 0, 0), Fraction(2))], 3, (0, 1, 2)) is None
    True
    """
    live = reduce_rows(rows)
    if not live:
        return tuple(Fraction(int(i == order[-1])) for i in range(n))
    k = len(live)
    # variables: σ_0 .. σ_{n-1}, surplus s_0 .. s_{k-1}
    eq: list[list[Fraction]] = []
    rhs: list[Fraction] = []
    for i, (a, q) in enumerate(live):
        eq.append([Fraction(x) for x in a] + [Fraction(-int(i == j)) for j in range(k)])
        rhs.append(q)
    eq.append([Fraction(1)] * n + [Fraction(0)] * k)
    rhs.append(Fraction(1))
    out = [Fraction(0)] * n
    for t in order[:-1]:  # the last coordinate takes what is left
        cost = [Fraction(int(j == t)) for j in range(n + k)]
        x = simplex_min(cost, eq, rhs)
        if x is None:
            return None
        out[t] = x[t]
        eq.append([Fraction(int(j == t)) for j in range(n + k)])
        rhs.append(x[t])
    out[order[-1]] = 1 - sum(out, Fraction(0))
    return tuple(out)
