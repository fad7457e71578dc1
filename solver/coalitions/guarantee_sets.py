"""The exact guarantee sets of the N-goal game at ``H = inf``, on a refined set of facet normals.

The normal-restricted DP over a set ``A`` of facet normals (:mod:`solver.coalitions.normal_dp`)
has outer sets ``F_v ⊇ G_v``; they are the exact sets when they pass the arc test
(:mod:`solver.coalitions.arc_test`). :func:`guarantee_sets` finds ``A`` by *refinement*: the
DP with the 0/1 normals, the arc test ``F_v ⊆ F_u + wΔ`` at its fixpoint; where it fails, the
DP is re-run with the test at every layer, and at the first failing layer ``k`` (every earlier
layer then *is* the exact set) the exact set ``G_v^k = ∩_u (F_u^{k-1} + wΔ)`` at a failing
node is written out in H-representation (:mod:`solver.coalitions.local_facets`), its facets
that ``F_v^k`` violates are found (a candidate is a facet iff the other candidates do not
cover it as cheaply: one exact LP), and they join ``A`` with their permutations. Every
normal added is a facet normal of an exact layer set (or a permutation of one), so the
refinement stops whenever the exact layers repeat (proofs/NEXACT.md NX.6); a budget of rounds,
layers, normals and bases bounds it otherwise, and the caller reports the bracket.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from solver.coalitions.arc_graph import ArcGraph
from solver.coalitions.arc_test import arc_failures
from solver.coalitions.budget import Budget, BudgetExceeded
from solver.coalitions.local_facets import local_facets
from solver.coalitions.normal_dp import (
    Fixpoint,
    LayerFailure,
    fixpoint_failures,
    layered_dp,
    normal_dp,
)
from solver.coalitions.normal_system import NormalSystem, symmetric_closure
from solver.coalitions.vertex_tables import Normal, zero_one_normals


@dataclass(frozen=True, eq=False)
class GuaranteeSets:
    """The certified fixpoint: normals, exact support numbers, ranks.

    Attributes
    ----------
    fixpoint : Fixpoint
        The repeated layer over the final normals; its sets satisfy the arc condition at
        every walkable arc (so they are the exact sets ``G_v`` of the untruncated game).
    rounds : int
        Refinement rounds used (0: the 0/1 normals sufficed).
    """

    fixpoint: Fixpoint
    rounds: int

    @property
    def normals(self) -> tuple[Normal, ...]:
        """``A``: the 0/1 vectors, then the extra normals."""
        return self.fixpoint.system.normals

    @property
    def extra_normals(self) -> tuple[Normal, ...]:
        """The normals that are not 0/1 vectors."""
        return tuple(a for a in self.normals if any(x > 1 for x in a))


@dataclass(frozen=True)
class Unreached:
    """What :func:`guarantee_sets` knows when the budget ends: an upper bound's DP (the last
    fixpoint found, an outer approximation) and why it stopped."""

    reason: str
    upper: Fixpoint | None


HEURISTIC_ROUNDS = 3
"""Rounds that take the missing facets at the fixpoint itself (fast, no termination proof);
after them every round takes them at the first failing layer (proofs/NEXACT.md NX.6)."""


def guarantee_sets(graph: ArcGraph, budget: Budget | None = None,
                   initial: Sequence[Normal] = ()) -> GuaranteeSets | Unreached:
    """The exact guarantee sets at ``H = inf``: the refined normal-restricted DP, certified.

    Each round runs the DP to its fixpoint and tests the arc condition at every walkable arc;
    where it fails, the facets of ``∩_u (F_u + wΔ)`` that ``F_v`` violates join the normals
    (with their permutations): for the first :data:`HEURISTIC_ROUNDS` rounds at the fixpoint,
    afterwards at the first failing layer of a run tested layer by layer, where every earlier
    layer is exact, so that each normal added is a facet of an exact layer set (NX.6).

    Returns :class:`GuaranteeSets` when a fixpoint passes the arc test at every walkable arc,
    else :class:`Unreached` with the reason (the budget) and the best outer DP found.
    ``initial`` normals (with their permutations) join the 0/1 vectors from the start.

    Examples
    --------
    Two goals one step from the start: the 0/1 normals suffice, no refinement:

    >>> graph = ArcGraph(indptr=np.array([0, 2, 2, 2]), heads=np.array([1, 2]),
    ...                  weights=np.array([1, 1]), denominator=1, goals=(1, 2),
    ...                  terminal=np.array([[0, 2], [2, 0]]), start=0)
    >>> found = guarantee_sets(graph)
    >>> found.rounds, found.extra_normals, [str(found.fixpoint.value(2, 0))]
    (0, (), ['2'])
    """
    budget = Budget() if budget is None else budget
    n_goals = graph.n_goals
    max_layers = budget.layers if budget.layers is not None else 20 * graph.n_nodes + 200
    system = NormalSystem(symmetric_closure([*zero_one_normals(n_goals), *initial]))
    best: Fixpoint | None = None
    rounds = 0
    while True:
        try:
            fix = normal_dp(graph, system, max_layers)
        except BudgetExceeded as exc:
            return Unreached(str(exc), best)
        best = fix
        failing = fixpoint_failures(graph, fix)
        if not failing.size:
            return GuaranteeSets(fix, rounds)
        if rounds >= budget.rounds:
            return Unreached(f"no certified fixpoint within {budget.rounds} refinement rounds",
                             best)
        rounds += 1
        new: list[Normal] = []
        if rounds <= HEURISTIC_ROUNDS:
            # the fixpoint's own failures (no layer: -1; its ranks are not needed)
            at_fix = LayerFailure(-1, failing, np.arange(graph.n_nodes), fix.m, fix.m,
                                  fix.finite, fix.scale)
            for v in failing[:8]:
                new += local_facets(graph, system, at_fix, int(v), 8)
        if not new:  # the proved route: the first failing layer
            try:
                run = layered_dp(graph, system, check_layers=True, max_layers=max_layers)
            except BudgetExceeded as exc:
                return Unreached(str(exc), best)
            if isinstance(run, Fixpoint):  # pragma: no cover - NX.5: every layer exact
                return Unreached("a fixpoint whose layers all pass fails the arc test", best)
            for v in run.tails[:8]:
                new += local_facets(graph, system, run, int(v), 8)
        if not new:  # pragma: no cover - a failing layer always misses a facet (NX.6)
            return Unreached("no missing facet found at a failing layer", best)
        normals = symmetric_closure(list(system.normals) + new)
        if len(normals) - (2 ** n_goals - 1) > budget.extra_normals:
            return Unreached(f"more than {budget.extra_normals} extra normals needed", best)
        try:
            system = NormalSystem(normals)
        except ValueError as exc:
            return Unreached(str(exc), best)


def dominated_failures(graph: ArcGraph, normals: tuple[Normal, ...], max_layers: int
                       ) -> tuple[Fixpoint, list[Normal]]:
    """The rule's sets under the format's dominated reading (``docs/formats.md`` §2b) and the
    primitive directions in which they fail the arc test at some walkable arc (empty: the
    written rule's sets pass).

    Raises
    ------
    BudgetExceeded
        When the dominated DP does not repeat a layer within ``max_layers``.
    """
    system = NormalSystem(normals, dominated=True)
    fix = normal_dp(graph, system, max_layers)
    tails, heads = graph.tails, graph.heads
    keep = fix.finite[tails] & fix.finite[heads]
    w = graph.weights[keep] * (fix.scale // graph.denominator)
    _, bad = arc_failures(system, fix.m, fix.m, tails[keep], heads[keep], w)
    return fix, bad
