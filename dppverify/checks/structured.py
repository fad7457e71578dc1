"""The structured route's checks of a two-goal profile: the untruncated game, no walk tree.

For a two-goal profile whose Defender is a progress rule (σ* or the progress rule towards the
other goal) or a table with a ``default``: both Attacker types' exact regret over ALL walks of
any length (proofs/WALKBR.md, shortest paths only; for a table proofs/TABLEBR.md, the backward
induction of :mod:`dppverify.structured.table_br` on the table's trie plus an exact Dijkstra
off it); the Defender's exact regret (the greedy sums of
:mod:`dppverify.checks.structured_shared`, written once for N types), sequential rationality
and Bayes beliefs on the prefixes of the profile's own walks (the only information sets that
carry mass); payoffs walk by walk; the value by the three-field DP (proofs/DP.md); and, from
the two-goal layer :mod:`dppverify.checks.structured_twogoal`, the phases and the lemmas that
have a polynomial form. The lemma checks that need the tree (L3's and L4's random attackers
with their LPs) are not run here; the certificate says so.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from functools import cached_property
from typing import cast

from dppio.text import count
from dppverify.certificate import CheckRecord, Status
from dppverify.checks.skipped import NOT_WELLFORMED
from dppverify.checks.structured_shared import greedy_sums, mass_key
from dppverify.checks.structured_shared import structured_record as _rec
from dppverify.checks.structured_twogoal import (
    HALF,
    TRIE,
    WALKBR,
    l1_check,
    l2_check,
    l5_check,
    phases_check,
    telescoping_check,
    xi2_check,
)
from dppverify.exact import Number
from dppverify.game.arc_rows import ArcRows
from dppverify.game.defender import sigma_along
from dppverify.game.evaluation import Values, evaluate
from dppverify.game.instance import Instance, Roles
from dppverify.game.profile import DefenderRule, Profile
from dppverify.game.step_weights import step_weight
from dppverify.numbers import NumberMode
from dppverify.structured.table_br_twogoal import table_minima
from dppverify.structured.trie import WalkTrie, mass_trie
from dppverify.text import show, show_walk
from dppverify.twogoal.progress_br import WalkMinima, walk_minima
from dppverify.twogoal.value_dp import structured_value

__all__ = ["TwoGoalStructured"]


TABLEBR = "relies on proofs/TABLEBR.md (a table Defender with a default)"
DP = "relies on proofs/DP.md"


@dataclass(frozen=True, eq=False)
class TwoGoalStructured:
    """A two-goal profile on the structured route: what its checks share, each part computed
    once (the runners of :data:`dppverify.checks.runners.RUNNERS` read it in registry order).

    Attributes
    ----------
    instance, profile
        The game and the resolved profile.
    horizon : int or None
        ``H`` of the truncated game for ``game.value``; None for the untruncated game.

    Examples
    --------
    >>> from dppverify.game.examples import triangle, triangle_profile
    >>> from dppverify.game.profile import profile_from_json
    >>> inst = triangle()
    >>> ctx = TwoGoalStructured(inst, profile_from_json(triangle_profile(), inst), None)
    >>> ctx.usable, [r.status for r in values_records(ctx)], game_value_record(ctx).message
    (True, ['pass', 'pass', 'pass', 'pass'], 'V_H (H = inf) = 12/5 = U by the three-field DP \
(2 steps, int64)')
    """

    instance: Instance
    profile: Profile
    horizon: int | None

    @cached_property
    def roles(self) -> Roles:
        """The labelling the profile uses."""
        return self.instance.roles(self.profile.primary_goal_index)

    @property
    def mode(self) -> NumberMode:
        """The instance's number mode."""
        return self.instance.numbers

    @cached_property
    def missing(self) -> tuple[int, ...] | None:
        """A prefix of a profile walk that a table without default leaves undefined."""
        return _unlisted_profile_prefix(self.profile)

    @property
    def usable(self) -> bool:
        """True when the checks about the profile can run (a well-formed profile)."""
        return (self.profile.wellformed and self.missing is None
                and self.profile.defender is not None)

    @property
    def rule(self) -> DefenderRule:
        """The profile's Defender (the two-goal reader's rules only)."""
        return cast(DefenderRule, self.profile.defender)

    @cached_property
    def values(self) -> Values:
        """U¹, U², U, Ū and VoI walk by walk."""
        return evaluate(self.instance, self.roles, self.rule, self.profile.primary,
                        self.profile.secondary)

    @cached_property
    def trie(self) -> WalkTrie:
        """The trie of the profile's walks, with each type's realization masses."""
        return mass_trie([self.profile.primary, self.profile.secondary])

    @cached_property
    def sigma(self) -> list[Number | None]:
        """σ(g1 | p) at every prefix of the trie."""
        return _sigma_on_trie(self.instance, self.roles, self.rule, self.trie)

    @cached_property
    def payoffs(self) -> tuple[Number, Number]:
        """``max_σ U`` (greedy per prefix) and ``U`` at the profile's σ, on the trie."""
        return _defender_payoffs(self.instance, self.roles, self.trie, self.sigma)

    @cached_property
    def star(self) -> WalkMinima:
        """The minima over all walks against σ* (shared by the Attacker, L1 and XI2 checks)."""
        return walk_minima(self.instance, self.roles.g1)

    @cached_property
    def beliefs(self) -> dict[int, Fraction]:
        """The Bayes belief in the primary type at every reached prefix."""
        return _beliefs(self.roles, self.trie)


def wellformed_record(ctx: TwoGoalStructured) -> CheckRecord:
    """``profile.wellformed`` (also a walk the profile plays that a table leaves undefined)."""
    return _wellformed(ctx.instance, ctx.profile, ctx.roles, ctx.missing)


def values_records(ctx: TwoGoalStructured) -> list[CheckRecord]:
    """``value.U1``, ``value.U2``, ``value.U`` walk by walk (and on the trie), ``value.VoI``."""
    return _values(ctx.profile, ctx.values, ctx.payoffs[1], ctx.mode)


def phases_record(ctx: TwoGoalStructured) -> CheckRecord:
    """``profile.phases`` (the two-goal layer's)."""
    return phases_check(ctx.instance, ctx.profile, ctx.roles, ctx.mode)


def attacker_records(ctx: TwoGoalStructured) -> list[CheckRecord]:
    """Both types' regrets over all walks: against σ* (WALKBR) or a table (TABLEBR)."""
    rule, roles = ctx.rule, ctx.roles
    if not rule.table:  # σ*'s best responses (proofs/WALKBR.md), else a table's
        mins = ctx.star if rule.goal == roles.g1 else walk_minima(ctx.instance, rule.goal)
        same = roles.g1 == rule.goal
        best = {1: mins.same if same else mins.other, 2: mins.other if same else mins.same}
        relies = WALKBR
    else:
        tm = table_minima(ctx.instance, roles, rule)
        best = {1: tm.primary, 2: tm.secondary}
        relies = TABLEBR
    return _attacker(ctx.values, ctx.mode, best, relies, ctx.horizon)


def defender_record(ctx: TwoGoalStructured) -> CheckRecord:
    """``pbne.defender_br`` on the trie."""
    return _defender(ctx.values, ctx.payoffs[0], ctx.mode)


def sequential_record(ctx: TwoGoalStructured) -> CheckRecord:
    """``pbne.sequential_rationality`` at the reached prefixes."""
    return _sequential(ctx.instance, ctx.trie, ctx.sigma, ctx.beliefs, ctx.mode)


def belief_record(ctx: TwoGoalStructured) -> CheckRecord:
    """``pbne.belief_consistency``: Bayes' rule step by step against the closed form."""
    return _belief_consistency(ctx.instance, ctx.profile, ctx.roles, ctx.trie, ctx.beliefs)


def game_value_record(ctx: TwoGoalStructured) -> CheckRecord:
    """``game.value`` by the three-field DP."""
    return _game_value(ctx.instance, ctx.values, ctx.mode, ctx.horizon)


def telescoping_record(ctx: TwoGoalStructured) -> CheckRecord:
    """``lemma.TEL.telescoping`` on the trie."""
    return telescoping_check(ctx.instance, ctx.roles, ctx.trie, ctx.mode)


def l1_record(ctx: TwoGoalStructured) -> CheckRecord:
    """``lemma.L1.lower_bound``."""
    return l1_check(ctx.instance, ctx.roles, ctx.profile, ctx.mode, ctx.star)


def l2_record(ctx: TwoGoalStructured) -> CheckRecord:
    """``lemma.L2.no_revisits``."""
    return l2_check(ctx.instance, ctx.profile)


def xi2_record(ctx: TwoGoalStructured) -> CheckRecord:
    """``lemma.XI2.secondary_value`` (a fact of the instance: run for any profile)."""
    return xi2_check(ctx.instance, ctx.roles, ctx.mode, ctx.star)


def l5_record(ctx: TwoGoalStructured) -> CheckRecord:
    """``lemma.L5.induced_beliefs``."""
    return l5_check(ctx.instance, ctx.profile, ctx.roles, ctx.trie, ctx.beliefs, ctx.mode)


def skipped_record(check_id: str, proof: str | None = None) -> CheckRecord:
    """The record of a check about an ill-formed profile (the profile's checks skipped)."""
    return _rec(check_id, "skipped", NOT_WELLFORMED, None, proof, None)


def _unlisted_profile_prefix(profile: Profile) -> tuple[int, ...] | None:
    """The shortest prefix of a profile walk where a table Defender without default is
    undefined (None when there is none, or the Defender is not such a table)."""
    rule = profile.defender
    if rule is None or rule.defined_everywhere:
        return None
    best: tuple[int, ...] | None = None
    for mw in (*profile.primary, *profile.secondary):
        listed = rule.listed_along(mw.walk)
        t = next((t for t in range(1, len(mw.walk)) if t not in listed), None)
        if t is not None and (best is None or t + 1 < len(best)):
            best = mw.walk[:t + 1]
    return best


def _wellformed(instance: Instance, profile: Profile, roles: Roles,
                missing: tuple[int, ...] | None = None) -> CheckRecord:
    defects = [str(d) for d in profile.defects]
    if missing is not None:
        defects.append(f"the Defender's table has no entry for walk "
                       f"{show_walk(instance, missing)}, which the profile plays, and no "
                       f"default")
    numbers: dict[str, Number | None] = {"defects": len(defects),
                                         "primary_walks": len(profile.primary),
                                         "secondary_walks": len(profile.secondary)}
    if defects:
        more = f"; and {len(defects) - 5} more" if len(defects) > 5 else ""
        return _rec("profile.wellformed", "fail", "; ".join(defects[:5]) + more, numbers, None,
                    "the profile document alone")
    return _rec("profile.wellformed", "pass",
                f"well-formed: {count(len(profile.primary), 'primary walk')} and "
                f"{count(len(profile.secondary), 'secondary walk')}, primary goal "
                f"{instance.nodes[roles.g1]!r}", numbers, None,
                "the profile document alone")


def _sigma_on_trie(instance: Instance, roles: Roles, rule: DefenderRule,
                   trie: WalkTrie) -> list[Number | None]:
    """σ(g1 | p) at every prefix id of the trie (None at a root): along each walk once."""
    out: list[Number | None] = [None] * trie.size
    done = [False] * trie.size
    for along in sorted(trie.ids, key=len, reverse=True):  # longest first: O(total length)
        if len(along) > 1 and not done[along[-1]]:
            walk = [trie.node[i] for i in along]
            for t, sv in enumerate(sigma_along(instance, roles, rule, walk), start=1):
                out[along[t]] = sv
                done[along[t]] = True
    return out


def _defender_payoffs(instance: Instance, roles: Roles, trie: WalkTrie,
                      sigma: list[Number | None]) -> tuple[Number, Number]:
    """``max_σ U(σ, γ)`` (greedy per prefix) and ``U`` at the profile's σ, on the trie.

    Exact mode sums ``w`` and ``w σ`` per realization-mass pair (the prefixes of one walk
    share few of them) and multiplies by the masses once per pair: ``Σ_p w_p max(y1, y2)``
    and ``Σ_p w_p (σ_p y1 + (1 - σ_p) y2)`` regrouped, the same rationals exactly.
    """
    best: Number = 0
    at_sigma: Number = 0
    mode = instance.numbers
    steps = [i for i in range(trie.size) if trie.parent[i] >= 0]
    weights = _last_step_weights(instance, trie, steps)
    weight_of = dict(zip(steps, weights, strict=True))
    if mode.exact:
        rows = []
        for i in steps:
            si = sigma[i]
            assert si is not None  # every non-root prefix lies on a walk (_sigma_on_trie)
            rows.append((si, 1 - si))
        best, at_sigma = greedy_sums(trie.masses, (roles.b1, roles.b2),
                                     zip(steps, weights, rows, strict=True))
    for i in range(trie.size):  # float mode: the order of the sums as before
        last = trie.node[i]
        on_step = trie.parent[i] >= 0 and not mode.exact
        if not (on_step or instance.is_goal(last)):
            continue
        x1, x2 = trie.masses[i]
        y1, y2 = roles.b1 * x1, roles.b2 * x2
        if on_step:
            w = weight_of[i]
            s = sigma[i]
            assert s is not None
            best += float(w) * float(max(y1, y2))
            at_sigma += float(w) * (float(s) * float(y1) + (1 - float(s)) * float(y2))
        if instance.is_goal(last):
            term = y1 * roles.d1[last] + y2 * roles.d2[last]
            best += mode.convert(term)
            at_sigma += mode.convert(term)
    return mode.convert(best), mode.convert(at_sigma)


def _last_step_weights(instance: Instance, trie: WalkTrie, ids: list[int]) -> list[Number]:
    """The weight of the last step of each prefix id (not a root), in one pass."""
    tails = [trie.node[trie.parent[i]] for i in ids]
    heads = [trie.node[i] for i in ids]
    if isinstance(instance.succ, ArcRows):
        found = instance.succ.find_many(tails, heads)
    else:
        found = [instance.weight(u, v) for u, v in zip(tails, heads, strict=True)]
    out: list[Number] = []
    for u, v, w in zip(tails, heads, found, strict=True):
        out.append(step_weight(instance, (u, v), 1) if w is None else w)  # raises
    return out


def _values(profile: Profile, v: Values, u_trie: Number, mode: NumberMode) -> list[CheckRecord]:
    claims = profile.claimed_values
    out = []
    for cid, key, exact in (("value.U1", "U1", v.U1), ("value.U2", "U2", v.U2),
                            ("value.U", "U", v.U)):
        numbers: dict[str, Number | None] = {key: exact, f"{key}_profile": claims.get(key)}
        status: Status = "pass"
        problems = []
        if key in claims and not mode.equal(claims[key], exact):
            status = "fail"
            problems.append(f"the profile claims {key} = {show(claims[key])}")
        if key == "U":
            numbers["U_trie"] = u_trie
            if not mode.equal(u_trie, exact):
                status = "error" if status == "pass" else status
                problems.append(f"the realization-mass route gives {show(u_trie)}")
        msg = f"{key} = {show(exact)} walk by walk"
        if problems:
            msg = f"{key} = {show(exact)} exactly, but " + "; ".join(problems)
        out.append(_rec(cid, status, msg, numbers, "TEL", "the profile's walks, walk by walk"))
    bad = [k for k, x in (("U_bar", v.U_bar), ("VoI", v.VoI))
           if k in claims and not mode.equal(claims[k], x)]
    msg = f"Ū = {show(v.U_bar)}, VoI = {show(v.VoI)}"
    if bad:
        msg += "; the profile claims " + ", ".join(f"{k} = {show(claims[k])}" for k in bad)
    out.append(_rec("value.VoI", "fail" if bad else "pass", msg,
                    {"U_bar": v.U_bar, "VoI": v.VoI}, "THM", "the profile's walks"))
    return out


def _attacker(v: Values, mode: NumberMode, minima: dict[int, Number],
              relies: str, horizon: int | None) -> list[CheckRecord]:
    """The two Attacker types' regrets over all walks of any length (WALKBR / TABLEBR).

    A positive regret refutes the profile only in the untruncated game: at a finite
    ``horizon`` the cheaper walk may be longer than ``H`` steps, which the truncated game does
    not have, so the record is ``skipped`` (decided by the tree route, or without a horizon).
    """
    out = []
    for role, cid, proof in ((1, "pbne.attacker_br.primary", "L1"),
                              (2, "pbne.attacker_br.secondary", "XI2")):
        best = minima[role]
        u = v.U1 if role == 1 else v.U2
        regret = mode.difference(u, best)
        numbers: dict[str, Number | None] = {"U": u, "min_over_walks": best, "regret": regret}
        kind = "primary" if role == 1 else "secondary"
        if mode.less_than(u, best):
            out.append(_rec(cid, "error", f"the {kind} type's cost {show(u)} is below the "
                            f"minimum over all walks {show(best)}: the routes disagree",
                            numbers, proof, relies))
        elif mode.equal(regret, 0):
            out.append(_rec(cid, "pass", f"{kind} regret 0 over all walks of any length: "
                            f"U = min = {show(best)}", numbers, proof, relies))
        elif horizon is not None:
            out.append(_rec(cid, "skipped", f"{kind} regret {show(regret)} > 0 over walks of "
                            f"any length (some walk costs {show(best)} < U = {show(u)}); "
                            f"whether a walk of at most H = {horizon} steps does is not decided "
                            f"by the structured route (use --route tree, or omit the horizon)",
                            numbers, proof, relies))
        else:
            out.append(_rec(cid, "fail", f"{kind} regret {show(regret)} > 0: some walk costs "
                            f"{show(best)} < U = {show(u)} against the profile's Defender",
                            numbers, proof, relies))
    return out


def _defender(v: Values, best: Number, mode: NumberMode) -> CheckRecord:
    regret = best - v.U
    numbers: dict[str, Number | None] = {"U": v.U, "max_sigma_U": best, "regret": regret}
    if mode.equal(regret, 0):
        return _rec("pbne.defender_br", "pass", f"Defender regret 0: greedy value "
                    f"{show(best)} = U on the profile's prefixes", numbers, "L3", TRIE)
    status: Status = "fail" if mode.less_than(0, regret) else "error"
    return _rec("pbne.defender_br", status, f"Defender regret {show(regret)}: greedy value "
                f"{show(best)} vs U = {show(v.U)}", numbers, "L3", TRIE)


def _beliefs(roles: Roles, trie: WalkTrie) -> dict[int, Fraction]:
    """The Bayes belief in the primary type at every reached prefix id."""
    out = {}
    by_mass: dict[tuple[int, ...], Fraction | None] = {}  # once per mass pair
    for i in range(trie.size):
        mass = trie.masses[i]
        key = mass_key(mass)
        if key in by_mass:
            b = by_mass[key]
        else:
            x1, x2 = mass
            y1, y2 = roles.b1 * x1, roles.b2 * x2
            b = by_mass[key] = y1 / (y1 + y2) if y1 + y2 > 0 else None
        if b is not None:
            out[i] = b
    return out


def _sequential(instance: Instance, trie: WalkTrie, sigma: list[Number | None],
                beliefs: dict[int, Fraction], mode: NumberMode) -> CheckRecord:
    bad = []
    side: dict[tuple[int, int], int] = {}  # the sign of b - 1/2, once per belief value
    for i, b in beliefs.items():
        if trie.parent[i] < 0:
            continue
        s = sigma[i]
        assert s is not None  # every non-root prefix lies on a walk (_sigma_on_trie)
        key = (b.numerator, b.denominator)
        c = side.get(key)
        if c is None:
            c = side[key] = (b > HALF) - (b < HALF)
        if (c > 0 and not mode.equal(s, 1)) or (c < 0 and not mode.equal(s, 0)):
            bad.append((i, b, s))
    numbers: dict[str, Number | None] = {"reached": len(beliefs) - 1, "violations": len(bad)}
    if bad:
        i, b, s = bad[0]
        return _rec("pbne.sequential_rationality", "fail",
                    f"{count(len(bad), 'reached information set')} where the Defender is "
                    f"not greedy, e.g. after "
                    f"{show_walk(instance, trie.walk(i))} the belief is {show(b)} but σ(g1) = "
                    f"{show(s)}", numbers, "THM", TRIE)
    return _rec("pbne.sequential_rationality", "pass", f"greedy on the Bayes belief at all "
                f"{len(beliefs) - 1} reached information sets", numbers, "THM", TRIE)


def _belief_consistency(instance: Instance, profile: Profile, roles: Roles, trie: WalkTrie,
                        beliefs: dict[int, Fraction]) -> CheckRecord:
    problems = []
    if profile.claimed_prior is not None and profile.claimed_prior != (roles.b1, roles.b2):
        c1, c2 = profile.claimed_prior
        problems.append(f"the profile states the prior ({show(c1)}, {show(c2)}) but the "
                        f"instance's is ({show(roles.b1)}, {show(roles.b2)})")
    steps: dict[tuple[int, ...], Fraction] = {}
    for i, b in beliefs.items():
        q = trie.parent[i]
        if q < 0:
            if b != roles.b1:
                problems.append(f"root belief {show(b)} is not the prior")
            continue
        mq, mp, prev = trie.masses[q], trie.masses[i], beliefs[q]
        key = (prev.numerator, prev.denominator, *mass_key(mq), *mass_key(mp))
        bayes = steps.get(key)  # Bayes' step: once per (belief, masses) triple
        if bayes is None:
            (a1, a2), (c1, c2) = mq, mp
            l1 = c1 / a1 if a1 else Fraction(0)  # P(step | type), eq. (2)
            l2 = c2 / a2 if a2 else Fraction(0)
            bayes = steps[key] = prev * l1 / (prev * l1 + (1 - prev) * l2)
        if bayes != b and len(problems) < 3:
            problems.append(f"after {show_walk(instance, trie.walk(i))}: Bayes' rule gives "
                            f"{show(bayes)}, the closed form {show(b)}")
        elif bayes != b:
            problems.append("")
    numbers: dict[str, Number | None] = {"reached": len(beliefs)}
    if problems:
        return _rec("pbne.belief_consistency", "fail", "; ".join(problems[:3]), numbers, "THM",
                    TRIE)
    return _rec("pbne.belief_consistency", "pass", f"Bayes' rule step by step equals the "
                f"closed form at all {len(beliefs)} reached information sets", numbers, "THM",
                TRIE)


def _game_value(instance: Instance, v: Values, mode: NumberMode,
                horizon: int | None) -> CheckRecord:
    sv = structured_value(instance, horizon)
    h = "inf" if horizon is None else str(horizon)
    numbers: dict[str, Number | None] = {"V_H": sv.value, "U": v.U, "dp_steps": sv.steps}
    if mode.equal(sv.value, v.U):
        return _rec("game.value", "pass", f"V_H (H = {h}) = {show(sv.value)} = U by the "
                    f"three-field DP ({sv.steps} steps, {sv.arithmetic})", numbers, "DP", DP)
    return _rec("game.value", "fail", f"V_H (H = {h}) = {show(sv.value)} but U = {show(v.U)}",
                numbers, "DP", DP)


