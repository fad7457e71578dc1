"""The tree route's runners, declared: for every check id, the function that computes it.

:data:`TREE_RUNNERS` is plain data, read by ``certify`` in registry order
(:data:`~dppverify.registry.CHECKS`); nothing is registered at import time. A runner takes
the shared :class:`~dppverify.tree_route.context.Context` and returns the records of its
ids, in that order. A runner of checks about the profile (:func:`on_profile`) is called
with an :class:`~dppverify.tree_route.context.EvaluatedContext` only: for an ill-formed
profile its records are ``skipped``.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass

from dppverify.certificate import CheckRecord
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
from dppverify.registry import CHECKS, RouteName, spec
from dppverify.tree_route.context import Context, EvaluatedContext

__all__ = ["TREE_RUNNERS", "Runner", "in_registry_order", "on_profile", "runner_of"]

Run = Callable[[Context], list[CheckRecord]]


@dataclass(frozen=True)
class Runner:
    """The function ``run`` computing the records ``ids`` (in that order) on the tree.

    Examples
    --------
    >>> runner_of("value.U1").ids
    ('value.U1', 'value.U2', 'value.U', 'value.VoI')
    """

    ids: tuple[str, ...]
    run: Run


def _one(check_id: str, fn: Callable[[Context], CheckRecord]) -> Runner:
    return Runner((check_id,), lambda ctx: [fn(ctx)])


def on_profile(ids: tuple[str, ...],
               fn: Callable[[EvaluatedContext], list[CheckRecord]]) -> Runner:
    """A runner of checks about the profile: ``fn`` is called with an
    :class:`~dppverify.tree_route.context.EvaluatedContext` only; for an ill-formed profile
    the records are ``skipped``.

    Examples
    --------
    >>> from tests.dppverify.checks.doctest_inputs import triangle_context
    >>> r = on_profile(("pbne.defender_br",), lambda ctx: [])
    >>> [(x.id, x.status) for x in r.run(triangle_context({"primary": []}))]
    [('pbne.defender_br', 'skipped')]
    """
    def run(ctx: Context) -> list[CheckRecord]:
        if isinstance(ctx, EvaluatedContext):
            return fn(ctx)
        return [skipped(i, spec(i).proof) for i in ids]
    return Runner(ids, run)


def _one_on_profile(check_id: str, fn: Callable[[EvaluatedContext], CheckRecord]) -> Runner:
    return on_profile((check_id,), lambda ctx: [fn(ctx)])


_RUNNERS: tuple[Runner, ...] = (
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
)

TREE_RUNNERS: dict[str, Runner] = {r.ids[0]: r for r in _RUNNERS}
"""The tree route's runners keyed by the first id each computes (registry order)."""


def runner_of(check_id: str) -> Runner:
    """The tree runner whose first record is ``check_id`` (KeyError if none).

    Examples
    --------
    >>> runner_of("lemma.L3.greedy").ids
    ('lemma.L3.greedy',)
    >>> from dppverify.registry import checks_of
    >>> [i for r in TREE_RUNNERS.values() for i in r.ids] == [
    ...     c.id for c in checks_of("two-goal") if "tree" in c.routes]
    True
    """
    return TREE_RUNNERS[check_id]


def in_registry_order(records: list[CheckRecord], route: RouteName) -> list[CheckRecord]:
    """The two-goal records in registry order, each tagged with its route and what it relies
    on; a check of the route without a record becomes an ``error`` record (never a silent gap).

    Examples
    --------
    >>> recs = in_registry_order([CheckRecord("value.U", "pass", "")], "tree")
    >>> len(recs), recs[0].status, recs[3].route, recs[3].relies_on
    (19, 'error', 'tree', 'the walk tree of H steps')
    """
    by_id = {r.id: r for r in records}
    out = []
    for s in CHECKS:
        if s.family != "two-goal" or route not in s.routes:
            continue
        r = by_id.get(s.id)
        if r is None:
            r = CheckRecord(s.id, "error", "internal: the check produced no record", {}, s.proof)
        relies = s.tree if route == "tree" else s.structured
        out.append(dataclasses.replace(r, route=route, relies_on=r.relies_on or relies))
    return out
