"""Mutation evidence: `dpp audit` catches every deliberately wrong solver of
``tests/mutants/solvers.py`` within its example budget, and the real solver passes the same
budget. The table of examples used is printed (``pytest -s``) and quoted in docs/audit.md.
"""

from __future__ import annotations

from typing import Any

import pytest
from hypothesis import strategies as st

from dppverify.audit import AuditConfig, run_audit
from solver.adapter import solve_json
from tests.mutants.solvers import MUTANTS

BUDGET = 300
"""Examples per audit (the real solver must pass all of them)."""

SEED = 0

GAME_CHECKS = ("profile.wellformed", "pbne.")
"""A mutant must be caught by the game itself: well-formedness or an equilibrium check."""


def test_there_are_at_least_eight_mutants() -> None:
    assert len(MUTANTS) >= 8
    assert all(fn.__name__.startswith("mutant_") for fn in MUTANTS.values())


def test_audit_catches_every_mutant_within_budget() -> None:
    rows = []
    for name, mutant in MUTANTS.items():
        report = run_audit(mutant, AuditConfig(examples=BUDGET, seed=SEED, shrink=False))
        assert not report.passed, f"the audit missed the mutant {name!r}"
        assert report.failure is not None
        assert report.failure.check.startswith(GAME_CHECKS), report.failure.message
        # the failing instance is a fair one: the real solver is certified on it
        fair = run_audit(solve_json, AuditConfig(examples=1),
                         strategy=_just(report.failure.instance))
        assert fair.passed, fair.summary()
        rows.append((name, report.examples, report.failure.check))
    width = max(len(r[0]) for r in rows)
    print(f"\n{'mutant':<{width}}  examples  first failing check  (budget {BUDGET}, seed {SEED})")
    for name, n, check in rows:
        print(f"{name:<{width}}  {n:>8}  {check}")


def test_the_real_solver_passes_the_same_budget() -> None:
    report = run_audit(solve_json, AuditConfig(examples=BUDGET, seed=SEED))
    assert report.passed, report.summary()
    assert report.examples + report.skipped >= BUDGET * 9 // 10


@pytest.mark.slow
@pytest.mark.parametrize("name", list(MUTANTS))
def test_mutant_detection_over_seeds_with_shrinking(name: str) -> None:
    """Examples needed for seeds 0-4, and the shrunk failing instance of seed 0."""
    used = []
    for seed in range(5):
        report = run_audit(MUTANTS[name],
                           AuditConfig(examples=BUDGET, seed=seed, shrink=seed == 0))
        assert not report.passed, f"seed {seed}: missed {name!r}"
        used.append(report.examples)
        if seed == 0:
            assert report.failure is not None
            print(f"\n{name}: minimal {report.failure.check}: {report.failure.instance}")
    print(f"{name}: examples used for seeds 0-4: {used}")


def _just(doc: dict[str, Any]) -> st.SearchStrategy[dict[str, Any]]:
    return st.just(doc)
