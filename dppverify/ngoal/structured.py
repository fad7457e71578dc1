"""The structured route of ``certify_ngoal``: an N-goal profile on the game without a walk tree.

For a ``dpp-ngoal-profile/1`` whose Defender is a table with a ``default`` (so that it is
defined on every walk of the game):

- every type's exact regret over ALL walks of any length (:mod:`dppverify.ngoal.walk_br`,
  proofs/NWALKBR.md NW.1: backward induction on the finite trie of the listed walks, one exact
  shortest-path computation per type for the walks that leave it);
- the Defender's exact regret, sequential rationality and Bayes beliefs on the prefixes of the
  profile's own walks, the only information sets with positive mass (NW.3; off the path every
  distribution is a best response to the belief uniform on its support, NW.4);
- payoffs walk by walk; the value by the guarantee sets at ``H`` or ``H = inf``
  (:func:`dppverify.structured.proved_value.nvalue`, proofs/NGOAL.md): where ``V_H`` is proved
  (N <= 3, or a certified DP for N = 4, 5) ``U`` must equal it; otherwise ``U`` outside the exact
  bracket refutes the profile, and ``U`` inside it passes only when every equilibrium check
  passed (a certified equilibrium has ``U = V_H``), else ``skipped`` (not decisive).

The check ids are the tree route's (``dppverify/checks.md``, "N goals"); the tree route's
``ngoal.value.structured`` (the DP against the tree LP) is not run here: the DP is this route's
value.
"""

from __future__ import annotations

from fractions import Fraction

from dppverify.certificate import CheckRecord, Status
from dppverify.errors import HorizonError
from dppverify.exact import INF, Number, normalize
from dppverify.ngoal.instance import NInstance
from dppverify.ngoal.profile import NProfile
from dppverify.ngoal.walk_br import TableDefender, exit_costs, table_defender, walk_best_response
from dppverify.structured.proved_value import NValue, nvalue

__all__ = ["NSTRUCTURED_NOT_RUN", "nstructured_checks"]

PROOF = "NGOAL"
BR = "NWALKBR"
WALKS = "the profile's walks, walk by walk"
NWALKBR = "relies on proofs/NWALKBR.md (NW.1: the minimum over all walks of any length)"
TRIE = ("the prefixes of the profile's walks (proofs/NWALKBR.md NW.3; off the path NW.4: any "
        "distribution is greedy for the belief uniform on its support)")
DOC = "the profile document alone"

NSTRUCTURED_NOT_RUN = {
    "ngoal.value.structured": "compares the structured value with the tree route's LP; the "
                              "structured route has no walk tree (its ngoal.value.V_H is the "
                              "structured value itself)"}
"""The N-goal checks the structured route does not run, with the reason."""

_IDS = ("ngoal.profile.wellformed", "ngoal.value.U", "ngoal.pbne.attacker_br",
        "ngoal.pbne.defender_br", "ngoal.pbne.sequential", "ngoal.value.V_H")


def _rec(cid: str, status: Status, message: str, numbers: dict[str, Number | None] | None,
         relies_on: str, proof: str | None = PROOF) -> CheckRecord:
    return CheckRecord(cid, status, message, numbers or {}, proof, route="structured",
                       relies_on=relies_on)


def _labels(inst: NInstance, walk: tuple[int, ...]) -> list[object]:
    return list(inst.labels(walk))


def nstructured_checks(instance: NInstance, profile: NProfile,
                       horizon: int | None) -> tuple[list[CheckRecord], int]:
    """Every check of the N-goal structured route, in certificate order, and the trie size.

    Parameters
    ----------
    instance : NInstance
        The game.
    profile : NProfile
        The resolved profile.
    horizon : int or None
        ``H`` of the value check (the guarantee sets); None for the untruncated game. The
        equilibrium checks are always over all walks of any length.

    Examples
    --------
    The hub profile is an equilibrium of the 2-step game but not of the untruncated one:
    type ``b`` loops ``s m s m b`` unguarded.

    >>> from dppverify.ngoal.examples import star3, star3_profile
    >>> from dppverify.ngoal.profile import nprofile_from_json
    >>> inst = star3()
    >>> recs, size = nstructured_checks(inst, nprofile_from_json(inst, star3_profile()), None)
    >>> [(r.id, r.status) for r in recs][2:4], size
    ([('ngoal.pbne.attacker_br', 'fail'), ('ngoal.pbne.defender_br', 'pass')], 5)
    >>> recs[2].message
    "type 2 (goal 'b') has regret 1: walk ['s', 'm', 's', 'm', 'b'] (4 steps) costs 0"
    """
    inst = instance
    n = inst.n_goals
    if profile.defects:
        more = f" (and {len(profile.defects) - 1} more)" if len(profile.defects) > 1 else ""
        out = [_rec(_IDS[0], "fail", profile.defects[0] + more, None, DOC, None)]
        out += [_rec(i, "skipped", "the profile is not well formed", None, "–")
                for i in _IDS[1:]]
        return out, 0
    if profile.rule is not None:  # the guarantee rule: dppverify.structured.guarantee
        from dppverify.checks.structured_guarantee import guarantee_checks

        return guarantee_checks(inst, profile, horizon)
    walks = [mw.walk for mix in profile.attacker for mw in mix]
    tdef = table_defender(inst, profile.entries, profile.default, walks)
    trie = tdef.trie
    # realization masses x_θ(p) on the profile's walks; payoffs walk by walk
    mass: dict[int, list[Fraction]] = {}
    per_type: list[Number] = []
    missing: tuple[int, ...] | None = None
    for theta, mix in enumerate(profile.attacker):
        total: Number = 0
        for mw in mix:
            p = 0
            cost: Number = 0
            mass.setdefault(0, [Fraction(0)] * n)[theta] += mw.probability
            for k, v in enumerate(mw.walk[1:], start=1):
                p = trie.children[p][v]
                mass.setdefault(p, [Fraction(0)] * n)[theta] += mw.probability
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
        out = [_rec(_IDS[0], "fail", f"the Defender's table has no entry for walk "
                    f"{_labels(inst, missing)} and no default", None, DOC, None)]
        out += [_rec(i, "skipped", "the profile is not well formed", None, "–")
                for i in _IDS[1:]]
        return out, len(trie)
    has_default = profile.default is not None
    out = [_rec(_IDS[0], "pass", f"{n} types, {len(walks)} walks, Defender table of "
                f"{len(profile.entries)} entries " + ("and a default (defined on every walk)"
                                                      if has_default else "without a default"),
                {"walks": len(walks), "prefixes": len(trie)}, DOC, None)]
    u = normalize(sum((inst.prior[t] * per_type[t] for t in range(n)), Fraction(0)))
    nums: dict[str, Number | None] = {f"U{t + 1}": per_type[t] for t in range(n)}
    nums["U"] = u
    ok = profile.claimed_u is None or profile.claimed_u == u
    said = "" if profile.claimed_u is None else f" (profile says {profile.claimed_u})"
    out.append(_rec("ngoal.value.U", "pass" if ok else "fail", f"U = {u}{said}", nums, WALKS))
    attacker = _attacker(inst, tdef, per_type)
    out.append(attacker)
    out += _defender(inst, tdef, mass, u)
    longest = max(len(w) - 1 for w in walks)
    covered = horizon is None or horizon >= longest  # NW.5: U = V_H for every H >= longest
    out.append(_value(inst, u, horizon, covered and all(r.passed for r in out)))
    return out, len(trie)


def _attacker(inst: NInstance, tdef: TableDefender, per_type: list[Number]) -> CheckRecord:
    regrets: list[tuple[Number, int, tuple[int, ...], Number]] = []
    for theta in range(inst.n_goals):
        exits = (None if tdef.default is None
                 else exit_costs(inst, tdef.default[theta], theta))
        br = walk_best_response(tdef, theta, exits)
        if br.value is None:
            assert br.undefined is not None
            return _rec("ngoal.pbne.attacker_br", "error", f"the Defender has no default and "
                        f"its table has no entry for walk {_labels(inst, br.undefined)}: no "
                        f"best response over all walks can be computed (give a default, or "
                        f"certify on the walk tree: --route tree)", None, NWALKBR, BR)
        regret = normalize(per_type[theta] - br.value) if br.value != INF else -INF
        regrets.append((regret, theta, br.walk, br.value))
    nums: dict[str, Number | None] = {f"regret{t + 1}": r for r, t, _, _ in regrets}
    if any(r < 0 for r, _, _, _ in regrets):
        r, t, _, v = min(regrets, key=lambda x: x[0])
        return _rec("ngoal.pbne.attacker_br", "error", f"type {t + 1}'s profile cost is below "
                    f"its minimum over all walks {v} (regret {r}): the checker's computations "
                    f"disagree", nums, NWALKBR, BR)
    worst = max(regrets, key=lambda x: x[0])
    if worst[0] == 0:
        return _rec("ngoal.pbne.attacker_br", "pass", "every type's exact regret over all "
                    "walks of any length is 0", nums, NWALKBR, BR)
    r, t, walk, v = worst
    return _rec("ngoal.pbne.attacker_br", "fail", f"type {t + 1} (goal "
                f"{inst.nodes[inst.goals[t]]!r}) has regret {r}: walk {_labels(inst, walk)} "
                f"({len(walk) - 1} steps) costs {v}", nums, NWALKBR, BR)


def _defender(inst: NInstance, tdef: TableDefender, mass: dict[int, list[Fraction]],
              u: Number) -> list[CheckRecord]:
    trie = tdef.trie
    best: Number = 0
    at: Number = 0
    bad: list[tuple[int, tuple[Fraction, ...], tuple[Fraction, ...]]] = []
    reached = 0
    for p in sorted(mass):
        if p == 0:
            continue
        y = [inst.prior[t] * x for t, x in enumerate(mass[p])]
        tot = sum(y, Fraction(0))
        if tot == 0:
            continue
        reached += 1
        s = tdef.at(p)
        assert s is not None  # checked by the well-formedness check
        parent = trie.parent[p]
        w = inst.weight(trie.node[parent], trie.node[p])
        assert w is not None
        top = max(y)
        best += w * top
        at += w * sum((s[t] * y[t] for t in range(len(y))), Fraction(0))
        if any(q > 0 and y[t] < top for t, q in enumerate(s)):
            bad.append((p, tuple(m / tot for m in y), s))
    regret = normalize(best - at)
    greedy = normalize(u + regret)
    status: Status = "pass" if regret == 0 else "fail"
    recs = [_rec("ngoal.pbne.defender_br", status, "Defender regret 0" if regret == 0 else
                 f"Defender regret {regret}: greedy best response {greedy}, profile {u}",
                 {"regret": regret, "greedy": greedy}, TRIE, BR)]
    if bad:
        p, belief, s = bad[0]
        msg = (f"{len(bad)} reached information set(s) where the Defender guards a goal of "
               f"less than maximal belief, e.g. after {_labels(inst, trie.walk(p))}: "
               f"belief {[str(b) for b in belief]}, Defender {[str(x) for x in s]}")
    else:
        msg = f"greedy on the Bayes belief at all {reached} reached information sets"
    recs.append(_rec("ngoal.pbne.sequential", "fail" if bad else "pass", msg,
                     {"infosets": reached}, TRIE, BR))
    return recs


def _value(inst: NInstance, u: Number, horizon: int | None, equilibrium: bool,
           known: NValue | None = None) -> CheckRecord:
    h = "inf" if horizon is None else str(horizon)
    relies = ("relies on proofs/NGOAL.md: NG.2, NG.5 (the coalition DP is an upper bound), "
              "NG.3/NG.4 (it is the value for N <= 3), NG.6-NG.10 (the guarantee sets: "
              "exact where certified, else a bracket)")
    try:
        v = known if known is not None else nvalue(inst, horizon)
    except (ValueError, HorizonError) as exc:
        return _rec("ngoal.value.V_H", "skipped", f"no structured value: {exc}", None, relies)
    nums: dict[str, Number | None] = {"V_H_lower": v.lower, "V_H_upper": v.upper, "U": u}
    if v.value is not None:
        nums = {"V_H": v.value, "U": u}
        if v.value == u:
            return _rec("ngoal.value.V_H", "pass", f"V_H (H = {h}) = {v.value} = U "
                        f"({v.upper_source}, {v.layers} layers)", nums, relies)
        return _rec("ngoal.value.V_H", "fail", f"U = {u} differs from V_H = {v.value} "
                    f"(H = {h}; {v.upper_source}): the profile is not an equilibrium",
                    nums, relies)
    if u > v.upper or u < v.lower:
        return _rec("ngoal.value.V_H", "fail", f"U = {u} lies outside the exact bracket "
                    f"[{v.lower}, {v.upper}] of V_H (H = {h}; lower: {v.lower_source}, upper: "
                    f"{v.upper_source}): the profile is not an equilibrium", nums, relies)
    if equilibrium:
        return _rec("ngoal.value.V_H", "pass", f"U = {u} lies in the bracket [{v.lower}, "
                    f"{v.upper}] of V_H (H = {h}), and the equilibrium checks above passed with "
                    f"H covering the profile's walks, so V_H = U by the certified equilibrium "
                    f"(NWALKBR NW.5)", nums, relies)
    return _rec("ngoal.value.V_H", "skipped", f"U = {u} lies in the bracket [{v.lower}, "
                f"{v.upper}] of V_H (H = {h}; not proved exact: {v.reason}): not decisive; "
                f"the failed checks above refute the profile", nums, relies)


# Public names of the records shared with the guarantee rule's checks
# (dppverify/checks/structured_guarantee.py).
NGOAL_IDS, PROFILE_DOC, PAYOFF_WALKS = _IDS, DOC, WALKS
ngoal_record, walk_labels, defender_records, value_record = _rec, _labels, _defender, _value
