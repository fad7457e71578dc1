"""Shared LP machinery: cvxpy + Clarabel, strict status checks, tree flow constraints.

Every LP of the checker is built from vectorised constraints on scipy.sparse matrices and
solved with ``solver=cp.CLARABEL`` at tightened tolerances. Any status other than
``optimal`` (``optimal_inaccurate`` included) raises :class:`LPError`: an LP never
contributes a silent number. LP values are floats; the checker compares them with the exact
values within :data:`LP_TOLERANCE` (relative, see :func:`lp_agrees`).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from dppverify.errors import LPError
from dppverify.exact import Number
from dppverify.tree_route.tree import WalkTree, flow_matrix

if TYPE_CHECKING:  # cvxpy (with scipy.stats) costs ~0.5 s: imported where an LP is built
    import cvxpy as cp

__all__ = ["LP_SOLVER", "LP_TOLERANCE", "SOLVER_SETTINGS", "LPStats", "flow_matrix", "lp_agrees",
           "realization_constraints", "solve"]

LP_SOLVER = "CLARABEL"
"""The LP solver (through cvxpy)."""

SOLVER_SETTINGS: dict[str, float] = {"tol_gap_abs": 1e-10, "tol_gap_rel": 1e-10,
                                     "tol_feas": 1e-10}
"""Clarabel settings: tighter than its defaults (1e-8) so that agreement at 1e-7 is routine."""

LP_TOLERANCE = 1e-7
"""Agreement of an LP value with an exact value: ``|lp - exact| <= 1e-7 * max(1, |exact|)``."""


@dataclass(frozen=True)
class LPStats:
    """What an LP solve reports: value, status, size and time."""

    value: float
    status: str
    variables: int
    constraints: int
    seconds: float


def lp_agrees(lp_value: float, exact_value: Number, tolerance: float = LP_TOLERANCE) -> bool:
    """True when an LP value matches an exact value within the relative tolerance.

    Examples
    --------
    >>> from fractions import Fraction
    >>> lp_agrees(2.4000000001, Fraction(12, 5)), lp_agrees(2.41, Fraction(12, 5))
    (True, False)
    """
    exact = float(exact_value)
    return math.isfinite(lp_value) and abs(lp_value - exact) <= tolerance * max(1.0, abs(exact))


def solve(problem: cp.Problem, what: str) -> LPStats:
    """Solve ``problem`` with Clarabel; raise :class:`LPError` unless the status is optimal.

    Examples
    --------
    >>> import cvxpy as cp
    >>> x = cp.Variable(2)
    >>> solve(cp.Problem(cp.Minimize(cp.sum(x)), [x >= 1]), "demo").status
    'optimal'
    >>> solve(cp.Problem(cp.Minimize(cp.sum(x)), [x >= 1, x <= 0]), "demo")
    Traceback (most recent call last):
    dppverify.errors.LPError: demo: CLARABEL returned status 'infeasible', not 'optimal'
    """
    import cvxpy as cp

    t0 = time.perf_counter()
    try:
        problem.solve(solver=cp.CLARABEL, **SOLVER_SETTINGS)
    except cp.error.SolverError as exc:
        raise LPError(f"{what}: CLARABEL failed ({exc})") from None
    seconds = time.perf_counter() - t0
    if problem.status != cp.OPTIMAL:
        raise LPError(f"{what}: CLARABEL returned status {problem.status!r}, not 'optimal'")
    value = float(problem.value)
    if not math.isfinite(value):  # pragma: no cover - optimal implies finite
        raise LPError(f"{what}: CLARABEL returned a non-finite optimum {value}")
    size = problem.size_metrics
    return LPStats(value=value, status=str(problem.status),
                   variables=int(size.num_scalar_variables),
                   constraints=int(size.num_scalar_eq_constr + size.num_scalar_leq_constr),
                   seconds=seconds)


def realization_constraints(tree: WalkTree, x: cp.Variable) -> list[cp.Constraint]:
    """``x`` is a realization plan on ``tree``: ``x >= 0``, ``x[root] = 1``, flow conservation.

    Parameters
    ----------
    tree : WalkTree
        The walk tree (any number of goals).
    x : cvxpy.Variable
        One entry per prefix.

    Returns
    -------
    list of cvxpy.Constraint
        Three constraints (two when the tree is only its root).

    Examples
    --------
    On the triangle (prefixes 0 = s, 1 = s g1, 2 = s g2) a plan puts the root's unit of
    probability on the two walks; the cheapest plan for the costs (1, 3) is pure:

    >>> from dppverify.game.examples import triangle
    >>> from dppverify.tree_route.tree import build_tree
    >>> tree = build_tree(triangle(), 1)
    >>> import cvxpy as cp
    >>> x = cp.Variable(tree.n_prefixes)
    >>> stats = solve(cp.Problem(cp.Minimize(x[1] + 3 * x[2]), realization_constraints(tree, x)),
    ...               "demo")
    >>> round(stats.value, 6), [round(float(v), 6) + 0.0 for v in x.value]
    (1.0, [1.0, 1.0, 0.0])
    """
    cons: list[Any] = [x >= 0, x[0] == 1]
    if tree.n_prefixes > 1:
        cons.append(flow_matrix(tree) @ x == 0)
    return cons
