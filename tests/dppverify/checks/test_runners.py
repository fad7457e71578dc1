"""The one runner table: every check of every family and route has one runner, in registry
order, and the one loop never leaves a silent gap."""

from __future__ import annotations

import pytest

from dppverify.checks import runners
from dppverify.checks.runners import RUNNERS, Runner, run_checks, runners_of
from dppverify.errors import LPError
from dppverify.registry import FAMILIES, checks_of


@pytest.mark.parametrize("family", FAMILIES)
@pytest.mark.parametrize("route", ["tree", "structured"])
def test_every_check_has_one_runner_in_registry_order(family: str, route: str) -> None:
    ids = [i for r in runners_of(family, route) for i in r.ids]  # type: ignore[arg-type]
    assert ids == [c.id for c in checks_of(family) if route in c.routes]  # type: ignore[arg-type]


def test_the_table_holds_nothing_else() -> None:
    assert {(r.family, r.route) for r in RUNNERS} == {
        (f, route) for f in FAMILIES for route in ("tree", "structured")
        if any(route in c.routes for c in checks_of(f))}  # type: ignore[arg-type]
    assert ("selection", "tree") not in {(r.family, r.route) for r in RUNNERS}


def test_an_lp_failure_and_a_missing_record_are_errors(monkeypatch: pytest.MonkeyPatch) -> None:
    def fails(ctx: object) -> list:
        raise LPError("did not solve")

    monkeypatch.setattr(runners, "RUNNERS", (
        Runner(("profile.wellformed",), lambda ctx: [], "per-goal"),
        Runner(("value.U", "pbne.attacker_br"), fails, "per-goal")))
    recs = {r.id: r for r in run_checks("per-goal", "tree", object())}
    assert len(recs) == len(checks_of("per-goal"))
    assert recs["value.U"].status == "error" and recs["value.U"].message == (
        "LP failure: did not solve")
    assert recs["profile.wellformed"].status == "error"
    assert "produced no record" in recs["pbne.defender_br"].message
    assert all(r.route == "tree" for r in recs.values())
