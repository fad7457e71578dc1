"""The profile's payoffs and the game value: ``value.U1``, ``value.U2``, ``value.U``,
``value.VoI`` and ``game.value``."""

from __future__ import annotations

import numpy as np

from dppverify.certificate import CheckRecord, Status
from dppverify.checks.skipped import NOT_WELLFORMED
from dppverify.exact import Number
from dppverify.text import show
from dppverify.tree_route.best_response import objective_vector, payoff_on_tree
from dppverify.tree_route.context import Context, EvaluatedContext
from dppverify.tree_route.lp import LP_TOLERANCE, lp_agrees
from dppverify.tree_route.value_lp import exact_bracket, solve_value_lp


def values(ctx: EvaluatedContext) -> list[CheckRecord]:
    """``value.U1``, ``value.U2``, ``value.U``, ``value.VoI``.

    Three routes must agree: walk by walk (exact), realization plans on the tree (exact),
    and the LP objective vectors at the profile's plans (float, within the LP tolerance);
    the profile's claimed numbers, when present, must equal the exact ones.

    Parameters
    ----------
    ctx : Context
        The shared inputs (:func:`~dppverify.tree_route.context.make_context`).

    Returns
    -------
    list of CheckRecord
        The four records, in that order.

    Examples
    --------
    >>> from dppverify.game.examples import triangle_attacker
    >>> from tests.dppverify.checks.doctest_inputs import triangle_context as context
    >>> eq = triangle_attacker()
    >>> for r in values(context(eq)):
    ...     print(r.id, r.status, r.message)
    value.U1 pass U1 = 3, LP evaluation 3
    value.U2 pass U2 = 1, LP evaluation 1
    value.U pass U = 12/5, LP evaluation 2.4
    value.VoI pass Ū = 27/10, VoI = 1/9
    >>> r = values(context(eq, value={"U": "5/2"}))[2]
    >>> r.status, r.message
    ('fail', 'U = 12/5 exactly, but the profile claims U = 5/2')
    """
    ev = ctx.evaluated
    v = ev.values
    claims = ctx.profile.claimed_values
    tree, roles = ctx.tree, ctx.roles
    lp_u: dict[int, float] = {}
    for role, x in ((1, ev.x1), (2, ev.x2)):
        vec = np.zeros(tree.n_prefixes)
        for p, prob in x.items():
            vec[p] = float(prob)
        lp_u[role] = float(objective_vector(tree, roles, ev.defender, role) @ vec)
    lp_total = float(roles.b1) * lp_u[1] + float(roles.b2) * lp_u[2]
    tree_u = payoff_on_tree(tree, roles, ev.defender, {1: ev.x1, 2: ev.x2})
    out = []
    for cid, key, exact, lp_value in (("value.U1", "U1", v.U1, lp_u[1]),
                                      ("value.U2", "U2", v.U2, lp_u[2]),
                                      ("value.U", "U", v.U, lp_total)):
        numbers: dict[str, Number | None] = {key: exact, f"{key}_profile": claims.get(key),
                                             f"{key}_lp": lp_value}
        problems = []
        status: Status = "pass"
        if key in claims and not ctx.numbers.equal(claims[key], exact):
            status = "fail"
            problems.append(f"the profile claims {key} = {show(claims[key])}")
        if not lp_agrees(lp_value, exact):
            status = "error" if status == "pass" else status
            problems.append(f"LP evaluation {show(lp_value)} disagrees")
        if key == "U":
            numbers["U_tree"] = tree_u
            if not ctx.numbers.equal(tree_u, exact):
                status = "error" if status == "pass" else status
                problems.append(f"the realization-plan route gives {show(tree_u)}")
        claim = f" (profile says {show(claims[key])})" if key in claims else ""
        msg = f"{key} = {show(exact)}{claim}, LP evaluation {show(lp_value)}"
        if problems:
            msg = f"{key} = {show(exact)} exactly, but " + "; ".join(problems)
        out.append(CheckRecord(cid, status, msg, numbers, "TEL"))
    numbers = {"U_bar": v.U_bar, "VoI": v.VoI, "U_bar_profile": claims.get("U_bar"),
               "VoI_profile": claims.get("VoI")}
    bad = [k for k, x in (("U_bar", v.U_bar), ("VoI", v.VoI))
           if k in claims and not ctx.numbers.equal(claims[k], x)]
    msg = f"Ū = {show(v.U_bar)}, VoI = {show(v.VoI)}"
    if bad:
        msg += "; the profile claims " + ", ".join(f"{k} = {show(claims[k])}" for k in bad)
    out.append(CheckRecord("value.VoI", "fail" if bad else "pass", msg, numbers, "THM"))
    return out


def value_check(ctx: Context) -> CheckRecord:
    """``game.value``: ``V_H`` (compact LP, proofs/LP.md) equals ``U`` of the profile.

    Exact bounds: the profile's Defender gives ``b1 min U¹ + b2 min U² <= V_H`` and its
    Attacker gives ``V_H <= max_σ U``; with both regrets 0 they meet at ``U``, so ``V_H = U``
    exactly. The LP value must lie within the exact bracket (within the LP tolerance).

    Examples
    --------
    A secondary type walking to g1 makes ``U = 27/10``, not the value ``V_1 = 12/5``:

    >>> from dppverify.game.examples import triangle_attacker

    >>> from tests.dppverify.checks.doctest_inputs import triangle_context as context
    >>> eq = triangle_attacker()
    >>> r = value_check(context(eq))
    >>> r.status, r.numbers["V_H"], r.numbers["U"]
    ('pass', Fraction(12, 5), Fraction(12, 5))
    >>> r = value_check(context(dict(eq, secondary=[{"path": ["s", "g1"], "probability": 1}])))
    >>> r.status, r.numbers["V_H_lower"], r.numbers["V_H_upper"], r.numbers["U"]
    ('fail', Fraction(12, 5), Fraction(12, 5), Fraction(27, 10))
    """
    cid = "game.value"
    tree, roles = ctx.tree, ctx.roles
    lp = solve_value_lp(tree, roles)
    defenders = []
    attackers = []
    if isinstance(ctx, EvaluatedContext):
        ev = ctx.evaluated
        defenders.append(("the profile's Defender", ev.defender))
        attackers.append(("the profile's Attacker", {1: ev.x1, 2: ev.x2}))
    bracket = exact_bracket(tree, roles, lp, defenders, attackers, sigma_star=ctx.sigma_star)
    numbers: dict[str, Number | None] = {"V_H_lp": lp.value, "V_H": bracket.exact,
                                         "V_H_lower": bracket.lower, "V_H_upper": bracket.upper,
                                         "H": tree.horizon}
    closed = ctx.numbers.equal(bracket.lower, bracket.upper)
    vh = f"V_H = {show(bracket.lower)}" + (" exactly" if ctx.numbers.exact else "") if closed else (
        f"{show(bracket.lower)} <= V_H <= {show(bracket.upper)}")
    vh += f" (LP {show(lp.value)}, H = {tree.horizon})"
    inside = (lp.value >= float(bracket.lower) - _slack(bracket.lower)
              and lp.value <= float(bracket.upper) + _slack(bracket.upper))
    if not inside:
        return CheckRecord(cid, "error", f"the LP value lies outside the exact bracket: {vh}",
                           numbers, "LP")
    if not isinstance(ctx, EvaluatedContext):
        return CheckRecord(cid, "skipped", f"{vh}; {NOT_WELLFORMED}", numbers, "LP")
    u = ctx.evaluated.values.U
    numbers["U"] = u
    exact_equal = ctx.numbers.equal(bracket.lower, u) and ctx.numbers.equal(bracket.upper, u)
    if exact_equal and lp_agrees(lp.stats, u):
        return CheckRecord(cid, "pass", f"{vh} = U", numbers, "HORIZON")
    return CheckRecord(cid, "fail", f"U = {show(u)} is not the value of the truncated game: {vh}",
                       numbers, "HORIZON")


def _slack(x: Number) -> float:
    return LP_TOLERANCE * max(1.0, abs(float(x)))
