"""The structured route's records of a per-goal profile (``dpp-ngoal-profile/1``): no walk tree.

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
``game.value.structured`` (the DP against the tree LP) is not run here: the DP is this route's
value.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from functools import cached_property
from typing import cast

from dppio.text import count
from dppverify.certificate import CheckRecord
from dppverify.checks.per_goal_records import (
    BR,
    NWALKBR,
    PROFILE_DOC,
    STRUCTURED_IDS,
    Evaluated,
    defender_records,
    payoff_record,
    per_goal_record,
    value_record,
    walk_labels,
)
from dppverify.checks.structured_guarantee import guarantee_evaluation
from dppverify.exact import INF, Number, normalize
from dppverify.game.instance import Instance
from dppverify.game.profile import GoalTable, Profile
from dppverify.structured.table_br import TableDefender, exit_costs, walk_best_response
from dppverify.structured.trie import mass_trie

__all__ = ["ENGINES", "Evaluation", "PerGoalStructured"]


Evaluation = tuple[Evaluated | str, int]
"""An engine's result: the profile evaluated on the trie of its walks, or why it is not well
formed; and the size of that trie."""


@dataclass(frozen=True, eq=False)
class PerGoalStructured:
    """A per-goal profile on the structured route: what its checks share, each part computed
    once. The profile is evaluated by its Defender's engine (:data:`ENGINES`, by the rule's
    ``kind``: a table, or the guarantee rule of :mod:`dppverify.checks.structured_guarantee`).

    Attributes
    ----------
    instance, profile
        The game and the resolved profile.
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
    >>> ctx = PerGoalStructured(inst, profile_from_json(star3_profile(), inst), None)
    >>> ctx.trie_prefixes, attacker_record(ctx).message
    (5, "type 2 (goal 'b') has regret 1: walk ['s', 'm', 's', 'm', 'b'] (4 steps) costs 0")
    """

    instance: Instance
    profile: Profile
    horizon: int | None

    @cached_property
    def evaluation(self) -> Evaluation:
        """The engine's result (:data:`Evaluation`)."""
        defects = self.profile.defects
        if defects:
            more = f" (and {len(defects) - 1} more)" if len(defects) > 1 else ""
            return f"{defects[0]}{more}", 0
        rule = self.profile.defender
        assert rule is not None  # well formed: a Defender
        return ENGINES[rule.kind](self.instance, self.profile, self.horizon)

    @property
    def wellformed(self) -> bool:
        """True when the checks about the profile can run."""
        return not isinstance(self.evaluation[0], str)

    @property
    def ev(self) -> Evaluated:
        """The evaluated profile (a well-formed profile only)."""
        ev = self.evaluation[0]
        assert not isinstance(ev, str)  # the runners call the profile's checks only then
        return ev

    @property
    def trie_prefixes(self) -> int:
        """The size of the trie of the profile's walks."""
        return self.evaluation[1]

    @cached_property
    def u(self) -> Number:
        """``U = Σ_θ b_θ U^θ``."""
        inst = self.instance
        return normalize(sum((inst.prior[t] * self.ev.per_type[t] for t in range(inst.n_goals)),
                             Fraction(0)))

    @cached_property
    def payoff(self) -> CheckRecord:
        """``value.U``."""
        return payoff_record(self.ev.per_type, self.u, self.profile.claimed_u)

    @cached_property
    def defender(self) -> list[CheckRecord]:
        """``pbne.defender_br`` and ``pbne.sequential_rationality``."""
        return defender_records(self.instance, self.ev.defender, self.ev.mass, self.u)


def wellformed_record(ctx: PerGoalStructured) -> CheckRecord:
    """``profile.wellformed``: why the profile is ill formed, or what the engine evaluated."""
    ev = ctx.evaluation[0]
    if isinstance(ev, str):
        return per_goal_record(STRUCTURED_IDS[0], "fail", ev, None, PROFILE_DOC, None)
    return per_goal_record(STRUCTURED_IDS[0], "pass", ev.described, ev.sizes, PROFILE_DOC, None)


def payoff_record_of(ctx: PerGoalStructured) -> CheckRecord:
    """``value.U``: every type's payoff, walk by walk, and ``U``."""
    return ctx.payoff


def attacker_record(ctx: PerGoalStructured) -> CheckRecord:
    """``pbne.attacker_br``: every type's exact regret over all walks, from the engine."""
    return ctx.ev.attacker


def defender_records_of(ctx: PerGoalStructured) -> list[CheckRecord]:
    """``pbne.defender_br`` and ``pbne.sequential_rationality`` on the prefixes with mass."""
    return ctx.defender


def value_record_of(ctx: PerGoalStructured) -> CheckRecord:
    """``game.value``: ``U`` against the structured value at ``H``; where only a bracket is
    known, decisive for an equilibrium (every record before it passed, ``H`` covering the
    profile's walks)."""
    before = [wellformed_record(ctx), ctx.payoff, ctx.ev.attacker, *ctx.defender]
    return value_record(ctx.instance, ctx.u, ctx.horizon,
                        ctx.ev.covered and all(r.passed for r in before), ctx.ev.known)


def skipped_record(check_id: str) -> CheckRecord:
    """A check after an ill-formed profile."""
    return per_goal_record(check_id, "skipped", "the profile is not well formed", None, "–")


def table_evaluation(inst: Instance, profile: Profile, horizon: int | None) -> Evaluation:
    """The engine of a table Defender: payoffs walk by walk on the trie of the profile's walks
    and every type's best response over all walks (:func:`_attacker`)."""
    n = inst.n_goals
    walks = [mw.walk for mix in profile.attacker for mw in mix]
    # realization masses x_θ(p) on the profile's walks, then the table's entries
    trie = mass_trie(profile.attacker, start=inst.start)
    table = cast(GoalTable, profile.defender)  # well formed: a table, or the guarantee rule
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
        return (f"the Defender's table has no entry for walk {walk_labels(inst, missing)} and "
                f"no default"), len(trie)
    has_default = table.default is not None
    text = (f"{n} types, {len(walks)} walks, Defender table of {len(table.entries)} entries "
            + ("and a default (defined on every walk)" if has_default else "without a default"))
    longest = max(len(w) - 1 for w in walks)
    covered = horizon is None or horizon >= longest  # NW.5: U = V_H for every H >= longest
    ev = Evaluated(text, {"walks": len(walks), "prefixes": len(trie)}, per_type,
                   _attacker(inst, tdef, per_type, horizon), tdef, dict(enumerate(trie.masses)),
                   covered=covered)
    return ev, len(trie)


def _attacker(inst: Instance, tdef: TableDefender, per_type: list[Number],
              horizon: int | None) -> CheckRecord:
    """``pbne.attacker_br``: every type's exact regret over all walks (NW.1).

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
            return per_goal_record("pbne.attacker_br", "error", f"the Defender has no default "
                        f"and its table has no entry for walk "
                        f"{walk_labels(inst, br.undefined)}: no best response over all walks "
                        f"can be computed (give a default, or certify on the walk tree: --route "
                        f"tree)", None, NWALKBR, BR)
        regret = normalize(per_type[theta] - br.value) if br.value != INF else -INF
        regrets.append((regret, theta, br.walk, br.value))
    nums: dict[str, Number | None] = {f"regret{t + 1}": r for r, t, _, _ in regrets}
    if any(r < 0 for r, _, _, _ in regrets):
        r, t, _, v = min(regrets, key=lambda x: x[0])
        return per_goal_record("pbne.attacker_br", "error", f"type {t + 1}'s profile cost is "
                    f"below its minimum over all walks {v} (regret {r}): the checker's "
                    f"computations disagree", nums, NWALKBR, BR)
    worst = max(regrets, key=lambda x: x[0])
    if worst[0] == 0:
        return per_goal_record("pbne.attacker_br", "pass", "every type's exact regret over all "
                    "walks of any length is 0", nums, NWALKBR, BR)
    within = [x for x in regrets if x[0] > 0 and (horizon is None or len(x[2]) - 1 <= horizon)]
    if not within:
        r, t, walk, v = worst
        return per_goal_record("pbne.attacker_br", "skipped", f"type {t + 1}'s regret over "
                    f"walks of any length is {r} (walk {walk_labels(inst, walk)}, "
                    f"{len(walk) - 1} steps > H = {horizon}); whether a walk of at most "
                    f"{horizon} steps beats the profile is not decided by the structured route "
                    f"(use --route tree, or omit the horizon)", nums, NWALKBR, BR)
    r, t, walk, v = max(within, key=lambda x: x[0])
    return per_goal_record("pbne.attacker_br", "fail", f"type {t + 1} (goal "
                f"{inst.nodes[inst.goals[t]]!r}) has regret {r}: walk {walk_labels(inst, walk)} "
                f"({count(len(walk) - 1, 'step')}) costs {v}", nums, NWALKBR, BR)




ENGINES: dict[str, Callable[[Instance, Profile, int | None], Evaluation]] = {
    "table": table_evaluation, "guarantee": guarantee_evaluation}
"""The engine of each Defender ``kind`` of a per-goal profile."""
