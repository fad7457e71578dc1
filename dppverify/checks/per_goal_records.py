"""The structured route's records of a per-goal profile (``dpp-ngoal-profile/1``, any N),
shared by the table Defender's checks (:mod:`dppverify.checks.structured_per_goal`) and the
guarantee rule's (:mod:`dppverify.checks.structured_guarantee`): the record form, the payoffs,
the Defender's regret and sequential rationality on the walk trie, and the value."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from fractions import Fraction

from dppverify.certificate import CheckRecord, Status
from dppverify.checks.structured_shared import greedy_sums, structured_record
from dppverify.errors import HorizonError
from dppverify.exact import Number, normalize
from dppverify.game.instance import Instance
from dppverify.registry import checks_of
from dppverify.structured.proved_value import NValue, nvalue
from dppverify.structured.table_br import TableDefender

__all__ = ["BR", "NWALKBR", "PAYOFF_WALKS", "PROFILE_DOC", "STRUCTURED_IDS", "TRIE",
           "defender_records", "payoff_record", "per_goal_record", "profile_records",
           "value_record", "walk_labels"]

PROOF = "NGOAL"
BR = "NWALKBR"
PAYOFF_WALKS = "the profile's walks, walk by walk"
NWALKBR = "relies on proofs/NWALKBR.md (NW.1: the minimum over all walks of any length)"
TRIE = ("the prefixes of the profile's walks (proofs/NWALKBR.md NW.3; off the path NW.4: any "
        "distribution is greedy for the belief uniform on its support)")
PROFILE_DOC = "the profile document alone"

STRUCTURED_IDS = tuple(c.id for c in checks_of("per-goal") if "structured" in c.routes)
"""The per-goal structured route's check ids, in certificate order (the registry's)."""


def per_goal_record(cid: str, status: Status, message: str,
                 numbers: dict[str, Number | None] | None, relies_on: str,
                 proof: str | None = PROOF) -> CheckRecord:
    """A record of the per-goal structured route (proof ``NGOAL`` unless given).

    Examples
    --------
    >>> per_goal_record("value.U", "pass", "U = 1", None, PAYOFF_WALKS).proof
    'NGOAL'
    """
    return structured_record(cid, status, message, numbers, proof, relies_on)


def payoff_record(per_type: Sequence[Number], u: Number, claimed_u: Number | None
                  ) -> CheckRecord:
    """``value.U``: every type's payoff ``U_θ`` and ``U``, against the profile's claim.

    Examples
    --------
    >>> payoff_record([2, 1], Fraction(3, 2), 2).message
    'U = 3/2 (profile says 2)'
    """
    nums: dict[str, Number | None] = {f"U{t + 1}": x for t, x in enumerate(per_type)}
    nums["U"] = u
    ok = claimed_u is None or claimed_u == u
    said = "" if claimed_u is None else f" (profile says {claimed_u})"
    return per_goal_record("value.U", "pass" if ok else "fail", f"U = {u}{said}", nums,
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


def defender_records(inst: Instance, tdef: TableDefender,
                     mass: Mapping[int, Sequence[Fraction]], u: Number) -> list[CheckRecord]:
    """``pbne.defender_br`` and ``pbne.sequential_rationality`` (NW.3) on the prefixes with
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
    recs = [per_goal_record("pbne.defender_br", status, "Defender regret 0" if regret == 0 else
                 f"Defender regret {regret}: greedy best response {greedy}, profile {u}",
                 {"regret": regret, "greedy": greedy}, TRIE, BR)]
    if bad:
        p, belief, s = bad[0]
        msg = (f"{len(bad)} reached information set(s) where the Defender guards a goal of "
               f"less than maximal belief, e.g. after {walk_labels(inst, trie.walk(p))}: "
               f"belief {[str(b) for b in belief]}, Defender {[str(x) for x in s]}")
    else:
        msg = f"greedy on the Bayes belief at all {reached} reached information sets"
    recs.append(per_goal_record("pbne.sequential_rationality", "fail" if bad else "pass", msg,
                     {"infosets": reached}, TRIE, BR))
    return recs


def profile_records(inst: Instance, described: str, sizes: dict[str, Number | None],
                    per_type: Sequence[Number], claimed_u: Number | None,
                    attacker: CheckRecord, tdef: TableDefender,
                    mass: Mapping[int, Sequence[Fraction]], horizon: int | None, *,
                    covered: bool = True, known: NValue | None = None) -> list[CheckRecord]:
    """Every record of a well-formed per-goal profile, in certificate order.

    ``profile.wellformed`` passes with ``described`` and ``sizes``; ``value.U`` from the
    types' payoffs ``per_type`` (:func:`payoff_record`); the Attacker's record ``attacker``;
    the Defender's (:func:`defender_records` on ``tdef`` and ``mass``); ``game.value``
    (:func:`value_record`), an equilibrium when ``covered`` (``H`` covers the profile's
    walks) and every record before it passed.

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> from dppverify.structured.table_br import table_defender
    >>> inst = star3()
    >>> d = table_defender(inst, {}, (Fraction(1), Fraction(0), Fraction(0)), walks=[(0, 1, 2)])
    >>> mass = {p: (Fraction(1), Fraction(0), Fraction(0)) for p in range(len(d.trie))}
    >>> br = per_goal_record("pbne.attacker_br", "pass", "regret 0", None, NWALKBR, BR)
    >>> recs = profile_records(inst, "one walk", {}, [2, 0, 0], None, br, d, mass, 2)
    >>> [r.id for r in recs] == list(STRUCTURED_IDS)
    True
    """
    out = [per_goal_record(STRUCTURED_IDS[0], "pass", described, sizes, PROFILE_DOC, None)]
    u = normalize(sum((inst.prior[t] * per_type[t] for t in range(inst.n_goals)), Fraction(0)))
    out.append(payoff_record(per_type, u, claimed_u))
    out.append(attacker)
    out += defender_records(inst, tdef, mass, u)
    out.append(value_record(inst, u, horizon, covered and all(r.passed for r in out), known))
    return out


def value_record(inst: Instance, u: Number, horizon: int | None, equilibrium: bool,
           known: NValue | None = None) -> CheckRecord:
    """``game.value``: ``U`` against the structured value at ``H`` (proofs/NGOAL.md), or
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
        return per_goal_record("game.value", "skipped", f"no structured value: {exc}", None,
                            relies)
    nums: dict[str, Number | None] = {"V_H_lower": v.lower, "V_H_upper": v.upper, "U": u}
    if v.value is not None:
        nums = {"V_H": v.value, "U": u}
        if v.value == u:
            return per_goal_record("game.value", "pass", f"V_H (H = {h}) = {v.value} = U "
                        f"({v.upper_source}, {v.effort})", nums, relies)
        return per_goal_record("game.value", "fail", f"U = {u} differs from V_H = {v.value} "
                    f"(H = {h}; {v.upper_source}): the profile is not an equilibrium",
                    nums, relies)
    if u > v.upper or u < v.lower:
        return per_goal_record("game.value", "fail", f"U = {u} lies outside the exact bracket "
                    f"[{v.lower}, {v.upper}] of V_H (H = {h}; lower: {v.lower_source}, upper: "
                    f"{v.upper_source}): the profile is not an equilibrium", nums, relies)
    if equilibrium:
        return per_goal_record("game.value", "pass", f"U = {u} lies in the bracket [{v.lower}, "
                    f"{v.upper}] of V_H (H = {h}), and the equilibrium checks above passed with "
                    f"H covering the profile's walks, so V_H = U by the certified equilibrium "
                    f"(NWALKBR NW.5)", nums, relies)
    return per_goal_record("game.value", "skipped", f"U = {u} lies in the bracket [{v.lower}, "
                f"{v.upper}] of V_H (H = {h}; not proved exact: {v.reason}): not decisive; "
                f"the failed checks above refute the profile", nums, relies)
