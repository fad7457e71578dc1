"""Shared LP machinery: cvxpy + Clarabel, strict status checks, tree flow constraints.

Every LP of the checker is built from vectorised constraints on scipy.sparse matrices and
solved with ``solver=cp.CLARABEL`` at tightened tolerances. Any status other than
``optimal`` (``optimal_inaccurate`` included) raises :class:`LPError`: an LP never
contributes a silent number. LP values are floats; the checker compares them with the exact
values within :data:`LP_TOLERANCE` (relative, see :func:`lp_agrees`).

Costs far from size one are rescaled before an LP is built (:func:`cost_scale`): when the
largest cost coefficient lies outside ``[2**-16, 2**16]``, every cost coefficient of the LP's
objective is multiplied by one power of two that brings the largest into [1/2, 1), and the
optimum is divided by it again (:func:`unscaled`). The optimal strategies are those of
the unscaled LP (a positive factor on the objective changes no optimal point, and the
Defender's duals, divided by the equally scaled weights, are unchanged), a power of two is
exact in binary floating point, and the solver's absolute tolerances then act on numbers of
size one: an instance whose weights are all multiplied by 10^12 or 10^-12 is solved as well
as the instance itself.
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from dppverify.errors import LPError
from dppverify.exact import Number
from dppverify.tree_route.tree import WalkTree, flow_matrix

if TYPE_CHECKING:  # cvxpy (with scipy.stats) costs ~0.5 s: imported where an LP is built
    import cvxpy as cp


LP_SOLVER = "CLARABEL"
"""The LP solver (through cvxpy)."""

SOLVER_SETTINGS: dict[str, float] = {"tol_gap_abs": 1e-10, "tol_gap_rel": 1e-10,
                                     "tol_feas": 1e-10}
"""Clarabel settings: tighter than its defaults (1e-8) so that agreement at 1e-7 is routine."""

LP_TOLERANCE = 1e-7
"""Agreement of an LP value with an exact value: ``|lp - exact| <= 1e-7 * max(1, |exact|)``."""


@dataclass(frozen=True)
class LPStats:
    """What an LP solve reports: value, status, size and time; ``magnitude`` is the size of
    the LP's costs (the power of two above the largest, :func:`cost_scale`), the scale of its
    absolute error (:func:`lp_agrees`)."""

    value: float
    status: str
    variables: int
    constraints: int
    seconds: float
    magnitude: float = 1.0


SCALED_BEYOND = 2.0 ** 16
"""Costs are rescaled only when the largest lies outside ``[2**-16, 2**16]``: instances of
ordinary size keep their LPs exactly as posed (and their LP values to the last digit)."""


def cost_scale(*costs: np.ndarray | float) -> float:
    """The power of two ``2**-k`` by which to multiply an LP's cost coefficients: 1 when the
    largest in absolute value lies within ``[2**-16, 2**16]`` (:data:`SCALED_BEYOND`), is 0 or
    is not finite; otherwise the one that brings it into [1/2, 1).

    Examples
    --------
    >>> cost_scale(np.array([3.0, -0.5])), cost_scale(np.array([2e12]), 7.0) * 2e12
    (1.0, 0.9094947017729282)
    >>> cost_scale(np.array([1e-12])) * 1e-12, cost_scale(np.zeros(3)), cost_scale()
    (0.549755813888, 1.0, 1.0)
    """
    largest = max((float(np.max(np.abs(c), initial=0.0)) for c in costs), default=0.0)
    if not math.isfinite(largest) or largest == 0.0 or \
            1.0 / SCALED_BEYOND <= largest <= SCALED_BEYOND:
        return 1.0
    return math.ldexp(1.0, -math.frexp(largest)[1])


def unscaled(stats: LPStats, scale: float) -> LPStats:
    """The statistics of an LP solved with costs multiplied by ``scale``, with the value of
    the LP as posed (divided by ``scale``: exact, a power of two).

    Examples
    --------
    >>> stats = unscaled(LPStats(0.75, "optimal", 2, 3, 0.1), 2.0 ** -20)
    >>> stats.value, stats.magnitude
    (786432.0, 1048576.0)
    >>> unscaled(LPStats(0.75, "optimal", 2, 3, 0.1), 1.0).magnitude  # not rescaled: 1
    1.0
    """
    if scale == 1.0:
        return stats
    return dataclasses.replace(stats, value=stats.value / scale, magnitude=1.0 / scale)


def lp_agrees(lp: float | LPStats, exact_value: Number,
              tolerance: float = LP_TOLERANCE) -> bool:
    """True when an LP value matches an exact value within the relative tolerance:
    ``|lp - exact| <= tolerance * max(|exact|, m)``, where ``m`` is the LP's ``magnitude``
    (the size of its costs: an LP solved on costs of size one is accurate relative to them)
    when ``lp`` is an :class:`LPStats`, else 1.

    Examples
    --------
    >>> from fractions import Fraction
    >>> lp_agrees(2.4000000001, Fraction(12, 5)), lp_agrees(2.41, Fraction(12, 5))
    (True, False)
    >>> huge = LPStats(-4.4e1, "optimal", 1, 1, 0.0, magnitude=2.0 ** 43)  # weights ~ 10^12
    >>> lp_agrees(huge, 0), lp_agrees(-4.4e1, 0)
    (True, False)
    """
    if isinstance(lp, LPStats):
        value, floor = lp.value, lp.magnitude
    else:
        value, floor = lp, 1.0
    exact = float(exact_value)
    return math.isfinite(value) and abs(value - exact) <= tolerance * max(floor, abs(exact))


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
