"""`dpp audit` through click's CliRunner: exit codes 0/1/2, one-line errors, files on failure,
the --solver-cmd route, and the `dpp` group."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner, Result

from dppverify.cli.audit import audit_command
from dppverify.cli.certify import certify_command
from solver.adapter import solve_json

ROOT = Path(__file__).resolve().parents[3]
SOLVER_CMD = f"{sys.executable} {ROOT / 'examples' / 'solver_cmd.py'} {{instance}} {{profile}}"


def run(*args: str) -> Result:
    result = CliRunner().invoke(audit_command, list(args))
    assert "Traceback" not in result.output
    assert result.exception is None or isinstance(result.exception, SystemExit)
    return result


def test_exit_0_when_every_example_is_certified(tmp_path: Path) -> None:
    out = tmp_path / "out"
    result = run("--solver", "solver.adapter:solve_json", "--examples", "25", "--seed", "3",
                 "--output-dir", str(out))
    assert result.exit_code == 0, result.output
    assert "audit PASS: 25 examples certified (seed 3" in result.output
    assert not out.exists()  # nothing written on success


def test_exit_1_writes_the_minimal_failure(tmp_path: Path) -> None:
    out = tmp_path / "failure"
    result = run("--solver", "tests.mutants.solvers:mutant_drop_phase_ii", "--examples", "300",
                 "--max-nodes", "6", "--shrink-calls", "150", "--output-dir", str(out))
    assert result.exit_code == 1, result.output
    assert "audit FAIL after" in result.output
    assert "failing check: pbne." in result.output
    names = sorted(p.name for p in out.iterdir())
    assert names == ["certificate.json", "failure.json", "instance.json", "profile.json"]
    instance = json.loads((out / "instance.json").read_text())
    assert len(instance["graph"]["nodes"]) <= 6
    assert json.loads((out / "certificate.json").read_text())["verdict"] == "fail"
    failure = json.loads((out / "failure.json").read_text())
    assert failure["check"] in result.output
    # the written files reproduce the refutation with `dpp certify`...
    cert = CliRunner().invoke(certify_command, [str(out / "instance.json"),
                                                str(out / "profile.json")])
    assert cert.exit_code == 1, cert.output
    # ...and the real solver is certified on the same minimal instance
    good = tmp_path / "good.json"
    good.write_text(json.dumps(solve_json(instance)))
    cert = CliRunner().invoke(certify_command, [str(out / "instance.json"), str(good)])
    assert cert.exit_code == 0, cert.output


def test_solver_errors_are_failures_not_crashes(tmp_path: Path) -> None:
    result = run("--solver", "json:dumps", "--examples", "5", "--no-shrink",
                 "--output-dir", str(tmp_path))
    assert result.exit_code == 1
    assert "failing check: solver.output" in result.output
    assert (tmp_path / "instance.json").exists()
    assert not (tmp_path / "profile.json").exists()


def test_solver_cmd_route_passes() -> None:
    result = run("--solver-cmd", SOLVER_CMD, "--examples", "8")
    assert result.exit_code == 0, result.output
    assert "8 examples certified" in result.output


def test_solver_cmd_failures(tmp_path: Path) -> None:
    crash = f"{sys.executable} -c 'import sys; sys.exit(\"boom\")' {{instance}} {{profile}}"
    result = run("--solver-cmd", crash, "--examples", "3", "--output-dir", str(tmp_path / "a"))
    assert result.exit_code == 1
    assert "command exited 1: boom" in result.output
    copy = "cp {instance} {profile}"  # "solves" by echoing the instance: not a profile
    result = run("--solver-cmd", copy, "--examples", "3", "--output-dir", str(tmp_path / "b"))
    assert result.exit_code == 1
    assert "failing check: profile.format" in result.output


@pytest.mark.parametrize("args, message", [
    (["--solver", "nocolon"], "must look like MODULE:FUNCTION"),
    (["--solver", "no_such_module_xyz:f"], "cannot import module"),
    (["--solver", "json:nope"], "has no attribute"),
    (["--solver", "json:__doc__"], "is not callable"),
    ([], "exactly one of"),
    (["--solver", "json:dumps", "--solver-cmd", "p {instance} {profile}"], "exactly one of"),
    (["--solver-cmd", "prog {instance}"], "must contain {instance} and {profile}"),
    (["--solver-cmd", "prog '{instance} {profile}"], "--solver-cmd"),
])
def test_bad_input_exits_2_with_one_line(args: list[str], message: str) -> None:
    result = run(*args)
    assert result.exit_code == 2
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ") and message in lines[0]


@pytest.mark.parametrize("args", [["--examples", "0"], ["--max-nodes", "1"],
                                  ["--seed", "x"]])
def test_bad_options_exit_2(args: list[str]) -> None:
    result = run("--solver", "solver.adapter:solve_json", *args)
    assert result.exit_code == 2


def test_audit_through_the_dpp_group() -> None:
    from dpp import main

    result = CliRunner().invoke(main, ["audit", "--solver", "solver.adapter:solve_json",
                                       "--examples", "3"])
    assert "Traceback" not in result.output
    assert result.exit_code == 0, result.output


def test_pruning_goes_towards_undirected_unit_weight_graphs() -> None:
    """The shrunk failing instance kept fractional weights on a directed graph,
    although shrinking goes towards small undirected unit-weight graphs (docs/audit.md)."""
    from dppverify.audit.examine import examine
    from dppverify.audit.pruning import prune_failure

    def stay_put(doc):  # type: ignore[no-untyped-def]  # fails on every graph
        s = doc["start"]
        return {"format": "dpp-profile/1",
                "attacker": {"primary": [{"path": [s], "probability": "1"}],
                             "secondary": [{"path": [s], "probability": "1"}]}}

    doc = {"graph": {"directed": True, "nodes": [{"id": i} for i in range(3)],
                     "edges": [{"source": 0, "target": 1, "weight": "3/2"},
                               {"source": 0, "target": 2, "weight": "5/3"},
                               {"source": 1, "target": 2, "weight": "7/2"},
                               {"source": 2, "target": 1, "weight": "1/2"}]},
           "start": 0, "goals": [1, 2], "prior": ["1/2", "1/2"]}
    pruned, _ = prune_failure(stay_put, examine(stay_put, doc))
    graph = pruned.instance["graph"]
    assert pruned.check == "profile.wellformed"
    assert not graph.get("directed") and all(e.get("weight", 1) == 1 for e in graph["edges"])
