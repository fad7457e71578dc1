"""The structured route's N-goal records (``dpp-ngoal-profile/1``): the game without a walk tree.

For a ``dpp-ngoal-profile/1`` whose Defender is a table with a ``default`` (so that it is
defined on every walk of the game):

- every type's exact regret over ALL walks of any length (:mod:`dppverify.structured.table_br`,
  proofs/NWALKBR.md NW.1: backward induction on the finite trie of the listed walks, one exact
  shortest-path computation per type for the walks that leave it);
- the Defender's exact regret (:func:`dppverify.checks.structured_shared.greedy_sums`, as for
  two goals), sequential rationality and Bayes beliefs on the prefixes of the profile's own
  walks (:func:`dppverify.structured.trie.mass_trie`), the only information sets with positive
  mass (NW.3; off the path every distribution is a best response to the belief uniform on its
  support, NW.4);
- payoffs walk by walk; the value by the guarantee sets at ``H`` or ``H = inf``
  (:func:`dppverify.structured.proved_value.nvalue`, proofs/NGOAL.md): where ``V_H`` is proved
  (N <= 3, or a certified DP for N = 4, 5) ``U`` must equal it; otherwise ``U`` outside the exact
  bracket refutes the profile, and ``U`` inside it passes only when every equilibrium check
  passed (a certified equilibrium has ``U = V_H``), else ``skipped`` (not decisive).

The check ids are the tree route's (``dppverify/checks.md``, "N goals"); the two-goal route's
records are :mod:`dppverify.checks.structured`'s. The tree route's
``ngoal.value.structured`` (the DP against the tree LP) is not run here: the DP is this route's
value.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from fractions import Fraction

from dppverify.certificate import CheckRecord, Status
from dppverify.checks.structured_shared import greedy_sums, structured_record
from dppverify.errors import HorizonError
from dppverify.exact import INF, Number, normalize
from dppverify.game.instance import Instance
from dppverify.game.profile import GoalTable, GuaranteeRule, Profile
from dppverify.structured.proved_value import NValue, nvalue
from dppverify.structured.table_br import (
    TableDefender,
    exit_costs,
    walk_best_response,
)
from dppverify.structured.trie import mass_trie

__all__ = ["NGOAL_IDS", "NSTRUCTURED_NOT_RUN", "PAYOFF_WALKS", "PROFILE_DOC", "defender_records",
           "ngoal_record", "nstructured_checks", "payoff_record", "value_record", "walk_labels"]

PROOF = "NGOAL"
BR = "NWALKBR"
PAYOFF_WALKS = "the profile's walks, walk by walk"
NWALKBR = "relies on proofs/NWALKBR.md (NW.1: the minimum over all walks of any length)"
TRIE = ("the prefixes of the profile's walks (proofs/NWALKBR.md NW.3; off the path NW.4: any "
        "distribution is greedy for the belief uniform on its support)")
PROFILE_DOC = "the profile document alone"

NSTRUCTURED_NOT_RUN = {
    "ngoal.value.structured": "compares the structured value with the tree route's LP; the "
                              "structured route has no walk tree (its ngoal.value.V_H is the "
                              "structured value itself)"}
"""The N-goal checks the structured route does not run, with the reason."""

NGOAL_IDS = ("ngoal.profile.wellformed", "ngoal.value.U", "ngoal.pbne.attacker_br",
        "ngoal.pbne.defender_br", "ngoal.pbne.sequential", "ngoal.value.V_H")


def ngoal_record(cid: str, status: Status, message: str,
                 numbers: dict[str, Number | None] | None, relies_on: str,
                 proof: str | None = PROOF) -> CheckRecord:
    """A record of the N-goal structured route (proof ``NGOAL`` unless given).

    Examples
    --------
    >>> ngoal_record("ngoal.value.U", "pass", "U = 1", None, PAYOFF_WALKS).proof
    'NGOAL'
    """
    return structured_record(cid, status, message, numbers, proof, relies_on)


def payoff_record(per_type: Sequence[Number], u: Number, claimed_u: Number | None
                  ) -> CheckRecord:
    """``ngoal.value.U``: every type's payoff ``U_θ`` and ``U``, against the profile's claim.

    Examples
    --------
    >>> payoff_record([2, 1], Fraction(3, 2), 2).message
    'U = 3/2 (profile says 2)'
    """
    nums: dict[str, Number | None] = {f"U{t + 1}": x for t, x in enumerate(per_type)}
    nums["U"] = u
    ok = claimed_u is None or claimed_u == u
    said = "" if claimed_u is None else f" (profile says {claimed_u})"
    return ngoal_record("ngoal.value.U", "pass" if ok else "fail", f"U = {u}{said}", nums,
                        PAYOFF_WALKS)


def walk_labels(inst: Instance, walk: tuple[int, ...]) -> list[object]:
    """The node ids of a walk, as the records print it.

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> walk_labels(star3(), (0, 1, 3))
    ['s', 'm', 'b']
    """
    return list(inst.labels(walk))


def nstructured_checks(instance: Instance, profile: Profile,
                       horizon: int | None) -> tuple[list[CheckRecord], int]:
    """Every check of the N-goal structured route, in certificate order, and the trie size.

    Parameters
    ----------
    instance : Instance
        The game.
    profile : Profile
        The resolved profile.
    horizon : int or None
        ``H`` of the value check (the guarantee sets); None for the untruncated game. The
        equilibrium checks are always over all walks of any length.

    Examples
    --------
    The hub profile is an equilibrium of the 2-step game but not of the untruncated one:
    type ``b`` loops ``s m s m b`` unguarded.

    >>> from dppverify.game.examples import star3, star3_profile
    >>> from dppverify.game.profile import profile_from_json
    >>> inst = star3()
    >>> recs, size = nstructured_checks(inst, profile_from_json(star3_profile(), inst), None)
    >>> [(r.id, r.status) for r in recs][2:4], size
    ([('ngoal.pbne.attacker_br', 'fail'), ('ngoal.pbne.defender_br', 'pass')], 5)
    >>> recs[2].message
    "type 2 (goal 'b') has regret 1: walk ['s', 'm', 's', 'm', 'b'] (4 steps) costs 0"
    """
    inst = instance
    n = inst.n_goals
    if profile.defects:
        more = f" (and {len(profile.defects) - 1} more)" if len(profile.defects) > 1 else ""
        out = [ngoal_record(NGOAL_IDS[0], "fail", f"{profile.defects[0]}{more}", None,
                            PROFILE_DOC, None)]
        out += [ngoal_record(i, "skipped", "the profile is not well formed", None, "–")
                for i in NGOAL_IDS[1:]]
        return out, 0
    if isinstance(profile.defender, GuaranteeRule):  # dppverify.structured.guarantee
        from dppverify.checks.structured_guarantee import guarantee_checks

        return guarantee_checks(inst, profile, horizon)
    walks = [mw.walk for mix in profile.attacker for mw in mix]
    # realization masses x_θ(p) on the profile's walks, then the table's entries
    trie = mass_trie(profile.attacker, start=inst.start)
    table = profile.defender
    assert isinstance(table, GoalTable)  # well-formed: a table or the guarantee rule
    sigma = {trie.insert(w): tuple(d) for w, d in table.entries.items()}
    tdef = TableDefender(instance=inst, trie=trie, sigma=sigma, default=None
                         if table.default is None else tuple(table.default))
    # payoffs walk by walk
    per_type: list[Number] = []
    missing: tuple[int, ...] | None = None
    for theta, mix in enumerate(profile.attacker):
        total: Number = 0
        for mw in mix:
            p = 0
            cost: Number = 0
            for k, v in enumerate(mw.walk[1:], start=1):
                p = trie.extend(p, v)
                s = tdef.at(p)
                if s is None:
                    if missing is None or k < len(missing):
                        missing = mw.walk[:k + 1]
                    continue
                w = inst.weight(mw.walk[k - 1], v)
                assert w is not None
                cost += w * s[theta]
            total += mw.probability * (cost + inst.dist_to[theta][mw.walk[-1]])
        per_type.append(normalize(total))
    if missing is not None:
        out = [ngoal_record(NGOAL_IDS[0], "fail", f"the Defender's table has no entry for walk "
                    f"{walk_labels(inst, missing)} and no default", None, PROFILE_DOC, None)]
        out += [ngoal_record(i, "skipped", "the profile is not well formed", None, "–")
                for i in NGOAL_IDS[1:]]
        return out, len(trie)
    has_default = table.default is not None
    out = [ngoal_record(NGOAL_IDS[0], "pass", f"{n} types, {len(walks)} walks, Defender table of "
                f"{len(table.entries)} entries " + ("and a default (defined on every walk)"
                                                      if has_default else "without a default"),
                {"walks": len(walks), "prefixes": len(trie)}, PROFILE_DOC, None)]
    u = normalize(sum((inst.prior[t] * per_type[t] for t in range(n)), Fraction(0)))
    out.append(payoff_record(per_type, u, profile.claimed_u))
    attacker = _attacker(inst, tdef, per_type, horizon)
    out.append(attacker)
    out += defender_records(inst, tdef, dict(enumerate(trie.masses)), u)
    longest = max(len(w) - 1 for w in walks)
    covered = horizon is None or horizon >= longest  # NW.5: U = V_H for every H >= longest
    out.append(value_record(inst, u, horizon, covered and all(r.passed for r in out)))
    return out, len(trie)


def _attacker(inst: Instance, tdef: TableDefender, per_type: list[Number],
              horizon: int | None) -> CheckRecord:
    """``ngoal.pbne.attacker_br``: every type's exact regret over all walks (NW.1).

    At a finite ``horizon`` only a better walk of at most ``horizon`` steps refutes the profile
    (the truncated game has no longer walks); a better walk found that is longer decides
    nothing, and the record is ``skipped`` (the regret over walks of at most ``H`` steps is not
    computed by this route).
    """
    regrets: list[tuple[Number, int, tuple[int, ...], Number]] = []
    arcs = None if tdef.default is None else tdef.exit_graph()
    for theta in range(inst.n_goals):
        exits = (None if tdef.default is None
                 else exit_costs(inst, tdef.default[theta], theta, arcs))
        br = walk_best_response(tdef, theta, exits)
        if br.value is None:
            assert br.undefined is not None
            return ngoal_record("ngoal.pbne.attacker_br", "error", f"the Defender has no default "
                        f"and its table has no entry for walk "
                        f"{walk_labels(inst, br.undefined)}: no best response over all walks "
                        f"can be computed (give a default, or certify on the walk tree: --route "
                        f"tree)", None, NWALKBR, BR)
        regret = normalize(per_type[theta] - br.value) if br.value != INF else -INF
        regrets.append((regret, theta, br.walk, br.value))
    nums: dict[str, Number | None] = {f"regret{t + 1}": r for r, t, _, _ in regrets}
    if any(r < 0 for r, _, _, _ in regrets):
        r, t, _, v = min(regrets, key=lambda x: x[0])
        return ngoal_record("ngoal.pbne.attacker_br", "error", f"type {t + 1}'s profile cost is "
                    f"below its minimum over all walks {v} (regret {r}): the checker's "
                    f"computations disagree", nums, NWALKBR, BR)
    worst = max(regrets, key=lambda x: x[0])
    if worst[0] == 0:
        return ngoal_record("ngoal.pbne.attacker_br", "pass", "every type's exact regret over all "
                    "walks of any length is 0", nums, NWALKBR, BR)
    within = [x for x in regrets if x[0] > 0 and (horizon is None or len(x[2]) - 1 <= horizon)]
    if not within:
        r, t, walk, v = worst
        return ngoal_record("ngoal.pbne.attacker_br", "skipped", f"type {t + 1}'s regret over "
                    f"walks of any length is {r} (walk {walk_labels(inst, walk)}, "
                    f"{len(walk) - 1} steps > H = {horizon}); whether a walk of at most "
                    f"{horizon} steps beats the profile is not decided by the structured route "
                    f"(use --route tree, or omit the horizon)", nums, NWALKBR, BR)
    r, t, walk, v = max(within, key=lambda x: x[0])
    return ngoal_record("ngoal.pbne.attacker_br", "fail", f"type {t + 1} (goal "
                f"{inst.nodes[inst.goals[t]]!r}) has regret {r}: walk {walk_labels(inst, walk)} "
                f"({len(walk) - 1} steps) costs {v}", nums, NWALKBR, BR)


def defender_records(inst: Instance, tdef: TableDefender,
                     mass: Mapping[int, Sequence[Fraction]], u: Number) -> list[CheckRecord]:
    """``ngoal.pbne.defender_br`` and ``ngoal.pbne.sequential`` (NW.3) on the prefixes with
    mass: ``mass[p][θ]`` is type θ's realization mass at trie prefix ``p`` of ``tdef``.

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> inst = star3()
    >>> one = (Fraction(1), Fraction(0), Fraction(0))
    >>> from dppverify.structured.table_br import table_defender
    >>> d = table_defender(inst, {}, one, walks=[(0, 1, 2)])
    >>> mass = {p: (Fraction(1), Fraction(0), Fraction(0)) for p in range(len(d.trie))}
    >>> [r.status for r in defender_records(inst, d, mass, 2)]
    ['pass', 'pass']
    """
    trie = tdef.trie
    prior = inst.prior
    steps: list[tuple[int, Number, Sequence[Number]]] = []
    bad: list[tuple[int, tuple[Fraction, ...], tuple[Fraction, ...]]] = []
    reached = 0
    for p in sorted(mass):
        if p == 0:
            continue
        y = [prior[t] * x for t, x in enumerate(mass[p])]
        tot = sum(y, Fraction(0))
        if tot == 0:
            continue
        reached += 1
        s = tdef.at(p)
        assert s is not None  # checked by the well-formedness check
        parent = trie.parent[p]
        w = inst.weight(trie.node[parent], trie.node[p])
        assert w is not None
        steps.append((p, w, s))
        top = max(y)
        if any(q > 0 and y[t] < top for t, q in enumerate(s)):
            bad.append((p, tuple(m / tot for m in y), s))
    best, at = greedy_sums(mass, prior, steps)
    regret = normalize(best - at)
    greedy = normalize(u + regret)
    status: Status = "pass" if regret == 0 else "fail"
    recs = [ngoal_record("ngoal.pbne.defender_br", status, "Defender regret 0" if regret == 0 else
                 f"Defender regret {regret}: greedy best response {greedy}, profile {u}",
                 {"regret": regret, "greedy": greedy}, TRIE, BR)]
    if bad:
        p, belief, s = bad[0]
        msg = (f"{len(bad)} reached information set(s) where the Defender guards a goal of "
               f"less than maximal belief, e.g. after {walk_labels(inst, trie.walk(p))}: "
               f"belief {[str(b) for b in belief]}, Defender {[str(x) for x in s]}")
    else:
        msg = f"greedy on the Bayes belief at all {reached} reached information sets"
    recs.append(ngoal_record("ngoal.pbne.sequential", "fail" if bad else "pass", msg,
                     {"infosets": reached}, TRIE, BR))
    return recs


def value_record(inst: Instance, u: Number, horizon: int | None, equilibrium: bool,
           known: NValue | None = None) -> CheckRecord:
    """``ngoal.value.V_H``: ``U`` against the structured value at ``H`` (proofs/NGOAL.md), or
    against ``known`` when given; ``equilibrium`` says the equilibrium checks passed with ``H``
    covering the profile's walks (then ``U`` inside the bracket is ``V_H``, NW.5).

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> value_record(star3(), Fraction(3, 2), 2, True).status
    'pass'
    """
    h = "inf" if horizon is None else str(horizon)
    relies = ("relies on proofs/NGOAL.md: NG.2, NG.5 (the coalition DP is an upper bound), "
              "NG.3/NG.4 (it is the value for N <= 3), NG.6-NG.10 (the guarantee sets: "
              "exact where certified, else a bracket)")
    try:
        v = known if known is not None else nvalue(inst, horizon)
    except (ValueError, HorizonError) as exc:
        return ngoal_record("ngoal.value.V_H", "skipped", f"no structured value: {exc}", None,
                            relies)
    nums: dict[str, Number | None] = {"V_H_lower": v.lower, "V_H_upper": v.upper, "U": u}
    if v.value is not None:
        nums = {"V_H": v.value, "U": u}
        if v.value == u:
            return ngoal_record("ngoal.value.V_H", "pass", f"V_H (H = {h}) = {v.value} = U "
                        f"({v.upper_source}, {v.layers} layers)", nums, relies)
        return ngoal_record("ngoal.value.V_H", "fail", f"U = {u} differs from V_H = {v.value} "
                    f"(H = {h}; {v.upper_source}): the profile is not an equilibrium",
                    nums, relies)
    if u > v.upper or u < v.lower:
        return ngoal_record("ngoal.value.V_H", "fail", f"U = {u} lies outside the exact bracket "
                    f"[{v.lower}, {v.upper}] of V_H (H = {h}; lower: {v.lower_source}, upper: "
                    f"{v.upper_source}): the profile is not an equilibrium", nums, relies)
    if equilibrium:
        return ngoal_record("ngoal.value.V_H", "pass", f"U = {u} lies in the bracket [{v.lower}, "
                    f"{v.upper}] of V_H (H = {h}), and the equilibrium checks above passed with "
                    f"H covering the profile's walks, so V_H = U by the certified equilibrium "
                    f"(NWALKBR NW.5)", nums, relies)
    return ngoal_record("ngoal.value.V_H", "skipped", f"U = {u} lies in the bracket [{v.lower}, "
                f"{v.upper}] of V_H (H = {h}; not proved exact: {v.reason}): not decisive; "
                f"the failed checks above refute the profile", nums, relies)
