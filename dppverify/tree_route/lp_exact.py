"""The compact tree LP solved exactly: an optimal basis from a float vertex, then exact rationals.

The LP of :func:`dppverify.tree_route.value_lp.solve_value_lp` (any number of goals) in standard
form::

    min  Σ_θ b_θ Σ_leaves d_θ(end ℓ) x_θ(ℓ) + Σ_{p ≠ root} w_p z_p
    s.t. x_θ(root) = 1,  x_θ(p) - Σ_children x_θ(c) = 0,  z_p - b_θ x_θ(p) - s_θ(p) = 0,
         x, z, s >= 0.

1. A vertex solution in floats: HiGHS's dual simplex (``scipy.optimize.linprog``,
   ``method="highs-ds"``, status checked).
2. An exact basis: the columns positive at that vertex first, then the others by increasing
   float reduced cost; the pivot columns of the exact sparse row reduction of the constraint
   matrix in that order (sympy's ``DomainMatrix`` over ``QQ``: exact, sparse, so the tree's
   structure keeps the elimination cheap) — the first independent columns, so the vertex's
   support is in the basis.
3. Exact primal ``x_B = B⁻¹ b`` and dual ``y = B⁻ᵀ c_B``; the basis is optimal iff ``x_B >= 0`` and
   every reduced cost ``c_j - yᵀA_j >= 0`` — checked exactly. Otherwise exact primal simplex
   pivots (Bland's rule) from that basis, a bounded number of them.

The caller turns the exact primal into Attacker plans and the dual of ``z_p >= b_θ x_θ(p)``
into a Defender (``σ_θ(p) = y_θ(p) / w_p``) and evaluates both with the exact best responses,
which prove the value independently of this module. Why sympy rather than ``python-flint``:
flint's rational matrices are dense, while these matrices have a handful of entries per row and
eliminate with little fill-in; sympy is already a dependency.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction

import numpy as np
import scipy.sparse as sps
from scipy.optimize import linprog
from sympy import QQ
from sympy.polys.matrices import DomainMatrix

from dppverify.exact import Number
from dppverify.tree_route.lp import cost_scale
from dppverify.tree_route.tree import WalkTree

MAX_EXACT_ROWS = 40_000
"""Largest LP (constraint rows) the exact closure attempts."""

MAX_PIVOTS = 60
"""Exact simplex pivots tried after the recovered basis."""


@dataclass(frozen=True)
class ExactLP:
    """An exactly optimal solution of the compact tree LP.

    Attributes
    ----------
    value : Fraction
        The LP optimum ``V_H``.
    plans : list of dict
        ``plans[θ]``: prefix -> ``x_θ(p) > 0`` (a realization plan).
    sigma : list of tuple of Fraction
        ``sigma[p]``: the Defender's distribution at prefix ``p`` (``p >= 1``; entry 0 unused).
    pivots : int
        Exact simplex pivots needed after the recovered basis.
    """

    value: Fraction
    plans: list[dict[int, Fraction]]
    sigma: list[tuple[Fraction, ...]]
    pivots: int


class _LP:
    """The standard form: sparse exact columns, right-hand side and costs."""

    def __init__(self, tree: WalkTree, priors: Sequence[Number],
                 dists: Sequence[Sequence[Number]]) -> None:
        n = tree.n_prefixes
        k = len(priors)
        self.n, self.k = n, k
        leaf = tree.is_leaf_mask()
        inner = [int(p) for p in np.flatnonzero(~leaf)]
        rows = 0
        entries: list[tuple[int, int, Fraction]] = []  # (row, col, value)
        self.b: list[Fraction] = []
        self.xcol = lambda t, p: t * n + p
        self.zcol = lambda p: k * n + p - 1
        self.scol = lambda t, p: k * n + (n - 1) + t * (n - 1) + p - 1
        self.ineq_row: dict[tuple[int, int], int] = {}
        for t in range(k):
            entries.append((rows, self.xcol(t, 0), Fraction(1)))
            self.b.append(Fraction(1))
            rows += 1
            for p in inner:
                entries.append((rows, self.xcol(t, p), Fraction(1)))
                for c in range(int(tree.child_start[p]), int(tree.child_stop[p])):
                    entries.append((rows, self.xcol(t, c), Fraction(-1)))
                self.b.append(Fraction(0))
                rows += 1
        for t in range(k):
            bt = Fraction(priors[t])
            for p in range(1, n):
                entries.append((rows, self.zcol(p), Fraction(1)))
                entries.append((rows, self.xcol(t, p), -bt))
                entries.append((rows, self.scol(t, p), Fraction(-1)))
                self.b.append(Fraction(0))
                self.ineq_row[(t, p)] = rows
                rows += 1
        self.m = rows
        self.ncols = k * n + (n - 1) * (k + 1)
        self.c = [Fraction(0)] * self.ncols
        for t in range(k):
            for q in np.flatnonzero(leaf).tolist():
                self.c[self.xcol(t, q)] = Fraction(priors[t]) * Fraction(
                    dists[t][int(tree.node[q])])
        for p in range(1, n):
            self.c[self.zcol(p)] = Fraction(tree.weight[p])
        self.weight = [Fraction(tree.weight[p]) for p in range(n)]
        self.cols: list[dict[int, Fraction]] = [{} for _ in range(self.ncols)]
        for r, j, v in entries:
            self.cols[j][r] = self.cols[j].get(r, Fraction(0)) + v

    def float_vertex(self) -> tuple[np.ndarray, np.ndarray] | str:
        rows, cols, vals = [], [], []
        for j, col in enumerate(self.cols):
            for r, v in col.items():
                rows.append(r)
                cols.append(j)
                vals.append(float(v))
        a = sps.csr_matrix((vals, (rows, cols)), shape=(self.m, self.ncols))
        costs = np.array([float(x) for x in self.c])
        costs *= cost_scale(costs)  # costs of size one (lp.py): the same vertices, ordering
        res = linprog(costs, A_eq=a, b_eq=np.array([float(x) for x in self.b]),
                      bounds=(0, None), method="highs-ds")
        if res.status != 0:
            return f"HiGHS's dual simplex returned status {res.status} ({res.message})"
        y = np.asarray(res.eqlin.marginals, dtype=float)
        reduced = costs - a.T @ y
        return np.asarray(res.x, dtype=float), reduced

    def basis(self, order: list[int]) -> list[int] | None:
        """The pivot columns (in ``order``) of the exact row reduction: an exact basis."""
        data: dict[int, dict[int, object]] = {}
        for pos, j in enumerate(order):
            for r, v in self.cols[j].items():
                if v:
                    data.setdefault(r, {})[pos] = QQ(v.numerator, v.denominator)
        mat = DomainMatrix(data, (self.m, len(order)), QQ)
        _, pivots = mat.rref()
        if len(pivots) < self.m:
            return None
        return [order[p] for p in pivots]

    def _solve(self, basis: list[int], rhs: Sequence[Fraction], transpose: bool
               ) -> list[Fraction]:
        """``B x = rhs`` (or ``Bᵀ x = rhs``) exactly, by sparse row reduction."""
        m = self.m
        data: dict[int, dict[int, object]] = {}
        for pos, j in enumerate(basis):
            for r, v in self.cols[j].items():
                if v:
                    i, c = (pos, r) if transpose else (r, pos)
                    data.setdefault(i, {})[c] = QQ(v.numerator, v.denominator)
        for i, v in enumerate(rhs):
            if v:
                data.setdefault(i, {})[m] = QQ(v.numerator, v.denominator)
        red, pivots = DomainMatrix(data, (m, m + 1), QQ).rref()
        if len(pivots) != m or pivots[-1] == m:  # pragma: no cover - B is a basis
            raise ArithmeticError("singular basis")
        rows = red.to_sdm()
        out = [Fraction(0)] * m
        for i, c in enumerate(pivots):
            v = rows.get(i, {}).get(m)
            if v is not None:
                out[c] = Fraction(int(v.numerator), int(v.denominator))
        return out

    def optimal(self, basis: list[int]) -> tuple[list[Fraction], list[Fraction], int] | str:
        """Exact primal and dual of an optimal basis reached from ``basis`` (or a reason)."""
        for pivots in range(MAX_PIVOTS + 1):
            xb = self._solve(basis, self.b, transpose=False)
            if any(v < 0 for v in xb):
                return "the recovered basis is not primal feasible"
            y = self._solve(basis, [self.c[j] for j in basis], transpose=True)
            inb = set(basis)
            entering = None
            for j in range(self.ncols):
                if j in inb:
                    continue
                rc = self.c[j] - sum((y[r] * v for r, v in self.cols[j].items()), Fraction(0))
                if rc < 0:
                    entering = j
                    break
            if entering is None:
                x = [Fraction(0)] * self.ncols
                for pos, j in enumerate(basis):
                    x[j] = xb[pos]
                return x, y, pivots
            # Bland: the leaving row by the smallest ratio, ties by the smallest column index
            d = self._solve(basis, self._dense(entering), transpose=False)
            best: tuple[Fraction, int, int] | None = None
            for pos, j in enumerate(basis):
                if d[pos] > 0:
                    key = (xb[pos] / d[pos], j, pos)
                    if best is None or key[:2] < best[:2]:
                        best = key
            if best is None:  # pragma: no cover - the LP is bounded below
                return "the LP is unbounded along an exact pivot"
            basis = list(basis)
            basis[best[2]] = entering
        return f"no exactly optimal basis within {MAX_PIVOTS} exact simplex pivots"

    def _dense(self, j: int) -> list[Fraction]:
        out = [Fraction(0)] * self.m
        for r, v in self.cols[j].items():
            out[r] = v
        return out


def solve_tree_lp_exactly(tree: WalkTree, priors: Sequence[Number],
                          dists: Sequence[Sequence[Number]]) -> ExactLP | str:
    """The compact LP's exact optimum with optimal strategies, or the reason it is not found.

    Parameters
    ----------
    tree : WalkTree
        The walk tree (any number of goals).
    priors, dists : Sequence
        ``b_θ`` and the distances ``d(·, g^θ)`` of each type (exact).

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> from dppverify.tree_route.tree import build_tree
    >>> inst = star3()
    >>> r = solve_tree_lp_exactly(build_tree(inst, 2), inst.prior, inst.dist_to)
    >>> r.value, r.sigma[1]
    (Fraction(3, 2), (Fraction(1, 1), Fraction(0, 1), Fraction(0, 1)))
    """
    lp = _LP(tree, priors, dists)
    if lp.m > MAX_EXACT_ROWS:
        return (f"the exact LP closure handles up to {MAX_EXACT_ROWS:,} constraint rows, this "
                f"tree's LP has {lp.m:,}")
    got = lp.float_vertex()
    if isinstance(got, str):
        return got
    x, reduced = got
    scale = max(1.0, float(np.abs(x).max(initial=0.0)))
    support = sorted(np.flatnonzero(x > 1e-9 * scale).tolist(), key=lambda j: -x[j])
    rest = sorted(set(range(lp.ncols)) - set(support), key=lambda j: (abs(reduced[j]), j))
    basis = lp.basis(support + rest)
    if basis is None:
        return "the LP's equality rows are linearly dependent"
    out = lp.optimal(basis)
    if isinstance(out, str):
        return out
    xs, y, pivots = out
    value = sum((c * v for c, v in zip(lp.c, xs, strict=True) if v), Fraction(0))
    plans = [{p: xs[lp.xcol(t, p)] for p in range(lp.n) if xs[lp.xcol(t, p)]}
             for t in range(lp.k)]
    sigma: list[tuple[Fraction, ...]] = [tuple(Fraction(0) for _ in range(lp.k))]
    for p in range(1, lp.n):
        lam = [y[lp.ineq_row[(t, p)]] for t in range(lp.k)]
        rest_w = lp.weight[p] - sum(lam, Fraction(0))  # >= 0 by dual feasibility (z_p)
        lam[0] += rest_w  # unused allocation: any goal (costs only rise, NG/LP duality)
        sigma.append(tuple(v / lp.weight[p] for v in lam))
    return ExactLP(value=value, plans=plans, sigma=sigma, pivots=pivots)
