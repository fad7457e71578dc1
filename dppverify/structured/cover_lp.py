"""Support functions of normal-described sets at many nodes at once: an exact cover LP whose
optimal bases are found lazily.

For a set ``F_v = { r : a·r <= m_a(v), a ∈ A }`` (``A ∋`` the unit vectors) and a direction
``y >= 0``, LP duality gives ``h_{F_v}(y) = min { Σ_a c_a m_a(v) : c >= 0, Σ_a c_a a = y }``
(``proofs/NGOAL.md`` S1). The feasible bases of this LP do not depend on ``v``; a basis ``B``
(``c_B = B^{-1} y >= 0``) is optimal at ``v`` iff its dual ``π = m_B(v) B^{-1}`` satisfies
``a·π <= m_a(v)`` for every usable normal. :func:`cover_values` starts from the optimal basis
of one node (exact simplex, :func:`dppverify.structured.lexmin.simplex_basis`), checks it at
every node at once (exact integer arithmetic), solves the LP again at a node where no known
basis is optimal, and repeats: on real instances a handful of bases serve every node, instead
of the whole vertex table of the cover polytope (:mod:`dppverify.structured.cover`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from fractions import Fraction

import numpy as np

from dppverify.structured.cover import Normal
from dppverify.structured.lexmin import simplex_basis


def _adjugate(mat: list[list[int]]) -> tuple[int, list[list[int]]]:
    """``(det, adj)`` of a small integer matrix (``adj = det · mat^{-1}``; ``det = 0``: no
    ``adj``), exact (Gauss-Jordan in rationals)."""
    m = len(mat)
    a = [[Fraction(x) for x in row] + [Fraction(int(i == j)) for j in range(m)]
         for i, row in enumerate(mat)]
    det = Fraction(1)
    for col in range(m):
        piv = next((r for r in range(col, m) if a[r][col] != 0), None)
        if piv is None:
            return 0, []
        if piv != col:
            a[col], a[piv] = a[piv], a[col]
            det = -det
        p = a[col][col]
        det *= p
        a[col] = [x / p for x in a[col]]
        for r in range(m):
            if r != col and a[r][col] != 0:
                f = a[r][col]
                a[r] = [x - f * y for x, y in zip(a[r], a[col], strict=True)]
    d = int(det)
    return d, [[int(d * a[i][m + j]) for j in range(m)] for i in range(m)]


def _float_basis(cost: np.ndarray, amat: np.ndarray, b: np.ndarray) -> list[int] | None:
    """A candidate optimal basis of ``min cost·c`` s.t. ``amat c = b``, ``c >= 0`` by a float
    simplex (Bland's rule; the caller verifies it exactly). None when it stalls."""
    m, k = amat.shape
    tab = np.zeros((m, k + m + 1))
    tab[:, :k] = amat
    tab[:, k:k + m] = np.eye(m)
    tab[:, -1] = b
    basis = list(range(k, k + m))
    eps = 1e-9

    def run(obj: np.ndarray, allowed: int) -> bool:
        for _ in range(200):
            cb = obj[basis]
            red = obj[:allowed] - cb @ tab[:, :allowed]
            red[[j for j in basis if j < allowed]] = 0
            cand = np.flatnonzero(red < -eps)
            if cand.size == 0:
                return True
            e = int(cand[0])
            col = tab[:, e]
            pos = col > eps
            if not pos.any():
                return False
            ratio = np.where(pos, tab[:, -1] / np.where(pos, col, 1), np.inf)
            best = ratio.min()
            ties = np.flatnonzero(ratio <= best + eps)
            leave = int(min(ties, key=lambda i: basis[i]))
            tab[leave] /= tab[leave, e]
            for i in range(m):
                if i != leave and abs(tab[i, e]) > 0:
                    tab[i] -= tab[i, e] * tab[leave]
            basis[leave] = e
        return False

    obj1 = np.concatenate([np.zeros(k), np.ones(m)])
    if not run(obj1, k + m):
        return None
    for i in range(m):  # drive the artificials out
        if basis[i] >= k:
            cand = [j for j in range(k) if abs(tab[i, j]) > eps and j not in basis]
            if not cand:
                return None
            j = cand[0]
            tab[i] /= tab[i, j]
            for r in range(m):
                if r != i and abs(tab[r, j]) > 0:
                    tab[r] -= tab[r, j] * tab[i]
            basis[i] = j
    obj2 = np.concatenate([cost.astype(np.float64), np.zeros(m)])
    return basis if run(obj2, k) else None


def _as(arr: np.ndarray, bound: int) -> np.ndarray:
    return arr.astype(np.int64) if bound < 2 ** 62 else arr.astype(object)


def _checked(amat: list[list[int]], b: list[int], basis: list[int]
             ) -> tuple[int, list[list[int]], list[int]] | None:
    """``(det > 0, adj, adj·b)`` of a basis that is non-singular and primal feasible."""
    det, adj = _adjugate([[amat[i][j] for j in basis] for i in range(len(b))])
    if det == 0:
        return None
    if det < 0:
        det, adj = -det, [[-x for x in row] for row in adj]
    cnum = [sum(adj[i][r] * b[r] for r in range(len(b))) for i in range(len(basis))]
    return (det, adj, cnum) if all(x >= 0 for x in cnum) else None


def _exact_basis(cost: np.ndarray, amat: list[list[int]], b: list[int]
                 ) -> tuple[list[int], tuple[int, list[list[int]], list[int]]]:
    """An optimal basis of ``min cost·c`` s.t. ``amat c = b``, ``c >= 0`` by the exact simplex,
    with its :func:`_checked` ``(det, adj, adj·b)``."""
    found = simplex_basis([Fraction(int(x)) for x in cost],
                          [[Fraction(x) for x in row] for row in amat],
                          [Fraction(x) for x in b])
    assert found is not None  # the unit vectors cover rhs
    basis = found[1]
    assert -1 not in basis  # full row rank: the unit vectors are columns
    adjusted = _checked(amat, b, basis)
    assert adjusted is not None  # primal feasible
    return basis, adjusted


def _candidate_basis(cost: np.ndarray, amat: list[list[int]], b: list[int]
                     ) -> tuple[list[int], tuple[int, list[list[int]], list[int]]]:
    """A feasible basis for the node whose costs are ``cost``: the float simplex's when it is
    non-singular and primal feasible, else the exact simplex's."""
    col_v = np.array([float(x) for x in cost])
    scale_v = max(1.0, float(np.abs(col_v).max(initial=0.0)))
    basis = _float_basis(col_v / scale_v, np.array(amat, dtype=np.float64),
                         np.array(b, dtype=np.float64))
    adjusted = None if basis is None else _checked(amat, b, basis)
    if basis is None or adjusted is None:  # the float simplex stalled or erred
        return _exact_basis(cost, amat, b)
    return basis, adjusted


def _optimal_where(vals: np.ndarray, idx: np.ndarray, basis: list[int],
                   adjusted: tuple[int, list[list[int]], list[int]], amat: list[list[int]]
                   ) -> tuple[np.ndarray, np.ndarray]:
    """``(num, ok)`` over the nodes ``idx``: ``ok`` where the basis is optimal (its dual
    ``π·det = m_B^T adj`` satisfies ``a·π·det <= det·m_a`` for every usable normal ``a``),
    ``num = h·det`` there."""
    det, adj, cnum = adjusted
    top = int(np.max(np.abs(vals), initial=0)) if vals.size else 0
    bound = (top + 1) * (max(abs(x) for row in adj for x in row) + 1) * (
        max(max(r) for r in amat) + 1) * (len(amat) + 1) ** 2 * (det + 1)
    mb = _as(vals[basis][:, idx].T, bound)  # nodes × m
    pi = mb @ _as(np.array(adj, dtype=object), bound)  # nodes × m  (π·det)
    red = pi @ _as(np.array(amat, dtype=object), bound)  # nodes × k  (a·π·det)
    ok = np.all(red <= _as(vals[:, idx].T, bound) * det, axis=1)
    return mb @ _as(np.array(cnum, dtype=object), bound), ok


def cover_values(normals: Sequence[Normal], values: np.ndarray, rhs: Sequence[int]
                 ) -> tuple[np.ndarray, int]:
    """``h(v) = min { Σ_j c_j values[j, v] : c >= 0, Σ_j c_j normals[j] = rhs }`` at every
    column ``v`` of ``values``, exactly: returns ``(num, den)`` with ``h(v) = num[v] / den``.

    ``normals`` must contain the unit vectors on the support of ``rhs`` (non-negative
    integers throughout); ``values`` is an integer array ``(len(normals), nodes)``.

    Examples
    --------
    Covers of (1, 1, 1) by the seven subsets of three goals, at two nodes:

    >>> from dppverify.structured.cover import zero_one_normals
    >>> vals = np.array([[2, 2], [2, 2], [2, 5], [2, 2], [2, 2], [2, 2], [5, 5]])
    >>> num, den = cover_values(zero_one_normals(3), vals, (1, 1, 1))
    >>> [Fraction(int(x), den) for x in num]
    [Fraction(3, 1), Fraction(4, 1)]
    """
    rhs = tuple(int(x) for x in rhs)
    rows = [i for i, x in enumerate(rhs) if x]
    n_nodes = values.shape[1]
    if not rows:
        return np.zeros(n_nodes, dtype=object), 1
    usable = [j for j, a in enumerate(normals)
              if any(a) and all(a[i] == 0 for i in range(len(rhs)) if not rhs[i])]
    amat = [[int(normals[j][i]) for j in usable] for i in rows]  # m × k
    b = [rhs[i] for i in rows]
    vals = np.asarray(values, dtype=object)[usable]  # k × nodes
    dens: list[int] = []  # den = |det| per basis found
    value = np.full(n_nodes, None, dtype=object)
    den_of = np.zeros(n_nodes, dtype=object)
    open_ = np.ones(n_nodes, dtype=bool)
    while open_.any():
        idx = np.flatnonzero(open_)
        v = int(idx[0])  # the first open node, ok[0] below
        basis, adjusted = _candidate_basis(vals[:, v], amat, b)
        num, ok = _optimal_where(vals, idx, basis, adjusted, amat)
        if not ok[0]:  # the float basis is not optimal at v
            basis, adjusted = _exact_basis(vals[:, v], amat, b)
            num, ok = _optimal_where(vals, idx, basis, adjusted, amat)
            assert ok[0]  # optimal where it was found
        good = idx[ok]
        value[good] = np.asarray(num, dtype=object)[ok]
        den_of[good] = adjusted[0]
        open_[good] = False
        dens.append(int(adjusted[0]))
        if len(dens) > 10 * len(usable) + 100:  # pragma: no cover - each round adds a basis
            raise AssertionError("cover_values: too many bases")
    den = math.lcm(*dens)
    out = np.array([int(x) * (den // int(d)) for x, d in zip(value, den_of, strict=True)],
                   dtype=object)
    return out, den
