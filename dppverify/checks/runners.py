"""The one runner table: for every check of every family and route, the function computing it.

:data:`RUNNERS` is plain data (nothing is registered at import time); :func:`run_checks` is
the one loop that runs a family's runners on a route, in registry order
(:data:`~dppverify.registry.CHECKS`), and :func:`in_registry_order` checks that every id of
the route has its record. A runner takes its family's context for the route and returns the
records of its ids, in that order:

- two-goal, tree: :class:`~dppverify.tree_route.context.Context` (σ*, the lemmas' facts: the
  two-goal mathematics behind the ids);
- per-goal, tree: :class:`~dppverify.tree_route.per_goal_checks.PerGoalTree`;
- two-goal, structured: :class:`~dppverify.checks.structured.TwoGoalStructured`;
- per-goal, structured: :class:`~dppverify.checks.structured_per_goal.PerGoalStructured`
  (the profile evaluated by its Defender's engine, chosen there by the rule's ``kind``).

A runner of checks about the profile (:func:`on_profile`) runs only on a profile that can be
evaluated; otherwise its records are ``skipped``.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from dppverify.certificate import CheckRecord
from dppverify.checks import structured as st
from dppverify.checks import structured_per_goal as spg
from dppverify.checks.attacker import attacker_br
from dppverify.checks.beliefs import belief_consistency
from dppverify.checks.defender import defender_br, sequential_rationality
from dppverify.checks.lemmas import (
    l1_lower_bound,
    l2_no_revisits,
    l3_greedy,
    l4_monotonicity,
    l5_induced_beliefs,
    telescoping,
    xi2_secondary_value,
)
from dppverify.checks.payoffs import value_check, values
from dppverify.checks.skipped import skipped
from dppverify.checks.wellformed import phases, wellformed
from dppverify.errors import LPError
from dppverify.registry import CHECKS, Family, RouteName, check_ids, spec
from dppverify.tree_route import per_goal_checks as pg
from dppverify.tree_route.context import EvaluatedContext

__all__ = ["RUNNERS", "Runner", "in_registry_order", "on_profile", "run_checks",
           "runners_of"]


@dataclass(frozen=True)
class Runner:
    """The function ``run`` computing the records ``ids`` (in that order) of ``family`` on
    ``route``, from the family's context for the route.

    Examples
    --------
    >>> [r.ids for r in runners_of("two-goal", "tree")][1]
    ('value.U1', 'value.U2', 'value.U', 'value.VoI')
    """

    ids: tuple[str, ...]
    run: Callable[[Any], list[CheckRecord]]
    family: Family = "two-goal"
    route: RouteName = "tree"


def on_profile(ids: tuple[str, ...], fn: Callable[[Any], list[CheckRecord]],
               family: Family = "two-goal") -> Runner:
    """A tree runner of checks about the profile: ``fn`` runs on a profile that can be
    evaluated (two goals: an :class:`~dppverify.tree_route.context.EvaluatedContext`; per
    goal: a well-formed profile); otherwise the records are ``skipped``.

    Examples
    --------
    >>> from tests.dppverify.checks.doctest_inputs import triangle_context
    >>> r = on_profile(("pbne.defender_br",), lambda ctx: [])
    >>> [(x.id, x.status) for x in r.run(triangle_context({"primary": []}))]
    [('pbne.defender_br', 'skipped')]
    """
    def run(ctx: Any) -> list[CheckRecord]:
        if family == "per-goal":
            return fn(ctx) if ctx.wellformed else [
                CheckRecord(i, "skipped", pg.NOT_WELL_FORMED) for i in ids]
        if isinstance(ctx, EvaluatedContext):
            return fn(ctx)
        return [skipped(i, spec(i).proof) for i in ids]
    return Runner(ids, run, family)


def _structured(ids: tuple[str, ...], fn: Callable[[Any], Any], *, always: bool = False,
                skip_proof: str | None = None) -> Runner:
    """A two-goal structured runner: ``fn`` on a usable profile (``always``: any profile),
    else ``skipped`` records (``skip_proof`` their proof)."""
    def run(ctx: st.TwoGoalStructured) -> list[CheckRecord]:
        if always or ctx.usable:
            got = fn(ctx)
            return got if isinstance(got, list) else [got]
        return [st.skipped_record(i, skip_proof) for i in ids]
    return Runner(ids, run, "two-goal", "structured")


def _per_goal_structured(ids: tuple[str, ...], fn: Callable[[Any], Any], *,
                         always: bool = False) -> Runner:
    """A per-goal structured runner: ``fn`` on a well-formed profile (``always``: any), else
    ``skipped`` records."""
    def run(ctx: spg.PerGoalStructured) -> list[CheckRecord]:
        if always or ctx.wellformed:
            got = fn(ctx)
            return got if isinstance(got, list) else [got]
        return [spg.skipped_record(i) for i in ids]
    return Runner(ids, run, "per-goal", "structured")


def _one(check_id: str, fn: Callable[[Any], CheckRecord], family: Family = "two-goal"
         ) -> Runner:
    return Runner((check_id,), lambda ctx: [fn(ctx)], family)


def _one_on_profile(check_id: str, fn: Callable[[Any], CheckRecord],
                    family: Family = "two-goal") -> Runner:
    return on_profile((check_id,), lambda ctx: [fn(ctx)], family)


def _selection(ctx: Any) -> list[CheckRecord]:
    """The goal-selection family's records: its context
    (:class:`~dppverify.checks.selection.SelectionContext`) runs this table's per-goal
    structured rows on the game at the choice, then the family's own checks."""
    return list(ctx.records())


RUNNERS: tuple[Runner, ...] = (
    _one("profile.wellformed", wellformed),
    on_profile(("value.U1", "value.U2", "value.U", "value.VoI"), values),
    _one("profile.phases", phases),
    _one_on_profile("pbne.attacker_br.primary", lambda ctx: attacker_br(ctx, 1)),
    _one_on_profile("pbne.attacker_br.secondary", lambda ctx: attacker_br(ctx, 2)),
    _one_on_profile("pbne.defender_br", defender_br),
    _one_on_profile("pbne.sequential_rationality", sequential_rationality),
    _one_on_profile("pbne.belief_consistency", belief_consistency),
    _one("game.value", value_check),
    _one("lemma.TEL.telescoping", telescoping),
    _one("lemma.L1.lower_bound", l1_lower_bound),
    _one("lemma.L2.no_revisits", l2_no_revisits),
    _one("lemma.XI2.secondary_value", xi2_secondary_value),
    _one("lemma.L3.greedy", l3_greedy),
    _one("lemma.L4.monotonicity", l4_monotonicity),
    _one_on_profile("lemma.L5.induced_beliefs", l5_induced_beliefs),
    _one("profile.wellformed", pg.wellformed_record, "per-goal"),
    _one_on_profile("value.U", pg.payoff_record, "per-goal"),
    _one_on_profile("pbne.attacker_br", pg.attacker_record, "per-goal"),
    _one_on_profile("pbne.defender_br", pg.defender_record, "per-goal"),
    _one_on_profile("pbne.sequential_rationality", pg.sequential_record, "per-goal"),
    on_profile(("game.value", "game.value.structured"), pg.value_records, "per-goal"),
    _structured(("profile.wellformed",), st.wellformed_record, always=True),
    _structured(("value.U1", "value.U2", "value.U", "value.VoI"), st.values_records),
    _structured(("profile.phases",), st.phases_record),
    _structured(("pbne.attacker_br.primary", "pbne.attacker_br.secondary"),
                st.attacker_records),
    _structured(("pbne.defender_br",), st.defender_record),
    _structured(("pbne.sequential_rationality",), st.sequential_record),
    _structured(("pbne.belief_consistency",), st.belief_record),
    _structured(("game.value",), st.game_value_record),
    _structured(("lemma.TEL.telescoping",), st.telescoping_record),
    _structured(("lemma.L1.lower_bound",), st.l1_record),
    _structured(("lemma.L2.no_revisits",), st.l2_record),
    _structured(("lemma.XI2.secondary_value",), st.xi2_record, always=True),
    _structured(("lemma.L5.induced_beliefs",), st.l5_record, skip_proof="L5"),
    _per_goal_structured(("profile.wellformed",), spg.wellformed_record, always=True),
    _per_goal_structured(("value.U",), spg.payoff_record_of),
    _per_goal_structured(("pbne.attacker_br",), spg.attacker_record),
    _per_goal_structured(("pbne.defender_br", "pbne.sequential_rationality"),
                         spg.defender_records_of),
    _per_goal_structured(("game.value",), spg.value_record_of),
    Runner(check_ids("selection"), _selection, "selection", "structured"),
)
"""Every runner, each family's and route's in registry order."""


def runners_of(family: Family, route: RouteName) -> tuple[Runner, ...]:
    """The runners of ``family`` on ``route``, in registry order.

    Examples
    --------
    >>> from dppverify.registry import checks_of
    >>> [i for r in runners_of("per-goal", "tree") for i in r.ids] == [
    ...     c.id for c in checks_of("per-goal") if "tree" in c.routes]
    True
    """
    return tuple(r for r in RUNNERS if r.family == family and r.route == route)


def run_checks(family: Family, route: RouteName, ctx: Any, bar: Any = None
               ) -> list[CheckRecord]:
    """Every check of ``family`` on ``route`` in registry order, from the context ``ctx``;
    an LP failure is an ``error`` record of the runner's ids; ``bar`` (a tqdm bar) names each
    runner as it starts.

    Examples
    --------
    >>> from tests.dppverify.checks.doctest_inputs import triangle_context
    >>> [r.status for r in run_checks("two-goal", "tree", triangle_context())][:4]
    ['pass', 'pass', 'pass', 'pass']
    """
    out: list[CheckRecord] = []
    for runner in runners_of(family, route):
        if bar is not None:
            bar.set_description(f"certify: {', '.join(runner.ids)}")
        try:
            records = runner.run(ctx)
        except LPError as exc:
            records = [CheckRecord(i, "error", f"LP failure: {exc}") for i in runner.ids]
        out += records
        if bar is not None:
            bar.update(len(runner.ids))
    return in_registry_order(out, route, family)


def in_registry_order(records: list[CheckRecord], route: RouteName,
                      family: Family = "two-goal") -> list[CheckRecord]:
    """The records of ``family`` in registry order, each tagged with its route and what it
    relies on; a check of the route without a record becomes an ``error`` record (never a
    silent gap).

    Examples
    --------
    >>> recs = in_registry_order([CheckRecord("value.U", "pass", "")], "tree")
    >>> len(recs), recs[0].status, recs[3].route, recs[3].relies_on
    (19, 'error', 'tree', 'the walk tree of H steps')
    """
    by_id = {r.id: r for r in records}
    out = []
    for s in CHECKS:
        if s.family != family or route not in s.routes:
            continue
        r = by_id.get(s.id)
        if r is None:
            r = CheckRecord(s.id, "error", "internal: the check produced no record", {}, s.proof)
        relies = s.tree if route == "tree" else s.structured
        out.append(dataclasses.replace(r, route=route, relies_on=r.relies_on or relies))
    return out

