"""Certify an N-goal profile as a weak PBNE of the N-goal game, exactly, by route.

Routes (as for two goals, ``docs/checker.md`` "Routes"): ``tree`` — the truncated game's walk
tree at ``H`` (below); ``structured`` — no walk tree, the game of ANY length
(:mod:`dppverify.ngoal.structured`, proofs/NWALKBR.md; the Defender needs a ``default``);
``auto`` — the tree when it fits ``max_prefixes``, else structured; ``both`` — both, and a
check whose statuses differ becomes an ``error`` record.

Tree route checks, in order (ids in ``dppverify/checks.md``, "N goals"):

``ngoal.profile.wellformed``
    The profile parses, every walk is a walk of the game, probabilities sum to exactly 1, and
    the Defender's table gives a distribution at every prefix of the walk tree.
``ngoal.value.U``
    ``U = Σ_θ b_θ U^θ`` exactly (each type's expected stage costs plus terminal costs); equal
    to the profile's ``value.U`` when it states one.
``ngoal.pbne.attacker_br``
    Every type's exact regret is 0: its cost equals the minimum over ALL walks of the tree
    against the profile's Defender (exact backward induction).
``ngoal.pbne.defender_br``
    The Defender's exact regret is 0: the profile's payoff equals the greedy best response's.
``ngoal.pbne.sequential``
    At every information set reached with positive probability the Defender's distribution
    puts mass only on goals of maximal Bayes belief ``μ(θ | p) ∝ b_θ x_θ(p)`` (off the path of
    play any distribution is rational for some belief: the one uniform on its support).
``ngoal.value.V_H``
    The tree route's ``V_H`` (compact LP, exact bracket, with the profile's strategies among
    the candidates) equals ``U``.
``ngoal.value.structured``
    The structured route's ``V_H`` (:func:`dppverify.ngoal.proved_value.nvalue`: exact where
    proved, else an exact bracket) agrees with the tree route: the brackets overlap and an
    exact structured value lies in the tree's bracket; a disagreement is an ``error`` (a bug
    to keep), not a refutation.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from fractions import Fraction
from pathlib import Path
from typing import Any, Literal

from dppverify.certificate import Certificate, CheckRecord, Status, merge_routes
from dppverify.errors import HorizonError, LPError, UndecidedError
from dppverify.exact import Number, normalize
from dppverify.horizons import parse_horizon
from dppverify.ngoal.instance import NInstance, load_ninstance, ninstance_from_json
from dppverify.ngoal.profile import NProfile, load_nprofile_document, nprofile_from_json
from dppverify.ngoal.proved_value import nvalue
from dppverify.ngoal.routes import ntree_fits
from dppverify.ngoal.structured import NSTRUCTURED_NOT_RUN, nstructured_checks
from dppverify.tree_route.best_response import (
    attacker_best_response,
    beliefs,
    defender_best_response,
    payoff_on_tree,
)
from dppverify.tree_route.lp import LP_SOLVER, LP_TOLERANCE, lp_agrees
from dppverify.tree_route.players import DefenderOnTree, defender_from_table
from dppverify.tree_route.tree import DEFAULT_MAX_PREFIXES, WalkTree, build_tree
from dppverify.tree_route.value_lp import exact_bracket, solve_value_lp

__all__ = ["NGOAL_CHECK_IDS", "NRoute", "certify_ngoal", "payoff_of_type"]

NRoute = Literal["auto", "tree", "structured", "both"]

NGOAL_CHECK_IDS = ("ngoal.profile.wellformed", "ngoal.value.U", "ngoal.pbne.attacker_br",
                   "ngoal.pbne.defender_br", "ngoal.pbne.sequential", "ngoal.value.V_H",
                   "ngoal.value.structured")
"""The N-goal certificate's check ids, in order."""

PROOF = "NGOAL"


def _skipped(ids: tuple[str, ...], why: str) -> list[CheckRecord]:
    return [CheckRecord(i, "skipped", why) for i in ids]


def _plans(tree: WalkTree, profile: NProfile) -> list[dict[int, Fraction]]:
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


def _defender(tree: WalkTree, profile: NProfile) -> DefenderOnTree | str:
    if profile.rule is not None:  # the guarantee rule, evaluated on every prefix of the tree
        from dppverify.ngoal.guarantee import guarantee_sets, rule_on_trie

        sets = guarantee_sets(tree.instance)
        sigma, _ = rule_on_trie(tree.instance, profile.rule, sets, tree.parent.tolist(),
                                tree.node.tolist())
        return defender_from_table(tree, sigma, None)
    table: dict[int, tuple[Fraction, ...]] = {}
    for walk, dist in profile.entries.items():
        p = tree.find(walk)
        if p is not None:
            table[p] = dist
    try:
        return defender_from_table(tree, table, profile.default)
    except KeyError as exc:
        labels = tree.instance.labels(tree.walk(int(exc.args[0])))
        return f"the Defender's table has no entry for walk {list(labels)} and no default"


def certify_ngoal(instance: NInstance | Mapping[str, Any] | str | Path,
                  profile: Mapping[str, Any] | str | Path, *,
                  horizon: int | Literal["inf"] | None = None,
                  max_prefixes: int = DEFAULT_MAX_PREFIXES, route: NRoute = "auto") -> Certificate:
    """Certify (or refute) an N-goal profile, on the walk tree of ``H`` steps or without it.

    Parameters
    ----------
    instance : NInstance, dict, or path
        The game.
    profile : dict or path
        A ``dpp-ngoal-profile/1`` document.
    horizon : int, "inf" or None
        None (default) or ``"inf"``: the untruncated game, by the structured route (the
        Defender needs a ``default`` unless its table lists every walk of the game; otherwise
        :class:`~dppverify.errors.UndecidedError`, exit 3). An integer ``H``: the game
        truncated at ``H``, an explicit request.
    max_prefixes : int
        Size guard of the walk tree.
    route : {"auto", "tree", "structured", "both"}
        ``tree``: the walk tree; ``structured``: best responses over all walks, the Defender
        on the profile's prefixes, the coalition DP (:mod:`dppverify.ngoal.structured`);
        ``auto``: the tree when it fits ``max_prefixes``, else structured; ``both``: both, a
        check whose statuses differ becomes an ``error`` (unless one route skipped it).

    Raises
    ------
    CheckerError
        Bad input (unreadable instance or profile, a horizon shorter than a listed walk, a
        tree above the size guard, the tree route with ``H = inf``);
        :class:`~dppverify.errors.UndecidedError` when the untruncated game cannot be
        decided (a table without default that leaves walks unlisted).

    Examples
    --------
    The hub profile is an equilibrium of the game truncated at H = 2 (an explicit request):

    >>> from dppverify.ngoal.examples import star3_document, star3_profile
    >>> cert = certify_ngoal(star3_document(), star3_profile(), horizon=2)
    >>> cert.verdict, cert.route, [c.status for c in cert.checks]
    ('pass', 'tree', ['pass', 'pass', 'pass', 'pass', 'pass', 'pass', 'pass'])
    >>> bad = star3_profile()
    >>> bad["defender"]["default"] = [0, 1, 0]   # guards b off the table: on s m and s m a
    >>> cert = certify_ngoal(star3_document(), bad, horizon=2)
    >>> cert.verdict, cert.check("ngoal.pbne.defender_br").message
    ('fail', 'Defender regret 2/3: greedy best response 3/2, profile 5/6')

    On the untruncated game (the default) type ``b`` may loop ``s m s m b`` where the default
    guards ``a``:

    >>> cert = certify_ngoal(star3_document(), star3_profile())
    >>> cert.route, cert.horizon, cert.check("ngoal.pbne.attacker_br").status
    ('structured', None, 'fail')
    """
    if isinstance(instance, NInstance):
        inst = instance
    elif isinstance(instance, str | Path):
        inst = load_ninstance(instance)
    else:
        inst = ninstance_from_json(instance)
    doc = (load_nprofile_document(profile) if isinstance(profile, str | Path)
           else dict(profile))
    prof = nprofile_from_json(inst, doc)
    if route not in ("auto", "tree", "structured", "both"):
        raise ValueError(f"unknown route {route!r}")
    asked = parse_horizon(horizon)
    if asked is not None and asked < prof.longest:
        raise HorizonError(f"the horizon H = {asked} is shorter than the profile's longest "
                           f"walk ({prof.longest} steps): give a horizon of at least "
                           f"{prof.longest}, or none for the untruncated game")
    chosen, h = _choose_route(inst, prof, asked, route, max_prefixes)
    tree_checks: list[CheckRecord] = []
    tree: WalkTree | None = None
    if chosen in ("tree", "both"):
        assert h is not None
        tree_checks, tree = _tree_checks(inst, prof, h, max_prefixes)
    checks = tree_checks
    trie_size = 0
    if chosen in ("structured", "both"):
        structured, trie_size = nstructured_checks(inst, prof, h)
        if h is None and prof.default is None and prof.rule is None:
            br = next((r for r in structured if r.id == "ngoal.pbne.attacker_br"), None)
            if br is not None and br.status == "error":  # undefined off the table: undecided
                raise UndecidedError(NTABLE_UNDECIDED)
        checks = structured if chosen == "structured" else merge_routes(tree_checks, structured)
    info = {"goals": inst.n_goals, "nodes": inst.n_nodes, "game": "N goals (dppverify.ngoal)"}
    if chosen != "tree":
        info["trie_prefixes"] = trie_size
    return Certificate(checks=tuple(checks), horizon=h if tree is None else tree.horizon,
                       exact=True, lp_solver=LP_SOLVER,
                       lp_tolerance=LP_TOLERANCE,
                       prefixes=0 if tree is None else tree.n_prefixes,
                       leaves=0 if tree is None else tree.n_leaves, info=info, route=chosen,
                       not_run=dict(NSTRUCTURED_NOT_RUN) if chosen == "structured" else {})


def _choose_route(inst: NInstance, prof: NProfile, horizon: int | None,
                  route: NRoute, max_prefixes: int
                  ) -> tuple[Literal["tree", "structured", "both"], int | None]:
    """The route(s) to run and the horizon (None: the untruncated game, the default)."""
    if horizon is None:
        if route in ("tree", "both"):
            raise HorizonError(f"--route {route} needs a finite horizon: the walk tree is the "
                               f"truncated game's (give --horizon H; without a horizon the "
                               f"untruncated game is certified by the structured route)")
        return "structured", None
    h = horizon
    if route == "auto":
        if ntree_fits(inst, max(h, inst.hops[inst.start]), max_prefixes):
            return "tree", h
        return "structured", h
    return route, h


NTABLE_UNDECIDED = (
    "the untruncated game (H = inf) cannot be decided for this profile: its Defender table has "
    "no \"default\" and does not list every walk of the game, so it is undefined on some; a "
    "\"default\" distribution would decide it, or --horizon H certifies the game truncated "
    "at H")
"""Why an N-goal table without default (that leaves walks unlisted) cannot be certified on
the untruncated game."""


def _tree_checks(inst: NInstance, prof: NProfile, h: int,
                 max_prefixes: int) -> tuple[list[CheckRecord], WalkTree]:
    """The tree route's records on the walk tree of ``h`` steps."""
    tree = build_tree(inst, max(h, inst.hops[inst.start]), max_prefixes=max_prefixes)
    checks: list[CheckRecord] = []
    tdef = None if prof.defects else _defender(tree, prof)
    problems = list(prof.defects) + ([tdef] if isinstance(tdef, str) else [])
    if problems:
        more = f" (and {len(problems) - 1} more)" if len(problems) > 1 else ""
        checks.append(CheckRecord("ngoal.profile.wellformed", "fail", problems[0] + more))
        checks += _skipped(NGOAL_CHECK_IDS[1:], "the profile is not well formed")
        return _tagged(checks), tree
    assert isinstance(tdef, DefenderOnTree)
    checks.append(CheckRecord("ngoal.profile.wellformed", "pass",
                              f"{inst.n_goals} types, {sum(map(len, prof.attacker))} walks, "
                              f"Defender defined on all {tree.n_prefixes - 1} prefixes"))
    plans = _plans(tree, prof)
    u = payoff_on_tree(tree, inst, tdef, dict(enumerate(plans)))
    per_type = [payoff_of_type(tree, tdef, plans[t], t) for t in range(inst.n_goals)]
    nums: dict[str, Number | None] = {f"U{t + 1}": per_type[t] for t in range(inst.n_goals)}
    nums["U"] = u
    ok = prof.claimed_u is None or prof.claimed_u == u
    said = "" if prof.claimed_u is None else f" (profile says {prof.claimed_u})"
    checks.append(CheckRecord("ngoal.value.U", "pass" if ok else "fail", f"U = {u}{said}", nums,
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
    checks.append(CheckRecord("ngoal.pbne.attacker_br", "pass" if ok else "fail", msg,
                              {f"regret{t + 1}": r for r, t, _ in sorted(regrets,
                                                                          key=lambda r: r[1])},
                              PROOF))
    dbr = defender_best_response(tree, inst, dict(enumerate(plans)))
    reg = normalize(dbr.value - u)
    checks.append(CheckRecord("ngoal.pbne.defender_br", "pass" if reg == 0 else "fail",
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
    checks.append(CheckRecord("ngoal.pbne.sequential", "fail" if bad else "pass", msg,
                              {"infosets": len(mu) - 1}, PROOF))
    try:
        lp = solve_value_lp(tree, inst)
        bracket = exact_bracket(tree, inst, lp, defenders=[("the profile's Defender", tdef)],
                                attackers=[("the profile's Attacker", dict(enumerate(plans)))])
    except LPError as exc:
        checks.append(CheckRecord("ngoal.value.V_H", "error", str(exc)))
        checks.append(CheckRecord("ngoal.value.structured", "skipped", "no tree value"))
        return _tagged(checks), tree
    vnums: dict[str, Number | None] = {"V_H_lower": bracket.lower, "V_H_upper": bracket.upper,
                                       "V_H_lp": lp.value, "U": u}
    status: Status
    if bracket.closed and bracket.exact == u:
        status, msg = "pass", f"V_H = {bracket.exact} = U (LP {lp.value:.10g})"
    elif bracket.lower > u or bracket.upper < u:
        status, msg = "fail", f"V_H in [{bracket.lower}, {bracket.upper}] excludes U = {u}"
    else:
        status, msg = "error", (f"V_H in [{bracket.lower}, {bracket.upper}] not closed "
                                f"exactly; U = {u}")
    checks.append(CheckRecord("ngoal.value.V_H", status, msg, vnums, PROOF))
    try:
        sv = nvalue(inst, tree.horizon)
    except (ValueError, HorizonError) as exc:
        checks.append(CheckRecord("ngoal.value.structured", "skipped", str(exc)))
        return _tagged(checks), tree
    overlap = sv.lower <= bracket.upper and bracket.lower <= sv.upper
    agree = overlap and (sv.value is None or (bracket.lower <= sv.value <= bracket.upper
                                              and lp_agrees(lp.value, sv.value, LP_TOLERANCE)))
    said = (f"structured V_H = {sv.value} ({sv.upper_source})" if sv.value is not None else
            f"structured bracket [{sv.lower}, {sv.upper}]")
    checks.append(CheckRecord(
        "ngoal.value.structured", "pass" if agree else "error",
        f"{said} agrees with the tree route" if agree else
        f"{said} disagrees with the tree route [{bracket.lower}, {bracket.upper}] "
        f"(LP {lp.value:.10g}): a bug — please keep this instance",
        {"V_H_structured_lower": sv.lower, "V_H_structured_upper": sv.upper}, PROOF))
    return _tagged(checks), tree


def payoff_of_type(tree: WalkTree, tdef: DefenderOnTree, plan: Mapping[int, Fraction],
                   theta: int) -> Number:
    """Type ``θ``'s expected cost ``U^θ`` under its plan (stage costs plus terminal cost).

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
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
