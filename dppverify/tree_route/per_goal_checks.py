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

from collections.abc import Mapping
from dataclasses import dataclass
from fractions import Fraction
from functools import cached_property
from typing import cast

from dppio.text import count, decimal
from dppverify.certificate import CheckRecord, Status
from dppverify.errors import HorizonError, LPError
from dppverify.exact import Number, normalize
from dppverify.game.instance import Instance
from dppverify.game.profile import GoalTable, GuaranteeRule, Profile
from dppverify.structured.proved_value import nvalue
from dppverify.tree_route.best_response import (
    attacker_best_response,
    beliefs,
    defender_best_response,
    payoff_on_tree,
)
from dppverify.tree_route.bracket import Bracket
from dppverify.tree_route.players import DefenderOnTree, defender_from_table
from dppverify.tree_route.tree import WalkTree, build_tree
from dppverify.tree_route.value_lp import (
    ValueLP,
    exact_bracket,
    solve_value_lp,
    structured_agrees,
)

__all__ = ["NOT_WELL_FORMED", "PerGoalTree", "payoff_of_type", "per_goal_tree"]

PROOF = "NGOAL"
NOT_WELL_FORMED = "the profile is not well formed"
"""The message of every per-goal tree check after an ill-formed profile."""


@dataclass(frozen=True, eq=False)
class PerGoalTree:
    """A per-goal profile on the walk tree: what its checks share, each part computed once.

    Attributes
    ----------
    instance, profile, tree
        The game, the profile, the walk tree (at ``max(H, hops to the nearest goal)``).
    defender : DefenderOnTree or None
        The profile's Defender on every prefix; None when the profile is not well formed.
    problems : tuple of str
        What makes it ill-formed (its defects, a prefix the Defender leaves undefined).
    """

    instance: Instance
    profile: Profile
    tree: WalkTree
    defender: DefenderOnTree | None
    problems: tuple[str, ...]

    @property
    def wellformed(self) -> bool:
        """True when the checks about the profile can run."""
        return self.defender is not None

    @property
    def tdef(self) -> DefenderOnTree:
        """The profile's Defender (a well-formed profile only)."""
        assert self.defender is not None  # the runners call the profile's checks only then
        return self.defender

    @cached_property
    def plans(self) -> dict[int, dict[int, Fraction]]:
        """Every type's realization plan, by goal index."""
        return dict(enumerate(_plans(self.tree, self.profile)))

    @cached_property
    def per_type(self) -> list[Number]:
        """Every type's payoff ``U^θ``."""
        return [payoff_of_type(self.tree, self.tdef, self.plans[t], t)
                for t in range(self.instance.n_goals)]

    @cached_property
    def u(self) -> Number:
        """``U`` on the tree."""
        return payoff_on_tree(self.tree, self.instance, self.tdef, self.plans)

    @cached_property
    def value(self) -> tuple[ValueLP, Bracket] | str:
        """The tree's LP and the exact bracket of ``V_H``, or why the LP failed."""
        try:
            lp = solve_value_lp(self.tree, self.instance)
            return lp, exact_bracket(self.tree, self.instance, lp,
                                     defenders=[("the profile's Defender", self.tdef)],
                                     attackers=[("the profile's Attacker", self.plans)])
        except LPError as exc:
            return str(exc)


def per_goal_tree(inst: Instance, prof: Profile, h: int, max_prefixes: int) -> PerGoalTree:
    """The per-goal checks' shared inputs on the walk tree of ``max(h, hops)`` steps.

    Examples
    --------
    >>> from dppverify.game.examples import star3, star3_profile
    >>> from dppverify.game.profile import profile_from_json
    >>> ctx = per_goal_tree(star3(), profile_from_json(star3_profile(), star3()), 2, 1000)
    >>> ctx.tree.n_prefixes, ctx.wellformed, ctx.u, [r.status for r in value_records(ctx)]
    (6, True, Fraction(3, 2), ['pass', 'pass'])
    """
    tree = build_tree(inst, max(h, inst.hops[inst.start]), max_prefixes=max_prefixes)
    tdef = None if prof.defects else _defender(tree, prof)
    problems = [str(d) for d in prof.defects] + ([tdef] if isinstance(tdef, str) else [])
    return PerGoalTree(inst, prof, tree, None if problems else cast(DefenderOnTree, tdef),
                       tuple(problems))


def wellformed_record(ctx: PerGoalTree) -> CheckRecord:
    """``profile.wellformed``: the profile's defects, or its Defender on every prefix."""
    if ctx.problems:
        more = f" (and {len(ctx.problems) - 1} more)" if len(ctx.problems) > 1 else ""
        return CheckRecord("profile.wellformed", "fail", ctx.problems[0] + more)
    return CheckRecord("profile.wellformed", "pass",
                       f"{ctx.instance.n_goals} types, {sum(map(len, ctx.profile.attacker))} "
                       f"walks, Defender defined on all {ctx.tree.n_prefixes - 1} prefixes")


def payoff_record(ctx: PerGoalTree) -> CheckRecord:
    """``value.U``: every type's payoff and ``U``, against the profile's claim."""
    nums: dict[str, Number | None] = {f"U{t + 1}": x for t, x in enumerate(ctx.per_type)}
    nums["U"] = u = ctx.u
    claimed = ctx.profile.claimed_u
    said = "" if claimed is None else f" (profile says {claimed})"
    return CheckRecord("value.U", "pass" if claimed is None or claimed == u else "fail",
                       f"U = {u}{said}", nums, PROOF)


def attacker_record(ctx: PerGoalTree) -> CheckRecord:
    """``pbne.attacker_br``: every type's exact regret over all walks of the tree."""
    inst = ctx.instance
    regrets = []
    for t in range(inst.n_goals):
        br = attacker_best_response(ctx.tree, inst, ctx.tdef, t)
        regrets.append((normalize(ctx.per_type[t] - br.value), t, br))
    worst = max(regrets, key=lambda r: r[0])
    ok = all(r[0] == 0 for r in regrets)
    msg = ("every type's exact regret is 0" if ok else
           f"type {worst[1] + 1} (goal {inst.nodes[inst.goals[worst[1]]]!r}) has regret "
           f"{worst[0]}: walk {list(inst.labels(worst[2].walk))} costs {worst[2].value}")
    return CheckRecord("pbne.attacker_br", "pass" if ok else "fail", msg,
                       {f"regret{t + 1}": r for r, t, _ in sorted(regrets, key=lambda r: r[1])},
                       PROOF)


def defender_record(ctx: PerGoalTree) -> CheckRecord:
    """``pbne.defender_br``: the Defender's exact regret against the greedy best response."""
    dbr = defender_best_response(ctx.tree, ctx.instance, ctx.plans)
    u = ctx.u
    reg = normalize(dbr.value - u)
    return CheckRecord("pbne.defender_br", "pass" if reg == 0 else "fail",
                       "Defender regret 0" if reg == 0 else
                       f"Defender regret {reg}: greedy best response {dbr.value}, profile {u}",
                       {"regret": reg, "greedy": dbr.value}, PROOF)


def sequential_record(ctx: PerGoalTree) -> CheckRecord:
    """``pbne.sequential_rationality``: mass only on goals of maximal Bayes belief."""
    inst, tdef = ctx.instance, ctx.tdef
    mu = beliefs(ctx.tree, inst, ctx.plans)
    bad = []
    for p, belief in mu.items():
        if p == 0:
            continue
        top = max(belief)
        if any(q > 0 and belief[t] < top for t, q in enumerate(tdef.sigma[p])):
            bad.append(p)
    msg = (f"greedy on the Bayes belief at all {len(mu) - 1} reached information sets" if not bad
           else f"{count(len(bad), 'reached information set')} where the Defender guards a goal of "
                f"less than maximal belief, e.g. after "
                f"{list(inst.labels(ctx.tree.walk(bad[0])))}: belief "
                f"{[str(b) for b in mu[bad[0]]]}, Defender {[str(s) for s in tdef.sigma[bad[0]]]}")
    return CheckRecord("pbne.sequential_rationality", "fail" if bad else "pass", msg,
                       {"infosets": len(mu) - 1}, PROOF)


def value_records(ctx: PerGoalTree) -> list[CheckRecord]:
    """``game.value`` (the tree's ``V_H`` against ``U``) and ``game.value.structured`` (the
    structured value against the tree's: a disagreement is an ``error``, a bug to keep)."""
    if isinstance(ctx.value, str):
        return [CheckRecord("game.value", "error", ctx.value),
                CheckRecord("game.value.structured", "skipped", "no tree value")]
    lp, bracket = ctx.value
    u = ctx.u
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
    return [CheckRecord("game.value", status, msg, vnums, PROOF),
            _structured_record(ctx, lp, bracket)]


def _structured_record(ctx: PerGoalTree, lp: ValueLP, bracket: Bracket) -> CheckRecord:
    try:
        sv = nvalue(ctx.instance, ctx.tree.horizon)
    except (ValueError, HorizonError) as exc:
        return CheckRecord("game.value.structured", "skipped", str(exc))
    agree = structured_agrees(bracket, lp.stats, sv)
    said = (f"structured V_H = {sv.value} ({sv.upper_source})" if sv.value is not None else
            f"structured bracket [{sv.lower}, {sv.upper}]")
    return CheckRecord(
        "game.value.structured", "pass" if agree else "error",
        f"{said} agrees with the tree route" if agree else
        f"{said} disagrees with the tree route [{bracket.lower}, {bracket.upper}] "
        f"(LP {decimal(lp.value)}): a bug — please keep this instance",
        {"V_H_structured_lower": sv.lower, "V_H_structured_upper": sv.upper}, PROOF)


def _plans(tree: WalkTree, profile: Profile) -> list[dict[int, Fraction]]:
    """Each type's realization plan, one step down the tree per step of a walk."""
    plans = []
    for mix in profile.attacker:
        x: dict[int, Fraction] = {0: Fraction(1)}
        for mw in mix:
            p = 0
            for v in mw.walk[1:]:
                lo, hi = int(tree.child_start[p]), int(tree.child_stop[p])
                p = lo + int((tree.node[lo:hi] == v).argmax())
                assert tree.node[p] == v  # the horizon covers every listed walk
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
