"""The Attacker types' regrets: ``pbne.attacker_br.primary`` and ``.secondary``."""

from __future__ import annotations

from dppverify.certificate import CheckRecord
from dppverify.exact import Number
from dppverify.game.evaluation import walk_cost
from dppverify.text import show, show_walk
from dppverify.tree_route.best_response import attacker_best_response_lp, leaf_totals
from dppverify.tree_route.context import EvaluatedContext
from dppverify.tree_route.lp import lp_agrees


def attacker_br(ctx: EvaluatedContext, role: int) -> CheckRecord:
    """``pbne.attacker_br.primary`` / ``.secondary``: type θ's exact regret is 0.

    The regret is ``U^θ(profile) − min over ALL walks of the tree`` against the profile's
    Defender (backward induction; a forward pass over the leaves and the sequence-form LP
    must agree with it).

    Parameters
    ----------
    ctx : Context
        The shared inputs (:func:`~dppverify.tree_route.context.make_context`).
    role : int
        1 (primary) or 2 (secondary).

    Returns
    -------
    CheckRecord

    Examples
    --------
    A secondary type that walks to g1 pays 2 where ``s -> g2`` costs it 1:

    >>> from dppverify.game.examples import triangle_attacker

    >>> from tests.dppverify.checks.doctest_inputs import triangle_context as context
    >>> eq = triangle_attacker()
    >>> r = attacker_br(context(eq), 2)
    >>> r.id, r.status, r.numbers["U2"], r.numbers["best_response"], r.numbers["regret"]
    ('pbne.attacker_br.secondary', 'pass', 1, 1, 0)
    >>> r = attacker_br(context(dict(eq, secondary=[{"path": ["s", "g1"], "probability": 1}])), 2)
    >>> r.status, r.numbers["regret"]
    ('fail', 1)
    """
    cid = "pbne.attacker_br." + ("primary" if role == 1 else "secondary")
    proof = "L1" if role == 1 else "XI2"
    inst, tree, roles = ctx.instance, ctx.tree, ctx.roles
    ev = ctx.evaluated
    br = ctx.best_response(ev.defender, role)
    totals = leaf_totals(tree, roles, ev.defender, role)
    forward = min(totals[p] for p in tree.leaves().tolist())
    lp = attacker_best_response_lp(tree, roles, ev.defender, role)
    u = ev.values.U1 if role == 1 else ev.values.U2
    regret = ctx.numbers.difference(u, br.value)
    numbers: dict[str, Number | None] = {f"U{role}": u, "best_response": br.value,
                                         "best_response_lp": lp.value, "regret": regret,
                                         "walks": tree.n_leaves}
    where = f"over all {tree.n_leaves} walks with <= {tree.horizon} steps"
    if not ctx.numbers.equal(forward, br.value) or not lp_agrees(lp, br.value):
        return CheckRecord(cid, "error", f"backward induction {show(br.value)}, forward pass "
                           f"{show(forward)} and LP {show(lp.value)} disagree", numbers, proof)
    if ctx.numbers.equal(regret, 0):
        return CheckRecord(cid, "pass", f"regret 0: U{role} = {show(u)} is the minimum {where} "
                           f"(LP {show(lp.value)})", numbers, proof)
    if regret < 0:
        return CheckRecord(cid, "error", f"U{role} = {show(u)} is below the best response "
                           f"{show(br.value)}: inconsistent evaluation", numbers, proof)
    costs = [(walk_cost(inst, roles, ev.rule, w.walk, role), w)
             for w in ctx.profile.walks(role) if w.probability > 0]
    worst_cost, worst = max(costs, key=lambda cw: cw[0])
    return CheckRecord(cid, "fail", f"regret {show(regret)}: the walk {show_walk(inst, br.walk)} "
                       f"costs {show(br.value)} < U{role} = {show(u)}; the profile's walk "
                       f"{show_walk(inst, worst.walk)} (probability {show(worst.probability)}) "
                       f"costs {show(worst_cost)}", numbers, proof)
