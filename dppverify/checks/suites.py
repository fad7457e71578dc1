"""The check suites: for each family of checks, the engines that run it on each route.

:func:`dppverify.certify` runs one flow for every profile (inputs read once, the horizon
checked, the route chosen, the routes run and merged, one certificate); what differs between
the families of :mod:`dppverify.registry` is asked of the profile's :class:`Suite`
(:func:`suite_of`, by the profile's format):

- ``two-goal`` (``dpp-profile/1``): the paper's primary and secondary types; the two-goal
  mathematics runs behind its ids — σ*, the phases, the lemmas L1–L5, TEL and XI2 on the walk
  tree (:data:`~dppverify.checks.runners.TREE_RUNNERS`), the three-field value DP and
  :mod:`dppverify.twogoal.progress_br` on the structured route
  (:mod:`dppverify.checks.structured`), which keeps the speed on million-cell maps;
- ``per-goal`` (``dpp-ngoal-profile/1``, any N): one type per goal index
  (:mod:`dppverify.tree_route.per_goal_checks`, :mod:`dppverify.checks.structured_per_goal`).

Another kind of game plugs in here: its profile format, its family of checks in the registry
and a :class:`Suite` in :data:`SUITES`.
"""

from __future__ import annotations

import sys
from collections.abc import Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any, Protocol

from tqdm import tqdm

from dppverify.certificate import CheckRecord
from dppverify.checks.runners import TREE_RUNNERS, in_registry_order
from dppverify.checks.structured import structured_checks
from dppverify.checks.structured_per_goal import per_goal_structured_checks
from dppverify.errors import LPError, UndecidedError
from dppverify.game.instance import Instance, arc_arrays, node_to_json
from dppverify.game.profile import PER_GOAL_PROFILE_FORMAT, PROFILE_FORMAT, Profile
from dppverify.registry import Family, checks_of
from dppverify.tree_route.context import Context, make_context
from dppverify.tree_route.per_goal_checks import per_goal_tree_checks
from dppverify.tree_route.tree import build_tree

__all__ = ["SUITES", "Options", "Run", "Suite", "shortest_horizon", "suite_of"]

NTABLE_UNDECIDED = (
    "the untruncated game (H = inf) cannot be decided for this profile: its Defender table has "
    "no \"default\" and does not list every walk of the game, so it is undefined on some; a "
    "\"default\" distribution would decide it, or --horizon H certifies the game truncated "
    "at H")
"""Why a per-goal table without default (that leaves walks unlisted) cannot be certified on
the untruncated game."""


@dataclass(frozen=True)
class Options:
    """What the engines take besides the game: the walk tree's size guard, the seed and the
    number of the random attackers (two-goal lemmas L3, L4), progress bars on stderr."""

    max_prefixes: int
    seed: int = 0
    trials: int = 5
    progress: bool = False


@dataclass(frozen=True)
class Run:
    """One route's records (in registry order, tagged with the route) and its sizes:
    the tree's ``prefixes``, ``leaves`` and ``horizon``, the structured route's trie."""

    records: list[CheckRecord]
    prefixes: int = 0
    leaves: int = 0
    horizon: int | None = None
    trie_prefixes: int = 0


@dataclass(frozen=True)
class Players:
    """The certificate's description of the game: ``info``, and each type's goal label and
    prior in the exploitability record's order; ``seed`` when the random attackers ran."""

    info: Mapping[str, Any]
    goals: list[Any]
    priors: list[Fraction]
    seeded: bool = field(default=True)


class Suite(Protocol):
    """How one family of checks is certified (see the module docstring)."""

    family: Family
    exact_only: bool

    def longest(self, instance: Instance, profile: Profile) -> tuple[int, str]:
        """The least finite horizon accepted, and the word for a walk in the refusal."""
        ...

    def tree_only(self, profile: Profile) -> bool:
        """True when only the walk tree certifies the profile on a truncated game."""
        ...

    def on_tree(self, instance: Instance, profile: Profile, horizon: int,
                options: Options) -> Run:
        """The tree route's run at ``horizon``."""
        ...

    def structured(self, instance: Instance, profile: Profile, horizon: int | None) -> Run:
        """The structured route's run (``horizon`` None: the untruncated game)."""
        ...

    def players(self, instance: Instance, profile: Profile, trie_prefixes: int | None
                ) -> Players:
        """The certificate's description (``trie_prefixes`` when the structured route ran)."""
        ...


def shortest_horizon(instance: Instance, profile: Profile) -> int:
    """The shortest horizon a truncated game needs for a two-goal profile: its longest walk
    (at least the steps to the nearest goal).

    This is never a default: a profile under test is not known to be an equilibrium, and
    truncating at its own length hides the longer deviations that would refute it
    (proofs/HORIZON.md, H.5). Without a horizon :func:`dppverify.certify` certifies the
    untruncated game.

    Examples
    --------
    On ``s – a – g1``, ``a – g2``, a secondary walk that goes back and forth takes 4 steps:

    >>> from dppverify.game.instance import instance_from_json
    >>> from dppverify.game.profile import profile_from_json
    >>> inst = instance_from_json({"graph": {"nodes": [{"id": v} for v in ("s", "a", "g1", "g2")],
    ...     "edges": [{"source": "s", "target": "a"}, {"source": "a", "target": "g1"},
    ...               {"source": "a", "target": "g2"}]},
    ...     "start": "s", "goals": ["g1", "g2"], "prior": ["1/2", "1/2"]})
    >>> doc = {"format": "dpp-profile/1", "goals": {"primary": "g1", "secondary": "g2"},
    ...     "defender": {"rule": "progress", "goal": "g1"},
    ...     "attacker": {"primary": [{"path": ["s", "a", "g1"], "probability": 1}],
    ...                  "secondary": [{"path": ["s", "a", "s", "a", "g2"], "probability": 1}]}}
    >>> shortest_horizon(inst, profile_from_json(doc, inst))
    4
    >>> shortest_horizon(inst, profile_from_json({"format": "dpp-profile/1"}, inst))
    2
    """
    lengths = [len(w.walk) - 1 for w in (*profile.primary, *profile.secondary)]
    return max([*lengths, instance.hops[instance.start]])


class TwoGoalSuite:
    """The ``two-goal`` family: a ``dpp-profile/1`` profile of a two-goal instance."""

    family: Family = "two-goal"
    exact_only = False

    def longest(self, instance: Instance, profile: Profile) -> tuple[int, str]:
        return shortest_horizon(instance, profile), "path"

    def tree_only(self, profile: Profile) -> bool:
        return profile.defender is not None and profile.defender.table

    def on_tree(self, instance: Instance, profile: Profile, horizon: int,
                options: Options) -> Run:
        tree = build_tree(instance, horizon, max_prefixes=options.max_prefixes,
                          progress=options.progress)
        with tqdm(total=len(checks_of(self.family)) + 1, desc="certify: strategies on the tree",
                  unit="check", disable=not options.progress, leave=False,
                  file=sys.stderr) as bar:
            ctx = make_context(instance, tree, profile, seed=options.seed, trials=options.trials)
            bar.update(1)
            records = _run_tree_checks(ctx, bar)
        return Run(records, tree.n_prefixes, tree.n_leaves, horizon)

    def structured(self, instance: Instance, profile: Profile, horizon: int | None) -> Run:
        return Run(in_registry_order(structured_checks(instance, profile, horizon),
                                     "structured"), horizon=horizon)

    def players(self, instance: Instance, profile: Profile, trie_prefixes: int | None
                ) -> Players:
        roles = instance.roles(profile.primary_goal_index)
        goals = [node_to_json(instance.nodes[roles.g1]), node_to_json(instance.nodes[roles.g2])]
        info = {"nodes": instance.n_nodes, "arcs": int(arc_arrays(instance).heads.size),
                "start": node_to_json(instance.nodes[instance.start]),
                "primary": goals[0], "secondary": goals[1],
                "prior": [str(roles.b1), str(roles.b2)],
                "defender_rule": profile.stated.rule}
        return Players(info, goals, [roles.b1, roles.b2])


class PerGoalSuite:
    """The ``per-goal`` family: a ``dpp-ngoal-profile/1`` profile, any number of goals."""

    family: Family = "per-goal"
    exact_only = True

    def longest(self, instance: Instance, profile: Profile) -> tuple[int, str]:
        return profile.longest, "walk"

    def tree_only(self, profile: Profile) -> bool:
        return False

    def on_tree(self, instance: Instance, profile: Profile, horizon: int,
                options: Options) -> Run:
        records, tree = per_goal_tree_checks(instance, profile, horizon, options.max_prefixes)
        return Run(records, tree.n_prefixes, tree.n_leaves, tree.horizon)

    def structured(self, instance: Instance, profile: Profile, horizon: int | None) -> Run:
        records, size = per_goal_structured_checks(instance, profile, horizon)
        rule = profile.defender
        if horizon is None and rule is not None and not rule.defined_everywhere:
            br = next((r for r in records if r.id == "pbne.attacker_br"), None)
            if br is not None and br.status == "error":  # undefined off the table: undecided
                raise UndecidedError(NTABLE_UNDECIDED)
        return Run(records, horizon=horizon, trie_prefixes=size)

    def players(self, instance: Instance, profile: Profile, trie_prefixes: int | None
                ) -> Players:
        info: dict[str, Any] = {"goals": instance.n_goals, "nodes": instance.n_nodes,
                                "game": "N goals"}
        if trie_prefixes is not None:
            info["trie_prefixes"] = trie_prefixes
        return Players(info, [node_to_json(instance.nodes[g]) for g in instance.goals],
                       list(instance.prior), seeded=False)


SUITES: dict[str, Suite] = {PROFILE_FORMAT: TwoGoalSuite(),
                            PER_GOAL_PROFILE_FORMAT: PerGoalSuite()}
"""The suite of each profile format."""


def suite_of(profile: Profile) -> Suite:
    """The suite that certifies ``profile`` (by its format).

    Examples
    --------
    >>> from dppverify.game.examples import star3, star3_profile
    >>> from dppverify.game.profile import profile_from_json
    >>> suite_of(profile_from_json(star3_profile(), star3())).family
    'per-goal'
    """
    return SUITES[profile.format]


def _run_tree_checks(ctx: Context, bar: tqdm | None = None) -> list[CheckRecord]:
    """Every two-goal tree check in registry order; ``bar`` names each check as it starts."""
    out: list[CheckRecord] = []
    for s in checks_of("two-goal"):
        if s.id not in TREE_RUNNERS:
            continue
        ids, fn = TREE_RUNNERS[s.id].ids, TREE_RUNNERS[s.id].run
        if bar is not None:
            bar.set_description(f"certify: {', '.join(ids)}")
        try:
            records = fn(ctx)
        except LPError as exc:
            records = [CheckRecord(i, "error", f"LP failure: {exc}") for i in ids]
        out += records
        if bar is not None:
            bar.update(len(ids))
    return in_registry_order(out, "tree")
