"""``dpp batch``'s output rule, its format and its run-time pieces, in-process (the hostile
suite runs the same classes as real processes under limits: ``tests/hostile/``)."""

from __future__ import annotations

import os
import random
import re
import time
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dppverify.formats.scen import (
    Scenario,
    candidates_of,
    goals_by_map,
)
from solver.cli.batch import BatchProgress
from solver.errors import InvalidInstanceError, OutputError
from solver.experiments.batch_csv import (
    HEADER,
    BatchTally,
    RowInfo,
    format_rows,
    parse_row,
    read_rows,
)
from solver.experiments.batch_output import BatchOutput
from tests.solver.experiments.doctest_inputs import example_row

KEY = "0123456789ab"


def _row(line: int, status: str = "ok", **kw: str) -> dict[str, str]:
    times = {"solve_seconds": "0.1", "certify_seconds": "0.2"} if status == "ok" else {}
    return example_row(line, status, config=KEY, **times) | kw


def _reference_candidates(scenarios: list[Scenario], index: int, seed: int) -> list:
    """The rule dpp-batch/1 as first written (quadratic): the reference for the linear one."""
    me = scenarios[index]
    seen: list = []
    for other in scenarios:
        if other.line == me.line or other.reason or other.map != me.map:
            continue
        if other.goal in (me.start, me.goal) or other.goal in seen:
            continue
        seen.append(other.goal)
    random.Random(f"dpp-batch:{seed}:{me.line}").shuffle(seen)
    return seen


cells = st.tuples(st.integers(0, 3), st.integers(0, 3))
scenario_lists = st.lists(st.tuples(st.sampled_from(["a.map", "b.map"]), cells, cells,
                                    st.booleans()), min_size=1, max_size=25)


@settings(max_examples=200, deadline=None)
@given(scenario_lists, st.integers(0, 5))
def test_the_linear_fake_goal_rule_is_the_rule(spec: list, seed: int) -> None:
    """goals_by_map + candidates_of (linear per line) give exactly the candidates of the rule
    as first written, for every line, map and seed (so batch and audit --scen rows keep their
    fake goals)."""
    scenarios = [Scenario(i + 2, reason="bad") if bad else Scenario(i + 2, m, 4, 4, s, g)
                 for i, (m, s, g, bad) in enumerate(spec)]
    table = goals_by_map(scenarios)
    for i, sc in enumerate(scenarios):
        expected = _reference_candidates(scenarios, i, seed)
        if not sc.reason:
            assert candidates_of(table[sc.map], sc, seed) == expected


def test_parse_row_refuses_what_a_batch_never_writes() -> None:
    good = format_rows([_row(3)]).rstrip(b"\n")
    assert parse_row(good, KEY) == RowInfo(3, "ok", "pass", 0.25, 0.1, 0.2)
    bad = {
        b"3,ok": "fields",
        good.replace(b"0.25", b"nan"): "finite",
        good.replace(b"0.25", b"1" * 5000): "not a number",
        good.replace(b",pass,", b",PASS,"): "verdict",
        good.replace(b"3,ok", b"0,ok", 1): "line number",
        good.replace(b"3,ok", b"3,fine", 1): "status",
        good.replace(b"3,ok", b"\xff,ok", 1): "CSV text",
    }
    # every field a batch writes, not only those the tally reads (a hand-edited cell)
    for column, value, why in [("VoI", "abc", "VoI 'abc' is not a number"),
                               ("U1", "1/0", "U1 '1/0' is not a number"),
                               ("U_bar", "", "U_bar '' is not a number"),
                               ("truthful_50", "nan", "truthful_50 'nan' is not a number"),
                               ("start", "0;0", "start '0;0' is not a cell"),
                               ("scen_optimal", "inf", "scen_optimal 'inf' is not a finite"),
                               ("scen_optimal", "-7", "scen_optimal '-7' is not a finite"),
                               ("route", "", "route '' is not a route"),
                               ("config", "0123456789aB", "config"),
                               ("reason", "why", "an ok row with a reason")]:
        bad[format_rows([_row(3, **{column: value})]).rstrip(b"\n")] = why
    bad[format_rows([_row(3, "error", reason="")]).rstrip(b"\n")] = "without its reason"
    bad[good.replace(b",pass,", b',"pa\x1b[2Kss",')] = "a control character"
    bad[format_rows([_row(3, "error", goal="x")]).rstrip(b"\n")] = "goal 'x' is not a cell"
    for raw, why in bad.items():
        with pytest.raises(ValueError, match=re.escape(why)):
            parse_row(raw, KEY)
    with pytest.raises(ValueError, match="another configuration"):
        parse_row(good, "ffffffffffff")


def test_format_rows_keeps_one_physical_line_per_row() -> None:
    row = _row(2, "error", reason="a\nb\rc\u2028d" + "x" * 5000, map="m\x00.map")
    data = format_rows([row])
    assert data.count(b"\n") == 1
    info = parse_row(data.rstrip(b"\n"), KEY)
    assert info.reason.startswith("a b c d") and len(info.reason) == 2000


def test_read_rows_drops_a_torn_row_and_refuses_other_tails() -> None:
    body = HEADER + format_rows([_row(2), _row(3)])
    assert [r.line for _, r in read_rows([body + b"4,ok,ti"])] == [2, 3]
    assert [r.line for _, r in read_rows([body[:10], body[10:]])] == [2, 3]  # chunks
    for tail in (b"my notes", b"x,ok"):
        with pytest.raises(InvalidInstanceError, match="neither a row"):
            list(read_rows([body + tail]))
    for text in (b"line,status", b"", b"\n"):  # a prefix of the header is not the header
        if text:
            with pytest.raises(InvalidInstanceError, match="header"):
                list(read_rows([text]))


def test_tally_exit_code_rule() -> None:
    def code(*rows: RowInfo) -> int:
        t = BatchTally()
        for r in rows:
            t.add(r)
        return t.exit_code()

    ok, err = RowInfo(2, "ok", "pass"), RowInfo(3, "error", reason="unknown map")
    assert code(ok) == 0
    assert code(ok, err) == 2
    assert code(err, RowInfo(4, "ok", "incomplete")) == 3
    assert code(err, RowInfo(5, "error", reason="internal error: X")) == 3
    assert code(RowInfo(6, "ok", "error"), RowInfo(7, "ok", "fail"), err) == 1


def test_a_new_file_appears_only_with_its_first_row(tmp_path: Path) -> None:
    target = tmp_path / "sub" / "b.csv"
    out = BatchOutput.open(target, KEY, lines={2, 3})
    assert not target.parent.exists()  # nothing before the first row
    out.append([_row(2)])
    assert target.read_bytes() == HEADER + format_rows([_row(2)])
    out.close()
    with BatchOutput.open(target, KEY, lines={2, 3}) as again:
        assert again.done == {2} and again.tally.rows == 1
        again.append([_row(3, "error")])
    assert again.tally.summary().startswith("2 rows: 1 ok (verdict pass 1), 1 error")
    assert [p.name for p in target.parent.iterdir()] == ["b.csv"]  # no temporary file


def test_a_run_that_fails_before_its_first_row_leaves_nothing(tmp_path: Path) -> None:
    link = tmp_path / "dl"
    link.symlink_to("nowhere/x.csv")
    out = BatchOutput.open(link, KEY, lines={2})
    out.close()
    assert link.is_symlink() and not (tmp_path / "nowhere").exists()


@pytest.mark.parametrize("content", [b'{"my": "notes"}', b"line\n", b"a,b\n1,2\n",
                                     b"\x00" * 100, HEADER + b"2,ok\n"])
def test_anything_but_a_batch_csv_is_refused_untouched(tmp_path: Path, content: bytes) -> None:
    target = tmp_path / "x.csv"
    target.write_bytes(content)
    before = os.stat(target)
    with pytest.raises(OutputError):
        BatchOutput.open(target, KEY, lines={2})
    after = os.stat(target)
    assert target.read_bytes() == content and after.st_mtime_ns == before.st_mtime_ns


def test_an_input_is_refused_by_any_path(tmp_path: Path) -> None:
    scen = tmp_path / "s.scen"
    scen.write_text("version 1\n")
    (tmp_path / "ln").symlink_to("s.scen")
    for name in ("s.scen", "ln", "./s.scen"):
        with pytest.raises(OutputError, match="is an input"):
            BatchOutput.open(tmp_path / name, KEY, lines={2}, inputs=[scen])


def test_a_failed_append_is_rolled_back(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    target = tmp_path / "b.csv"
    with BatchOutput.open(target, KEY, lines={2, 3, 4}) as out:
        out.append([_row(2)])
    before = target.read_bytes()
    import solver.experiments.batch_output as bo

    def full(fd: int, data: bytes) -> None:
        os.write(fd, data[:7])  # part of a row, then the disk is full
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(bo, "_write_all", full)
    with BatchOutput.open(target, KEY, lines={2, 3, 4}) as out, \
            pytest.raises(OutputError, match="1 row finished before is in it"):
        out.append([_row(3)])
    assert target.read_bytes() == before


def test_progress_counts_only_this_runs_rows() -> None:
    """After a resume the bar starts at the rows found (``initial``): its rate and ETA count
    only the rows this run made (the finding: 7 lines/s shown, 0.33 real)."""
    import io

    p = BatchProgress(True, "b.csv", file=io.StringIO())
    p.start(300, 400)
    time.sleep(0.2)
    p.update(1)
    d = p.bar.format_dict
    assert (d["initial"], d["n"]) == (300, 301)
    shown = p.bar.format_meter(**d)  # the bar's own rate and ETA
    rate = float(shown.rsplit(",", 1)[1].split("line/s")[0])
    assert rate <= 1 / 0.2 + 1e-9, shown  # one row in 0.2 s or more, never 301 / 0.2
    p.close()
