"""The command-line conventions of README "Command-line conventions", on every ``dpp`` command.

One file: ``-o/--output``; a folder: ``--output-dir`` (``--out`` only as a hidden deprecated
alias); ``--progress/--no-progress`` on every long command; status messages on stderr.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import click
import pytest
from click.testing import CliRunner

from dpp import main

ROOT = Path(__file__).resolve().parents[1]
TRIANGLE = str(ROOT / "examples" / "triangle.json")
LONG = {"certify", "value", "export-efg", "audit", "experiment compare", "experiment density"}


def _commands(group: click.Group = main, prefix: str = "") -> Iterator[tuple[str, click.Command]]:
    for name, cmd in group.commands.items():
        if isinstance(cmd, click.Group):
            yield from _commands(cmd, f"{prefix}{name} ")
        else:
            yield prefix + name, cmd


def _visible_options(cmd: click.Command) -> list[click.Option]:
    return [p for p in cmd.params if isinstance(p, click.Option) and not p.hidden]


def test_the_walk_finds_every_command() -> None:
    names = {name for name, _ in _commands()}
    assert LONG | {"solve", "plot map", "plot beliefs", "plot voi"} <= names


@pytest.mark.parametrize("name, cmd", list(_commands()), ids=lambda x: str(x))
def test_output_options_follow_the_convention(name: str, cmd: click.Command) -> None:
    for opt in _visible_options(cmd):
        if not any(o == "-o" or o.startswith("--out") for o in opt.opts):
            continue
        assert opt.opts in (["-o", "--output"], ["--output-dir"]), (name, opt.opts)
        assert isinstance(opt.type, click.Path)
        if opt.opts == ["-o", "--output"]:
            assert not opt.type.dir_okay, name  # a file
        else:
            assert not opt.type.file_okay, name  # a folder


@pytest.mark.parametrize("name", sorted(LONG))
def test_long_commands_have_progress_flags(name: str) -> None:
    cmd = dict(_commands())[name]
    (opt,) = [p for p in _visible_options(cmd) if "--progress" in p.opts]
    assert opt.secondary_opts == ["--no-progress"] and opt.default is None


def test_status_messages_go_to_stderr(tmp_path: Path) -> None:
    runs = [["solve", TRIANGLE, "-o", str(tmp_path / "p.json")],
            ["export-efg", TRIANGLE, "-H", "1", "-o", str(tmp_path / "g.efg")],
            ["experiment", "compare", TRIANGLE, "--output-dir", str(tmp_path / "c")]]
    for args in runs:
        r = CliRunner().invoke(main, args)
        assert r.exit_code == 0, (args, r.stderr)
        assert "wrote" in r.stderr and "wrote" not in r.stdout, args


def test_deprecated_out_still_works_with_a_warning(tmp_path: Path) -> None:
    r = CliRunner().invoke(main, ["experiment", "compare", TRIANGLE, "--out", str(tmp_path)])
    assert r.exit_code == 0, r.stderr
    assert "warning: --out is deprecated; use --output-dir" in r.stderr
    assert (tmp_path / "compare.csv").exists()
    r = CliRunner().invoke(main, ["experiment", "compare", TRIANGLE, "--out", "a",
                                  "--output-dir", "b"])
    assert r.exit_code == 2 and "deprecated spelling" in r.stderr


def test_progress_bars_only_on_request(tmp_path: Path) -> None:
    quiet = CliRunner().invoke(main, ["value", TRIANGLE, "-H", "3"])
    loud = CliRunner().invoke(main, ["value", TRIANGLE, "-H", "3", "--progress"])
    assert quiet.exit_code == loud.exit_code == 0
    assert quiet.stderr == ""  # CliRunner's stderr is not a terminal
    assert "walk tree" in loud.stderr and "value LP" in loud.stderr
    assert quiet.stdout.startswith("V_H (H = 3) = 12/5 (≈ 2.4) exactly")
    assert loud.stdout[:30] == quiet.stdout[:30]
    loud = CliRunner().invoke(main, ["certify", TRIANGLE, str(tmp_path / "missing.json"),
                                     "--progress"])
    assert loud.exit_code == 2


@pytest.mark.parametrize("name", sorted(n for n, c in _commands()
                                        if any(p.name in ("output", "output_dir")
                                               for p in c.params)))
def test_an_empty_output_path_is_refused_by_name(name: str, tmp_path: Path,
                                                 monkeypatch: pytest.MonkeyPatch) -> None:
    # Path("") is "." — an empty -o/--output-dir must not become the current folder
    monkeypatch.chdir(tmp_path)
    cmd = dict(_commands())[name]
    flag = "--output" if any(p.name == "output" for p in cmd.params) else "--output-dir"
    result = CliRunner().invoke(main, [*name.split(), flag, ""])
    assert result.exit_code == 2
    assert "the path is empty" in result.output
    assert list(tmp_path.iterdir()) == []
