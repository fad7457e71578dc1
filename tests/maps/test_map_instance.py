"""The compact map instance ``dpp-map-instance/1`` (docs/formats.md §1c) end to end.

``dpp solve --map ... --save-instance`` writes it; every command reads it; both packages read
it with their own map readers and check the map's sha256; mistakes are one line, exit 2.
"""

from __future__ import annotations

import hashlib
import json
import shutil
from fractions import Fraction
from pathlib import Path
from typing import Any

import pytest
from click.testing import CliRunner

from dpp import main
from dppverify.errors import InvalidInstanceError
from dppverify.formats.map_instance import MAP_INSTANCE_FORMAT
from dppverify.formats.movingai import grid_document, parse_map
from dppverify.game.instance import instance_from_json as checker_from_json
from dppverify.game.instance import load_instance as checker_load
from solver.errors import DPPError
from solver.game.instance_reading import load_instance as solver_load
from solver.game.instance_writing import instance_to_json
from tests.maps._maps import TINY_MAP

GROUP = ["--start", "2,0", "--goals", "0,3", "0,0", "--prior", "3/5,2/5"]


def _run(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(main, list(args))
    assert result.exception is None or isinstance(result.exception, SystemExit), result
    return result.exit_code, result.stdout, result.stderr


@pytest.fixture()
def game(tmp_path: Path) -> tuple[Path, Path, Path]:
    """(map, compact instance in a subdirectory, profile) written by dpp solve."""
    m = tmp_path / "maps" / "tiny.map"
    m.parent.mkdir()
    m.write_text(TINY_MAP)
    inst, prof = tmp_path / "out" / "tiny.json", tmp_path / "out" / "tiny.profile.json"
    inst.parent.mkdir()
    code, _, err = _run("solve", "--map", str(m), *GROUP, "-o", str(prof),
                        "--save-instance", str(inst))
    assert code == 0, err
    return m, inst, prof


def _doc(path: Path) -> dict[str, Any]:
    return dict(json.loads(path.read_text()))


def test_written_with_a_relative_map_path_and_the_map_hash(game: tuple[Path, Path, Path]
                                                           ) -> None:
    m, inst, _ = game
    doc = _doc(inst)
    assert doc["format"] == MAP_INSTANCE_FORMAT and doc["map"] == "../maps/tiny.map"
    assert doc["map_sha256"] == hashlib.sha256(m.read_bytes()).hexdigest()
    assert len(inst.read_bytes()) < 400


def test_both_packages_read_the_game_of_the_full_document(game: tuple[Path, Path, Path]
                                                          ) -> None:
    _, inst, _ = game
    full = grid_document(parse_map(TINY_MAP), (2, 0), ((0, 3), (0, 0)), ("3/5", "2/5"))
    a, b = checker_load(inst), checker_from_json(full)
    assert (a.nodes, tuple(a.succ), a.dist_to, a.hops, a.prior) == \
        (b.nodes, tuple(b.succ), b.dist_to, b.hops, b.prior)
    s = solver_load(inst)
    assert json.loads(json.dumps(instance_to_json(s)))["graph"]["edges"] == \
        json.loads(json.dumps(full))["graph"]["edges"]


def test_the_pair_moves_together_and_every_command_reads_it(
        game: tuple[Path, Path, Path], tmp_path: Path) -> None:
    _, inst, prof = game
    moved = tmp_path / "elsewhere"
    shutil.copytree(tmp_path / "out", moved / "out")
    shutil.copytree(tmp_path / "maps", moved / "maps")
    shutil.rmtree(tmp_path / "maps")
    inst, prof = moved / "out" / inst.name, moved / "out" / prof.name
    code, out, err = _run("certify", str(inst), str(prof))
    assert code == 0, err
    code, out, err = _run("value", str(inst), "--horizon", "inf")
    assert code == 0 and "exactly" in out, err
    code, out, err = _run("solve", str(inst), "--json")
    assert code == 0 and json.loads(out) == _doc(prof)
    code, _, err = _run("export-efg", str(inst), "--horizon", "6", "-o",
                        str(tmp_path / "g.efg"))
    assert code == 0, err


@pytest.mark.parametrize(("change", "message"), [
    ({"map_sha256": "0" * 64}, "map_sha256: the map ../maps/tiny.map has sha256"),
    ({"map_sha256": "ABC"}, "map_sha256: must be 64 lowercase hex digits"),
    ({"map": "../maps/missing.map"}, "missing.map"),
    ({"extra": 1}, "unknown key 'extra'"),
    ({"start": [1, 1]}, "start cell (1, 1) is an obstacle"),
    ({"start": [0]}, "start: a cell is [row, col]"),
    ({"connectivity": 6}, "connectivity: must be 4 or 8"),
    ({"connectivity": 4.0}, "connectivity: must be 4 or 8"),  # the solver took it once
    ({"connectivity": True}, "connectivity: must be 4 or 8"),
    ({"start": [0.0, 0]}, "start"),
    ({"prior": ["1/2", "1/3"]}, "prior"),
])
def test_mistakes_are_one_line_exit_2(game: tuple[Path, Path, Path], change: dict[str, Any],
                                      message: str) -> None:
    _, inst, prof = game
    doc = {**_doc(inst), **change}
    inst.write_text(json.dumps(doc))
    for args in (["certify", str(inst), str(prof)], ["value", str(inst), "-H", "inf"],
                 ["solve", str(inst)]):
        code, out, err = _run(*args)
        assert code == 2 and out == "" and len(err.strip().splitlines()) == 1, (args, err)
        if args[0] != "solve" or "prior" not in message:
            assert message in err, (args, err)


def test_n_goals_for_both_readers_and_a_two_goal_refusal(
        game: tuple[Path, Path, Path]) -> None:
    _, inst, _ = game
    doc = {**_doc(inst), "goals": [[0, 3], [0, 0], [2, 3]], "prior": ["1/2", "1/3", "1/6"]}
    inst.write_text(json.dumps(doc))
    n = checker_load(inst)
    assert len(n.goals) == 3 and n.prior[2] == Fraction(1, 6)
    code, out, _ = _run("value", str(inst), "--horizon", "inf")
    assert code == 0 and "N = 3 goals" in out
    assert solver_load(inst).n_goals == 3  # the solver reads any N (dpp solve)
    with pytest.raises(DPPError, match="lists 3 goals"):  # its two-goal commands refuse
        solver_load(inst, two_goals=True)


def test_an_octile_grid_with_more_than_two_goals_is_refused(
        game: tuple[Path, Path, Path]) -> None:
    """Float (sqrt 2) weights never reach the exact N-goal mathematics: a compact instance
    with three goals and connectivity 8 is refused as its full document is (it was read, and
    its float-weight value called exact, before the --map and compact routes became one)."""
    m, inst, _ = game
    doc = {**_doc(inst), "goals": [[0, 3], [0, 0], [2, 3]], "prior": ["1/2", "1/3", "1/6"],
           "connectivity": 8}
    inst.write_text(json.dumps(doc))
    full = grid_document(parse_map(TINY_MAP), (2, 0), ((0, 3), (0, 0), (2, 3)),
                         ("1/2", "1/3", "1/6"), connectivity=8)
    for read in (lambda: checker_load(inst), lambda: checker_from_json(full)):
        with pytest.raises(InvalidInstanceError, match="N-goal instances must be exact"):
            read()
    code, out, err = _run("value", str(inst))
    assert code == 2 and out == "" and "N-goal instances must be exact" in err, err
    code, out, err = _run("value", "--map", str(m), "--start", "2,0", "--goals", "0,3", "0,0",
                          "2,3", "--prior", "1/2,1/3,1/6", "--connectivity", "8")
    # the option group refuses it before the map is read (one line naming the option)
    assert code == 2 and out == "" and "--connectivity 8" in err and "exact" in err, err
