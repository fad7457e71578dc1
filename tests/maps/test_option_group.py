"""The ``--map`` option group on every command that takes an instance (CliRunner).

Every such command — solve, certify, value, export-efg, plot map, plot beliefs, experiment
compare — accepts ``--map FILE --start R,C --goals R,C R,C --prior p,q [--connectivity 4|8]``
(one definition, ``dppio.cli.map_options``), gives the same result as with the instance JSON
that ``dpp solve --save-instance`` writes for that grid, and reports every mistake in the
group as one line with exit code 2, leaving no file behind.
"""

from __future__ import annotations

import hashlib
import json
import os
import subprocess
import sys
from pathlib import Path

import click
import pytest
from click.testing import CliRunner

from dpp import main
from dppverify.__main__ import main as checker_main
from dppverify.game.instance import instance_from_json as checker_from_json
from dppverify.game.instance import load_instance as checker_load
from solver.formats.movingai import read_map
from solver.game.instance import Instance
from solver.game.instance_reading import load_instance
from solver.game.instance_writing import instance_to_json
from tests.maps._maps import ROOT, TINY_MAP

START, G1, G2 = "2,0", "0,3", "0,0"
GROUP = ["--start", START, "--goals", G1, G2, "--prior", "0.6,0.4"]
GROUP_PARAMS = ("map_file", "start", "goals", "prior_text", "connectivity")


def _run(*args: str, group: click.Group = main) -> tuple[int, str, str]:
    result = CliRunner().invoke(group, list(args))
    assert result.exception is None or isinstance(result.exception, SystemExit), result
    return result.exit_code, result.stdout, result.stderr


@pytest.fixture(scope="module")
def tiny(tmp_path_factory: pytest.TempPathFactory) -> Path:
    m = tmp_path_factory.mktemp("map") / "tiny.map"
    m.write_text(TINY_MAP)
    return m


@pytest.fixture(scope="module")
def saved(tmp_path_factory: pytest.TempPathFactory, tiny: Path) -> tuple[Path, Path]:
    """(instance JSON, profile JSON) of the tiny grid, written by dpp solve."""
    d = tmp_path_factory.mktemp("saved")
    inst, prof = d / "tiny.json", d / "tiny.profile.json"
    code, out, err = _run("solve", "--map", str(tiny), *GROUP, "-o", str(prof),
                          "--save-instance", str(inst))
    assert code == 0, err
    assert f"wrote {inst}" in err and f"wrote {prof}" in err and out == ""
    return inst, prof


def _command(path: str) -> click.Command:
    cmd: click.Command = main
    for name in path.split():
        assert isinstance(cmd, click.Group)
        cmd = cmd.commands[name]
    return cmd


INSTANCE_COMMANDS = ["solve", "certify", "value", "export-efg", "plot map", "plot beliefs",
                     "experiment compare"]


TWO_GOAL_COMMANDS = {"plot beliefs", "experiment compare"}  # their help says two goals


def test_one_definition_of_the_group_on_every_command() -> None:
    references: dict[bool, list[object]] = {}
    for path in INSTANCE_COMMANDS:
        params = {p.name: p for p in _command(path).params}
        group = [params[name] for name in GROUP_PARAMS]
        described = [(p.opts, p.nargs, p.help if isinstance(p, click.Option) else None)
                     for p in group]
        two = path in TWO_GOAL_COMMANDS
        assert references.setdefault(two, described) == described, path
        assert params["instance"].required is False
    assert "two goal" in str(references[True][2]) and "N-goal" in str(references[False][2])
    reference = references[False]
    assert reference is not None and reference[2][0] == ["--goals"]
    goals = {p.name: p for p in _command("solve").params}["goals"]
    assert goals.metavar == "R,C R,C [R,C ...]"  # two cells, or N for an N-goal game


def test_save_instance_writes_the_grid_instance(saved: tuple[Path, Path], tiny: Path) -> None:
    """A --map game is saved as the compact dpp-map-instance/1 document (docs/formats.md §1c):
    the map by reference (relative to the saved file) and its sha256; both packages read it
    as the grid instance of the full instance JSON."""
    inst, prof = saved
    expected = Instance.from_grid(read_map(tiny), (2, 0), ((0, 3), (0, 0)), ("3/5", "2/5"))
    doc = json.loads(inst.read_text())
    assert doc == {"format": "dpp-map-instance/1",
                   "map": os.path.relpath(tiny, inst.parent),
                   "map_sha256": hashlib.sha256(tiny.read_bytes()).hexdigest(),
                   "start": [2, 0], "goals": [[0, 3], [0, 0]], "prior": ["3/5", "2/5"],
                   "connectivity": 4}
    full = json.loads(json.dumps(instance_to_json(expected)))
    assert instance_to_json(load_instance(inst)) == full
    checker, reference = checker_load(inst), checker_from_json(full)
    assert (checker.nodes, tuple(checker.succ), checker.dist_to, checker.prior) == \
        (reference.nodes, tuple(reference.succ), reference.dist_to, reference.prior)
    assert json.loads(prof.read_text())["goals"] == {"primary": [0, 3], "secondary": [0, 0]}
    # solving the saved instance gives the same profile
    code, out, _ = _run("solve", str(inst), "--json")
    assert code == 0 and json.loads(out) == json.loads(prof.read_text())


def test_save_instance_without_o_and_with_json(tmp_path: Path, tiny: Path) -> None:
    inst = tmp_path / "only.json"
    code, out, err = _run("solve", "--map", str(tiny), *GROUP, "--json", "--save-instance",
                          str(inst))
    assert code == 0 and json.loads(out)["format"] == "dpp-profile/1"
    assert f"wrote {inst}" in err and json.loads(inst.read_text())["start"] == [2, 0]


def test_save_instance_and_o_must_differ(tmp_path: Path, tiny: Path) -> None:
    target = tmp_path / "same.json"
    code, _, err = _run("solve", "--map", str(tiny), *GROUP, "-o", str(target),
                        "--save-instance", str(target))
    assert code == 2 and "name the same file" in err and not target.exists()


def test_failed_solve_writes_neither_file(tmp_path: Path) -> None:
    wall = tmp_path / "wall.map"
    wall.write_text("type octile\nheight 3\nwidth 3\nmap\n.@.\n.@.\n.@.\n")
    before = set(tmp_path.iterdir())
    code, _, err = _run("solve", "--map", str(wall), "--start", "0,0", "--goals", "2,2", "0,2",
                        "--prior", "0.6,0.4", "-o", str(tmp_path / "p.json"),
                        "--save-instance", str(tmp_path / "i.json"))
    assert code == 2 and "unreachable" in err and len(err.strip().splitlines()) == 1
    assert set(tmp_path.iterdir()) == before


def test_certify_with_map_takes_just_the_profile(saved: tuple[Path, Path], tiny: Path) -> None:
    inst, prof = saved
    code, out, err = _run("certify", "--map", str(tiny), *GROUP, str(prof), "--json")
    assert code == 0, err
    via_map = json.loads(out)
    code, out, _ = _run("certify", str(inst), str(prof), "--json")
    via_file = json.loads(out)
    # the same game, the same checks; the provenance says which input each came from
    map_prov, file_prov = via_map.pop("provenance"), via_file.pop("provenance")
    assert code == 0 and via_file == via_map
    assert map_prov["profile"] == file_prov["profile"]
    assert map_prov["instance"]["bytes"] == "canonical-json" and "map" in map_prov["instance"]
    assert file_prov["instance"]["bytes"] == "file"
    assert via_map["verdict"] == "pass"
    # a profile for another prior is refuted on the map game
    code, out, _ = _run("certify", "--map", str(tiny), "--start", START, "--goals", G1, G2,
                        "--prior", "0.7,0.3", str(prof))
    assert code in (1, 2) and "PASS" not in out


def test_value_with_map_equals_value_of_saved_instance(saved: tuple[Path, Path],
                                                       tiny: Path) -> None:
    inst, _ = saved
    code, out, err = _run("value", "--map", str(tiny), *GROUP, "-H", "6", "--json")
    assert code == 0, err
    via_map = json.loads(out)
    code, out, _ = _run("value", str(inst), "-H", "6", "--json")
    via_file = json.loads(out)
    for key in ("value", "lower", "upper", "exact"):
        assert via_map[key] == via_file[key]
    assert via_map["tree"]["details"]["tree"] == via_file["tree"]["details"]["tree"]
    assert via_map["exact"] is True and via_map["tree"]["details"]["tree"]["prefixes"] > 1


def test_export_efg_with_map(saved: tuple[Path, Path], tiny: Path, tmp_path: Path) -> None:
    inst, _ = saved
    a, b = tmp_path / "a.efg", tmp_path / "b.efg"
    assert _run("export-efg", "--map", str(tiny), *GROUP, "-H", "2", "-o", str(a))[0] == 0
    assert _run("export-efg", str(inst), "-H", "2", "-o", str(b))[0] == 0
    assert a.read_text() == b.read_text() and a.read_text().startswith("EFG 2 R")


def test_experiment_compare_with_map(saved: tuple[Path, Path], tiny: Path) -> None:
    inst, _ = saved
    code, via_map, err = _run("experiment", "compare", "--map", str(tiny), *GROUP)
    assert code == 0, err
    assert _run("experiment", "compare", str(inst))[1] == via_map
    assert "σ*" in via_map and "γ*" in via_map


@pytest.mark.parametrize("kind", ["map", "beliefs"])
def test_plots_with_map(tiny: Path, tmp_path: Path, kind: str) -> None:
    target = tmp_path / f"{kind}.png"
    code, _, err = _run("plot", kind, "--map", str(tiny), *GROUP, "-o", str(target))
    assert code == 0, err
    assert target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_octile_connectivity(tiny: Path) -> None:
    code, out, err = _run("solve", "--map", str(tiny), *GROUP, "--connectivity", "8", "--json")
    assert code == 0, err
    doc = json.loads(out)
    assert doc["exact"] is False
    code, out4, _ = _run("solve", "--map", str(tiny), *GROUP, "--json")
    assert json.loads(out4)["exact"] is True and json.loads(out4) != doc
    code, out, _ = _run("value", "--map", str(tiny), *GROUP, "--connectivity", "8", "-H", "4",
                        "--json")
    assert code == 0 and json.loads(out)["exact"] is False


def test_checker_alone_reads_maps(tiny: Path) -> None:
    """``python -m dppverify`` (no solver) takes the same group and gives the same value."""
    args = ["value", "--map", str(tiny), *GROUP, "-H", "5", "--json"]
    code, out, err = _run(*args, group=checker_main)
    assert code == 0, err
    proc = subprocess.run([sys.executable, "-c",
                           "import sys\nfrom dppverify.__main__ import main\n"
                           "try:\n    main(sys.argv[1:], prog_name='dppverify')\n"
                           "finally:\n"
                           "    assert not any(m.split('.')[0] == 'solver' for m in sys.modules)",
                           *args], capture_output=True, text=True, cwd=ROOT, check=False)
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["value"] == json.loads(out)["value"]
    assert json.loads(out)["value"] == json.loads(_run(*args)[1])["value"]


# ------------------------------------------------------------------ mistakes in the group
def _invocation(path: str, group: list[str], tmp: Path, profile: Path) -> list[str]:
    """A full command line for ``path`` around ``group`` (outputs go to ``tmp``)."""
    extra = {"solve": ["-o", str(tmp / "out.json"), "--save-instance", str(tmp / "i.json")],
             "certify": [str(profile)], "value": ["-H", "3"],
             "export-efg": ["-H", "2", "-o", str(tmp / "g.efg")],
             "plot map": ["-o", str(tmp / "f.png")], "plot beliefs": ["-o", str(tmp / "f")],
             "experiment compare": ["--output-dir", str(tmp / "cmp")]}[path]
    return [*path.split(), *group, *extra]


MISTAKES = [
    (["--start", START, "--goals", G1, "--prior", "0.6,0.4"],
     "--goals takes two cells ROW,COL ROW,COL, got one: '0,3' (then '--prior')"),
    (["--start", "1,1", "--goals", G1, G2, "--prior", "0.6,0.4"],
     "start cell (1, 1) is an obstacle"),
    (["--start", "3,0", "--goals", G1, G2, "--prior", "0.6,0.4"],
     "start cell (3, 0) is outside the 3x4"),
    (["--start", START, "--goals", "0,4", G2, "--prior", "0.6,0.4"],
     "goal cell (0, 4) is outside the 3x4"),
    (["--start", START, "--goals", G1, "1,2", "--prior", "0.6,0.4"],
     "goal cell (1, 2) is an obstacle"),
    (["--start", "2", "--goals", G1, G2, "--prior", "0.6,0.4"],
     "--start takes cells ROW,COL (two integers), got '2'"),
    (["--start", START, "--goals", G1, G2, "--prior", "0.6"],
     "--prior takes two numbers P,Q"),
    (["--start", START, "--goals", G1, G2, "--prior", "0.6,0.5"], "prior"),
    (["--start", START, "--goals", G1, G1, "--prior", "0.6,0.4"], "goals must differ"),
    (["--start", START], "--map needs --start R,C --goals R,C R,C --prior P,Q: missing --goals "
                         "and --prior"),
]


@pytest.mark.parametrize("path", INSTANCE_COMMANDS)
@pytest.mark.parametrize("mistake,message", MISTAKES,
                         ids=[f"mistake{k}" for k in range(len(MISTAKES))])
def test_mistakes_are_one_line_exit_2(path: str, mistake: list[str], message: str,
                                      tiny: Path, saved: tuple[Path, Path],
                                      tmp_path: Path) -> None:
    out_dir = tmp_path / "outputs"
    out_dir.mkdir()
    args = _invocation(path, ["--map", str(tiny), *mistake], out_dir, saved[1])
    code, out, err = _run(*args)
    assert code == 2, (args, out, err)
    assert err.startswith("error: ") and len(err.strip().splitlines()) == 1, err
    assert message in err, err
    assert "not found in graph" not in err and "exactly one of INSTANCE" not in err
    assert list(out_dir.iterdir()) == []


@pytest.mark.parametrize("path", INSTANCE_COMMANDS)
@pytest.mark.parametrize("group,message", [
    (["--start", START, "--prior", "0.6,0.4"], "--start and --prior go with --map FILE"),
    (["--goals", G1, G2], "--goals goes with --map FILE, which is missing"),
    (["--connectivity", "8"], "--connectivity goes with --map FILE"),
])
def test_group_options_without_map(path: str, group: list[str], message: str,
                                   saved: tuple[Path, Path], tmp_path: Path) -> None:
    inst, prof = saved
    out_dir = tmp_path / "outputs"
    out_dir.mkdir()
    args = _invocation(path, [*group], out_dir, prof)
    if path != "certify":
        args.insert(len(path.split()), str(inst))
    else:
        args.insert(1, str(inst))
    code, _, err = _run(*args)
    assert code == 2 and message in err and len(err.strip().splitlines()) == 1, err
    assert list(out_dir.iterdir()) == []


@pytest.mark.parametrize("path", ["solve", "value", "export-efg", "plot map",
                                  "experiment compare"])
def test_instance_and_map_together(path: str, saved: tuple[Path, Path], tiny: Path,
                                   tmp_path: Path) -> None:
    inst, prof = saved
    args = _invocation(path, ["--map", str(tiny), *GROUP, str(inst)], tmp_path, prof)
    code, _, err = _run(*args)
    assert code == 2 and "give INSTANCE or --map FILE, not both" in err, err


def test_certify_positional_arguments(saved: tuple[Path, Path], tiny: Path) -> None:
    inst, prof = saved
    code, _, err = _run("certify", "--map", str(tiny), *GROUP, str(inst), str(prof))
    assert code == 2 and "with --map, certify takes only PROFILE" in err
    code, _, err = _run("certify", "--map", str(tiny), *GROUP)
    assert code == 2 and "missing PROFILE" in err
    code, _, err = _run("certify", str(inst))
    assert code == 2 and "missing PROFILE" in err
    code, _, err = _run("certify")
    assert code == 2 and "missing PROFILE" in err


def test_missing_instance() -> None:
    for args in (["solve"], ["value", "-H", "2"], ["export-efg", "-H", "2", "-o", "x.efg"]):
        code, _, err = _run(*args)
        assert code == 2 and "missing INSTANCE: give an instance JSON file, or --map FILE" in err
