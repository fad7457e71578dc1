"""The profile checks: well-formedness, payoffs, regrets, sequential rationality, beliefs, V_H.

Each function takes the shared :class:`~dppverify.context.Context` and returns one
:class:`~dppverify.certificate.CheckRecord` (ids in ``dppverify/checks.md``). Exact numbers
decide every pass/fail; LP numbers are reported beside them and must agree within
:data:`~dppverify.lp.LP_TOLERANCE` (a disagreement is an ``error``: the checker's two routes
contradict each other, which is not the profile's fault).
"""

from __future__ import annotations

from collections.abc import Mapping
from fractions import Fraction

import numpy as np

from dppverify.best_response import (
    attacker_best_response_lp,
    defender_best_response,
    defender_best_response_lp,
    leaf_totals,
    objective_vector,
    payoff_on_tree,
)
from dppverify.certificate import CheckRecord, Status
from dppverify.context import Context
from dppverify.defender import sigma_along
from dppverify.evaluation import Values, evaluate, walk_cost
from dppverify.exact import Number
from dppverify.lp import LP_TOLERANCE, lp_agrees
from dppverify.numbers import EXACT, NumberMode
from dppverify.profile import ProgressRule
from dppverify.text import show, show_walk
from dppverify.value_lp import exact_bracket, solve_value_lp

__all__ = ["NOT_WELLFORMED", "attacker_br", "belief_consistency", "defender_br",
           "phases", "phases_of", "profile_values", "sequential_rationality", "value_check",
           "values", "wellformed"]

NOT_WELLFORMED = "not evaluated: the profile is not well-formed (see profile.wellformed)"
HALF = Fraction(1, 2)


def _skip(check_id: str, proof: str | None = None,
          numbers: Mapping[str, Number | None] | None = None) -> CheckRecord:
    return CheckRecord(check_id, "skipped", NOT_WELLFORMED, numbers or {}, proof)


def wellformed(ctx: Context) -> CheckRecord:
    """``profile.wellformed``: the document describes a profile of this game.

    Parameters
    ----------
    ctx : Context
        The shared inputs (:func:`~dppverify.context.make_context`).

    Returns
    -------
    CheckRecord

    Examples
    --------
    The triangle's equilibrium (see :mod:`dppverify.examples`), then a primary mixture whose
    probabilities do not sum to 1:

    >>> from dppverify.examples import triangle_attacker, triangle_context as context
    >>> eq = triangle_attacker()
    >>> wellformed(context(eq)).message
    "well-formed: 2 primary and 1 secondary walk(s), primary goal 'g1'"
    >>> bad = dict(eq, primary=[{"path": ["s", "g1"], "probability": "1/7"},
    ...                         {"path": ["s", "g2"], "probability": "3/7"}])
    >>> r = wellformed(context(bad))
    >>> r.status, r.message
    ('fail', 'attacker.primary: probabilities sum to 4/7, not 1')
    """
    defects = [str(d) for d in ctx.profile.defects]
    if ctx.undefined:
        walk = show_walk(ctx.instance, ctx.tree.walk(ctx.undefined[0]))
        defects.append(f"defender: the table has no default and no entry for "
                       f"{len(ctx.undefined)} walk(s) of the H = {ctx.tree.horizon} tree, "
                       f"e.g. {walk}")
    numbers: dict[str, Number | None] = {"defects": len(defects),
                                         "primary_walks": len(ctx.profile.primary),
                                         "secondary_walks": len(ctx.profile.secondary)}
    if defects:
        shown = "; ".join(defects[:5])
        more = f"; and {len(defects) - 5} more" if len(defects) > 5 else ""
        return CheckRecord("profile.wellformed", "fail", shown + more, numbers)
    g1 = ctx.instance.nodes[ctx.roles.g1]
    return CheckRecord("profile.wellformed", "pass",
                       f"well-formed: {len(ctx.profile.primary)} primary and "
                       f"{len(ctx.profile.secondary)} secondary walk(s), primary goal {g1!r}",
                       numbers)


def profile_values(ctx: Context) -> Values:
    """Exact U¹, U², U, Ū, VoI of the (well-formed) profile, walk by walk.

    Parameters
    ----------
    ctx : Context
        The shared inputs (:func:`~dppverify.context.make_context`).

    Returns
    -------
    Values

    Examples
    --------
    >>> from dppverify.examples import triangle_attacker, triangle_context as context
    >>> eq = triangle_attacker()
    >>> profile_values(context(eq))
    Values(U1=3, U2=1, U=Fraction(12, 5), U_bar=Fraction(27, 10), VoI=Fraction(1, 9))
    """
    assert ctx.profile.defender is not None
    return evaluate(ctx.instance, ctx.roles, ctx.profile.defender, ctx.profile.primary,
                    ctx.profile.secondary)


def values(ctx: Context) -> list[CheckRecord]:
    """``value.U1``, ``value.U2``, ``value.U``, ``value.VoI``.

    Three routes must agree: walk by walk (exact), realization plans on the tree (exact),
    and the LP objective vectors at the profile's plans (float, within the LP tolerance);
    the profile's claimed numbers, when present, must equal the exact ones.

    Parameters
    ----------
    ctx : Context
        The shared inputs (:func:`~dppverify.context.make_context`).

    Returns
    -------
    list of CheckRecord
        The four records, in that order.

    Examples
    --------
    >>> from dppverify.examples import triangle_attacker, triangle_context as context
    >>> eq = triangle_attacker()
    >>> for r in values(context(eq)):
    ...     print(r.id, r.status, r.message)
    value.U1 pass U1 = 3, LP evaluation 3
    value.U2 pass U2 = 1, LP evaluation 1
    value.U pass U = 12/5, LP evaluation 2.4
    value.VoI pass U_bar = 27/10, VoI = 1/9
    >>> r = values(context(eq, value={"U": "5/2"}))[2]
    >>> r.status, r.message
    ('fail', 'U = 12/5 exactly, but the profile claims U = 5/2')
    """
    ids = ("value.U1", "value.U2", "value.U", "value.VoI")
    if not ctx.usable:
        return [_skip(i, "TEL") for i in ids]
    assert ctx.defender is not None and ctx.x1 is not None and ctx.x2 is not None
    v = profile_values(ctx)
    claims = ctx.profile.claimed_values
    tree, roles = ctx.tree, ctx.roles
    lp_u: dict[int, float] = {}
    for theta, x in ((1, ctx.x1), (2, ctx.x2)):
        vec = np.zeros(tree.n_prefixes)
        for p, prob in x.items():
            vec[p] = float(prob)
        lp_u[theta] = float(objective_vector(tree, roles, ctx.defender, theta) @ vec)
    lp_total = float(roles.b1) * lp_u[1] + float(roles.b2) * lp_u[2]
    tree_u = payoff_on_tree(tree, roles, ctx.defender, ctx.x1, ctx.x2)
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
    msg = f"U_bar = {show(v.U_bar)}, VoI = {show(v.VoI)}"
    if bad:
        msg += "; the profile claims " + ", ".join(f"{k} = {show(claims[k])}" for k in bad)
    out.append(CheckRecord("value.VoI", "fail" if bad else "pass", msg, numbers, "THM"))
    return out


def phases_of(schedule: list[Number], numbers: NumberMode = EXACT) -> tuple[int, int, int]:
    """``(t_I, t_II, T)`` of a σ*(g1) schedule along ξ² (eqs. (10)-(11), proofs/L5.md).

    Phase I is the maximal initial run of steps with σ* = 1; ``t_II`` is the last step with
    σ* > 0 (``t_I`` if there is none after it). In float mode "= 1" and "> 0" are decided
    within ``numbers``' tolerance.

    Examples
    --------
    >>> phases_of([1, 1, Fraction(1, 2), 0, 1, 0, 0])
    (2, 5, 7)
    >>> phases_of([0, 0]), phases_of([]), phases_of([1, 1])
    ((0, 0, 2), (0, 0, 0), (2, 2, 2))
    >>> from dppverify.numbers import FloatNumbers
    >>> phases_of([0.9999999999999998, 1e-17], FloatNumbers())
    (1, 1, 2)
    """
    T = len(schedule)
    t1 = 0
    while t1 < T and numbers.equal(schedule[t1], 1):
        t1 += 1
    positive = [t for t, s in enumerate(schedule, start=1) if numbers.less_than(0, s)]
    t2 = max([t1, *positive])
    return (t1, t2, T)


def phases(ctx: Context) -> CheckRecord:
    """``profile.phases``: the claimed ``t_I``, ``t_II``, ``T`` of ξ² match σ* along it.

    Parameters
    ----------
    ctx : Context
        The shared inputs (:func:`~dppverify.context.make_context`).

    Returns
    -------
    CheckRecord

    Examples
    --------
    On the triangle ξ² = ``s -> g2`` is all phase II (σ* = 1/2 on its one step):

    >>> from dppverify.examples import triangle_attacker, triangle_context as context
    >>> eq = triangle_attacker()
    >>> dict(phases(context(eq)).numbers)
    {'t_I': 0, 't_II': 1, 'T': 1}
    >>> r = phases(context(eq, phases={"t_I": 1, "t_II": 1, "T": 1}))
    >>> r.status, r.message
    ('fail', 't_I, t_II, T = (0, 1, 1) from σ* along ξ²; the profile claims (1, 1, 1)')
    """
    claim = ctx.profile.claimed_phases
    sec = [w for w in ctx.profile.secondary if w.probability > 0]
    if not ctx.profile.wellformed:
        return _skip("profile.phases", "L5")
    if len(sec) != 1:
        if claim is None:
            return CheckRecord("profile.phases", "pass", "no phases claimed (the secondary "
                               "mixes several walks)", {}, "L5")
        return CheckRecord("profile.phases", "fail", "phases are claimed but the secondary "
                           "type mixes several walks (phases are defined on one path ξ²)", {},
                           "L5")
    got = phases_of(sigma_along(ctx.instance, ctx.roles, ProgressRule(ctx.roles.g1), sec[0].walk),
                   ctx.numbers)
    numbers: dict[str, Number | None] = {"t_I": got[0], "t_II": got[1], "T": got[2]}
    if claim is None:
        return CheckRecord("profile.phases", "pass", f"no phases claimed; recomputed "
                           f"t_I = {got[0]}, t_II = {got[1]}, T = {got[2]}", numbers, "L5")
    ok = tuple(claim) == got
    return CheckRecord("profile.phases", "pass" if ok else "fail",
                       f"t_I, t_II, T = {got} from σ* along ξ²"
                       + ("" if ok else f"; the profile claims {tuple(claim)}"), numbers, "L5")


def attacker_br(ctx: Context, theta: int) -> CheckRecord:
    """``pbne.attacker_br.primary`` / ``.secondary``: type θ's exact regret is 0.

    The regret is ``U^θ(profile) − min over ALL walks of the tree`` against the profile's
    Defender (backward induction; a forward pass over the leaves and the sequence-form LP
    must agree with it).

    Parameters
    ----------
    ctx : Context
        The shared inputs (:func:`~dppverify.context.make_context`).
    theta : int
        1 (primary) or 2 (secondary).

    Returns
    -------
    CheckRecord

    Examples
    --------
    A secondary type that walks to g1 pays 2 where ``s -> g2`` costs it 1:

    >>> from dppverify.examples import triangle_attacker, triangle_context as context
    >>> eq = triangle_attacker()
    >>> r = attacker_br(context(eq), 2)
    >>> r.id, r.status, r.numbers["U2"], r.numbers["best_response"], r.numbers["regret"]
    ('pbne.attacker_br.secondary', 'pass', 1, 1, 0)
    >>> r = attacker_br(context(dict(eq, secondary=[{"path": ["s", "g1"], "probability": 1}])), 2)
    >>> r.status, r.numbers["regret"]
    ('fail', 1)
    """
    cid = "pbne.attacker_br." + ("primary" if theta == 1 else "secondary")
    proof = "L1" if theta == 1 else "XI2"
    if not ctx.usable:
        return _skip(cid, proof)
    assert ctx.defender is not None and ctx.profile.defender is not None
    inst, tree, roles = ctx.instance, ctx.tree, ctx.roles
    br = ctx.best_response(ctx.defender, theta)
    totals = leaf_totals(tree, roles, ctx.defender, theta)
    forward = min(totals[p] for p in tree.leaves().tolist())
    lp = attacker_best_response_lp(tree, roles, ctx.defender, theta)
    u = profile_values(ctx).U1 if theta == 1 else profile_values(ctx).U2
    regret = ctx.numbers.difference(u, br.value)
    numbers: dict[str, Number | None] = {f"U{theta}": u, "best_response": br.value,
                                         "best_response_lp": lp.value, "regret": regret,
                                         "walks": tree.n_leaves}
    where = f"over all {tree.n_leaves} walks with <= {tree.horizon} steps"
    if not ctx.numbers.equal(forward, br.value) or not lp_agrees(lp.value, br.value):
        return CheckRecord(cid, "error", f"backward induction {show(br.value)}, forward pass "
                           f"{show(forward)} and LP {show(lp.value)} disagree", numbers, proof)
    if ctx.numbers.equal(regret, 0):
        return CheckRecord(cid, "pass", f"regret 0: U{theta} = {show(u)} is the minimum {where} "
                           f"(LP {show(lp.value)})", numbers, proof)
    if regret < 0:
        return CheckRecord(cid, "error", f"U{theta} = {show(u)} is below the best response "
                           f"{show(br.value)}: inconsistent evaluation", numbers, proof)
    costs = [(walk_cost(inst, roles, ctx.profile.defender, w.walk, theta), w)
             for w in ctx.profile.walks(theta) if w.probability > 0]
    worst_cost, worst = max(costs, key=lambda cw: cw[0])
    return CheckRecord(cid, "fail", f"regret {show(regret)}: the walk {show_walk(inst, br.walk)} "
                       f"costs {show(br.value)} < U{theta} = {show(u)}; the profile's walk "
                       f"{show_walk(inst, worst.walk)} (probability {show(worst.probability)}) "
                       f"costs {show(worst_cost)}", numbers, proof)


def defender_br(ctx: Context) -> CheckRecord:
    """``pbne.defender_br``: the Defender's exact regret (greedy best response − U) is 0.

    Parameters
    ----------
    ctx : Context
        The shared inputs (:func:`~dppverify.context.make_context`).

    Returns
    -------
    CheckRecord

    Examples
    --------
    With the primary's probabilities swapped (3/7 to g1), allocating ``s -> g2`` to g1 gains
    the Defender 1/10:

    >>> from dppverify.examples import triangle_attacker, triangle_context as context
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
    if not ctx.usable:
        return _skip(cid, "L3")
    assert ctx.x1 is not None and ctx.x2 is not None and ctx.defender is not None
    tree, roles = ctx.tree, ctx.roles
    u = profile_values(ctx).U
    br = defender_best_response(tree, roles, ctx.x1, ctx.x2)
    lp, _ = defender_best_response_lp(tree, roles, ctx.x1, ctx.x2)
    regret = ctx.numbers.difference(br.value, u)
    numbers: dict[str, Number | None] = {"U": u, "best_response": br.value,
                                         "best_response_lp": lp.value, "regret": regret}
    if not lp_agrees(lp.value, br.value):
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
    for p in br.sigma1:
        v1 = roles.b1 * ctx.x1.get(p, Fraction(0))
        v2 = roles.b2 * ctx.x2.get(p, Fraction(0))
        s = ctx.defender.sigma1[p]
        gains.append((tree.weight[p] * (max(v1, v2) - (v1 * s + v2 * (1 - s))), p))
    gain, p = max(gains)
    walk = show_walk(ctx.instance, tree.walk(p))
    return CheckRecord(cid, "fail", f"regret {show(regret)}: the Defender gains by deviating, "
                       f"most ({show(gain)}) after the walk {walk}", numbers, "L3")


def _beliefs(ctx: Context) -> dict[int, Fraction]:
    """Closed-form Bayes beliefs ``b1 x1 / (b1 x1 + b2 x2)`` at every reached prefix."""
    assert ctx.x1 is not None and ctx.x2 is not None
    out = {}
    for p in set(ctx.x1) | set(ctx.x2):
        v1 = ctx.roles.b1 * ctx.x1.get(p, Fraction(0))
        v2 = ctx.roles.b2 * ctx.x2.get(p, Fraction(0))
        out[p] = v1 / (v1 + v2)
    return out


def sequential_rationality(ctx: Context) -> CheckRecord:
    """``pbne.sequential_rationality``: greedy w.r.t. the Bayes belief at every reached infoset.

    Lemma 3: allocate to g1 surely when ``b1_t > 1/2``, to g2 surely when ``b1_t < 1/2``;
    anything is rational at exactly 1/2.

    Parameters
    ----------
    ctx : Context
        The shared inputs (:func:`~dppverify.context.make_context`).

    Returns
    -------
    CheckRecord

    Examples
    --------
    In equilibrium the belief after ``s -> g2`` is exactly 1/2, so σ* = 1/2 is rational there;
    with the primary's probabilities swapped it is 4/7 and σ* is not greedy:

    >>> from dppverify.examples import triangle_attacker, triangle_context as context
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
    if not ctx.usable:
        return _skip(cid, "THM")
    assert ctx.defender is not None
    beliefs = _beliefs(ctx)
    bad = []
    half = 0
    mode = ctx.numbers
    for p in sorted(beliefs):
        if p == 0:
            continue
        b, s = beliefs[p], ctx.defender.sigma1[p]
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


def belief_consistency(ctx: Context) -> CheckRecord:
    """``pbne.belief_consistency``: beliefs follow Bayes' rule (eq. (2)) from the prior.

    The belief is propagated step by step with the behavioural probabilities
    ``γ_t(e_t | h_t, g^i) = x_i(child) / x_i(parent)`` and must equal the closed form
    ``b1 x1 / (b1 x1 + b2 x2)`` at every reached information set; the profile's stated prior
    (if any) must be the instance's. Off-path beliefs are unspecified (weak PBNE).

    Parameters
    ----------
    ctx : Context
        The shared inputs (:func:`~dppverify.context.make_context`).

    Returns
    -------
    CheckRecord

    Examples
    --------
    >>> from dppverify.examples import triangle_attacker, triangle_context as context
    >>> eq = triangle_attacker()
    >>> dict(belief_consistency(context(eq)).numbers)
    {'b1': Fraction(7, 10), 'b2': Fraction(3, 10), 'infosets': 2, 'mismatches': 0}
    >>> r = belief_consistency(context(eq, prior={"primary": "1/2", "secondary": "1/2"}))
    >>> r.status, r.message
    ('fail', "the profile states the prior (1/2, 1/2) but the instance's is (7/10, 3/10)")
    """
    cid = "pbne.belief_consistency"
    if not ctx.usable:
        return _skip(cid, "THM")
    assert ctx.x1 is not None and ctx.x2 is not None
    roles, tree = ctx.roles, ctx.tree
    claim = ctx.profile.claimed_prior
    numbers: dict[str, Number | None] = {"b1": roles.b1, "b2": roles.b2}
    if claim is not None and claim != (roles.b1, roles.b2):
        return CheckRecord(cid, "fail", f"the profile states the prior ({show(claim[0])}, "
                           f"{show(claim[1])}) but the instance's is ({show(roles.b1)}, "
                           f"{show(roles.b2)})", numbers, "THM")
    closed = _beliefs(ctx)
    recursive: dict[int, Fraction] = {0: roles.b1}
    parent = tree.parent
    mismatches = 0
    for p in sorted(closed):
        if p == 0:
            continue
        q = int(parent[p])
        b = recursive[q]
        g1 = ctx.x1.get(p, Fraction(0)) / ctx.x1[q] if ctx.x1.get(q) else Fraction(0)
        g2 = ctx.x2.get(p, Fraction(0)) / ctx.x2[q] if ctx.x2.get(q) else Fraction(0)
        num = b * g1
        den = num + (1 - b) * g2
        recursive[p] = num / den
        if recursive[p] != closed[p]:
            mismatches += 1
    numbers["infosets"] = len(closed) - 1
    numbers["mismatches"] = mismatches
    if mismatches:
        return CheckRecord(cid, "error", f"Bayes' rule step by step and the closed form "
                           f"disagree at {mismatches} information sets", numbers, "THM")
    return CheckRecord(cid, "pass", f"Bayes beliefs from the prior ({show(roles.b1)}, "
                       f"{show(roles.b2)}) at all {len(closed) - 1} reached information sets "
                       f"(step by step = closed form); off-path beliefs unspecified", numbers,
                       "THM")


def value_check(ctx: Context) -> CheckRecord:
    """``game.value``: ``V_H`` (compact LP, proofs/LP.md) equals ``U`` of the profile.

    Exact bounds: the profile's Defender gives ``b1 min U¹ + b2 min U² <= V_H`` and its
    Attacker gives ``V_H <= max_σ U``; with both regrets 0 they meet at ``U``, so ``V_H = U``
    exactly. The LP value must lie within the exact bracket (within the LP tolerance).

    Parameters
    ----------
    ctx : Context
        The shared inputs (:func:`~dppverify.context.make_context`).

    Returns
    -------
    CheckRecord

    Examples
    --------
    A secondary type walking to g1 makes ``U = 27/10``, not the value ``V_1 = 12/5``:

    >>> from dppverify.examples import triangle_attacker, triangle_context as context
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
    if ctx.usable:
        assert ctx.defender is not None and ctx.x1 is not None and ctx.x2 is not None
        defenders.append(("the profile's Defender", ctx.defender))
        attackers.append(("the profile's Attacker", ctx.x1, ctx.x2))
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
    if not ctx.usable:
        return CheckRecord(cid, "skipped", f"{vh}; {NOT_WELLFORMED}", numbers, "LP")
    u = profile_values(ctx).U
    numbers["U"] = u
    exact_equal = ctx.numbers.equal(bracket.lower, u) and ctx.numbers.equal(bracket.upper, u)
    if exact_equal and lp_agrees(lp.value, u):
        return CheckRecord(cid, "pass", f"{vh} = U", numbers, "HORIZON")
    return CheckRecord(cid, "fail", f"U = {show(u)} is not the value of the truncated game: {vh}",
                       numbers, "HORIZON")


def _slack(x: Number) -> float:
    return LP_TOLERANCE * max(1.0, abs(float(x)))
