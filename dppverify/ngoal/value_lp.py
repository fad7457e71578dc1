"""The tree route: ``V_H`` of the truncated N-goal game as one compact LP, plus an exact bracket.

LP (cvxpy + Clarabel, status checked; ``proofs/LP.md`` with N types)::

    V_H = min  Σ_θ b_θ Σ_leaves x_θ(ℓ) d(end ℓ, g^θ) + Σ_{p ≠ root} w_p z_p
          s.t. x_θ realization plans on the walk tree,  z_p >= b_θ x_θ(p)  for every θ.

The Defender's best response to fixed plans is greedy per information set, so ``max_σ`` of the
bilinear payoff is ``Σ_p w_p max_θ b_θ x_θ(p)``. The duals ``λ_θ(p)`` of ``z_p >= b_θ x_θ(p)``
sum to ``w_p`` at every prefix (stationarity in ``z_p``), so ``σ(g^θ | p) = λ_θ(p) / w_p`` is an
optimal Defender strategy.

The LP, the rounding of its plans and the bracket search are the two-goal ones
(:func:`~dppverify.tree_route.value_lp.solve_types_lp`,
:func:`~dppverify.tree_route.value_lp.rational_plan`,
:class:`~dppverify.tree_route.value_lp.BracketSearch`); this module adds the N-type bounds.

Exact bracket (the two-goal method of :mod:`dppverify.tree_route.value_lp`, for N types): for ANY
rational
Defender ``σ``, ``Σ_θ b_θ min_walk U^θ(σ)`` (exact backward induction) is a lower bound on
``V_H``; for ANY rational Attacker plans the exact greedy Defender value is an upper bound.
The LP's dual and primal solutions are rounded to small-denominator rationals (the same
denominator limits as for two goals); if that leaves the bracket open, the LP is solved exactly
(:mod:`dppverify.tree_route.lp_exact`) and its strategies close it. ``V_H`` is reported exactly
when the
best bounds meet; an open bracket carries its reason.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from dppverify.exact import Number, normalize
from dppverify.ngoal.best_response import (
    NTreeDefender,
    attacker_best_response,
    defender_best_response,
    defender_from_table,
)
from dppverify.ngoal.instance import NInstance
from dppverify.tree_route.lp import LPStats
from dppverify.tree_route.tree import DEFAULT_MAX_PREFIXES, WalkTree, build_tree
from dppverify.tree_route.value_lp import Bracket, BracketSearch, rational_plan, solve_types_lp

__all__ = ["NGameValue", "NValueLP", "exact_nbracket", "lower_nbound", "ngame_value",
           "solve_nvalue_lp", "upper_nbound"]

Plan = Mapping[int, Fraction]


@dataclass(frozen=True)
class NValueLP:
    """The compact LP's solution: ``V_H`` (float), the types' plans and the Defender.

    Attributes
    ----------
    stats : LPStats
        Value, status, size, time.
    plans : numpy.ndarray
        ``plans[θ]``: type θ's realization plan (one float per prefix).
    sigma : numpy.ndarray
        ``sigma[θ][p]``: the Defender's probability on goal θ at prefix ``p`` (from duals).
    """

    stats: LPStats
    plans: np.ndarray
    sigma: np.ndarray

    @property
    def value(self) -> float:
        """``V_H`` as computed by the LP."""
        return self.stats.value


def solve_nvalue_lp(tree: WalkTree) -> NValueLP:
    """Solve the compact N-type value LP on ``tree`` (Clarabel; status checked).

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> round(solve_nvalue_lp(build_tree(star3(), 2)).value, 6)
    1.5
    """
    inst = tree.instance
    stats, plans, sigma = solve_types_lp(tree, inst.prior, inst.dist_to,
                                         f"N-goal value LP (N = {inst.n_goals}, "
                                         f"H = {tree.horizon})")
    return NValueLP(stats=stats, plans=plans, sigma=sigma)


def lower_nbound(tree: WalkTree, tdef: NTreeDefender) -> Number:
    """Exact ``Σ_θ b_θ min_walk U^θ`` against a fixed Defender: a lower bound on ``V_H``.

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> t = build_tree(star3(), 2)
    >>> third = Fraction(1, 3)
    >>> lower_nbound(t, defender_from_table(t, {}, (third, third, third)))
    Fraction(2, 3)
    """
    inst = tree.instance
    total = sum((inst.prior[t] * attacker_best_response(tree, tdef, t).value
                 for t in range(inst.n_goals)), Fraction(0))
    return normalize(total)


def upper_nbound(tree: WalkTree, plans: Sequence[Plan]) -> Number:
    """Exact greedy Defender value against fixed Attacker plans: an upper bound on ``V_H``.

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> t = build_tree(star3(), 1)
    >>> upper_nbound(t, [{0: Fraction(1), 1: Fraction(1)}] * 3)
    2
    """
    return defender_best_response(tree, plans).value


def _rational_defender(tree: WalkTree, sigma: np.ndarray, den: int) -> NTreeDefender:
    k = tree.instance.n_goals
    table: dict[int, tuple[Fraction, ...]] = {}
    for p in range(1, tree.n_prefixes):
        raw = [float(sigma[t, p]) if np.isfinite(sigma[t, p]) else 0.0 for t in range(k)]
        fr = [Fraction(max(r, 0.0)).limit_denominator(den) for r in raw]
        s = sum(fr, Fraction(0))
        if s == 0:
            top = int(np.argmax(raw))
            fr = [Fraction(int(t == top)) for t in range(k)]
            s = Fraction(1)
        table[p] = tuple(f / s for f in fr)
    return defender_from_table(tree, table, None)


def exact_nbracket(tree: WalkTree, lp: NValueLP | None = None,
                   defenders: Iterable[tuple[str, NTreeDefender]] = (),
                   attackers: Iterable[tuple[str, Sequence[Plan]]] = ()) -> Bracket:
    """Exact bounds on ``V_H`` from rational strategies (see the module docstring).

    Candidates: the given ``defenders`` and ``attackers``, the uniform Defender, and the LP
    solution rounded at each denominator limit (stopping once the bracket closes).

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> t = build_tree(star3(), 2)
    >>> b = exact_nbracket(t, solve_nvalue_lp(t))
    >>> b.exact, b.closed
    (Fraction(3, 2), True)
    """
    k = tree.instance.n_goals
    search = BracketSearch()
    uniform = tuple(Fraction(1, k) for _ in range(k))
    search.offer_lower(lower_nbound(tree, defender_from_table(tree, {}, uniform)),
                       "uniform Defender")
    for src, tdef in defenders:
        search.offer_lower(lower_nbound(tree, tdef), src)
    for src, plans in attackers:
        search.offer_upper(upper_nbound(tree, plans), src)
    if lp is not None:
        search.rounded(
            lambda den: lower_nbound(tree, _rational_defender(tree, lp.sigma, den)),
            lambda den: upper_nbound(tree, [rational_plan(tree, lp.plans[t], den)
                                            for t in range(k)]))
        inst = tree.instance
        search.exact_lp(tree, inst.prior, inst.dist_to,
                        lambda sigma: lower_nbound(tree, defender_from_table(
                            tree, dict(enumerate(sigma)), None)),
                        lambda plans: upper_nbound(tree, plans))
    return search.bracket(lambda plan: upper_nbound(tree, [plan] * k), tree)


@dataclass(frozen=True)
class NGameValue:
    """``V_H`` of an N-goal instance by the tree route: LP value, exact bracket, tree size.

    Attributes
    ----------
    horizon : int
        ``H``.
    lp : LPStats
        The compact LP's value (float), status, size and time.
    bracket : Bracket
        Exact bounds on ``V_H`` (closed when ``V_H`` is known exactly).
    prefixes, leaves : int
        Size of the walk tree.
    """

    horizon: int
    lp: LPStats
    bracket: Bracket
    prefixes: int
    leaves: int

    @property
    def value(self) -> float:
        """``V_H`` from the LP."""
        return self.lp.value


def ngame_value(instance: NInstance, horizon: int, *,
                max_prefixes: int = DEFAULT_MAX_PREFIXES) -> NGameValue:
    """``V_H`` of the truncated N-goal game: compact LP plus exact bracket.

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> v = ngame_value(star3(), 2)
    >>> v.bracket.exact, round(v.value, 6), v.prefixes
    (Fraction(3, 2), 1.5, 6)
    """
    tree = build_tree(instance, horizon, max_prefixes=max_prefixes)
    lp = solve_nvalue_lp(tree)
    return NGameValue(horizon=horizon, lp=lp.stats, bracket=exact_nbracket(tree, lp),
                      prefixes=tree.n_prefixes, leaves=tree.n_leaves)
