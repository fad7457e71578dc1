"""The lemmas checked against random non-reacting attackers: ``lemma.L3.greedy`` and
``lemma.L4.monotonicity`` (proofs/L3.md, L4.md), with :func:`random_mixture`.

See :mod:`dppverify.checks.lemmas` for what each checks.
"""

from __future__ import annotations

import random
from collections.abc import Sequence
from fractions import Fraction

from dppio.text import count, decimal
from dppverify.certificate import CheckRecord, Status
from dppverify.exact import Number
from dppverify.game.evaluation import realization
from dppverify.game.profile import StrategyWalk
from dppverify.text import show, show_walk
from dppverify.tree_route.best_response import defender_best_response, defender_best_response_lp
from dppverify.tree_route.context import Context, EvaluatedContext
from dppverify.tree_route.lp import lp_agrees
from dppverify.tree_route.tree import WalkTree

GREEDY_COEFFICIENT = 1e-6
"""L3: LP allocations are checked for greediness where the exact objective coefficient
``|w (b1 x1 − b2 x2)|`` is at least this fraction of the largest one (below it an
interior-point solution cannot be told apart from a tie)."""

GREEDY_SIGMA_TOLERANCE = 1e-4
"""L3: an LP allocation counts as 1 (resp. 0) when within this distance of it."""


def _random_walk(tree: WalkTree, rng: random.Random, start: int = 0) -> tuple[int, ...]:
    p = start
    while True:
        kids = tree.children(p)
        if not kids:
            return tree.walk(p)
        p = rng.choice(list(kids))


def random_mixture(tree: WalkTree, rng: random.Random, through: Sequence[int] | None = None,
                   k_max: int = 4) -> tuple[StrategyWalk, ...]:
    """A random non-reacting mixed strategy: 1..k_max random walks, rational probabilities.

    With ``through`` (a root-to-leaf list of prefixes), each walk follows it for a random
    number of steps before branching at random: random deviations from a given walk.

    Parameters
    ----------
    tree : WalkTree
        The walks to choose from (root to leaf).
    rng : random.Random
        The source of randomness (seeded by the caller: same seed, same mixture).
    through : sequence of int, optional
        Prefixes of a root-to-leaf walk to branch off from.
    k_max : int
        At most this many distinct walks.

    Returns
    -------
    tuple of StrategyWalk
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
    return tuple(StrategyWalk(w, Fraction(c, total)) for w, c in weights.items())


def l3_greedy(ctx: Context) -> CheckRecord:
    """``lemma.L3.greedy``: Lemma 3 for the profile's attacker and random attackers.

    ``ctx.seed`` and ``ctx.trials`` choose the random attackers.

    Examples
    --------
    The profile's attacker and ``ctx.trials = 2`` random ones:

    >>> from tests.dppverify.checks.doctest_inputs import triangle_context as context
    >>> r = l3_greedy(context())
    >>> r.status, r.numbers["attackers"], r.numbers["max_value_gap"] < 1e-7
    ('pass', 3, True)
    """
    tree, roles = ctx.tree, ctx.roles
    rng = random.Random(f"{ctx.seed}-L3")
    attackers = []
    if isinstance(ctx, EvaluatedContext):
        attackers.append(("the profile's attacker", ctx.evaluated.x1, ctx.evaluated.x2))
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
        if not lp_agrees(lp, greedy.value):
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
                problems.append(f"{name}: the LP allocates σ(g1) = {decimal(s)} after "
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
           f"optimum equals the greedy value (gap <= {decimal(worst_value)}) and is greedy at all "
           f"{checked} strict-belief information sets (within {decimal(worst_sigma)})")
    return CheckRecord("lemma.L3.greedy", status, msg, numbers, "L3")


def l4_monotonicity(ctx: Context) -> CheckRecord:
    """``lemma.L4.monotonicity``: Lemma 4 along the secondary walk(s) ξ.

    ``ctx.seed`` and ``ctx.trials`` choose the random attackers.

    Examples
    --------
    >>> from tests.dppverify.checks.doctest_inputs import triangle_context as context
    >>> r = l4_monotonicity(context())
    >>> r.status, dict(r.numbers)
    ('pass', {'secondary_walks': 1, 'primary_strategies': 3, 'violations': 0, 'seed': 0})
    """
    tree, roles = ctx.tree, ctx.roles
    rng = random.Random(f"{ctx.seed}-L4")
    walks: dict[tuple[int, ...], str] = {}
    if ctx.profile.wellformed:
        for w in ctx.profile.secondary:
            if w.probability > 0:
                walks.setdefault(w.walk, "the profile's secondary walk")
    br = ctx.best_response(ctx.sigma_star, 2)
    walks.setdefault(br.walk, "a secondary best response to σ*")
    violations = []
    strategies = 0
    for walk, _origin in walks.items():
        leaf = tree.find(walk)
        assert leaf is not None
        along = tree.prefixes(leaf)
        primaries: list[tuple[str, tuple[StrategyWalk, ...]]] = []
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
    numbers: dict[str, Number | None] = {"secondary_walks": len(walks),
                                         "primary_strategies": strategies,
                                         "violations": len(violations), "seed": ctx.seed}
    if violations:
        return CheckRecord("lemma.L4.monotonicity", "fail", "; ".join(violations[:3]), numbers,
                           "L4")
    return CheckRecord("lemma.L4.monotonicity", "pass",
                       f"b1_t never increases along {count(len(walks), 'secondary walk')} under "
                       f"{count(strategies, 'primary strategy')} (seed {ctx.seed})", numbers, "L4")
