"""The structured route of ``certify``: the untruncated game, without the walk tree.

For a two-goal profile whose Defender is a progress rule (σ* or the progress rule towards the
other goal) or a table with a ``default``: both Attacker types' exact regret over ALL walks of
any length (proofs/WALKBR.md, shortest paths only; for a table proofs/TABLEBR.md, the
backward induction of :mod:`dppverify.structured.table_br` on the table's trie plus an exact
Dijkstra off it); the Defender's exact regret (the greedy sums of
:mod:`dppverify.checks.structured_shared`, written once for N types), sequential rationality
and Bayes beliefs on the prefixes of the profile's own walks (the only information sets that
carry mass); payoffs walk by walk; the value by the three-field DP (proofs/DP.md); and, from
the two-goal layer :mod:`dppverify.checks.structured_twogoal`, the phases and the lemmas that
have a polynomial form. The lemma checks that need the tree (L3's and L4's random attackers
with their LPs) are not run on this route; the certificate says so. The N-goal records
(the registry's ``per-goal`` family) are :mod:`dppverify.checks.structured_per_goal`'s.
"""

from __future__ import annotations

from fractions import Fraction
from typing import cast

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
from dppverify.game.defender import sigma_along
from dppverify.game.distances import ArcRows
from dppverify.game.evaluation import Values, evaluate
from dppverify.game.instance import Instance, Roles
from dppverify.game.profile import DefenderRule, Profile
from dppverify.game.step_weights import step_weight
from dppverify.numbers import NumberMode
from dppverify.structured.table_br_twogoal import table_minima
from dppverify.structured.trie import WalkTrie, mass_trie
from dppverify.text import show, show_walk
from dppverify.twogoal.progress_br import walk_minima
from dppverify.twogoal.value_dp import structured_value

__all__ = ["structured_checks"]


TABLEBR = "relies on proofs/TABLEBR.md (a table Defender with a default)"
DP = "relies on proofs/DP.md"


def structured_checks(instance: Instance, profile: Profile,
                      horizon: int | None) -> list[CheckRecord]:
    """Every check of the structured route, in certificate order.

    Parameters
    ----------
    instance : Instance
        The game.
    profile : Profile
        The resolved profile; its Defender must be a progress rule or a table with a default
        (or the profile ill-formed).
    horizon : int or None
        ``H`` of the truncated game for ``game.value``; None for the untruncated game.

    Returns
    -------
    list of CheckRecord

    Examples
    --------
    >>> from dppverify.game.examples import triangle, triangle_profile
    >>> from dppverify.game.profile import profile_from_json
    >>> inst = triangle()
    >>> recs = structured_checks(inst, profile_from_json(triangle_profile(), inst),
    ...                          None)
    >>> [r.status for r in recs] == ["pass"] * len(recs), len(recs)
    (True, 17)
    """
    roles = instance.roles(profile.primary_goal_index)
    mode = instance.numbers
    missing = _unlisted_profile_prefix(profile)
    out: list[CheckRecord] = [_wellformed(instance, profile, roles, missing)]
    usable = profile.wellformed and missing is None and profile.defender is not None
    if not usable:
        ids = ("value.U1", "value.U2", "value.U", "value.VoI", "profile.phases",
               "pbne.attacker_br.primary", "pbne.attacker_br.secondary", "pbne.defender_br",
               "pbne.sequential_rationality", "pbne.belief_consistency", "game.value",
               "lemma.TEL.telescoping", "lemma.L1.lower_bound", "lemma.L2.no_revisits")
        out += [_rec(i, "skipped", NOT_WELLFORMED, None, None, None) for i in ids]
        out.append(xi2_check(instance, roles, mode, walk_minima(instance, roles.g1)))
        out.append(_rec("lemma.L5.induced_beliefs", "skipped", NOT_WELLFORMED, None, "L5", None))
        return out
    rule = cast(DefenderRule, profile.defender)  # the two-goal reader's rules only
    v = evaluate(instance, roles, rule, profile.primary, profile.secondary)
    trie = mass_trie([profile.primary, profile.secondary])
    sigma = _sigma_on_trie(instance, roles, rule, trie)
    defender_max, u_trie = _defender_payoffs(instance, roles, trie, sigma)
    out += _values(profile, v, u_trie, mode)
    out.append(phases_check(instance, profile, roles, mode))
    star = walk_minima(instance, roles.g1)  # shared by the Attacker, L1 and XI2 checks
    if not rule.table:  # σ*'s best responses (proofs/WALKBR.md), else a table's
        mins = star if rule.goal == roles.g1 else walk_minima(instance, rule.goal)
        same = roles.g1 == rule.goal
        best = {1: mins.same if same else mins.other, 2: mins.other if same else mins.same}
        relies = WALKBR
    else:
        tm = table_minima(instance, roles, rule)
        best = {1: tm.primary, 2: tm.secondary}
        relies = TABLEBR
    out += _attacker(v, mode, best, relies, horizon)
    out.append(_defender(v, defender_max, mode))
    beliefs = _beliefs(roles, trie)
    out.append(_sequential(instance, trie, sigma, beliefs, mode))
    out.append(_belief_consistency(instance, profile, roles, trie, beliefs))
    out.append(_game_value(instance, v, mode, horizon))
    out.append(telescoping_check(instance, roles, trie, mode))
    out.append(l1_check(instance, roles, profile, mode, star))
    out.append(l2_check(instance, profile))
    out.append(xi2_check(instance, roles, mode, star))
    out.append(l5_check(instance, profile, roles, trie, beliefs, mode))
    return out


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
                f"well-formed: {len(profile.primary)} primary and {len(profile.secondary)} "
                f"secondary walk(s), primary goal {instance.nodes[roles.g1]!r}", numbers, None,
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
    msg = f"U_bar = {show(v.U_bar)}, VoI = {show(v.VoI)}"
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
        return _rec("pbne.sequential_rationality", "fail", f"{len(bad)} reached information "
                    f"set(s) where the Defender is not greedy, e.g. after "
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


