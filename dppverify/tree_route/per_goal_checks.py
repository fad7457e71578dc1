"""The tree route's checks of a per-goal profile (``dpp-ngoal-profile/1``, any N) on the walk tree.

Run by :func:`dppverify.certify` for a per-goal profile when the route is ``tree`` or ``both``
(the route is chosen in :func:`dppverify.routes.resolve_route`). Checks, in order (ids in
``dppverify/checks.md``, "N goals"):

``profile.wellformed``
    The profile parses, every walk is a walk of the game, probabilities sum to exactly 1, and
    the Defender's table gives a distribution at every prefix of the walk tree.
``value.U``
    ``U = Σ_θ b_θ U^θ`` exactly (each type's expected stage costs plus terminal costs); equal
    to the profile's ``value.U`` when it states one.
``pbne.attacker_br``
    Every type's exact regret is 0: its cost equals the minimum over ALL walks of the tree
    against the profile's Defender (exact backward induction).
``pbne.defender_br``
    The Defender's exact regret is 0: the profile's payoff equals the greedy best response's.
``pbne.sequential_rationality``
    At every information set reached with positive probability the Defender's distribution
    puts mass only on goals of maximal Bayes belief ``μ(θ | p) ∝ b_θ x_θ(p)`` (off the path
    of play any distribution is rational for some belief: the one uniform on its support).
``game.value``
    The tree route's ``V_H`` (compact LP, exact bracket, with the profile's strategies among
    the candidates) equals ``U``.
``game.value.structured``
    The structured route's ``V_H`` (:func:`dppverify.structured.proved_value.nvalue`: exact where
    proved, else an exact bracket) agrees with the tree route: the brackets overlap and an
    exact structured value lies in the tree's bracket; a disagreement is an ``error`` (a bug
    to keep), not a refutation.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from fractions import Fraction
from typing import cast

from dppio.text import decimal
from dppverify.certificate import CheckRecord, Status
from dppverify.errors import HorizonError, LPError
from dppverify.exact import Number, normalize
from dppverify.game.instance import Instance
from dppverify.game.profile import GoalTable, GuaranteeRule, Profile
from dppverify.registry import check_ids
from dppverify.structured.proved_value import nvalue
from dppverify.tree_route.best_response import (
    attacker_best_response,
    beliefs,
    defender_best_response,
    payoff_on_tree,
)
from dppverify.tree_route.lp import LP_TOLERANCE, lp_agrees
from dppverify.tree_route.players import DefenderOnTree, defender_from_table
from dppverify.tree_route.tree import WalkTree, build_tree
from dppverify.tree_route.value_lp import exact_bracket, solve_value_lp

__all__ = ["payoff_of_type", "per_goal_tree_checks"]

_IDS = check_ids("per-goal")

PROOF = "NGOAL"


def _skipped(ids: tuple[str, ...], why: str) -> list[CheckRecord]:
    return [CheckRecord(i, "skipped", why) for i in ids]


def _plans(tree: WalkTree, profile: Profile) -> list[dict[int, Fraction]]:
    plans = []
    for mix in profile.attacker:
        x: dict[int, Fraction] = {0: Fraction(1)}
        for mw in mix:
            for k in range(1, len(mw.walk)):
                p = tree.find(mw.walk[:k + 1])
                assert p is not None  # the horizon covers every listed walk
                x[p] = x.get(p, Fraction(0)) + mw.probability
        plans.append(x)
    return plans


def _defender(tree: WalkTree, profile: Profile) -> DefenderOnTree | str:
    rule = profile.defender
    if rule is not None and rule.kind == "guarantee":  # evaluated on every prefix of the tree
        from dppverify.structured.guarantee import guarantee_sets, rule_on_trie

        g = cast(GuaranteeRule, rule)
        sets = guarantee_sets(tree.instance, g.normals)
        sigma, _ = rule_on_trie(tree.instance, g, sets, tree.parent.tolist(),
                                tree.node.tolist())
        return defender_from_table(tree, sigma, None)
    rule = cast(GoalTable, rule)  # well formed: a table, or the guarantee rule
    table: dict[int, tuple[Fraction, ...]] = {}
    for walk, dist in rule.entries.items():
        p = tree.find(walk)
        if p is not None:
            table[p] = dist
    try:
        return defender_from_table(tree, table, rule.default)
    except KeyError as exc:
        labels = tree.instance.labels(tree.walk(int(exc.args[0])))
        return f"the Defender's table has no entry for walk {list(labels)} and no default"


def per_goal_tree_checks(inst: Instance, prof: Profile, h: int,
                      max_prefixes: int) -> tuple[list[CheckRecord], WalkTree]:
    """The tree route's records of an N-goal profile on the walk tree of ``h`` steps.

    The tree is built at ``max(h, hops to the nearest goal)``; the records are
    the per-goal family's ids, in registry order, tagged with the tree route.

    Examples
    --------
    >>> from dppverify.game.examples import star3, star3_profile
    >>> from dppverify.game.profile import profile_from_json
    >>> checks, tree = per_goal_tree_checks(star3(), profile_from_json(star3_profile(), star3()),
    ...                                  2, 1000)
    >>> [c.status for c in checks], tree.n_prefixes
    (['pass', 'pass', 'pass', 'pass', 'pass', 'pass', 'pass'], 6)
    """
    tree = build_tree(inst, max(h, inst.hops[inst.start]), max_prefixes=max_prefixes)
    checks: list[CheckRecord] = []
    tdef = None if prof.defects else _defender(tree, prof)
    problems = [str(d) for d in prof.defects] + ([tdef] if isinstance(tdef, str) else [])
    if problems:
        more = f" (and {len(problems) - 1} more)" if len(problems) > 1 else ""
        checks.append(CheckRecord("profile.wellformed", "fail", problems[0] + more))
        checks += _skipped(_IDS[1:], "the profile is not well formed")
        return _tagged(checks), tree
    assert isinstance(tdef, DefenderOnTree)
    checks.append(CheckRecord("profile.wellformed", "pass",
                              f"{inst.n_goals} types, {sum(map(len, prof.attacker))} walks, "
                              f"Defender defined on all {tree.n_prefixes - 1} prefixes"))
    plans = _plans(tree, prof)
    u = payoff_on_tree(tree, inst, tdef, dict(enumerate(plans)))
    per_type = [payoff_of_type(tree, tdef, plans[t], t) for t in range(inst.n_goals)]
    nums: dict[str, Number | None] = {f"U{t + 1}": per_type[t] for t in range(inst.n_goals)}
    nums["U"] = u
    ok = prof.claimed_u is None or prof.claimed_u == u
    said = "" if prof.claimed_u is None else f" (profile says {prof.claimed_u})"
    checks.append(CheckRecord("value.U", "pass" if ok else "fail", f"U = {u}{said}", nums,
                              PROOF))
    regrets = []
    for t in range(inst.n_goals):
        br = attacker_best_response(tree, inst, tdef, t)
        regrets.append((normalize(per_type[t] - br.value), t, br))
    worst = max(regrets, key=lambda r: r[0])
    ok = all(r[0] == 0 for r in regrets)
    msg = ("every type's exact regret is 0" if ok else
           f"type {worst[1] + 1} (goal {inst.nodes[inst.goals[worst[1]]]!r}) has regret "
           f"{worst[0]}: walk {list(inst.labels(worst[2].walk))} costs {worst[2].value}")
    checks.append(CheckRecord("pbne.attacker_br", "pass" if ok else "fail", msg,
                              {f"regret{t + 1}": r for r, t, _ in sorted(regrets,
                                                                          key=lambda r: r[1])},
                              PROOF))
    dbr = defender_best_response(tree, inst, dict(enumerate(plans)))
    reg = normalize(dbr.value - u)
    checks.append(CheckRecord("pbne.defender_br", "pass" if reg == 0 else "fail",
                              "Defender regret 0" if reg == 0 else
                              f"Defender regret {reg}: greedy best response {dbr.value}, "
                              f"profile {u}", {"regret": reg, "greedy": dbr.value}, PROOF))
    mu = beliefs(tree, inst, dict(enumerate(plans)))
    bad = []
    for p, belief in mu.items():
        if p == 0:
            continue
        top = max(belief)
        if any(q > 0 and belief[t] < top for t, q in enumerate(tdef.sigma[p])):
            bad.append(p)
    msg = (f"greedy on the Bayes belief at all {len(mu) - 1} reached information sets" if not bad
           else f"{len(bad)} reached information set(s) where the Defender guards a goal of "
                f"less than maximal belief, e.g. after {list(inst.labels(tree.walk(bad[0])))}: "
                f"belief {[str(b) for b in mu[bad[0]]]}, "
                f"Defender {[str(s) for s in tdef.sigma[bad[0]]]}")
    checks.append(CheckRecord("pbne.sequential_rationality", "fail" if bad else "pass", msg,
                              {"infosets": len(mu) - 1}, PROOF))
    try:
        lp = solve_value_lp(tree, inst)
        bracket = exact_bracket(tree, inst, lp, defenders=[("the profile's Defender", tdef)],
                                attackers=[("the profile's Attacker", dict(enumerate(plans)))])
    except LPError as exc:
        checks.append(CheckRecord("game.value", "error", str(exc)))
        checks.append(CheckRecord("game.value.structured", "skipped", "no tree value"))
        return _tagged(checks), tree
    vnums: dict[str, Number | None] = {"V_H_lower": bracket.lower, "V_H_upper": bracket.upper,
                                       "V_H_lp": lp.value, "U": u}
    status: Status
    if bracket.closed and bracket.exact == u:
        status, msg = "pass", f"V_H = {bracket.exact} = U (LP {decimal(lp.value)})"
    elif bracket.lower > u or bracket.upper < u:
        status, msg = "fail", f"V_H in [{bracket.lower}, {bracket.upper}] excludes U = {u}"
    else:
        status, msg = "error", (f"V_H in [{bracket.lower}, {bracket.upper}] not closed "
                                f"exactly; U = {u}")
    checks.append(CheckRecord("game.value", status, msg, vnums, PROOF))
    try:
        sv = nvalue(inst, tree.horizon)
    except (ValueError, HorizonError) as exc:
        checks.append(CheckRecord("game.value.structured", "skipped", str(exc)))
        return _tagged(checks), tree
    overlap = sv.lower <= bracket.upper and bracket.lower <= sv.upper
    agree = overlap and (sv.value is None or (bracket.lower <= sv.value <= bracket.upper
                                              and lp_agrees(lp.stats, sv.value, LP_TOLERANCE)))
    said = (f"structured V_H = {sv.value} ({sv.upper_source})" if sv.value is not None else
            f"structured bracket [{sv.lower}, {sv.upper}]")
    checks.append(CheckRecord(
        "game.value.structured", "pass" if agree else "error",
        f"{said} agrees with the tree route" if agree else
        f"{said} disagrees with the tree route [{bracket.lower}, {bracket.upper}] "
        f"(LP {decimal(lp.value)}): a bug — please keep this instance",
        {"V_H_structured_lower": sv.lower, "V_H_structured_upper": sv.upper}, PROOF))
    return _tagged(checks), tree


def payoff_of_type(tree: WalkTree, tdef: DefenderOnTree, plan: Mapping[int, Fraction],
                   theta: int) -> Number:
    """Type ``θ``'s expected cost ``U^θ`` under its plan (stage costs plus terminal cost).

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> t = build_tree(star3(), 1)
    >>> d = defender_from_table(t, {}, (Fraction(1), Fraction(0), Fraction(0)))
    >>> [payoff_of_type(t, d, {0: Fraction(1), 1: Fraction(1)}, th) for th in range(3)]
    [2, 2, 2]
    """
    inst = tree.instance
    leaf = tree.is_leaf_mask()
    a = tdef.alloc(theta)
    d = inst.dist_to[theta]
    total: Number = 0
    for p, prob in plan.items():
        if p:
            total += prob * a[p]
        if leaf[p]:
            total += prob * d[int(tree.node[p])]
    return normalize(total)


def _tagged(checks: list[CheckRecord]) -> list[CheckRecord]:
    return [dataclasses.replace(r, route="tree", relies_on=r.relies_on or _TREE) for r in checks]


_TREE = "the walk tree of H steps"
