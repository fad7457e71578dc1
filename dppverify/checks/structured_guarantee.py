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
from dppverify.checks.per_goal_records import per_goal_record, profile_records, walk_labels
from dppverify.exact import Number
from dppverify.game.instance import Instance
from dppverify.game.profile import Profile
from dppverify.structured.guarantee import (
    GuaranteeRule,
    dp_value,
    evaluate_rule_profile,
    in_start_set,
)
from dppverify.structured.normal_fixpoint import NormalSets
from dppverify.structured.proved_value import coalition_nvalue
from dppverify.structured.rule_response import RuleSearch, rule_response

__all__ = ["NRULE", "guarantee_checks"]

NRULE = ("relies on proofs/NRULE.md (NR.2: every walk costs type θ at least h_θ when h ∈ F_s0 "
         "and the arc condition holds; NR.4: the exact search over the rule's states; NR.3: "
         "costs telescope)")
PROOF = "NRULE"


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
    text = (f"{n} types, {ev.walks} walks, Defender: the guarantee rule with h = "
            f"({', '.join(map(str, rule.h))}) and {len(rule.normals)} extra normals (defined "
            f"on every walk)")
    attacker = _attacker_record(inst, rule, ev.sets, per_type, horizon)
    known = (coalition_nvalue(dp_value(ev.sets), inst.n_goals)  # proved for N <= 3 (NG.4)
             if horizon is None and inst.n_goals <= 3 else None)
    out = profile_records(inst, text, {"walks": ev.walks, "prefixes": len(trie)}, per_type,
                          profile.claimed_u, attacker, ev.defender, ev.mass, horizon,
                          known=known)
    return out, len(trie)


def _normal_text(inst: Instance, a: tuple[int, ...]) -> str:
    """A normal as text: its non-zero entries by goal id (``2·g1 + 2·g2 + 1·g4``)."""
    return " + ".join(f"{x}·{inst.nodes[inst.goals[i]]}" for i, x in enumerate(a) if x)


def _attacker_record(inst: Instance, rule: GuaranteeRule, sets: NormalSets,
                     per_type: Sequence[Fraction], horizon: int | None) -> CheckRecord:
    """``pbne.attacker_br``: every type's exact regret over all walks (NRULE), of at most
    ``horizon`` steps when given."""
    cid = "pbne.attacker_br"
    out, rs = rule_response(inst, rule, sets, per_type, max_steps=horizon)
    nums: dict[str, Number | None] = {}
    for r in out:
        nums[f"regret{r.theta + 1}"] = (None if not r.decided else
                                        r.bound - r.value if r.value is not None else 0)
    nums["arcs"] = rs.arc.arcs
    nums["states"] = sum(r.states for r in out)
    found = [r for r in out if r.value is not None]
    if found:
        r = max(found, key=lambda x: (x.bound - (x.value or 0), -x.theta))
        assert r.value is not None and r.walk is not None
        return per_goal_record(cid, "fail", f"type {r.theta + 1} (goal "
                            f"{inst.nodes[inst.goals[r.theta]]!r}) has regret "
                            f"{r.bound - r.value}: walk {walk_labels(inst, r.walk)} "
                            f"({len(r.walk) - 1} steps) costs {r.value} against the rule "
                            f"({r.how})", nums, NRULE, PROOF)
    undecided = [r for r in out if not r.decided]
    if undecided:
        r = undecided[0]
        return per_goal_record(cid, "error", f"could not decide type {r.theta + 1}'s regret: "
                            f"{r.how} without a walk below its cost {r.bound} or a proof that "
                            f"none exists ({_why_no_guarantee(inst, rule, rs)})", nums, NRULE,
                            PROOF)
    hows = sorted({r.how for r in out})
    walks = "of any length" if horizon is None else f"of at most {horizon} steps"
    return per_goal_record(cid, "pass", f"every type's exact regret over all walks {walks} "
                        f"is 0 ({'; '.join(hows)}; {_guarantee_text(inst, rule, rs)})", nums,
                        NRULE, PROOF)


def _guarantee_text(inst: Instance, rule: GuaranteeRule, rs: RuleSearch) -> str:
    if rs.in_start and rs.arc.holds:
        extra = f", {rs.arc.rays} non-pattern directions" if rs.arc.rays else ""
        return (f"h ∈ F_s0 and the arc condition holds on all {rs.arc.arcs} walkable arcs"
                f"{extra}")
    return _why_no_guarantee(inst, rule, rs)


def _why_no_guarantee(inst: Instance, rule: GuaranteeRule, rs: RuleSearch) -> str:
    if not rs.in_start:
        bad = in_start_set(rule, rs.sets)
        assert bad is not None
        return f"h is not in F_s0: a·h > m_a(s0) for a = {_normal_text(inst, bad)}"
    if not rs.arc.holds:
        assert rs.arc.failure is not None
        v, u, _ = rs.arc.failure
        return (f"the arc condition F_v ⊆ F_u + wΔ fails on {len(rs.arc.failing)} arc(s), e.g. "
                f"{inst.nodes[v]!r} -> {inst.nodes[u]!r}")
    return "h ∈ F_s0 and the arc condition holds"
