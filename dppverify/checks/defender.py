"""The Defender's rationality: ``pbne.defender_br`` (regret over all Defender strategies) and
``pbne.sequential_rationality`` (greedy on the Bayes belief at every reached infoset)."""

from __future__ import annotations

from fractions import Fraction

from dppverify.certificate import CheckRecord
from dppverify.exact import Number
from dppverify.text import show, show_walk
from dppverify.tree_route.best_response import defender_best_response, defender_best_response_lp
from dppverify.tree_route.context import EvaluatedContext
from dppverify.tree_route.lp import lp_agrees

HALF = Fraction(1, 2)


def defender_br(ctx: EvaluatedContext) -> CheckRecord:
    """``pbne.defender_br``: the Defender's exact regret (greedy best response − U) is 0.

    Examples
    --------
    With the primary's probabilities swapped (3/7 to g1), allocating ``s -> g2`` to g1 gains
    the Defender 1/10:

    >>> from dppverify.game.examples import triangle_attacker

    >>> from tests.dppverify.checks.doctest_inputs import triangle_context as context
    >>> eq = triangle_attacker()
    >>> defender_br(context(eq)).numbers["regret"]
    0
    >>> swapped = dict(eq, primary=[{"path": ["s", "g1"], "probability": "3/7"},
    ...                             {"path": ["s", "g2"], "probability": "4/7"}])
    >>> r = defender_br(context(swapped))
    >>> r.status, r.numbers["U"], r.numbers["best_response"], r.numbers["regret"]
    ('fail', Fraction(12, 5), Fraction(5, 2), Fraction(1, 10))
    """
    cid = "pbne.defender_br"
    tree, roles = ctx.tree, ctx.roles
    ev = ctx.evaluated
    u = ev.values.U
    br = defender_best_response(tree, roles, {1: ev.x1, 2: ev.x2})
    lp, _ = defender_best_response_lp(tree, roles, {1: ev.x1, 2: ev.x2})
    regret = ctx.numbers.difference(br.value, u)
    numbers: dict[str, Number | None] = {"U": u, "best_response": br.value,
                                         "best_response_lp": lp.value, "regret": regret}
    if not lp_agrees(lp, br.value):
        return CheckRecord(cid, "error", f"greedy best response {show(br.value)} and LP "
                           f"{show(lp.value)} disagree", numbers, "L3")
    if ctx.numbers.equal(regret, 0):
        return CheckRecord(cid, "pass", f"regret 0: no Defender strategy beats U = {show(u)} "
                           f"(greedy best response {show(br.value)}, LP {show(lp.value)})",
                           numbers, "L3")
    if regret < 0:
        return CheckRecord(cid, "error", f"U = {show(u)} exceeds the Defender's best response "
                           f"{show(br.value)}: inconsistent evaluation", numbers, "L3")
    gains = []
    for p in br.choice:
        v1 = roles.b1 * ev.x1.get(p, Fraction(0))
        v2 = roles.b2 * ev.x2.get(p, Fraction(0))
        s = ev.defender.sigma1[p]
        gains.append((tree.weight[p] * (max(v1, v2) - (v1 * s + v2 * (1 - s))), p))
    gain, p = max(gains)
    walk = show_walk(ctx.instance, tree.walk(p))
    return CheckRecord(cid, "fail", f"regret {show(regret)}: the Defender gains by deviating, "
                       f"most ({show(gain)}) after the walk {walk}", numbers, "L3")


def sequential_rationality(ctx: EvaluatedContext) -> CheckRecord:
    """``pbne.sequential_rationality``: greedy w.r.t. the Bayes belief at every reached infoset.

    Lemma 3: allocate to g1 surely when ``b1_t > 1/2``, to g2 surely when ``b1_t < 1/2``;
    anything is rational at exactly 1/2.

    Examples
    --------
    In equilibrium the belief after ``s -> g2`` is exactly 1/2, so σ* = 1/2 is rational there;
    with the primary's probabilities swapped it is 4/7 and σ* is not greedy:

    >>> from dppverify.game.examples import triangle_attacker

    >>> from tests.dppverify.checks.doctest_inputs import triangle_context as context
    >>> eq = triangle_attacker()
    >>> dict(sequential_rationality(context(eq)).numbers)
    {'infosets': 2, 'at_one_half': 1, 'violations': 0}
    >>> swapped = dict(eq, primary=[{"path": ["s", "g1"], "probability": "3/7"},
    ...                             {"path": ["s", "g2"], "probability": "4/7"}])
    >>> print(sequential_rationality(context(swapped)).message)  # doctest: +NORMALIZE_WHITESPACE
    1 of 2 reached information sets are not greedy; e.g. after "s" -> "g2" the belief in g1
    is 4/7 but σ(g1) = 1/2
    """
    cid = "pbne.sequential_rationality"
    ev = ctx.evaluated
    beliefs = ev.beliefs
    bad = []
    half = 0
    mode = ctx.numbers
    for p in sorted(beliefs):
        if p == 0:
            continue
        b, s = beliefs[p], ev.defender.sigma1[p]
        if b == HALF:
            half += 1
        elif (b > HALF and not mode.equal(s, 1)) or (b < HALF and not mode.equal(s, 0)):
            bad.append((p, b, s))
    n = len(beliefs) - 1
    numbers: dict[str, Number | None] = {"infosets": n, "at_one_half": half,
                                         "violations": len(bad)}
    if not bad:
        return CheckRecord(cid, "pass", f"greedy at all {n} information sets reached "
                           f"({half} at belief 1/2, where any allocation is rational)",
                           numbers, "THM")
    p, b, s = bad[0]
    return CheckRecord(cid, "fail", f"{len(bad)} of {n} reached information sets are not "
                       f"greedy; e.g. after {show_walk(ctx.instance, ctx.tree.walk(p))} the "
                       f"belief in g1 is {show(b)} but σ(g1) = {show(s)}", numbers, "THM")
