"""Audit campaigns are nested. Example i depends only on the seed, i and the
generator's settings, never on the budget: a budget of N audits exactly the first N examples
of a larger budget, and a solver caught at example k is caught there by every budget >= k.

The solver runs in this process through a recording runner, so the test sees every game the
campaign hands it, in order.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest

from dppverify.audit import Answer, AuditConfig, AuditReport, SolverRunner, run_audit
from dppverify.audit.campaign import game_key
from dppverify.audit.runner import call_in_process
from solver.adapter import solve_json
from tests.mutants.solvers import (
    mutant_drop_phase_ii,
    mutant_first_walk_only,
    mutant_swapped_mixing,
)

Doc = dict[str, Any]


class Recording(SolverRunner):
    """Calls ``solve`` in this process and records every game it is given."""

    def __init__(self, solve: Callable[[Doc], Any]) -> None:
        self.solve = solve
        self.games: list[str] = []

    def __call__(self, doc: Doc) -> Answer:
        self.games.append(game_key(doc))
        return call_in_process(self.solve, doc)


def audit(solve: Callable[[Doc], Any], examples: int, seed: int,
          max_nodes: int = 8) -> tuple[AuditReport, list[str]]:
    runner = Recording(solve)
    report = run_audit(runner, AuditConfig(examples=examples, seed=seed, max_nodes=max_nodes,
                                           shrink=False))
    return report, runner.games


@pytest.mark.parametrize("seed, max_nodes", [(0, 8), (1, 8), (7, 5)])
def test_budget_n_audits_the_first_n_games_of_budget_2n(seed: int, max_nodes: int) -> None:
    small, games_n = audit(solve_json, 12, seed, max_nodes)
    large, games_2n = audit(solve_json, 24, seed, max_nodes)
    assert small.passed and large.passed, (small.summary(), large.summary())
    assert small.examples == 12 and large.examples == 24
    assert games_n == games_2n[:len(games_n)]
    assert len(set(games_2n)) == len(games_2n)  # examples are distinct games


@pytest.mark.parametrize("solve, seed", [(mutant_drop_phase_ii, 0), (mutant_swapped_mixing, 1),
                                         (mutant_first_walk_only, 2),
                                         (mutant_first_walk_only, 4)])
def test_a_solver_caught_at_k_is_caught_at_k_by_every_budget_from_k(
        solve: Callable[[Doc], Any], seed: int) -> None:
    wide, games = audit(solve, 80, seed)
    assert not wide.passed, wide.summary()
    k = wide.examples
    assert k >= 2, "pick a seed where the mutant passes some examples first"
    for budget in (k, k + 1, 2 * k):
        report, seen = audit(solve, budget, seed)
        assert not report.passed and report.examples == k, (budget, report.summary())
        assert report.failure is not None and wide.failure is not None
        assert report.failure.check == wide.failure.check
        assert seen == games
    below, seen = audit(solve, k - 1, seed)
    assert below.passed and below.examples == k - 1, below.summary()
    assert seen == games[:k - 1]


def test_the_real_solver_sees_the_mutants_games() -> None:
    """The stream of games does not depend on the solver: before a mutant's first failure,
    the real solver is handed exactly the same games."""
    wide, games = audit(mutant_drop_phase_ii, 80, 0)
    assert not wide.passed
    _, real = audit(solve_json, wide.examples, 0)
    assert real == games
