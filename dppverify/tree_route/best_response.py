"""Best responses, payoffs and Bayes beliefs in the truncated game (any ``N >= 2`` goals).

The players are those of :mod:`dppverify.tree_route.players`: the Attacker's types θ, each a
realization plan ``x_θ`` (prefix -> reach probability), and a Defender that gives type θ the
stage cost ``a_θ(p) = w(p)·σ(g^θ | p)`` at every prefix ``p``.

*Attacker* (per type θ, against a Defender fixed at every prefix): the minimum over ALL walks
of the tree — not only simple paths — of stage costs plus terminal cost, by exact backward
induction ``J(p) = min_c [a_θ(c) + J(c)]``, ``J(leaf) = d(end, g^θ)``; and the same as the
sequence-form LP ``min c·x`` over realization plans ``x``. Against a Defender whose strategy
depends only on the walk, seeing the Defender's past actions does not help the Attacker (they
never change the state), so this is the best response over all behavioural strategies
within the horizon.

*Defender* (against a non-reacting Attacker given by realization plans): greedy per
information set (Lemma 3; ``proofs/L3.md``'s argument does not use the number of types):
``Σ_p w_p max_θ b_θ x_θ(p)`` plus the terminal costs, exactly; for two types also the LP
``max Σ_p w_p [b1 x1(p) σ_p + b2 x2(p) (1 - σ_p)]`` over ``σ ∈ [0, 1]^P``.

*Beliefs*: at a prefix reached with positive probability, ``μ(θ | p) = b_θ x_θ(p) /
Σ_η b_η x_η(p)``.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from dppverify.exact import INF, Number
from dppverify.tree_route.lp import LPStats, cost_scale, realization_constraints, solve, unscaled
from dppverify.tree_route.players import AnyTypes, Plan, TreeStrategy, Types, as_types
from dppverify.tree_route.tree import WalkTree


@dataclass(frozen=True)
class AttackerBR:
    """The best response of type ``who`` (a role or a goal index) in the tree: its cost and one
    minimising walk."""

    who: int
    value: Number
    leaf: int
    walk: tuple[int, ...]


@dataclass(frozen=True)
class DefenderBR:
    """The Defender's greedy best response: its value and a best type per information set.

    ``choice[p]`` is the type θ with the largest ``b_θ x_θ(p)`` (the first in the plans' order
    at a tie, where any allocation is optimal), for every prefix ``p`` reached with positive
    probability: allocating the step to ``g^θ`` is a best response.
    """

    value: Number
    choice: Mapping[int, int]


def terminal_costs(tree: WalkTree, types: AnyTypes, who: int
                   ) -> list[Number]:
    """``d(end(p), g^θ)`` at every leaf ``p`` (0 at inner prefixes), full-graph distances.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> from dppverify.tree_route.tree import build_tree
    >>> inst = triangle()
    >>> tree = build_tree(inst, 1)   # prefixes: 0 = s, 1 = s g1, 2 = s g2
    >>> terminal_costs(tree, inst.roles(), 1), terminal_costs(tree, inst.roles(), 2)
    ([0, 0, 2], [0, 2, 0])
    """
    d = as_types(types).dist(who)
    out: list[Number] = [0] * tree.n_prefixes
    for p in tree.leaves().tolist():
        out[p] = d[int(tree.node[p])]
    return out


def leaf_totals(tree: WalkTree, types: AnyTypes, tdef: TreeStrategy,
                who: int) -> list[Number]:
    """Forward pass: total cost of type θ for the walk of every prefix.

    At a leaf: the walk's stage costs plus its terminal cost; at an inner prefix: the stage
    costs so far. A second, independent route to the minimum of
    :func:`attacker_best_response`.

    Examples
    --------
    Against σ* on the triangle, ``s -> g2`` costs the primary 1 + d(g2, g1) = 3, as much
    as ``s -> g1`` (Lemma 1), and the secondary 1 (σ* = 1/2 on that step):

    >>> from tests.dppverify.checks.doctest_inputs import triangle_context
    >>> ctx = triangle_context()   # prefixes: 0 = s, 1 = s g1, 2 = s g2
    >>> tree, r, td = ctx.tree, ctx.roles, ctx.sigma_star   # σ*: progress to g1
    >>> leaf_totals(tree, r, td, 1), leaf_totals(tree, r, td, 2)
    ([0, 3, 3], [0, 2, 1])
    """
    a = tdef.alloc(who)
    parent = tree.parent.tolist()
    acc: list[Number] = [0] * tree.n_prefixes
    for p in range(1, tree.n_prefixes):
        acc[p] = acc[parent[p]] + a[p]
    term = terminal_costs(tree, types, who)
    for p in tree.leaves().tolist():
        acc[p] = acc[p] + term[p]
    return acc


def attacker_best_response(tree: WalkTree, types: AnyTypes,
                           tdef: TreeStrategy, who: int,
                           allowed: np.ndarray | None = None) -> AttackerBR:
    """Exact best response of type θ by backward induction over the walk tree.

    Parameters
    ----------
    tree, types, tdef
        The tree, the types, and the Defender evaluated on the tree.
    who : int
        The type.
    allowed : numpy.ndarray of bool, optional
        Restrict to walks through allowed prefixes only (e.g. simple paths, Lemma 2).

    Examples
    --------
    >>> from tests.dppverify.checks.doctest_inputs import triangle_context
    >>> ctx = triangle_context(horizon=3)
    >>> br = attacker_best_response(ctx.tree, ctx.roles, ctx.sigma_star, 2)
    >>> br.value, ctx.instance.labels(br.walk)
    (1, ('s', 'g2'))

    With three goals, against a Defender that always guards goal ``a``, type ``b`` walks
    ``s m b`` for free and type ``a`` pays 2 whichever way it walks:

    >>> from dppverify.game.examples import star3
    >>> from dppverify.tree_route.players import defender_from_table
    >>> from dppverify.tree_route.tree import build_tree
    >>> inst = star3()
    >>> t = build_tree(inst, 2)
    >>> d = defender_from_table(t, {}, (Fraction(1), Fraction(0), Fraction(0)))
    >>> [(br.value, inst.labels(br.walk)) for br in (attacker_best_response(t, inst, d, 0),
    ...                                               attacker_best_response(t, inst, d, 1))]
    [(2, ('s', 'm', 'a')), (0, ('s', 'm', 'b'))]
    """
    a = tdef.alloc(who)
    term = terminal_costs(tree, types, who)
    start = tree.child_start.tolist()
    stop = tree.child_stop.tolist()
    ok = allowed.tolist() if allowed is not None else None
    n = tree.n_prefixes
    J: list[Number] = [INF] * n
    best = [-1] * n
    for p in range(n - 1, -1, -1):
        if ok is not None and not ok[p]:
            continue
        lo, hi = start[p], stop[p]
        if lo == hi:
            J[p] = term[p]
            continue
        bj: Number = INF
        bc = -1
        for c in range(lo, hi):
            v = a[c] + J[c]
            if v < bj:
                bj, bc = v, c
        J[p], best[p] = bj, bc
    if J[0] == INF:
        raise ValueError("no allowed walk in the tree")
    p = 0
    while best[p] >= 0:
        p = best[p]
    value = tree.instance.numbers.convert(J[0])
    return AttackerBR(who=who, value=value, leaf=p, walk=tree.walk(p))


def objective_vector(tree: WalkTree, types: AnyTypes, tdef: TreeStrategy,
                     who: int) -> np.ndarray:
    """Type θ's sequence-form cost vector: stage cost at every prefix plus terminal at leaves.

    ``objective_vector(...) @ x`` is type θ's expected cost under realization plan ``x``.

    Examples
    --------
    >>> from tests.dppverify.checks.doctest_inputs import triangle_context
    >>> ctx = triangle_context()   # prefixes: 0 = s, 1 = s g1, 2 = s g2; σ*: progress to g1
    >>> c = objective_vector(ctx.tree, ctx.roles, ctx.sigma_star, 1)
    >>> c.tolist(), float(c @ [1, 4 / 7, 3 / 7])   # U¹ of the mixture (4/7, 3/7)
    ([0.0, 3.0, 3.0], 3.0)
    """
    c = np.array([float(v) for v in tdef.alloc(who)])
    c[0] = 0.0
    c += np.array([float(v) for v in terminal_costs(tree, types, who)])
    return c


def attacker_best_response_lp(tree: WalkTree, types: AnyTypes,
                              tdef: TreeStrategy, who: int) -> LPStats:
    """Type θ's best-response value as the sequence-form LP ``min c·x`` (realization plans).

    The exact counterpart is :func:`attacker_best_response`.

    Examples
    --------
    >>> from tests.dppverify.checks.doctest_inputs import triangle_context
    >>> ctx = triangle_context()   # prefixes: 0 = s, 1 = s g1, 2 = s g2
    >>> tree, r, td = ctx.tree, ctx.roles, ctx.sigma_star   # σ*: progress to g1
    >>> lp = attacker_best_response_lp(tree, r, td, 2)
    >>> lp.status, round(lp.value, 6), attacker_best_response(tree, r, td, 2).value
    ('optimal', 1.0, 1)
    """
    import cvxpy as cp  # lazily: its import costs ~0.5 s

    c = objective_vector(tree, types, tdef, who)
    scale = cost_scale(c)  # costs of size one (lp.py)
    x = cp.Variable(tree.n_prefixes)
    problem = cp.Problem(cp.Minimize((scale * c) @ x), realization_constraints(tree, x))
    return unscaled(solve(problem, f"attacker best response LP (type {who}, H = "
                                   f"{tree.horizon})"), scale)


def _terminal_part(tree: WalkTree, types: Types, plans: Mapping[int, Plan]) -> Number:
    """``Σ_θ b_θ Σ_leaves x_θ(ℓ) d(end ℓ, g^θ)``."""
    total: Number = 0
    leaf = tree.is_leaf_mask()
    for who, x in plans.items():
        d = types.dist(who)
        b = types.prior(who)
        for p, prob in x.items():
            if leaf[p]:
                total += b * prob * d[int(tree.node[p])]
    return total


def payoff_on_tree(tree: WalkTree, types: AnyTypes, tdef: TreeStrategy,
                   plans: Mapping[int, Plan]) -> Number:
    """``U = Σ_θ b_θ [Σ_p x_θ(p) a_θ(p) + terminal]`` from realization plans (a second route to U).

    Parameters
    ----------
    tree, types, tdef
        The tree, the types, and the Defender evaluated on the tree.
    plans : Mapping
        ``plans[θ]``: type θ's realization plan, for every type.

    Returns
    -------
    Number
        ``U``, exact for rational instances.

    Examples
    --------
    The triangle's equilibrium: primary ``s -> g1`` w.p. 4/7, ``s -> g2`` w.p. 3/7;
    secondary ``s -> g2``. ``U = 7/10 · 3 + 3/10 · 1``:

    >>> from tests.dppverify.checks.doctest_inputs import triangle_context
    >>> ctx = triangle_context()   # prefixes: 0 = s, 1 = s g1, 2 = s g2
    >>> tree, r, td = ctx.tree, ctx.roles, ctx.sigma_star   # σ*: progress to g1
    >>> ev = ctx.evaluated
    >>> ev.x1
    {0: Fraction(1, 1), 1: Fraction(4, 7), 2: Fraction(3, 7)}
    >>> payoff_on_tree(tree, r, td, {1: ev.x1, 2: ev.x2})
    Fraction(12, 5)

    Three goals, all types walking ``s a`` against a Defender guarding ``a``:

    >>> from dppverify.game.examples import star3
    >>> from dppverify.tree_route.players import defender_from_table
    >>> from dppverify.tree_route.tree import build_tree
    >>> t = build_tree(star3(), 1)
    >>> d = defender_from_table(t, {}, (Fraction(1), Fraction(0), Fraction(0)))
    >>> payoff_on_tree(t, star3(), d, dict.fromkeys(range(3), {0: Fraction(1), 1: Fraction(1)}))
    2
    """
    t = as_types(types)
    total: Number = _terminal_part(tree, t, plans)
    for who, x in plans.items():
        a = tdef.alloc(who)
        b = t.prior(who)
        for p, prob in x.items():
            if p:
                total += b * prob * a[p]
    return tree.instance.numbers.convert(total)


def defender_best_response(tree: WalkTree, types: AnyTypes,
                           plans: Mapping[int, Plan]) -> DefenderBR:
    """Exact greedy Defender best response against realization plans (one per type).

    Examples
    --------
    Against the triangle's equilibrium plans (the primary's mixture 4/7, 3/7):

    >>> from tests.dppverify.checks.doctest_inputs import triangle_context
    >>> ctx = triangle_context()   # prefixes: 0 = s, 1 = s g1, 2 = s g2
    >>> ev = ctx.evaluated
    >>> br = defender_best_response(ctx.tree, ctx.roles, {1: ev.x1, 2: ev.x2})
    >>> br.value, dict(br.choice)
    (Fraction(12, 5), {1: 1, 2: 1})

    Three goals, all types walking ``s a``:

    >>> from dppverify.game.examples import star3
    >>> from dppverify.tree_route.tree import build_tree
    >>> t = build_tree(star3(), 1)
    >>> br = defender_best_response(t, star3(), dict.fromkeys(range(3), {0: 1, 1: 1}))
    >>> br.value, dict(br.choice)
    (2, {1: 0})
    """
    t = as_types(types)
    total: Number = _terminal_part(tree, t, plans)
    choice: dict[int, int] = {}
    w = tree.weight
    for p in sorted({p for x in plans.values() for p, prob in x.items() if prob and p}):
        masses = [(t.prior(who) * x.get(p, Fraction(0)), who) for who, x in plans.items()]
        top = max(m for m, _ in masses)
        choice[p] = next(who for m, who in masses if m == top)
        total += w[p] * top
    return DefenderBR(value=tree.instance.numbers.convert(total), choice=choice)


def defender_best_response_lp(tree: WalkTree, types: AnyTypes,
                              plans: Mapping[int, Plan]) -> tuple[LPStats, dict[int, float]]:
    """The Defender's best response against two types' plans as an LP over ``σ ∈ [0, 1]^P``.

    Parameters
    ----------
    tree, types
        The tree and the (two) types.
    plans : Mapping
        The two types' realization plans; ``σ_p`` is the allocation to the first one's goal.

    Returns
    -------
    tuple of LPStats and dict
        The LP statistics (value = the Defender's optimum) and the LP's allocation ``σ_p``
        at every information set of the plans.

    Raises
    ------
    ValueError
        Unless there are exactly two plans.

    Examples
    --------
    If the primary went to g2 more often (3/7 to g1, 4/7 to g2), the Defender could get
    5/2 instead of the equilibrium's 12/5 by allocating to g1 everywhere:

    >>> from dppverify.game.examples import triangle
    >>> from dppverify.tree_route.tree import build_tree
    >>> inst = triangle()
    >>> tree = build_tree(inst, 1)   # prefixes: 0 = s, 1 = s g1, 2 = s g2
    >>> plans = {1: {0: Fraction(1), 1: Fraction(3, 7), 2: Fraction(4, 7)},
    ...          2: {0: Fraction(1), 2: Fraction(1)}}
    >>> lp, sigma = defender_best_response_lp(tree, inst.roles(), plans)
    >>> round(lp.value, 6), {p: round(s, 6) for p, s in sigma.items()}
    (2.5, {1: 1.0, 2: 1.0})
    >>> defender_best_response(tree, inst.roles(), plans).value
    Fraction(5, 2)
    """
    if len(plans) != 2:
        raise ValueError(f"the Defender's LP takes two types' plans, got {len(plans)}")
    t = as_types(types)
    (w1, x1), (w2, x2) = plans.items()
    support = sorted(p for p in set(x1) | set(x2) if p != 0)
    const = float(_terminal_part(tree, t, plans))
    w = tree.weight_float
    if not support:
        return LPStats(const, "optimal", 0, 0, 0.0), {}
    idx = np.array(support)
    b1x1 = np.array([float(t.prior(w1) * x1.get(p, Fraction(0))) for p in support])
    b2x2 = np.array([float(t.prior(w2) * x2.get(p, Fraction(0))) for p in support])
    import cvxpy as cp  # lazily: its import costs ~0.5 s

    sigma = cp.Variable(len(support))
    slope, offset = w[idx] * (b1x1 - b2x2), float(w[idx] @ b2x2)
    scale = cost_scale(slope, offset + const)  # costs of size one (lp.py)
    objective = (scale * slope) @ sigma + scale * offset + scale * const
    problem = cp.Problem(cp.Maximize(objective), [sigma >= 0, sigma <= 1])
    stats = unscaled(solve(problem, f"defender best response LP (H = {tree.horizon})"), scale)
    values = np.asarray(sigma.value, dtype=float)
    return stats, {p: float(values[k]) for k, p in enumerate(support)}


def beliefs(tree: WalkTree, types: AnyTypes, plans: Mapping[int, Plan]
            ) -> dict[int, tuple[Fraction, ...]]:
    """Bayes beliefs ``μ(· | p)`` (in the plans' order) at every prefix reached.

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> from dppverify.tree_route.players import defender_from_table
    >>> from dppverify.tree_route.tree import build_tree
    >>> t = build_tree(star3(), 1)
    >>> beliefs(t, star3(), dict.fromkeys(range(3), {0: Fraction(1), 1: Fraction(1)}))[1]
    (Fraction(1, 2), Fraction(1, 3), Fraction(1, 6))
    """
    t = as_types(types)
    out: dict[int, tuple[Fraction, ...]] = {}
    for p in sorted({p for x in plans.values() for p, prob in x.items() if prob}):
        masses = [t.prior(who) * x.get(p, Fraction(0)) for who, x in plans.items()]
        tot = sum(masses, Fraction(0))
        out[p] = tuple(m / tot for m in masses)
    return out
