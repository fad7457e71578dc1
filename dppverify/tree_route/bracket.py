"""Exact bounds on ``V_H`` from rational strategies, and the search that closes them.

For ANY rational Defender strategy σ, ``Σ_θ b_θ min_walk U^θ(σ)`` (exact backward induction,
:func:`lower_bound`) is a lower bound on the truncated game's value ``V_H``; for ANY rational
Attacker realization plans, the exact greedy Defender value (:func:`upper_bound`) is an upper
bound. :class:`BracketSearch` keeps the best bounds offered (strategies given, the LP's
solution rounded to small denominators, the exactly solved LP) until they meet;
:func:`dppverify.tree_route.value_lp.exact_bracket` drives it. Any number of goals.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from fractions import Fraction

import numpy as np

from dppverify.exact import Bracket, Number, normalize
from dppverify.tree_route.best_response import attacker_best_response, defender_best_response
from dppverify.tree_route.players import (
    AnyTypes,
    DefenderOnTree,
    Plan,
    TreeStrategy,
    Types,
    as_types,
    defender_from_rows,
)
from dppverify.tree_route.tree import WalkTree

DENOMINATORS = (1, 2, 3, 4, 5, 6, 8, 10, 12, 20, 24, 60, 100, 360, 720, 1000, 5040, 10**4, 10**6)
"""Denominator limits tried when rounding LP solutions to rationals."""


def lower_bound(tree: WalkTree, types: AnyTypes, tdef: TreeStrategy) -> Number:
    """Exact ``Σ_θ b_θ min_walk U^θ`` against a fixed Defender: a lower bound on ``V_H``.

    ``tdef`` is the Defender evaluated on ``tree``; the bound is exact for rational instances.

    Examples
    --------
    Against σ* on the triangle the types' best responses cost 3 and 1; a Defender that
    always allocates to g1 lets the secondary reach g2 for free (7/10 · 3 + 3/10 · 0):

    >>> from dppverify.tree_route.tree_defender import tree_defender
    >>> from dppverify.game.examples import triangle
    >>> from dppverify.game.profile import ProgressRule, TableRule
    >>> from dppverify.tree_route.tree import build_tree
    >>> inst = triangle()
    >>> r = inst.roles()
    >>> tree = build_tree(inst, 1)
    >>> lower_bound(tree, r, tree_defender(tree, r, ProgressRule(r.g1)))
    Fraction(12, 5)
    >>> lower_bound(tree, r, tree_defender(tree, r, TableRule(r.g1, {}, Fraction(1))))
    Fraction(21, 10)
    >>> from dppverify.game.examples import star3
    >>> from dppverify.tree_route.players import defender_from_table
    >>> t = build_tree(star3(), 2)
    >>> third = Fraction(1, 3)
    >>> lower_bound(t, star3(), defender_from_table(t, {}, (third, third, third)))
    Fraction(2, 3)
    """
    ts = as_types(types)
    total = sum((ts.prior(who) * attacker_best_response(tree, ts, tdef, who).value
                 for who in ts.keys), Fraction(0))
    return tree.instance.numbers.convert(total)


def upper_bound(tree: WalkTree, types: AnyTypes, plans: Mapping[int, Plan]) -> Number:
    """Exact greedy Defender value against fixed Attacker plans: an upper bound on ``V_H``.

    ``plans[θ]`` is type θ's realization plan (prefix -> reach probability); the bound is
    exact for rational instances.

    Examples
    --------
    The triangle's equilibrium plans give ``12/5 = V_1``; a primary that always walks to
    g1 gives the Defender more:

    >>> from dppverify.game.examples import triangle
    >>> from dppverify.tree_route.tree import build_tree
    >>> inst = triangle()
    >>> tree = build_tree(inst, 1)   # prefixes: 0 = s, 1 = s g1, 2 = s g2
    >>> x2 = {0: Fraction(1), 2: Fraction(1)}
    >>> x1 = {0: Fraction(1), 1: Fraction(4, 7), 2: Fraction(3, 7)}
    >>> upper_bound(tree, inst.roles(), {1: x1, 2: x2})
    Fraction(12, 5)
    >>> upper_bound(tree, inst.roles(), {1: {0: Fraction(1), 1: Fraction(1)}, 2: x2})
    Fraction(27, 10)
    """
    return defender_best_response(tree, types, plans).value


def rounded_defender(tree: WalkTree, types: Types, sigma: np.ndarray, den: int
                     ) -> DefenderOnTree:
    """The LP's Defender ``sigma`` (``sigma[k][p]``, floats) rounded to denominators ``<= den``.

    With two types the first type's share is rounded and the second gets the rest (floats in
    float mode); with more, each share is rounded and the shares renormalised.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> from dppverify.tree_route.tree import build_tree
    >>> inst = triangle()
    >>> sigma = np.array([[np.nan, 0.9999999, 0.4999999], [np.nan, 0.0, 0.5]])
    >>> rounded_defender(build_tree(inst, 1), as_types(inst.roles()), sigma, 10).sigma
    ((0, 0), (1, 0), (Fraction(1, 2), Fraction(1, 2)))
    """
    exact = tree.instance.exact
    k = len(types.keys)
    rows: list[tuple[Number, ...]] = [tuple(0 for _ in range(k))]
    for p in range(1, tree.n_prefixes):
        raw = [float(sigma[j, p]) if np.isfinite(sigma[j, p]) else 0.0 for j in range(k)]
        if k == 2:
            q: Number = normalize(Fraction(raw[0]).limit_denominator(den)) if exact else raw[0]
            q = min(max(q, 0), 1)
            rows.append((q, 1 - q))
            continue
        fr = [Fraction(max(r, 0.0)).limit_denominator(den) for r in raw]
        s = sum(fr, Fraction(0))
        if s == 0:
            top = int(np.argmax(raw))
            fr = [Fraction(int(j == top)) for j in range(k)]
            s = Fraction(1)
        rows.append(tuple(f / s for f in fr))
    return defender_from_rows(tree, types, rows)


def rational_plan(tree: WalkTree, x: np.ndarray, den: int,
                  snap: float = 1e-7) -> dict[int, Fraction]:
    """Round a float realization plan to an exactly feasible rational one (behavioural form).

    At every reached prefix the children's shares ``x[c] / Σ x[c]`` are rounded to
    denominators ``<= den`` (shares below ``snap`` become 0) and renormalised; a prefix
    whose children have no mass sends everything to its first (or heaviest) child.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> from dppverify.tree_route.tree import build_tree
    >>> tree = build_tree(triangle(), 1)   # prefixes: 0 = s, 1 = s g1, 2 = s g2
    >>> rational_plan(tree, np.array([1.0, 0.5714286, 0.4285714]), 10)
    {0: Fraction(1, 1), 1: Fraction(4, 7), 2: Fraction(3, 7)}
    """
    plan: dict[int, Fraction] = {0: Fraction(1)}
    for p in range(tree.n_prefixes):  # breadth-first: parents before children
        if p not in plan:
            continue
        kids = tree.children(p)
        if not kids:
            continue
        raw = np.clip(np.asarray([x[c] for c in kids], dtype=float), 0.0, None)
        tot = float(raw.sum())
        if tot <= 0:
            probs = [Fraction(1)] + [Fraction(0)] * (len(kids) - 1)
        else:
            fr = [Fraction(float(r / tot)).limit_denominator(den) if r / tot > snap else
                  Fraction(0) for r in raw]
            s = sum(fr)
            if s == 0:
                fr = [Fraction(1) if k == int(np.argmax(raw)) else Fraction(0)
                      for k in range(len(kids))]
                s = Fraction(1)
            probs = [f / s for f in fr]
        for c, pr in zip(kids, probs, strict=True):
            if pr:
                plan[c] = plan[p] * pr
    return plan


class BracketSearch:
    """The best exact bounds offered so far; the search loop of :func:`exact_bracket`.

    Lower bounds come from rational Defenders, upper bounds from rational Attacker plans;
    :meth:`rounded` offers the LP solution rounded at each limit of :data:`DENOMINATORS`
    until the bracket closes. Used by :func:`exact_bracket`.

    Examples
    --------
    >>> search = BracketSearch()
    >>> search.offer_lower(Fraction(1), "a"); search.offer_lower(Fraction(2), "b")
    >>> search.offer_upper(Fraction(3), "c"); search.closed
    False
    >>> search.offer_upper(Fraction(2), "d"); search.closed
    True
    >>> search.bracket()
    Bracket(lower=Fraction(2, 1), upper=Fraction(2, 1), lower_source='b', upper_source='d', \
reason=None)
    """

    def __init__(self) -> None:
        self.lower: tuple[Number, str] | None = None
        self.upper: tuple[Number, str] | None = None
        self.reason: str | None = None

    def offer_lower(self, value: Number, source: str) -> None:
        """Keep ``value`` if it is a better (larger) lower bound."""
        if self.lower is None or value > self.lower[0]:
            self.lower = (value, source)

    def offer_upper(self, value: Number, source: str) -> None:
        """Keep ``value`` if it is a better (smaller) upper bound."""
        if self.upper is None or value < self.upper[0]:
            self.upper = (value, source)

    @property
    def closed(self) -> bool:
        """True once the best bounds meet."""
        return (self.lower is not None and self.upper is not None
                and self.lower[0] >= self.upper[0])

    def rounded(self, lower: Callable[[int], Number], upper: Callable[[int], Number]) -> None:
        """Offer ``lower(den)`` / ``upper(den)`` (the LP's dual / primal rounded at ``den``)."""
        for den in DENOMINATORS:
            if self.closed:
                break
            self.offer_lower(lower(den), f"LP dual rounded (denominators <= {den})")
            self.offer_upper(upper(den), f"LP primal rounded (denominators <= {den})")

    def exact_lp(self, tree: WalkTree, types: Types,
                 lower: Callable[[list[tuple[Fraction, ...]]], Number],
                 upper: Callable[[list[dict[int, Fraction]]], Number]) -> None:
        """Offer the exactly solved LP's strategies (:mod:`dppverify.tree_route.lp_exact`) if
        still open.

        ``lower(sigma)`` / ``upper(plans)`` evaluate them with the exact best responses, so the
        bounds do not rely on the LP solve; a failure is kept as the bracket's reason.
        """
        if self.closed:
            return
        from dppverify.tree_route.lp_exact import solve_tree_lp_exactly  # scipy, sympy: only here

        got = solve_tree_lp_exactly(tree, types.priors, types.dists)
        if isinstance(got, str):
            self.reason = f"no exact LP solution: {got}"
            return
        what = "exact LP {} (optimal basis, solved in rationals)"
        self.offer_lower(lower(got.sigma), what.format("dual"))
        self.offer_upper(upper(got.plans), what.format("primal"))
        if not self.closed:  # pragma: no cover - an exact optimum closes the bracket
            self.reason = "the exact LP solution did not close the bracket (a bug to report)"

    def bracket(self, pure: Callable[[dict[int, Fraction]], Number] | None = None,
                tree: WalkTree | None = None) -> Bracket:
        """The bracket; without an upper bound yet, ``pure(plan)`` of a pure plan on ``tree``."""
        if self.upper is None and pure is not None and tree is not None:
            # no attacker candidate: any pure plan gives a (weak) upper bound
            self.offer_upper(pure(rational_plan(tree, np.ones(tree.n_prefixes), 1)),
                             "a pure attacker plan")
        assert self.lower is not None and self.upper is not None
        return Bracket(lower=self.lower[0], upper=self.upper[0], lower_source=self.lower[1],
                       upper_source=self.upper[1],
                       reason=None if self.closed else self.reason or "not searched exactly")
