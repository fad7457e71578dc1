"""The checks of a goal-selection profile on the untruncated game (proofs/SELECT.md SELECT.6).

``(q, γ, σ)`` is an equilibrium of the goal-selection game exactly when

1. it is an equilibrium of the game with prior ``q`` in the sense the N-goal checks decide:
   every type's exact regret over all walks is 0 (**every** type, also those ``q`` never
   chooses), the Defender's regret given ``q`` is 0 and it is sequentially rational on the
   prefixes ``q`` reaches; these are the records of the per-goal structured route on the game at
   ``q`` (:class:`~dppverify.checks.structured_per_goal.PerGoalStructured`: the
   guarantee rule or a table), or of :mod:`dppverify.structured.mixture_br` for the two-goal
   progress mixture;
2. ``selection.goal_indifference``: with ``c_i`` type ``i``'s exact best-response cost against
   ``σ`` and ``V = min_i (c_i − r_i)``, ``c_i − r_i = V`` on the support of ``q`` (and ``>= V``
   off it, by the definition of ``V``): no goal is cheaper to choose than the ones chosen.

Then ``V`` is the goal-selection game's value: ``selection.value`` compares it with the
checker's own ``V_sel`` (:func:`~dppverify.structured.selection_value.selection_value`) and with the
profile's claim.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction

from dppverify.certificate import CheckRecord, Status
from dppverify.checks.per_goal_records import (
    BR,
    PROFILE_DOC,
    STRUCTURED_IDS,
    defender_records,
    payoff_record,
    per_goal_record,
    value_record,
    walk_labels,
)
from dppverify.checks.runners import run_checks
from dppverify.checks.structured_per_goal import PerGoalStructured
from dppverify.exact import Number, normalize
from dppverify.game.goal_selection import with_choice
from dppverify.game.instance import Instance
from dppverify.game.mixture_rule import ProgressMixture
from dppverify.game.profile import Profile
from dppverify.registry import check_ids
from dppverify.structured.mixture_br import mixture_response
from dppverify.structured.selection_value import SelectionValue, goal_values, selection_value
from dppverify.structured.table_br import TableDefender
from dppverify.structured.trie import mass_trie

SELECT = "SELECT"
INDIFFERENCE = ("relies on proofs/SELECT.md (SELECT.6: c_i, the exact best-response costs of "
                "pbne.attacker_br)")
VALUE = ("relies on proofs/SELECT.md (SELECT.2: V_sel = max t with t·1 + r in the exact "
         "guarantee set at the start; SELECT.6)")
MIXTURE = ("relies on proofs/SELECT.md (SELECT.7: the mixture of the two progress rules' minima "
           "over all walks, proofs/WALKBR.md, or an exact search over (node, running minima))")

SELECTION_IDS = check_ids("selection")
"""Every check id of a goal-selection certificate, in certificate order (the registry's)."""


@dataclass(frozen=True)
class SelectionContext:
    """The goal-selection family's context on the structured route (its row of the one runner
    table, :data:`dppverify.checks.runners.RUNNERS`): the game and the profile."""

    instance: Instance
    profile: Profile

    def records(self) -> list[CheckRecord]:
        """Every record of the family (:func:`selection_checks`)."""
        return selection_checks(self.instance, self.profile)


def _goal(inst: Instance, t: int) -> str:
    return repr(inst.nodes[inst.goals[t]])


def selection_checks(instance: Instance, profile: Profile,
                     known: SelectionValue | None = None) -> list[CheckRecord]:
    """Every record of a goal-selection certificate, in :data:`SELECTION_IDS` order.

    ``known``: the game's ``V_sel`` when the caller has it (else computed here).

    Examples
    --------
    The paper's σ* against an Attacker who chooses (the triangle, chosen as at its prior
    7/10): the goal ``g2`` costs 1 against σ*, ``g1`` costs 3:

    >>> from dppverify.game.examples import triangle_document
    >>> from dppverify.game.instance import instance_from_json
    >>> from dppverify.game.selection_profile import selection_profile_from_json
    >>> inst = {**triangle_document(), "goal_selection": True}
    >>> del inst["prior"]
    >>> sel = instance_from_json(inst)
    >>> paper = {"format": "dpp-profile/1", "goals": {"primary": "g1", "secondary": "g2"},
    ...          "prior": {"primary": "7/10", "secondary": "3/10"},
    ...          "defender": {"rule": "progress", "goal": "g1"},
    ...          "attacker": {"primary": [{"path": ["s", "g1"], "probability": "4/7"},
    ...                                   {"path": ["s", "g2"], "probability": "3/7"}],
    ...                       "secondary": [{"path": ["s", "g2"], "probability": 1}]}}
    >>> recs = selection_checks(sel, selection_profile_from_json(paper, sel))
    >>> [(r.id, r.status) for r in recs][2:]   # doctest: +NORMALIZE_WHITESPACE
    [('pbne.attacker_br', 'pass'), ('pbne.defender_br', 'pass'),
     ('pbne.sequential_rationality', 'pass'), ('game.value', 'pass'),
     ('selection.goal_indifference', 'fail'), ('selection.value', 'fail')]
    >>> print(recs[6].message)   # doctest: +ELLIPSIS
    goal 'g2' is cheap: c − r = 1 there, 3 on the chosen goal 'g1'; choosing 'g2' against \
this Defender gains the Attacker 7/5 over the choice q
    >>> print(recs[7].message)   # doctest: +ELLIPSIS
    against this Defender the Attacker's best choice costs V = min_i (c_i − r_i) = 1 but \
V_sel = 2 (...); the game with the prior q has the value 12/5: choosing its goal gains the \
Attacker 2/5
    """
    n = instance.n_goals
    if not profile.wellformed or profile.choice is None:
        return _ill_formed(profile)
    q = profile.choice
    game = with_choice(instance, q)
    if isinstance(profile.defender, ProgressMixture):
        recs = _mixture_records(game, profile, profile.defender)
    else:
        recs = run_checks("per-goal", "structured", PerGoalStructured(game, profile, None))
    byid = {r.id: r for r in recs}
    costs = _best_costs(byid, n)
    values = goal_values(instance)
    indiff, v = _indifference(game, values, q, costs)
    recs.append(indiff)
    ok = all(r.passed for r in recs)
    u = byid["value.U"].numbers.get("U") if "value.U" in byid else None
    at_q = None if u is None else normalize(Fraction(u) - sum(
        (x * r for x, r in zip(q, values, strict=True)), Fraction(0)))
    recs.append(_value(instance, v, profile.claimed_values.get("V"), ok, known, at_q))
    return recs


def _ill_formed(profile: Profile) -> list[CheckRecord]:
    d = profile.defects
    more = f" (and {len(d) - 1} more)" if len(d) > 1 else ""
    first = str(d[0]) if d else "the choice is unusable"
    return ([per_goal_record(SELECTION_IDS[0], "fail", first + more, None, PROFILE_DOC, None)]
            + [per_goal_record(i, "skipped", "the profile is not well formed", None, "–")
               for i in SELECTION_IDS[1:]])


def _best_costs(byid: dict[str, CheckRecord], n: int) -> list[Number | None]:
    """``c_i = U_i − regret_i`` from ``value.U`` and ``pbne.attacker_br`` (None: undecided)."""
    pay, br = byid.get("value.U"), byid.get("pbne.attacker_br")
    out: list[Number | None] = []
    for t in range(n):
        u = None if pay is None else pay.numbers.get(f"U{t + 1}")
        reg = None if br is None else br.numbers.get(f"regret{t + 1}")
        out.append(None if u is None or reg is None else normalize(Fraction(u) - Fraction(reg)))
    return out


def _indifference(game: Instance, values: Sequence[Fraction], q: Sequence[Fraction],
                  costs: Sequence[Number | None]) -> tuple[CheckRecord, Fraction | None]:
    cid = "selection.goal_indifference"
    n = game.n_goals
    if any(c is None for c in costs):
        return per_goal_record(cid, "skipped", "some type's best-response cost is undecided "
                            "(pbne.attacker_br)", None, INDIFFERENCE, SELECT), None
    net = [Fraction(c) - values[t] for t, c in enumerate(costs)]  # type: ignore[arg-type]
    v = min(net)
    nums: dict[str, Number | None] = {f"c{t + 1}": costs[t] for t in range(n)}
    nums |= {f"r{t + 1}": normalize(values[t]) for t in range(n)}
    nums["V"] = normalize(v)
    chosen = [t for t in range(n) if q[t]]
    worst = max(chosen, key=lambda t: (net[t], -t))
    if net[worst] == v:
        return per_goal_record(cid, "pass", f"c_i − r_i = {v} on every chosen goal and >= {v} "
                            f"on the others (costs ({', '.join(map(str, costs))}))", nums,
                            INDIFFERENCE, SELECT), v
    cheap = min(range(n), key=lambda t: (net[t], t))
    gain = sum((q[t] * net[t] for t in range(n)), Fraction(0)) - v
    nums["gain"] = normalize(gain)
    return per_goal_record(cid, "fail", f"goal {_goal(game, cheap)} is cheap: c − r = {v} there, "
                        f"{net[worst]} on the chosen goal {_goal(game, worst)}; choosing "
                        f"{_goal(game, cheap)} against this Defender gains the Attacker "
                        f"{gain} over the choice q", nums, INDIFFERENCE, SELECT), v


def _value(instance: Instance, v: Fraction | None, claimed: Number | None,
           equilibrium: bool, known: SelectionValue | None, at_q: Number | None
           ) -> CheckRecord:
    """``selection.value``: ``V = min_i (c_i − r_i)`` against the checker's ``V_sel`` (and
    the claim); ``at_q`` is ``U − q·r``, the game at the prior ``q`` in the same payoff."""
    cid = "selection.value"
    sv = known if known is not None else selection_value(instance)
    nums: dict[str, Number | None] = {"V_sel_lower": normalize(Fraction(sv.lower)),
                                      "V_sel_upper": normalize(Fraction(sv.upper)),
                                      "V": None if v is None else normalize(v),
                                      "claimed": claimed}
    if claimed is not None and v is not None and claimed != v:
        return per_goal_record(cid, "fail", f"the profile says V = {claimed}, its equilibrium "
                            f"conditions give {v}", nums, VALUE, SELECT)
    exact = (f"V_sel = {sv.value} ({sv.upper_source})" if sv.value is not None else
             f"V_sel in [{sv.lower}, {sv.upper}] (lower: {sv.lower_source}; upper: "
             f"{sv.upper_source})")
    if v is None:
        return per_goal_record(cid, "skipped", f"{exact}; the best-response costs are undecided",
                            nums, VALUE, SELECT)
    said = f"against this Defender the Attacker's best choice costs V = min_i (c_i − r_i) = {v}"
    status: Status
    if sv.value is not None:
        status = "pass" if v == sv.value and equilibrium else "fail"
        text = f"{said} {'=' if v == sv.value else 'but'} {exact}"
    elif not sv.lower <= v <= sv.upper:
        status, text = "fail", f"{said}, outside the exact bracket: {exact}"
    else:
        status = "pass" if equilibrium else "skipped"
        text = (f"{said}, inside the bracket {exact}; " + (
            "the equilibrium checks above passed, so V_sel = V (SELECT.6)" if equilibrium
            else "not decisive"))
    if at_q is not None and sv.value is not None and at_q != sv.value:
        gain = normalize(Fraction(at_q) - Fraction(sv.value))
        nums["gain"] = gain
        text += (f"; the game with the prior q has the value {at_q}: choosing its goal gains "
                 f"the Attacker {gain}")
    return per_goal_record(cid, status, text, nums, VALUE, SELECT)


def _mixture_records(game: Instance, profile: Profile, mix: ProgressMixture
                     ) -> list[CheckRecord]:
    """The per-goal records for the two-goal progress mixture (the ids of ``STRUCTURED_IDS``)."""
    attacker = profile.attacker
    trie = mass_trie(attacker, start=game.start)
    sigma: dict[int, tuple[Fraction, ...]] = {}
    for mix_walks in attacker:
        for mw in mix_walks:
            p = 0
            for v, dist in zip(mw.walk[1:], mix.along(game, mw.walk), strict=True):
                p = trie.extend(p, v)
                sigma[p] = dist
    tdef = TableDefender(instance=game, trie=trie, sigma=sigma, default=None)
    per_type: list[Number] = []
    for theta, mix_walks in enumerate(attacker):
        total = Fraction(0)
        for mw in mix_walks:
            cost = Fraction(game.dist_to[theta][mw.walk[-1]])
            for k, dist in enumerate(mix.along(game, mw.walk)):
                w = game.weight(mw.walk[k], mw.walk[k + 1])
                assert w is not None
                cost += Fraction(w) * dist[theta]
            total += mw.probability * cost
        per_type.append(normalize(total))
    walks = sum(len(m) for m in attacker)
    out = [per_goal_record(STRUCTURED_IDS[0], "pass", f"2 types, {walks} walks, Defender: "
                        f"{mix.describe(game)} (defined on every walk)",
                        {"walks": walks, "prefixes": len(trie)}, PROFILE_DOC, None)]
    u = normalize(sum((game.prior[t] * Fraction(per_type[t]) for t in range(2)), Fraction(0)))
    out.append(payoff_record(per_type, u, None))
    out.append(_mixture_attacker(game, mix, per_type))
    out += defender_records(game, tdef, dict(enumerate(trie.masses)), u)
    out.append(value_record(game, u, None, all(r.passed for r in out)))
    return out


def _mixture_attacker(game: Instance, mix: ProgressMixture, per_type: Sequence[Number]
                      ) -> CheckRecord:
    cid = "pbne.attacker_br"
    nums: dict[str, Number | None] = {}
    found = []
    for theta in range(2):
        r = mixture_response(game, mix, theta, per_type[theta])
        nums[f"regret{theta + 1}"] = (None if r.value is None
                                      else normalize(Fraction(per_type[theta]) - Fraction(r.value)))
        found.append(r)
    nums["states"] = sum(r.states for r in found)
    undecided = [r for r in found if r.value is None]
    if undecided:
        return per_goal_record(cid, "error", f"could not decide type {undecided[0].theta + 1}'s "
                            f"regret: {undecided[0].how}", nums, MIXTURE, BR)
    bad = [r for r in found if r.value is not None and r.value < per_type[r.theta]]
    if bad:
        r = max(bad, key=lambda x: Fraction(per_type[x.theta]) - Fraction(x.value or 0))
        assert r.walk is not None and r.value is not None
        regret = normalize(Fraction(per_type[r.theta]) - Fraction(r.value))
        return per_goal_record(cid, "fail", f"type {r.theta + 1} (goal {_goal(game, r.theta)}) "
                            f"has regret {regret}: "
                            f"walk {walk_labels(game, r.walk)} ({len(r.walk) - 1} steps) costs "
                            f"{r.value} against the mixture ({r.how})", nums, MIXTURE, BR)
    hows = "; ".join(sorted({r.how for r in found}))
    return per_goal_record(cid, "pass", f"every type's exact regret over all walks of any length "
                        f"is 0 ({hows})", nums, MIXTURE, BR)
