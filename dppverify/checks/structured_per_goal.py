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

from typing import cast

from dppverify.certificate import CheckRecord
from dppverify.checks.per_goal_records import (
    BR,
    NWALKBR,
    PROFILE_DOC,
    STRUCTURED_IDS,
    per_goal_record,
    profile_records,
    walk_labels,
)
from dppverify.checks.structured_guarantee import guarantee_checks
from dppverify.exact import INF, Number, normalize
from dppverify.game.instance import Instance
from dppverify.game.profile import GoalTable, Profile
from dppverify.structured.table_br import TableDefender, exit_costs, walk_best_response
from dppverify.structured.trie import mass_trie

__all__ = ["per_goal_structured_checks"]


def per_goal_structured_checks(instance: Instance, profile: Profile,
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
    >>> prof = profile_from_json(star3_profile(), inst)
    >>> recs, size = per_goal_structured_checks(inst, prof, None)
    >>> [(r.id, r.status) for r in recs][2:4], size
    ([('pbne.attacker_br', 'fail'), ('pbne.defender_br', 'pass')], 5)
    >>> recs[2].message
    "type 2 (goal 'b') has regret 1: walk ['s', 'm', 's', 'm', 'b'] (4 steps) costs 0"
    """
    inst = instance
    n = inst.n_goals
    if profile.defects:
        more = f" (and {len(profile.defects) - 1} more)" if len(profile.defects) > 1 else ""
        return _ill_formed(f"{profile.defects[0]}{more}"), 0
    if profile.defender is not None and profile.defender.kind == "guarantee":
        return guarantee_checks(inst, profile, horizon)  # dppverify.structured.guarantee
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
        return _ill_formed(f"the Defender's table has no entry for walk "
                           f"{walk_labels(inst, missing)} and no default"), len(trie)
    has_default = table.default is not None
    text = (f"{n} types, {len(walks)} walks, Defender table of {len(table.entries)} entries "
            + ("and a default (defined on every walk)" if has_default else "without a default"))
    longest = max(len(w) - 1 for w in walks)
    covered = horizon is None or horizon >= longest  # NW.5: U = V_H for every H >= longest
    out = profile_records(inst, text, {"walks": len(walks), "prefixes": len(trie)}, per_type,
                          profile.claimed_u, _attacker(inst, tdef, per_type, horizon), tdef,
                          dict(enumerate(trie.masses)), horizon, covered=covered)
    return out, len(trie)


def _ill_formed(message: str) -> list[CheckRecord]:
    """``profile.wellformed`` fails with ``message``; every other check is skipped."""
    return ([per_goal_record(STRUCTURED_IDS[0], "fail", message, None, PROFILE_DOC, None)]
            + [per_goal_record(i, "skipped", "the profile is not well formed", None, "–")
               for i in STRUCTURED_IDS[1:]])


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
                f"({len(walk) - 1} steps) costs {v}", nums, NWALKBR, BR)


