"""The structured route's records for a profile whose Defender is the guarantee rule (NSOLVE).

The mathematics is :mod:`dppverify.structured.guarantee` (the rule evaluated on the trie of the
profile's walks, ``h ∈ G_s0``) and :mod:`dppverify.structured.arc_condition` (NSOLVE.2); the
records shared with table Defenders (Defender regret, sequential rationality, the value) are
those of the N-goal structured checks. Check ids, messages and numbers are those of
``dppverify/checks.md`` ("N goals").
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction

from dppverify.certificate import CheckRecord
from dppverify.checks.per_goal_records import (
    NGOAL_IDS,
    PROFILE_DOC,
    defender_records,
    ngoal_record,
    payoff_record,
    value_record,
)
from dppverify.exact import Number
from dppverify.game.instance import Instance
from dppverify.game.profile import Profile
from dppverify.structured.arc_condition import arc_condition
from dppverify.structured.guarantee import (
    GuaranteeRule,
    GuaranteeSets,
    dp_value,
    evaluate_rule_profile,
    in_start_set,
)
from dppverify.structured.proved_value import coalition_nvalue

__all__ = ["NSOLVE", "guarantee_checks"]

NSOLVE = "relies on proofs/NSOLVE.md (NSOLVE.1: every walk costs type θ at least h_θ when " \
    "h ∈ G_s0 and the arc condition holds; NSOLVE.2: the arc condition from the DP fixpoint " \
    "and the non-pattern rays)"


def guarantee_checks(instance: Instance, profile: Profile, horizon: int | None
                     ) -> tuple[list[CheckRecord], int]:
    """The structured route's records for a profile whose Defender is the guarantee rule.

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> from dppverify.game.profile import profile_from_json
    >>> doc = {"format": "dpp-ngoal-profile/1",
    ...        "attacker": [[{"path": ["s", "m", "a"], "probability": 1}],
    ...                     [{"path": ["s", "m", "b"], "probability": 1}],
    ...                     [{"path": ["s", "m", "c"], "probability": 1}]],
    ...        "defender": {"rule": "guarantee", "h": [2, 1, 1]}}
    >>> recs, _ = guarantee_checks(star3(), profile_from_json(doc, star3()), None)
    >>> [(r.id, r.status) for r in recs][2]
    ('pbne.attacker_br', 'pass')
    """
    inst = instance
    n = inst.n_goals
    rule = profile.defender
    assert isinstance(rule, GuaranteeRule)  # the caller dispatches on the guarantee rule
    ev = evaluate_rule_profile(inst, rule, profile.attacker)
    per_type = ev.per_type
    trie = ev.defender.trie
    out = [ngoal_record(NGOAL_IDS[0], "pass", f"{n} types, {ev.walks} walks, Defender: the "
                        f"guarantee rule with h = ({', '.join(map(str, rule.h))}) (defined on "
                        f"every walk)", {"walks": ev.walks, "prefixes": len(trie)}, PROFILE_DOC,
                        None)]
    u = sum((inst.prior[t] * per_type[t] for t in range(n)), Fraction(0))
    out.append(payoff_record(per_type, u, profile.claimed_u))
    out.append(_attacker_record(inst, rule, ev.sets, per_type, ev.feasible))
    out += defender_records(inst, ev.defender, ev.mass, u)
    known = (coalition_nvalue(dp_value(ev.sets), inst.n_goals)  # proved for N <= 3 (NG.4)
             if horizon is None and inst.n_goals <= 3 else None)
    out.append(value_record(inst, u, horizon, all(r.passed for r in out), known))
    return out, len(trie)


def _direction(inst: Instance, ray: tuple[tuple[int, Fraction], ...]) -> str:
    """A cover as text: ``1/2·{g1, g2} + …`` (goal ids)."""
    def goals(mask: int) -> str:
        return ", ".join(str(inst.nodes[inst.goals[i]]) for i in range(inst.n_goals)
                         if mask >> i & 1)

    return " + ".join(f"{c}·{{{goals(s)}}}" for s, c in ray)


def _attacker_record(inst: Instance, rule: GuaranteeRule, sets: GuaranteeSets,
                     per_type: Sequence[Fraction], feasible: bool) -> CheckRecord:
    cid = "pbne.attacker_br"
    proof = "NSOLVE"
    bad_start = in_start_set(rule, sets)
    if bad_start is not None:
        goal_numbers = [i + 1 for i in range(inst.n_goals) if bad_start >> i & 1]
        return ngoal_record(cid, "error", f"h is not in G_s0: h(S) > m_S(s0) for S = "
                            f"{goal_numbers}; the rule guarantees nothing (could not decide the "
                            f"Attacker's regret)", None, NSOLVE, proof)
    arc = arc_condition(sets)
    if not arc.holds:
        assert arc.failure is not None
        v, u, ray = arc.failure
        return ngoal_record(cid, "error", f"the arc condition G_v ⊆ G_u + wΔ fails on arc "
                            f"{inst.nodes[v]!r} -> {inst.nodes[u]!r} (direction "
                            f"{_direction(inst, ray)}; proofs/NSOLVE.md NSOLVE.2): no lower "
                            f"bound over all walks, could not decide the Attacker's regret",
                            {"arcs": arc.arcs}, NSOLVE, proof)
    nums: dict[str, Number | None] = {f"regret{t + 1}": per_type[t] - rule.h[t]
                                      for t in range(inst.n_goals)}
    nums["arcs"] = arc.arcs
    below = [t for t in range(inst.n_goals) if per_type[t] < rule.h[t]]
    if below or not feasible:
        return ngoal_record(cid, "error", "a type pays less than its proved guarantee h: the "
                            "checker's computations disagree", nums, NSOLVE, proof)
    above = [t for t in range(inst.n_goals) if per_type[t] > rule.h[t]]
    if above:
        t = above[0]
        return ngoal_record(cid, "error", f"type {t + 1} pays {per_type[t]}, above its "
                            f"guarantee h = {rule.h[t]} (a lower bound over all walks): could "
                            f"not decide its regret", nums, NSOLVE, proof)
    rays = f", {arc.rays} non-pattern directions" if arc.rays else ""
    return ngoal_record(cid, "pass", f"every type pays exactly h_θ, its minimum over all walks "
                        f"of any length (arc condition on all {arc.arcs} walkable arcs{rays})",
                        nums, NSOLVE, proof)
