"""One verdict: the failure folder ``dpp audit`` writes for each deliberately wrong
solver replays to the same verdict with ``dpp certify`` and with ``dppverify.certify()``: the
same exit code (the one ``failure.json`` records) and the same first failing check.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from dppverify import certify
from dppverify.certificate import Certificate
from dppverify.cli.audit import audit_command
from dppverify.cli.certify import VERDICT_EXIT, certify_command
from tests.mutants.solvers import MUTANTS


def _first_failing(cert: Certificate) -> str:
    """The check the audit names: the first failing one that decides the verdict."""
    bad = [c for c in cert.checks if c.status != "pass" and c.kind != "fact"]
    return next((c.id for c in bad if c.status == "fail"), bad[0].id)


def _audit(name: str, out: Path, *extra: str) -> dict[str, object]:
    result = CliRunner().invoke(audit_command, [
        "--solver", f"tests.mutants.solvers:{MUTANTS[name].__name__}", "--examples", "300",
        "--output-dir", str(out), *extra])
    assert result.exit_code == 1, result.output
    failure: dict[str, object] = json.loads((out / "failure.json").read_text())
    return failure


def _replays(out: Path, failure: dict[str, object]) -> None:
    instance, profile = out / "instance.json", out / "profile.json"
    cli = CliRunner().invoke(certify_command, [str(instance), str(profile)])
    assert cli.exit_code == failure["certify_exit"] == 1, (cli.output, failure)
    row = next(line for line in cli.stdout.splitlines() if line.startswith(f"{failure['check']} "))
    assert row.split()[1] == "fail", row
    api = certify(instance, profile)
    assert VERDICT_EXIT[api.verdict] == failure["certify_exit"]
    assert _first_failing(api) == failure["check"]
    written = json.loads((out / "certificate.json").read_text())
    assert written["verdict"] == api.verdict == "fail"


@pytest.mark.parametrize("name", list(MUTANTS))
def test_the_failure_folder_replays_to_the_same_verdict(name: str, tmp_path: Path) -> None:
    out = tmp_path / "failure"
    _replays(out, _audit(name, out, "--no-shrink"))


@pytest.mark.slow
@pytest.mark.parametrize("name", list(MUTANTS))
def test_the_shrunk_failure_folder_replays_to_the_same_verdict(name: str,
                                                               tmp_path: Path) -> None:
    out = tmp_path / "failure"
    _replays(out, _audit(name, out, "--shrink-calls", "60", "--max-nodes", "6"))
