"""Lemma certificates on the instance (proofs/TEL.md, L1.md, L2.md, XI2.md, L5.md).

All lemma checks use the paper's σ* (progress towards the profile's primary goal) on the
walk tree, whatever Defender the profile proposes, and exact arithmetic:

- ``lemma.TEL.telescoping``: along every walk, ``Σ w σ*(g1) = c_0 − c_t`` and σ* ∈ [0, 1].
- ``lemma.L1.lower_bound``: min over walks of U¹ against σ* is ``d(s0, g1)``; every walk
  ending at g1 costs exactly that; a walk ending at g2 costs ``d(s0,g1) − c_T + d(g2,g1)``.
- ``lemma.L2.no_revisits``: the secondary's best response over walks equals that over
  simple paths, and every minimising walk is simple.
- ``lemma.XI2.secondary_value``: that minimum is at least ``M − d(s0, g1)`` (proofs/XI2.md), with
  equality once the horizon admits an optimal path.
- ``lemma.L3.greedy``: for the profile's attacker and random non-reacting attackers, the
  Defender's LP optimum equals the exact greedy-on-belief value and is greedy wherever the
  belief is strict.
- ``lemma.L4.monotonicity``: with the secondary deterministic on a walk ξ, the belief in g1
  along ξ never increases, for the profile's and for random primary strategies.
- ``lemma.L5.induced_beliefs``: the profile induces beliefs ``b1`` / 1/2 / 0 on phases
  I / II / III of ξ². Lemma 5's belief 1 off ξ² is not checked: with one secondary walk the
  secondary puts no mass off ξ², so that belief is 1 by Bayes' rule whatever the profile
  (a check that cannot fail is no evidence); the message says so (:data:`OFF_XI2`).
"""

from __future__ import annotations

import random
from collections.abc import Sequence
from fractions import Fraction

from dppverify.certificate import CheckRecord, Status
from dppverify.exact import Number
from dppverify.game.defender import sigma_along
from dppverify.game.distances import dijkstra
from dppverify.game.evaluation import realization
from dppverify.game.profile import ProgressRule, StrategyPath
from dppverify.text import show, show_walk
from dppverify.tree_route.best_response import (
    attacker_best_response,
    defender_best_response,
    defender_best_response_lp,
    leaf_totals,
)
from dppverify.tree_route.context import Context, EvaluatedContext
from dppverify.tree_route.lp import lp_agrees
from dppverify.tree_route.tree import WalkTree, simple_mask
from dppverify.twogoal.phases import phases_of

__all__ = ["GREEDY_COEFFICIENT", "GREEDY_SIGMA_TOLERANCE", "OFF_XI2", "l1_lower_bound",
           "l2_no_revisits", "l3_greedy", "l4_monotonicity", "l5_induced_beliefs",
           "random_mixture", "telescoping", "xi2_secondary_value"]

GREEDY_COEFFICIENT = 1e-6
"""L3: LP allocations are checked for greediness where the exact objective coefficient
``|w (b1 x1 − b2 x2)|`` is at least this fraction of the largest one (below it an
interior-point solution cannot be told apart from a tie)."""

GREEDY_SIGMA_TOLERANCE = 1e-4
"""L3: an LP allocation counts as 1 (resp. 0) when within this distance of it."""

HALF = Fraction(1, 2)

OFF_XI2 = ("off ξ² the belief is 1 by construction (the single secondary walk puts no mass "
           "there; not checked)")
"""L5's note on the primary prefixes off ξ² (see the module docstring)."""


def telescoping(ctx: Context) -> CheckRecord:
    """``lemma.TEL.telescoping`` (proofs/TEL.md) on every prefix of the tree.

    Parameters
    ----------
    ctx : Context
        The shared inputs (:func:`~dppverify.tree_route.context.make_context`).

    Returns
    -------
    CheckRecord

    Examples
    --------
    >>> from dppverify.game.examples import triangle_attacker, triangle_context
    >>> def context(p_g1="4/7", p_g2="3/7"):   # the triangle's equilibrium by default
    ...     return triangle_context(triangle_attacker(p_g1, p_g2))
    >>> r = telescoping(context())
    >>> r.status, dict(r.numbers)
    ('pass', {'prefixes': 3, 'sum_violations': 0, 'range_violations': 0})
    """
    tree, roles, mode = ctx.tree, ctx.roles, ctx.numbers
    d1 = roles.d1
    node = tree.node.tolist()
    parent = tree.parent.tolist()
    s1, weight = ctx.sigma_star.sigma1, tree.weight
    c: list[Number] = [d1[node[0]]] * tree.n_prefixes
    acc: list[Number] = [0] * tree.n_prefixes
    bad_sum = bad_range = 0
    for p in range(1, tree.n_prefixes):
        q = parent[p]
        c[p] = min(c[q], d1[node[p]])
        # the probability σ*(g1) times the step's weight, not σ*'s stored increment c_{t-1} − c_t
        taken = mode.product(weight[p], s1[p])
        acc[p] = acc[q] + taken
        if not mode.equal(acc[p], c[0] - c[p]):
            bad_sum += 1
        if not (mode.at_most(0, s1[p]) and mode.at_most(s1[p], 1)):
            bad_range += 1
    numbers: dict[str, Number | None] = {"prefixes": tree.n_prefixes,
                                         "sum_violations": bad_sum,
                                         "range_violations": bad_range}
    ok = bad_sum == 0 and bad_range == 0
    msg = (f"Σ w σ*(g1) = c_0 − c_t and σ* ∈ [0, 1] on all {tree.n_prefixes} prefixes"
           if ok else f"{bad_sum} prefixes break Σ w σ* = c_0 − c_t, {bad_range} have σ* "
                      f"outside [0, 1]")
    return CheckRecord("lemma.TEL.telescoping", "pass" if ok else "fail", msg, numbers, "TEL")


def _c_at_leaves(tree: WalkTree, d: Sequence[Number]) -> dict[int, tuple[Number, Number]]:
    """``(c_{T-1}, c_T)`` (running minimum of ``d`` before and at the last step) per leaf."""
    out = {}
    for p in tree.leaves().tolist():
        walk = tree.walk(p)
        before = min(d[v] for v in walk[:-1]) if len(walk) > 1 else d[walk[0]]
        out[p] = (before, min(before, d[walk[-1]]))
    return out


def l1_lower_bound(ctx: Context) -> CheckRecord:
    """``lemma.L1.lower_bound``: Lemma 1 and its equality case, over all walks of the tree.

    Parameters
    ----------
    ctx : Context
        The shared inputs (:func:`~dppverify.tree_route.context.make_context`).

    Returns
    -------
    CheckRecord

    Examples
    --------
    On the triangle the primary pays ``d(s, g1) = 3`` against σ* on both walks: ``s -> g2``
    costs it 1 (σ* = 1/2 on a step of weight 2) plus ``d(g2, g1) = 2``.

    >>> from dppverify.game.examples import triangle_attacker, triangle_context
    >>> def context(p_g1="4/7", p_g2="3/7"):   # the triangle's equilibrium by default
    ...     return triangle_context(triangle_attacker(p_g1, p_g2))
    >>> r = l1_lower_bound(context())
    >>> r.status, r.numbers["d_s0_g1"], r.numbers["min_U1"], r.numbers["walks_to_g2_attaining"]
    ('pass', 3, 3, 1)
    """
    tree, roles, mode = ctx.tree, ctx.roles, ctx.numbers
    inst = ctx.instance
    d0 = roles.d1[inst.start]
    totals = leaf_totals(tree, roles, ctx.sigma_star, 1)
    br = ctx.best_response(ctx.sigma_star, 1)
    leaves = tree.leaves().tolist()
    cs = _c_at_leaves(tree, roles.d1)
    d21 = roles.d1[roles.g2]
    at_g1 = [p for p in leaves if int(tree.node[p]) == roles.g1]
    at_g2 = [p for p in leaves if int(tree.node[p]) == roles.g2]
    bad_g1 = [p for p in at_g1 if not mode.equal(totals[p], d0)]
    bad_g2 = [p for p in at_g2 if not mode.equal(totals[p], d0 - cs[p][1] + d21)
              or mode.less_than(totals[p], d0)]
    attain_g2 = [p for p in at_g2 if mode.equal(totals[p], d0)]
    minimum = min(totals[p] for p in leaves)
    numbers: dict[str, Number | None] = {"d_s0_g1": d0, "min_U1": minimum,
                                         "min_U1_backward": br.value, "walks_to_g1": len(at_g1),
                                         "walks_to_g2": len(at_g2),
                                         "walks_to_g2_attaining": len(attain_g2)}
    problems = []
    if not (mode.equal(minimum, d0) and mode.equal(br.value, d0)):
        problems.append(f"the minimum of U¹ is {show(minimum)} (backward induction "
                        f"{show(br.value)}), not d(s0,g1) = {show(d0)}")
    if bad_g1:
        problems.append(f"{len(bad_g1)} walks ending at g1 do not cost d(s0,g1), e.g. "
                        f"{show_walk(inst, tree.walk(bad_g1[0]))} costs {show(totals[bad_g1[0]])}")
    if bad_g2:
        problems.append(f"{len(bad_g2)} walks ending at g2 break d(s0,g1) − c_T + d(g2,g1) "
                        f"≥ d(s0,g1), e.g. {show_walk(inst, tree.walk(bad_g2[0]))}")
    if problems:
        return CheckRecord("lemma.L1.lower_bound", "fail", "; ".join(problems), numbers, "L1")
    extra = (f"; {len(attain_g2)} of the {len(at_g2)} walks ending at g2 also attain it "
             f"(exactly those with d(g2,g1) <= c_(T-1), proofs/L1.md)" if attain_g2 else
             f"; the {len(at_g2)} walks ending at g2 cost more")
    return CheckRecord("lemma.L1.lower_bound", "pass",
                       f"min over all {len(leaves)} walks of U¹ against σ* is d(s0,g1) = "
                       f"{show(d0)}, attained by all {len(at_g1)} walks ending at g1{extra}",
                       numbers, "L1")


def l2_no_revisits(ctx: Context) -> CheckRecord:
    """``lemma.L2.no_revisits``: Lemma 2 over all walks of the tree.

    Parameters
    ----------
    ctx : Context
        The shared inputs (:func:`~dppverify.tree_route.context.make_context`).

    Returns
    -------
    CheckRecord

    Examples
    --------
    The triangle's tree has no revisiting walk (every neighbour of ``s`` is a goal):

    >>> from dppverify.game.examples import triangle_attacker, triangle_context
    >>> def context(p_g1="4/7", p_g2="3/7"):   # the triangle's equilibrium by default
    ...     return triangle_context(triangle_attacker(p_g1, p_g2))
    >>> r = l2_no_revisits(context())
    >>> r.status, r.numbers["min_U2_walks"], r.numbers["min_U2_paths"], r.numbers["walks"]
    ('pass', 1, 1, 2)
    >>> r.numbers["min_U2_revisiting"] is None
    True
    """
    tree, roles, mode = ctx.tree, ctx.roles, ctx.numbers
    totals = leaf_totals(tree, roles, ctx.sigma_star, 2)
    simple = simple_mask(tree)
    leaves = tree.leaves().tolist()
    m_all = min(totals[p] for p in leaves)
    simple_leaves = [p for p in leaves if simple[p]]
    m_simple = min(totals[p] for p in simple_leaves)
    non_simple = [totals[p] for p in leaves if not simple[p]]
    m_non = min(non_simple) if non_simple else None
    br_all = ctx.best_response(ctx.sigma_star, 2)
    br_simple = attacker_best_response(tree, roles, ctx.sigma_star, 2, allowed=simple)
    numbers: dict[str, Number | None] = {"min_U2_walks": m_all, "min_U2_paths": m_simple,
                                         "min_U2_revisiting": m_non, "walks": len(leaves),
                                         "paths": len(simple_leaves)}
    ok = (mode.equal(m_all, m_simple) and mode.equal(br_all.value, m_all)
          and mode.equal(br_simple.value, m_simple)
          and (m_non is None or mode.less_than(m_all, m_non)))
    if ok:
        tail = ("no walk of the tree revisits a node" if m_non is None else
                f"every walk that revisits a node costs more (at least {show(m_non)})")
        return CheckRecord("lemma.L2.no_revisits", "pass",
                           f"the secondary's best response over all {len(leaves)} walks "
                           f"({show(m_all)}) equals that over the {len(simple_leaves)} simple "
                           f"paths; {tail}", numbers, "L2")
    return CheckRecord("lemma.L2.no_revisits", "fail",
                       f"min over walks {show(m_all)}, over simple paths {show(m_simple)}, over "
                       f"revisiting walks {show(m_non)} (backward induction {show(br_all.value)}"
                       f" / {show(br_simple.value)})", numbers, "L2")


def xi2_secondary_value(ctx: Context) -> CheckRecord:
    """``lemma.XI2.secondary_value``: proofs/XI2.md's ``U²* = M − d(s0, g1)`` bounds the tree's min.

    Parameters
    ----------
    ctx : Context
        The shared inputs (:func:`~dppverify.tree_route.context.make_context`).

    Returns
    -------
    CheckRecord

    Examples
    --------
    ``M = min_v d(s0, v) + d(v, g1) + d(v, g2) = 4`` (at ``v = g2``), so ``U²* = 4 − 3 = 1``:

    >>> from dppverify.game.examples import triangle_attacker, triangle_context
    >>> def context(p_g1="4/7", p_g2="3/7"):   # the triangle's equilibrium by default
    ...     return triangle_context(triangle_attacker(p_g1, p_g2))
    >>> r = xi2_secondary_value(context())
    >>> r.status, dict(r.numbers)
    ('pass', {'M': 4, 'U2_star': 1, 'min_U2_tree': 1})
    """
    inst, roles, mode = ctx.instance, ctx.roles, ctx.numbers
    d0 = dijkstra(inst.succ, inst.start)
    M = min(d0[v] + roles.d1[v] + roles.d2[v] for v in range(inst.n_nodes))
    u2_star = M - roles.d1[inst.start]
    u2_star = mode.convert(u2_star)
    br = ctx.best_response(ctx.sigma_star, 2)
    numbers: dict[str, Number | None] = {"M": M, "U2_star": u2_star, "min_U2_tree": br.value}
    if mode.less_than(br.value, u2_star):
        return CheckRecord("lemma.XI2.secondary_value", "fail",
                           f"the walk {show_walk(inst, br.walk)} costs the secondary "
                           f"{show(br.value)} < M − d(s0,g1) = {show(u2_star)}", numbers, "XI2")
    how = ("equals it" if mode.equal(br.value, u2_star) else
           f"exceeds it: an optimal path needs more than H = {ctx.tree.horizon} steps")
    return CheckRecord("lemma.XI2.secondary_value", "pass",
                       f"min over the tree of U² against σ* is {show(br.value)}; M − d(s0,g1) = "
                       f"{show(u2_star)} (M = {show(M)}); the tree's minimum {how}", numbers,
                       "XI2")


def _random_walk(tree: WalkTree, rng: random.Random, start: int = 0) -> tuple[int, ...]:
    p = start
    while True:
        kids = tree.children(p)
        if not kids:
            return tree.walk(p)
        p = rng.choice(list(kids))


def random_mixture(tree: WalkTree, rng: random.Random, through: Sequence[int] | None = None,
                   k_max: int = 4) -> tuple[StrategyPath, ...]:
    """A random non-reacting mixed strategy: 1..k_max random walks, rational probabilities.

    With ``through`` (a root-to-leaf list of prefixes), each walk follows it for a random
    number of steps before branching at random: random deviations from a given path.

    Parameters
    ----------
    tree : WalkTree
        The walks to choose from (root to leaf).
    rng : random.Random
        The source of randomness (seeded by the caller: same seed, same mixture).
    through : sequence of int, optional
        Prefixes of a root-to-leaf path to branch off from.
    k_max : int
        At most this many distinct walks.

    Returns
    -------
    tuple of StrategyPath
        Walks (node indices) with exact probabilities summing to 1.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> from dppverify.tree_route.tree import build_tree
    >>> tree = build_tree(triangle(), 1)   # walks (0, 1) = s g1 and (0, 2) = s g2
    >>> mix = random_mixture(tree, random.Random(3))
    >>> [(w.walk, str(w.probability)) for w in mix]
    [((0, 1), '1/3'), ((0, 2), '2/3')]
    >>> mix == random_mixture(tree, random.Random(3)), sum(w.probability for w in mix)
    (True, Fraction(1, 1))
    """
    weights: dict[tuple[int, ...], int] = {}
    for _ in range(rng.randint(1, k_max)):
        start = 0 if through is None else through[rng.randrange(len(through))]
        walk = _random_walk(tree, rng, start)
        weights[walk] = weights.get(walk, 0) + rng.randint(1, 6)
    total = sum(weights.values())
    return tuple(StrategyPath(w, Fraction(c, total)) for w, c in weights.items())


def l3_greedy(ctx: Context) -> CheckRecord:
    """``lemma.L3.greedy``: Lemma 3 for the profile's attacker and random attackers.

    Parameters
    ----------
    ctx : Context
        The shared inputs (:func:`~dppverify.tree_route.context.make_context`).

    Returns
    -------
    CheckRecord

    Examples
    --------
    The profile's attacker and ``ctx.trials = 2`` random ones:

    >>> from dppverify.game.examples import triangle_attacker, triangle_context
    >>> def context(p_g1="4/7", p_g2="3/7"):   # the triangle's equilibrium by default
    ...     return triangle_context(triangle_attacker(p_g1, p_g2))
    >>> r = l3_greedy(context())
    >>> r.status, r.numbers["attackers"], r.numbers["max_value_gap"] < 1e-7
    ('pass', 3, True)
    """
    tree, roles = ctx.tree, ctx.roles
    rng = random.Random(f"{ctx.seed}-L3")
    attackers = []
    if isinstance(ctx, EvaluatedContext):
        attackers.append(("the profile's attacker", ctx.x1, ctx.x2))
    for k in range(ctx.trials):
        attackers.append((f"random attacker {k + 1}",
                          realization(tree, random_mixture(tree, rng)),
                          realization(tree, random_mixture(tree, rng))))
    worst_value = 0.0
    worst_sigma = 0.0
    problems = []
    checked = 0
    for name, x1, x2 in attackers:
        greedy = defender_best_response(tree, roles, {1: x1, 2: x2})
        lp, sigma = defender_best_response_lp(tree, roles, {1: x1, 2: x2})
        err = abs(lp.value - float(greedy.value))
        worst_value = max(worst_value, err)
        if not lp_agrees(lp.value, greedy.value):
            problems.append(f"{name}: LP optimum {show(lp.value)} ≠ greedy value "
                            f"{show(greedy.value)}")
        coef = {p: tree.weight[p] * (roles.b1 * x1.get(p, Fraction(0))
                                     - roles.b2 * x2.get(p, Fraction(0))) for p in sigma}
        scale = max([abs(float(c)) for c in coef.values()] + [0.0])
        for p, s in sigma.items():
            c = float(coef[p])
            if abs(c) < GREEDY_COEFFICIENT * scale or coef[p] == 0:
                continue
            checked += 1
            target = 1.0 if c > 0 else 0.0
            worst_sigma = max(worst_sigma, abs(s - target))
            if abs(s - target) > GREEDY_SIGMA_TOLERANCE:
                problems.append(f"{name}: the LP allocates σ(g1) = {s:.6g} after "
                                f"{show_walk(ctx.instance, tree.walk(p))} where the belief is "
                                f"strictly {'above' if c > 0 else 'below'} 1/2")
                break
    numbers: dict[str, Number | None] = {"attackers": len(attackers), "seed": ctx.seed,
                                         "max_value_gap": worst_value,
                                         "strict_infosets_checked": checked,
                                         "max_sigma_deviation": worst_sigma}
    status: Status = "fail" if problems else "pass"
    msg = ("; ".join(problems[:3]) if problems else
           f"for {len(attackers)} non-reacting attackers (seed {ctx.seed}) the Defender's LP "
           f"optimum equals the greedy value (gap <= {worst_value:.2g}) and is greedy at all "
           f"{checked} strict-belief information sets (within {worst_sigma:.2g})")
    return CheckRecord("lemma.L3.greedy", status, msg, numbers, "L3")


def l4_monotonicity(ctx: Context) -> CheckRecord:
    """``lemma.L4.monotonicity``: Lemma 4 along the secondary walk(s) ξ.

    Parameters
    ----------
    ctx : Context
        The shared inputs (:func:`~dppverify.tree_route.context.make_context`).

    Returns
    -------
    CheckRecord

    Examples
    --------
    >>> from dppverify.game.examples import triangle_attacker, triangle_context
    >>> def context(p_g1="4/7", p_g2="3/7"):   # the triangle's equilibrium by default
    ...     return triangle_context(triangle_attacker(p_g1, p_g2))
    >>> r = l4_monotonicity(context())
    >>> r.status, dict(r.numbers)
    ('pass', {'secondary_walks': 1, 'primary_strategies': 3, 'violations': 0, 'seed': 0})
    """
    tree, roles = ctx.tree, ctx.roles
    rng = random.Random(f"{ctx.seed}-L4")
    paths: dict[tuple[int, ...], str] = {}
    if ctx.profile.wellformed:
        for w in ctx.profile.secondary:
            if w.probability > 0:
                paths.setdefault(w.walk, "the profile's secondary walk")
    br = ctx.best_response(ctx.sigma_star, 2)
    paths.setdefault(br.walk, "a secondary best response to σ*")
    violations = []
    strategies = 0
    for walk, _origin in paths.items():
        leaf = tree.find(walk)
        assert leaf is not None
        along = tree.prefixes(leaf)
        primaries: list[tuple[str, tuple[StrategyPath, ...]]] = []
        if isinstance(ctx, EvaluatedContext):
            primaries.append(("the profile's primary", ctx.profile.primary))
        primaries += [(f"random primary {k + 1}", random_mixture(tree, rng, through=along))
                      for k in range(ctx.trials)]
        for name, prim in primaries:
            strategies += 1
            x1 = realization(tree, prim)
            beliefs = [roles.b1 * x1.get(p, Fraction(0))
                       / (roles.b1 * x1.get(p, Fraction(0)) + roles.b2) for p in along]
            for t in range(1, len(beliefs)):
                if beliefs[t] > beliefs[t - 1]:
                    violations.append(f"{name}: along {show_walk(ctx.instance, walk)} the "
                                      f"belief rises from {show(beliefs[t - 1])} to "
                                      f"{show(beliefs[t])} at step {t}")
                    break
    numbers: dict[str, Number | None] = {"secondary_walks": len(paths),
                                         "primary_strategies": strategies,
                                         "violations": len(violations), "seed": ctx.seed}
    if violations:
        return CheckRecord("lemma.L4.monotonicity", "fail", "; ".join(violations[:3]), numbers,
                           "L4")
    return CheckRecord("lemma.L4.monotonicity", "pass",
                       f"b1_t never increases along {len(paths)} secondary walk(s) under "
                       f"{strategies} primary strategies (seed {ctx.seed})", numbers, "L4")


def l5_induced_beliefs(ctx: EvaluatedContext) -> CheckRecord:
    """``lemma.L5.induced_beliefs``: Lemma 5 for the profile's attacker.

    Parameters
    ----------
    ctx : Context
        The shared inputs (:func:`~dppverify.tree_route.context.make_context`).

    Returns
    -------
    CheckRecord

    Examples
    --------
    ξ² = ``s -> g2`` is all phase II: the equilibrium mixture makes the belief 1/2 after its
    step; with the primary's probabilities swapped it is 4/7.

    >>> from dppverify.game.examples import triangle_attacker, triangle_context
    >>> def context(p_g1="4/7", p_g2="3/7"):   # the triangle's equilibrium by default
    ...     return triangle_context(triangle_attacker(p_g1, p_g2))
    >>> l5_induced_beliefs(context()).status
    'pass'
    >>> r = l5_induced_beliefs(context("3/7", "4/7"))
    >>> r.status, r.message
    ('fail', 'at step 1 of ξ² (phase II) the belief is 4/7, not 1/2')
    """
    cid = "lemma.L5.induced_beliefs"
    sec = [w for w in ctx.profile.secondary if w.probability > 0]
    if len(sec) != 1:
        return CheckRecord(cid, "skipped", "not applicable: the secondary type mixes several "
                           "walks, Lemma 5 is about the paper's deterministic ξ²", {}, "L5")
    inst, tree, roles = ctx.instance, ctx.tree, ctx.roles
    xi2 = sec[0].walk
    t1, t2, T = phases_of(sigma_along(inst, roles, ProgressRule(roles.g1), xi2),
                          ctx.numbers).as_tuple()
    leaf = tree.find(xi2)
    assert leaf is not None
    along = tree.prefixes(leaf)

    problems = []
    for t, p in enumerate(along):
        want = roles.b1 if t <= t1 else (HALF if t <= t2 else Fraction(0))
        got = ctx.beliefs[p]
        if got != want:
            phase = "I" if t <= t1 else ("II" if t <= t2 else "III")
            problems.append(f"at step {t} of ξ² (phase {phase}) the belief is {show(got)}, "
                            f"not {show(want)}")
    on_xi2 = set(along)
    off = [p for p in ctx.x1 if p not in on_xi2]
    numbers: dict[str, Number | None] = {"t_I": t1, "t_II": t2, "T": T, "b1": roles.b1,
                                         "off_path_prefixes": len(off)}
    if problems:
        return CheckRecord(cid, "fail", "; ".join(problems[:3]), numbers, "L5")
    return CheckRecord(cid, "pass", f"beliefs along ξ² are {show(roles.b1)} on phase I "
                       f"(t <= {t1}), 1/2 on phase II (t <= {t2}), 0 on phase III (t <= {T}); "
                       f"{OFF_XI2}", numbers, "L5")

