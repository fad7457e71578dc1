"""The value ``V_H`` of the truncated game: the compact LP of proofs/LP.md, plus an exact bracket.

LP (cvxpy + Clarabel, vectorised)::

    V_H = min  Σ_θ b_θ Σ_leaves x_θ(ℓ) d(end ℓ, g^θ) + Σ_{p ≠ root} w_p z_p
          s.t. x_θ realization plans on the walk tree,  z ≥ b1 x1[1:],  z ≥ b2 x2[1:].

The Defender's infoset is the walk prefix and its best response is greedy per infoset
(Lemma 3), so ``max_σ`` of the bilinear payoff is ``Σ_p w_p max_θ b_θ x_θ(p)``. The dual
multipliers ``λ1`` of ``z ≥ b1 x1`` give an optimal Defender strategy ``σ_p = λ1_p / w_p``.

Exact bracket (our choice of exact certificate, cheap and sound): for ANY rational Defender
strategy σ, ``b1 min_walk U¹(σ) + b2 min_walk U²(σ)`` (exact backward induction) is a lower
bound on ``V_H``; for ANY rational Attacker realization plans, the exact greedy Defender
value is an upper bound. We round the LP's dual (Defender) and primal (Attacker) solutions
to small-denominator rationals, also try the progress rule σ* and, when given, a profile's
attacker; if the bracket is still open, the LP is solved exactly
(:mod:`dppverify.tree_route.lp_exact`:
an optimal basis recovered from a float vertex and solved in rationals) and its strategies are
offered too, which closes it. ``V_H`` is reported exactly when the best bounds coincide; an
open bracket carries its reason (``Bracket.reason``). With a
certified PBNE (both exact regrets 0) the bracket closes at ``U`` itself, so ``V_H = U``
exactly.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import TYPE_CHECKING, Any

import numpy as np
from tqdm import tqdm

from dppverify.errors import HorizonError
from dppverify.exact import Number, normalize
from dppverify.game.defender import TreeDefender, tree_defender
from dppverify.game.instance import Instance, Roles, as_instance
from dppverify.game.profile import ProgressRule
from dppverify.horizons import parse_horizon
from dppverify.tree_route.best_response import attacker_best_response, defender_best_response
from dppverify.tree_route.lp import LPStats, realization_constraints, solve
from dppverify.tree_route.tree import DEFAULT_MAX_PREFIXES, WalkTree, build_tree

if TYPE_CHECKING:  # imported where the LP is built: cvxpy's import costs ~0.5 s
    import cvxpy as cp

__all__ = ["DENOMINATORS", "Bracket", "BracketSearch", "GameValue", "ValueLP", "exact_bracket",
           "game_value", "lower_bound", "rational_plan", "solve_types_lp", "solve_value_lp",
           "upper_bound"]

DENOMINATORS = (1, 2, 3, 4, 5, 6, 8, 10, 12, 20, 24, 60, 100, 360, 720, 1000, 5040, 10**4, 10**6)
"""Denominator limits tried when rounding LP solutions to rationals."""


@dataclass(frozen=True)
class ValueLP:
    """The compact LP's solution: ``V_H`` (float) with the optimal strategies it found.

    Attributes
    ----------
    stats : LPStats
        Value, status, size, time.
    x1, x2 : numpy.ndarray
        The Attacker types' realization plans (one entry per prefix).
    sigma1 : numpy.ndarray
        The Defender's allocation to ``g1`` per prefix from the duals (``nan`` at the root).
    """

    stats: LPStats
    x1: np.ndarray
    x2: np.ndarray
    sigma1: np.ndarray

    @property
    def value(self) -> float:
        """``V_H`` as computed by the LP."""
        return self.stats.value


@dataclass(frozen=True)
class Bracket:
    """Exact bounds ``lower <= V_H <= upper``, where they come from, and why still open."""

    lower: Number
    upper: Number
    lower_source: str
    upper_source: str
    reason: str | None = None

    @property
    def closed(self) -> bool:
        """True when the bounds coincide: ``V_H`` is then known exactly."""
        return self.lower == self.upper

    @property
    def exact(self) -> Number | None:
        """``V_H`` exactly when the bracket is closed, else None."""
        return self.lower if self.closed else None


def solve_value_lp(tree: WalkTree, roles: Roles) -> ValueLP:
    """Solve the compact LP of proofs/LP.md on ``tree``.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> from dppverify.tree_route.tree import build_tree
    >>> inst = triangle()
    >>> round(solve_value_lp(build_tree(inst, 1), inst.roles()).value, 6)
    2.4
    """
    stats, plans, sigma = solve_types_lp(tree, (roles.b1, roles.b2), (roles.d1, roles.d2),
                                         f"value LP (H = {tree.horizon})")
    return ValueLP(stats=stats, x1=plans[0], x2=plans[1], sigma1=sigma[0])


def solve_types_lp(tree: WalkTree, priors: Sequence[Number],
                   dists: Sequence[Sequence[Number]], what: str
                   ) -> tuple[LPStats, np.ndarray, np.ndarray]:
    """The compact LP for any number of types (two goals and N goals share it).

    ``min Σ_θ b_θ Σ_leaves x_θ(ℓ) d_θ(end ℓ) + Σ_{p ≠ root} w_p z_p`` over realization
    plans ``x_θ`` with ``z_p >= b_θ x_θ(p)`` for every type.

    Parameters
    ----------
    tree : WalkTree
        The walk tree.
    priors, dists : Sequence
        ``b_θ`` and the distances ``d(·, g^θ)`` of each type, in the same order.
    what : str
        Names the LP in an :class:`~dppverify.errors.LPError`.

    Returns
    -------
    stats : LPStats
    plans : numpy.ndarray
        ``plans[θ]``: type θ's realization plan (one float per prefix).
    sigma : numpy.ndarray
        ``sigma[θ][p] = λ_θ(p) / w_p`` from the duals of ``z_p >= b_θ x_θ(p)`` (``nan`` at
        the root): an optimal Defender strategy.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> from dppverify.tree_route.tree import build_tree
    >>> inst = triangle()
    >>> r = inst.roles()
    >>> stats, plans, sigma = solve_types_lp(build_tree(inst, 1), (r.b1, r.b2), (r.d1, r.d2),
    ...                                      "demo")
    >>> round(stats.value, 6), [round(float(v), 4) for v in plans[0]]
    (2.4, [1.0, 0.5714, 0.4286])
    """
    import cvxpy as cp

    n = tree.n_prefixes
    leaf = tree.is_leaf_mask()
    node = tree.node
    xs = [cp.Variable(n) for _ in priors]
    cons: list[cp.Constraint] = []
    terms: list[cp.Expression] = []
    for b, d, x in zip(priors, dists, xs, strict=True):
        cost = np.array([float(d[int(v)]) if leaf[p] else 0.0 for p, v in enumerate(node)])
        cons += realization_constraints(tree, x)
        terms.append(float(b) * (cost @ x))
    objective = terms[0]
    for term in terms[1:]:
        objective = objective + term
    duals: list[cp.Constraint] = []
    if n > 1:
        z = cp.Variable(n - 1)
        duals = [z >= float(b) * x[1:] for b, x in zip(priors, xs, strict=True)]
        cons += duals
        objective = objective + tree.weight_float[1:] @ z
    stats = solve(cp.Problem(cp.Minimize(objective), cons), what)
    sigma = np.full((len(xs), n), np.nan)
    for theta, c in enumerate(duals):
        lam = np.asarray(c.dual_value, dtype=float).reshape(-1)
        sigma[theta, 1:] = np.clip(lam / tree.weight_float[1:], 0.0, 1.0)
    plans = np.array([np.asarray(x.value, dtype=float).reshape(-1) for x in xs])
    return stats, plans, sigma


def lower_bound(tree: WalkTree, roles: Roles, tdef: TreeDefender) -> Number:
    """Exact ``b1 min U¹ + b2 min U²`` against a fixed Defender: a lower bound on ``V_H``.

    Parameters
    ----------
    tree, roles
        The walk tree and the labelling.
    tdef : TreeDefender
        The Defender, evaluated on the tree.

    Returns
    -------
    Number
        Exact for rational instances.

    Examples
    --------
    Against σ* on the triangle the types' best responses cost 3 and 1; a Defender that
    always allocates to g1 lets the secondary reach g2 for free (7/10 · 3 + 3/10 · 0):

    >>> from dppverify.game.defender import tree_defender
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
    """
    v = (roles.b1 * attacker_best_response(tree, roles, tdef, 1).value
         + roles.b2 * attacker_best_response(tree, roles, tdef, 2).value)
    return tree.instance.numbers.convert(v)


def upper_bound(tree: WalkTree, roles: Roles, x1: Mapping[int, Fraction],
                x2: Mapping[int, Fraction]) -> Number:
    """Exact greedy Defender value against fixed Attacker plans: an upper bound on ``V_H``.

    Parameters
    ----------
    tree, roles
        The walk tree and the labelling.
    x1, x2 : Mapping
        Realization plans of the two types: prefix -> reach probability.

    Returns
    -------
    Number
        Exact for rational instances.

    Examples
    --------
    The triangle's equilibrium plans give ``12/5 = V_1``; a primary that always walks to
    g1 gives the Defender more:

    >>> from dppverify.game.examples import triangle
    >>> from dppverify.tree_route.tree import build_tree
    >>> inst = triangle()
    >>> tree = build_tree(inst, 1)   # prefixes: 0 = s, 1 = s g1, 2 = s g2
    >>> x2 = {0: Fraction(1), 2: Fraction(1)}
    >>> upper_bound(tree, inst.roles(), {0: Fraction(1), 1: Fraction(4, 7), 2: Fraction(3, 7)}, x2)
    Fraction(12, 5)
    >>> upper_bound(tree, inst.roles(), {0: Fraction(1), 1: Fraction(1)}, x2)
    Fraction(27, 10)
    """
    return defender_best_response(tree, roles, x1, x2).value


def _rational_defender(tree: WalkTree, sigma: np.ndarray, den: int) -> TreeDefender:
    exact = tree.instance.exact
    numbers = tree.instance.numbers
    w = tree.weight
    s1: list[Number] = [0] * tree.n_prefixes
    a1: list[Number] = [0] * tree.n_prefixes
    a2: list[Number] = [0] * tree.n_prefixes
    for p in range(1, tree.n_prefixes):
        x = float(sigma[p]) if np.isfinite(sigma[p]) else 0.0
        q = normalize(Fraction(x).limit_denominator(den)) if exact else x
        q = min(max(q, 0), 1)
        s1[p] = q
        a1[p] = numbers.product(w[p], q)
        a2[p] = numbers.difference(w[p], a1[p])
    return TreeDefender(sigma1=tuple(s1), alloc1=tuple(a1), alloc2=tuple(a2))


def rational_plan(tree: WalkTree, x: np.ndarray, den: int,
                  snap: float = 1e-7) -> dict[int, Fraction]:
    """Round a float realization plan to an exactly feasible rational one (behavioural form).

    At every reached prefix the children's shares ``x[c] / Σ x[c]`` are rounded to
    denominators ``<= den`` (shares below ``snap`` become 0) and renormalised; a prefix
    whose children have no mass sends everything to its first (or heaviest) child. Serves
    both trees (two goals and N goals).

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
    """The best exact bounds offered so far; the search loop of both exact brackets.

    Lower bounds come from rational Defenders, upper bounds from rational Attacker plans;
    :meth:`rounded` offers the LP solution rounded at each limit of :data:`DENOMINATORS`
    until the bracket closes. Used by :func:`exact_bracket` and the N-goal
    :func:`~dppverify.ngoal.value_lp.exact_nbracket`.

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

    def exact_lp(self, tree: WalkTree, priors: Sequence[Number],
                 dists: Sequence[Sequence[Number]],
                 lower: Callable[[list[tuple[Fraction, ...]]], Number],
                 upper: Callable[[list[dict[int, Fraction]]], Number]) -> None:
        """Offer the exactly solved LP's strategies (:mod:`dppverify.tree_route.lp_exact`) if still
        open.

        ``lower(sigma)`` / ``upper(plans)`` evaluate them with the exact best responses, so the
        bounds do not rely on the LP solve; a failure is kept as the bracket's reason.
        """
        if self.closed:
            return
        from dppverify.tree_route.lp_exact import solve_tree_lp_exactly  # scipy, sympy: only here

        got = solve_tree_lp_exactly(tree, priors, dists)
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


def exact_bracket(tree: WalkTree, roles: Roles, lp: ValueLP | None = None,
                  defenders: Sequence[tuple[str, TreeDefender]] = (),
                  attackers: Iterable[tuple[str, Mapping[int, Fraction], Mapping[int, Fraction]]]
                  = (), sigma_star: TreeDefender | None = None) -> Bracket:
    """Exact bounds on ``V_H`` from rational strategies (see the module docstring).

    Candidates: the progress rule σ* for either goal, the given ``defenders`` /
    ``attackers``, and the LP solution rounded at each denominator limit in
    :data:`DENOMINATORS` (stopping early once the bracket closes). ``sigma_star``, when
    given, is σ* (progress to ``g1``) already evaluated on ``tree``: it is reused, and not
    offered twice when it is also one of ``defenders``.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> from dppverify.tree_route.tree import build_tree
    >>> inst = triangle()
    >>> tree = build_tree(inst, 2)
    >>> b = exact_bracket(tree, inst.roles(), solve_value_lp(tree, inst.roles()))
    >>> b.exact
    Fraction(12, 5)
    """
    search = BracketSearch()
    for src, tdef in defenders:
        search.offer_lower(lower_bound(tree, roles, tdef), src)
    given = {id(tdef) for _, tdef in defenders}
    for g, name in ((roles.g1, "sigma* (progress to g1)"), (roles.g2, "progress to g2")):
        progress = (sigma_star if g == roles.g1 and sigma_star is not None
                    else tree_defender(tree, roles, ProgressRule(g)))
        if id(progress) not in given:
            search.offer_lower(lower_bound(tree, roles, progress), name)
    for src, a1, a2 in attackers:
        search.offer_upper(upper_bound(tree, roles, a1, a2), src)
    if lp is not None:
        search.rounded(
            lambda den: lower_bound(tree, roles, _rational_defender(tree, lp.sigma1, den)),
            lambda den: upper_bound(tree, roles, rational_plan(tree, lp.x1, den),
                                    rational_plan(tree, lp.x2, den)))
        if tree.instance.exact:
            search.exact_lp(tree, (roles.b1, roles.b2), (roles.d1, roles.d2),
                            lambda sigma: lower_bound(tree, roles, _exact_defender(tree, sigma)),
                            lambda plans: upper_bound(tree, roles, plans[0], plans[1]))
        else:
            search.reason = "float-mode instance: no exact LP closure"
    return search.bracket(lambda plan: upper_bound(tree, roles, plan, plan), tree)


def _exact_defender(tree: WalkTree, sigma: Sequence[tuple[Fraction, ...]]) -> TreeDefender:
    """The two-goal Defender whose allocation to ``g1`` at ``p`` is ``sigma[p][0]``."""
    numbers = tree.instance.numbers
    w = tree.weight
    s1: list[Number] = [0] * tree.n_prefixes
    a1: list[Number] = [0] * tree.n_prefixes
    a2: list[Number] = [0] * tree.n_prefixes
    for p in range(1, tree.n_prefixes):
        s1[p] = normalize(sigma[p][0])
        a1[p] = numbers.product(w[p], s1[p])
        a2[p] = numbers.difference(w[p], a1[p])
    return TreeDefender(sigma1=tuple(s1), alloc1=tuple(a1), alloc2=tuple(a2))


@dataclass(frozen=True)
class GameValue:
    """``V_H`` of an instance: the LP value, the exact bracket, and the tree's size.

    Attributes
    ----------
    horizon : int
        ``H``.
    lp : LPStats
        The compact LP's value (float), status, size and solve time.
    bracket : Bracket
        Exact bounds on ``V_H`` (closed when ``V_H`` is known exactly).
    prefixes, leaves : int
        Size of the walk tree.
    exact : bool
        False for float-mode instances (the bracket is then in floats).
    """

    horizon: int
    lp: LPStats
    bracket: Bracket
    prefixes: int
    leaves: int
    exact: bool

    @property
    def value(self) -> float:
        """``V_H`` from the LP."""
        return self.lp.value


def game_value(instance: Instance | Any, horizon: int, *,
               max_prefixes: int = DEFAULT_MAX_PREFIXES, progress: bool = False) -> GameValue:
    """``V_H`` of the truncated game of ``instance``: compact LP plus exact bracket.

    ``instance`` may be an :class:`Instance`, an instance document (dict), a file path or any
    object with ``to_json()`` (:func:`~dppverify.game.instance.as_instance`). The value does not
    depend on which goal is called primary (the LP is symmetric in the two types), so the
    instance's own labelling is used.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> inst = triangle()
    >>> v = game_value(inst, 3)
    >>> v.bracket.exact, round(v.value, 6), v.prefixes
    (Fraction(12, 5), 2.4, 3)
    """
    h = parse_horizon(horizon)
    if h is None:
        raise HorizonError("game_value is the truncated game's LP and needs a finite horizon; "
                           "dppverify.value(instance) gives the untruncated game's value")
    horizon = h
    instance = as_instance(instance)
    tree = build_tree(instance, horizon, max_prefixes=max_prefixes, progress=progress)
    roles = instance.roles()
    with tqdm(total=2, desc=f"value LP ({tree.n_prefixes} prefixes)", disable=not progress,
              leave=False) as bar:
        lp = solve_value_lp(tree, roles)
        bar.update(1)
        bar.set_description("exact bracket")
        bracket = exact_bracket(tree, roles, lp)
        bar.update(1)
    return GameValue(horizon=horizon, lp=lp.stats, bracket=bracket, prefixes=tree.n_prefixes,
                     leaves=tree.n_leaves, exact=instance.exact)
