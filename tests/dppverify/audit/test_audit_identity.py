"""The audit's shrinking stays on the first failure; its traceback is kept.

A solver that fails one way on larger instances and another way on small ones: shrinking must
not slide from the first failure (its check id, or its exception type and place) to the
other, and the final report, ``failure.json`` and ``DPP_DEBUG=1`` name the first one.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from click.testing import CliRunner
from hypothesis import strategies as st

from dppverify.audit import AuditConfig, run_audit
from dppverify.audit.examine import examine
from dppverify.cli.audit import audit_command
from dppverify.game.examples import triangle_document
from dppverify.strategies import instances, weighted_graphs

Doc = dict[str, Any]


def two_faced(doc: Doc) -> Doc:
    """ValueError on instances of 4+ nodes, KeyError on smaller ones."""
    if len(doc["graph"]["nodes"]) >= 4:
        raise ValueError("big instance")
    raise KeyError("small instance")


def wrong_then_raising(doc: Doc) -> Doc:
    """A non-equilibrium profile on 4+ nodes (stay at the start), a crash on smaller ones."""
    if len(doc["graph"]["nodes"]) < 4:
        raise RuntimeError("small instance")
    s = doc["start"]
    return {"format": "dpp-profile/1",
            "attacker": {"primary": [{"path": [s], "probability": 1}],
                         "secondary": [{"path": [s], "probability": 1}]}}


BIG = instances(graphs=weighted_graphs(min_nodes=2, max_nodes=6))


def _big_first() -> st.SearchStrategy[Doc]:
    return BIG.filter(lambda d: d["start"] not in d["goals"])


def test_shrinking_keeps_the_exception_type_and_place(tmp_path: Path) -> None:
    report = run_audit(two_faced, AuditConfig(examples=60, seed=3, out=tmp_path / "fail",
                                              shrink_calls=80, shrink_seconds=60),
                       strategy=_big_first())
    assert not report.passed and report.first_failure is not None
    first = report.first_failure
    assert first.where.startswith("ValueError@")  # the generated examples have 4+ nodes
    assert report.failure is not None and report.failure.identity == first.identity
    failure = json.loads((tmp_path / "fail" / "failure.json").read_text())
    assert failure["identity"] == first.identity
    assert "Traceback (most recent call last)" in failure["traceback"]
    assert first.where.split("@")[0] in failure["traceback"]


def test_shrinking_keeps_the_check_id(tmp_path: Path) -> None:
    report = run_audit(wrong_then_raising, AuditConfig(examples=60, seed=5, shrink_calls=80,
                                                       shrink_seconds=60),
                       strategy=_big_first())
    assert not report.passed and report.first_failure is not None
    assert report.failure is not None
    assert report.failure.identity == report.first_failure.identity
    assert report.first_failure.check == "profile.wellformed"
    assert len(report.failure.instance["graph"]["nodes"]) >= 4  # never slid to the crash


def test_identity_of_outcomes() -> None:
    a = examine(two_faced, triangle_document())   # 3 nodes: KeyError
    assert a.check == "solver.error" and a.identity.startswith("solver.error:KeyError@")
    assert a.identity.endswith(f":{two_faced.__code__.co_firstlineno + 4}")
    assert "KeyError" in a.traceback


def test_dpp_debug_prints_the_solvers_traceback(tmp_path: Path, monkeypatch: Any) -> None:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "crashy.py").write_text("def solve(doc):\n    raise KeyError('boom')\n")
    args = ["--solver", "crashy:solve", "--examples", "3", "--no-shrink",
            "--output-dir", str(tmp_path / "out")]
    quiet = CliRunner().invoke(audit_command, args)
    assert quiet.exit_code == 1 and "Traceback" not in quiet.output
    monkeypatch.setenv("DPP_DEBUG", "1")
    loud = CliRunner().invoke(audit_command, args)
    assert loud.exit_code == 1
    assert "Traceback (most recent call last)" in loud.output and "KeyError: 'boom'" in loud.output
    failure = json.loads((tmp_path / "out" / "failure.json").read_text())
    assert "KeyError: 'boom'" in failure["traceback"]
