"""Hostile probes of the shared edges: the lock discipline of batch CSVs, the output rule of
every command, documents that try to forge a line, standard input that is no stream, the
bound on a solver's answer, inputs validated where they enter.

Each probe runs the real ``dpp`` in a session of its own under CPU and memory limits
(``_harness.py``) and asserts its exit code, one stderr line where an error is expected, no
traceback, untouched files (only the listed entries may change) and no surviving process.
The concurrent probes run two commands at once and wait for a *state* (a row written, a
reader blocked on a FIFO), never for a time.
"""

from __future__ import annotations

import csv
import json
import os
import stat
import subprocess
import sys
from pathlib import Path

import pytest

from tests import _guard
from tests.hostile._harness import ROOT, Probe, Result, check, launcher, listing, run

pytestmark = pytest.mark.hostile

TINY_MAP = "type octile\nheight 3\nwidth 4\nmap\n....\n.@@.\n....\n"
LINES = ["0\ttiny.map\t4\t3\t0\t0\t3\t2\t5", "0\ttiny.map\t4\t3\t3\t0\t0\t2\t5",
         "0\ttiny.map\t4\t3\t0\t2\t3\t0\t3"]
BATCH = ["batch", "tiny.scen", "--no-progress", "--chunk", "1"]


def _tiny(d: Path, repeat: int = 1, text: str | None = None) -> None:
    (d / "tiny.map").write_text(TINY_MAP)
    (d / "tiny.scen").write_text(text if text is not None
                                 else "version 1\n" + "\n".join(LINES * repeat) + "\n")


def _ok(result: Result, probe: Probe, before: dict[str, tuple[str, int, int]], d: Path) -> None:
    check(result, probe, before, listing(d))


def _start(args: list[str], d: Path) -> subprocess.Popen[bytes]:
    """A second ``dpp`` run beside the probe (its own session; ended by the test)."""
    return subprocess.Popen([sys.executable, "-m", "dpp", *args], cwd=d,
                            env={**os.environ, "PYTHONPATH": str(ROOT)},
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            start_new_session=True)


def _finish(proc: subprocess.Popen[bytes]) -> tuple[int, str]:
    _, err = _guard.communicate(proc)
    return proc.returncode, err.decode("utf-8", "replace")


def _rows(path: Path) -> int:
    return path.read_bytes().count(b"\n") - 1 if path.exists() else 0


def _flocked_by(pid: int, path: Path) -> bool:
    """True when process ``pid`` holds a ``flock`` on ``path`` (``/proc/locks``)."""
    ino = os.stat(path).st_ino
    try:
        text = Path("/proc/locks").read_text()
    except OSError:  # pragma: no cover - not Linux
        pytest.skip("no /proc/locks here")
    for line in text.splitlines():
        f = line.split()
        if len(f) >= 6 and f[1] == "FLOCK" and f[4] == str(pid) and \
                f[5].rsplit(":", 1)[-1] == str(ino):
            return True
    return False


def _stop(batch: subprocess.Popen[bytes], out: Path) -> None:
    """End a long batch with SIGTERM and check that its rows are all in its CSV: the line it
    prints names exactly the rows the file holds (no row vanished)."""
    batch.terminate()
    code, err = _finish(batch)
    assert code == 143, err
    held = _rows(out)
    assert f"{held} rows finished so far are in" in err or held == 0, (held, err)
    assert out.read_bytes().endswith(b"\n")


# --- merge and batch share one lock discipline -----------------------------------------------
@pytest.mark.parametrize("written, merge, says", [
    ("C.csv", ["-o", "C.csv", "s.csv"], "another dpp batch"),  # the batch's output
    ("s-1.csv", ["-o", "all.csv", "s-1.csv"], "still writing this shard"),  # a shard
], ids=["the output a batch appends to", "a shard a batch writes"])
def test_merge_refuses_what_a_running_batch_writes(scratch: Path, written: str,
                                                   merge: list[str], says: str) -> None:
    """The batch's rows never vanish: a merge onto the CSV a batch is writing, or of a shard
    a batch is still writing, is refused (one line, nothing written), and the batch's last
    line names the rows its file holds."""
    _tiny(scratch, repeat=2000)
    out = scratch / written
    batch = _start([*BATCH, *(["--shard", "1/2"] if "-1" in written else []), "-o", written],
                   scratch)
    try:
        _guard.until(lambda: _rows(out) >= 2, batch, "the batch's first rows")
        (scratch / "s.csv").write_bytes(out.read_bytes().split(b"\n", 1)[0] + b"\n")
        before = {k: v for k, v in listing(scratch).items() if k != written}
        result = run(["batch", "merge", *merge], scratch)
        check(result, Probe([], code=2, contains=says), before,
              {k: v for k, v in listing(scratch).items() if k != written})
        assert batch.poll() is None, "the batch ended before the merge: the probe shows nothing"
    finally:
        _stop(batch, out)
    assert not (scratch / "all.csv").exists()


def test_a_batch_refuses_a_shard_and_an_output_a_running_merge_holds(scratch: Path) -> None:
    """The other way round: while a merge holds its locks (it waits on a FIFO shard whose
    writer stays open), a batch onto its shard or onto its output is refused in one line."""
    _tiny(scratch)
    assert run([*BATCH, "--shard", "1/2", "-o", "s-1.csv"], scratch).code == 0
    (scratch / "all.csv").write_bytes((scratch / "s-1.csv").read_bytes())  # an older merge
    os.mkfifo(scratch / "ff")
    writer = os.open(scratch / "ff", os.O_RDWR)  # a writer before the merge reads it (Linux)
    merge = _start(["batch", "merge", "-o", "all.csv", "s-1.csv", "ff"], scratch)
    try:
        _guard.until(lambda: _flocked_by(merge.pid, scratch / "s-1.csv")
                     and _flocked_by(merge.pid, scratch / "all.csv"), merge,
                     "the merge holds its locks")
        for target in ("s-1.csv", "all.csv"):
            before = listing(scratch)
            result = run([*BATCH, "--shard", "1/2", "-o", target], scratch)
            check(result, Probe([], code=2, contains="another dpp batch or dpp batch merge"),
                  before, listing(scratch))
    finally:
        os.close(writer)  # the FIFO shard is empty: the merge refuses it
        code, err = _finish(merge)
    assert code == 2 and "ff: empty: not a dpp batch CSV" in err


# --- outputs: one rule for every command ---------------------------------------------------
def _shards(d: Path) -> None:
    _tiny(d)
    assert run([*BATCH, "--shard", "1/2", "-o", "s-1.csv"], d).code == 0
    assert run([*BATCH, "--shard", "2/2", "-o", "s-2.csv"], d).code == 0


def _device(d: Path) -> str:
    """A character device to write into: as root, a null device made in the scratch folder
    (a regression would replace it, not the machine's /dev/null); else /dev/null, which a
    normal user cannot replace."""
    if os.geteuid() != 0:
        return "/dev/null"
    node = d / "null"
    os.mknod(node, stat.S_IFCHR | 0o666, os.makedev(1, 3))
    return str(node)


@pytest.mark.parametrize("name, args, code, changes, setup", [
    ("merge -o a hard link of a shard", ["batch", "merge", "-o", "h.csv", "s-1.csv", "s-2.csv"],
     2, (), lambda d: os.link(d / "s-1.csv", d / "h.csv")),
    ("merge -o a character device: written into", ["batch", "merge", "-o", "DEVICE",
                                                   "s-1.csv", "s-2.csv"], 0, (), None),
    ("merge -o a dangling symlink: its target made", ["batch", "merge", "-o", "dl.csv",
                                                      "s-1.csv", "s-2.csv"], 0,
     ("sub", "dl.csv"), lambda d: (d / "dl.csv").symlink_to("sub/m.csv")),
    ("merge -o through a dangling folder link", ["batch", "merge", "-o", "dd/m.csv", "s-1.csv",
                                                 "s-2.csv"], 2, (),
     lambda d: (d / "dd").symlink_to("nowhere")),
])
def test_merge_follows_the_output_rule(scratch: Path, name: str, args: list[str], code: int,
                                       changes: tuple[str, ...], setup: object) -> None:
    _shards(scratch)
    if callable(setup):
        setup(scratch)
    if "DEVICE" in args:
        args = [_device(scratch) if a == "DEVICE" else a for a in args]
    before = listing(scratch)
    shard = (scratch / "s-1.csv").read_bytes()
    result = run(args, scratch)
    check(result, Probe([], code=code, one_line=code == 2, changes=changes), before,
          listing(scratch))
    assert (scratch / "s-1.csv").read_bytes() == shard
    if "dangling symlink" in name:
        assert (scratch / "dl.csv").is_symlink() and (scratch / "sub" / "m.csv").read_text() \
            .count("\n") == 4


@pytest.mark.parametrize("cmd", [["value", "tri.json"], ["solve", "tri.json"],
                                 ["certify", "tri.json", "prof.json"],
                                 ["export-efg", "tri.json", "-H", "1"]])
def test_o_a_dangling_symlink_writes_its_target(scratch: Path, cmd: list[str]) -> None:
    (scratch / "out.x").symlink_to("made/target.x")
    before = listing(scratch)
    result = run([*cmd, "-o", "out.x"], scratch)
    check(result, Probe([], code=0, one_line=False, changes=("made", "out.x")), before,
          listing(scratch))
    assert (scratch / "out.x").is_symlink() and (scratch / "made" / "target.x").stat().st_size


@pytest.mark.parametrize("cmd", [["value", "tri.json"], ["solve", "tri.json"],
                                 ["certify", "tri.json", "prof.json"]])
def test_o_a_hard_link_of_the_input_is_refused(scratch: Path, cmd: list[str]) -> None:
    os.link(scratch / "tri.json", scratch / "same.json")
    before = listing(scratch)
    result = run([*cmd, "-o", "same.json"], scratch)
    check(result, Probe([], code=2, contains="is an input of this command"), before,
          listing(scratch))


def test_value_from_stdin_to_stdout(scratch: Path) -> None:
    """``-o -`` is standard output, not a second ``-`` input."""
    before = listing(scratch)
    result = run(["value", "-", "-o", "-"], scratch, stdin=(scratch / "tri.json").read_bytes())
    check(result, Probe([], code=0, one_line=False), before, listing(scratch))
    assert json.loads(result.stdout)["value"] == "12/5"
    assert not (scratch / "-").exists()


@pytest.mark.parametrize("setup, out, says", [
    (lambda d: (d / "dang").symlink_to("nowhere/x"), "dang/sub",
     "is a symbolic link to a missing folder"),
    (lambda d: (d / "f").write_text("x"), "f/sub", "is not a folder"),
    (lambda d: (d / "fo" / "failure.json").mkdir(parents=True), "fo", "is a folder"),
])
def test_audit_an_output_folder_that_cannot_be_made_is_one_line(scratch: Path, setup: object,
                                                                 out: str, says: str) -> None:
    assert callable(setup)
    setup(scratch)
    before = listing(scratch)
    result = run(["audit", "--solver-cmd", "false {instance} {profile}", "--examples", "2",
                  "--no-shrink", "--output-dir", out], scratch)
    check(result, Probe([], code=2, contains=says), before, listing(scratch))
    assert result.stdout == ""


def test_audit_a_failure_it_cannot_write_is_one_line_exit_2(scratch: Path) -> None:
    """The folder passed the check before the first example, but the disk is full (a file
    size limit) when the failure is written: one line naming the failing check, exit 2 (it
    was exit 1 and three lines, one of them claiming the files were written)."""
    before = listing(scratch)
    result = run(["audit", "--solver", "tests.dppverify.audit.hostile_solvers:exits_zero",
                  "--examples", "2", "--no-shrink", "--output-dir", "af"], scratch, fsize=300)
    check(result, Probe([], code=2, contains="cannot write the failing example (solver.error)"),
          before, listing(scratch))
    assert result.stdout == "" and not (scratch / "af").exists()


# --- documents cannot forge a line ---------------------------------------------------------
def _certificate(d: Path, **provenance: object) -> None:
    r = run(["certify", "tri.json", "prof.json", "--json"], d)
    doc = json.loads(r.stdout)
    doc["provenance"].update(provenance)
    doc["provenance"]["instance"]["sha256"] = "0" * 64  # a mismatch: exit 1
    (d / "c.json").write_text(json.dumps(doc))


@pytest.mark.parametrize("version", ["0.1.0\rprovenance OK: instance, profile match",
                                     "0.1.0\x1b[2K\x1b[1Aprovenance OK", "\u202eKO ecnanevorp",
                                     "v" * 5_000_000])
def test_verify_provenance_escapes_and_bounds_the_certificate(scratch: Path,
                                                              version: str) -> None:
    _certificate(scratch, dppverify=version)
    before = listing(scratch)
    result = run(["certify", "--verify-provenance", "c.json", "tri.json", "prof.json"], scratch)
    check(result, Probe([], code=1, one_line=False), before, listing(scratch))
    line = result.stdout
    assert line.startswith("provenance MISMATCH") and line.count("\n") == 1
    assert not any(c in line for c in "\r\x1b\u202e"), repr(line[:300])
    assert len(line) < 1000  # a 5 MB version is not echoed (twice)


def test_a_node_name_with_escape_sequences_reaches_no_terminal_raw(scratch: Path) -> None:
    doc = json.loads((scratch / "tri.json").read_text())
    text = json.dumps(doc).replace('"s"', '"s\\u001b[2K\\u202e\\r"')
    (scratch / "evil.json").write_text(text)
    for cmd in (["solve", "evil.json"], ["value", "evil.json", "--json"],
                ["certify", "evil.json", "prof.json"], ["value", "evil.json", "-H", "x"]):
        result = run(cmd, scratch)
        assert "Traceback" not in result.stderr
        out = result.stdout + result.stderr
        assert not any(c in out for c in "\x1b\u202e"), (cmd, out[:500])


def _edit(path: Path, line: int, **cells: str) -> None:
    """Hand-edit the row of scenario ``line`` of a batch CSV (through ``csv``: cells hold
    quoted commas)."""
    with open(path, encoding="utf-8", newline="") as fh:
        rows = list(csv.reader(fh))
    head = rows[0]
    for row in rows[1:]:
        if row[0] == str(line):
            for k, v in cells.items():
                row[head.index(k)] = v
    with open(path, "w", encoding="utf-8", newline="") as fh:
        csv.writer(fh, lineterminator="\n").writerows(rows)


def test_a_batch_csv_cell_cannot_forge_the_summary_line(scratch: Path) -> None:
    """A reason cell with a right-to-left override is merged (a well-formed row), and the
    summary line shows it escaped; one with an escape sequence is no batch row at all."""
    _tiny(scratch)
    assert run([*BATCH, "-o", "b.csv", "--lines", "2"], scratch).code == 0
    row = {k: "" for k in ("verdict", "nash_conv", "route", "VoI_float", "solve_seconds",
                           "certify_seconds")}
    values = ("distance", "U1", "U2", "U", "U_bar", "VoI", "cost", "cost_ratio", "ldp",
              "deceptive_density", *(f"truthful_{p}" for p in (10, 25, 50, 75, 90, 99)))
    _edit(scratch / "b.csv", 2, status="error", reason="\u202eSSAP lla :ecnanevorp",
          fake_goal="", primary="", **row, **dict.fromkeys(values, ""))
    before = listing(scratch)
    result = run(["batch", "merge", "-o", "m.csv", "b.csv"], scratch)
    check(result, Probe([], code=0, one_line=False, changes=("m.csv",)), before,
          listing(scratch))
    assert "\u202e" not in result.stdout and "\\u202e" in result.stdout, result.stdout
    _edit(scratch / "b.csv", 2, reason="ok\x1b[2K\rall rows pass")
    before = listing(scratch)
    result = run(["batch", "merge", "-o", "m2.csv", "b.csv"], scratch)
    check(result, Probe([], code=2, contains="a control character"), before, listing(scratch))


# --- standard input ----------------------------------------------------------------------
@pytest.mark.parametrize("stdin_is, says", [("closed", "standard input is closed"),
                                            ("write-only", "not open for reading")])
@pytest.mark.parametrize("cmd", [["value", "-"], ["certify", "tri.json", "-"],
                                 ["batch", "-", "-o", "b.csv", "--no-progress"]])
def test_a_standard_input_that_cannot_be_read_is_one_line(scratch: Path, cmd: list[str],
                                                          stdin_is: str, says: str) -> None:
    before = listing(scratch)
    result = run(cmd, scratch, stdin_is=stdin_is)
    check(result, Probe([], code=2, contains=says), before, listing(scratch))
    assert "(None)" not in result.stderr


@pytest.mark.parametrize("cmd, code", [(["--version"], 0), (["value", "tri.json"], 0),
                                       (["value", "-"], 2), (["value", "/dev/stdin"], 2),
                                       (["certify", "tri.json", "-"], 2),
                                       (["solve", "-", "-o", "p.json"], 2)])
def test_standard_input_a_folder_through_the_launcher(scratch: Path, cmd: list[str],
                                                      code: int) -> None:
    """No Python interpreter starts with standard input a folder; the ``dpp`` launcher gives
    the command ``/dev/null`` and says so: ``--version`` and every command not reading ``-``
    run, one that reads it is one line."""
    program = launcher()
    if program is None:
        pytest.skip("the dpp launcher (bin/dpp) is not installed next to this interpreter")
    before = listing(scratch)
    result = run(cmd, scratch, stdin_is="folder", program=program)
    check(result, Probe([], code=code, one_line=code == 2,
                        contains="standard input is a folder" if code == 2 else ""),
          before, listing(scratch))
    assert "Fatal Python error" not in result.stderr


# --- the two regressions -----------------------------------------------------------------
def test_a_scen_with_a_byte_order_mark_and_crlf_lines_runs(scratch: Path) -> None:
    (scratch / "tiny.map").write_text(TINY_MAP)
    text = "\ufeffversion 1\r\n" + "\r\n".join(LINES) + "\r\n"
    (scratch / "tiny.scen").write_bytes(text.encode("utf-8"))
    before = listing(scratch)
    result = run([*BATCH, "-o", "b.csv"], scratch)
    check(result, Probe([], code=0, one_line=False, changes=("b.csv",)), before,
          listing(scratch))
    assert result.stdout.startswith("3 rows: 3 ok (verdict pass 3), 0 errors")


def test_audit_bounds_a_python_solver_s_answer(scratch: Path) -> None:
    """An 80 MB answer is the solver's failure (larger than the 64 MiB every input is bounded
    at), under a 2 GiB address-space limit (the audit reached 3.2 GB on an 800 MB answer),
    and nothing of it is written."""
    before = listing(scratch)
    result = run(["audit", "--solver", "tests.dppverify.audit.hostile_solvers:huge_answer",
                  "--examples", "1", "--no-shrink", "--output-dir", "af"], scratch,
                 memory=2 << 30)
    check(result, Probe([], code=1, one_line=False, changes=("af",)), before,
          listing(scratch))
    assert "larger than the limit of 64 MiB" in result.stdout
    assert not (scratch / "af" / "profile.json").exists()
    assert sum(p.stat().st_size for p in (scratch / "af").iterdir()) < 100_000


# --- inputs validated where they enter -----------------------------------------------------
@pytest.mark.parametrize("length", ["nan", "inf", "1e999999999", "-7", "1" * 5000])
def test_a_published_length_that_is_no_decimal_is_an_error_row(scratch: Path,
                                                               length: str) -> None:
    bad = LINES[0].rsplit("\t", 1)[0] + "\t" + length
    _tiny(scratch, text="version 1\n" + "\n".join([bad, *LINES]) + "\n")
    before = listing(scratch)
    result = run([*BATCH, "-o", "b.csv"], scratch)
    check(result, Probe([], code=2, one_line=False, changes=("b.csv",)), before,
          listing(scratch))
    first = (scratch / "b.csv").read_text().splitlines()[1]
    assert first.startswith("2,error,") and "not a finite non-negative decimal" in first
    assert length not in first or len(length) < 40
    assert len(first) < 600


def test_a_hand_edited_row_is_neither_merged_nor_resumed(scratch: Path) -> None:
    _tiny(scratch)
    assert run([*BATCH, "--lines", "2-3", "-o", "b.csv"], scratch).code == 0
    _edit(scratch / "b.csv", 2, VoI="abc")
    for args in (["batch", "merge", "-o", "m.csv", "b.csv"], [*BATCH, "-o", "b.csv"]):
        before = listing(scratch)
        result = run(args, scratch)
        check(result, Probe([], code=2, contains="VoI 'abc' is not a number"), before,
              listing(scratch))


@pytest.mark.parametrize("option, value", [("--shard", "1/\u0662"), ("--shard", "\u0661/2"),
                                           ("--lines", "\u0662-3"), ("--lines", "2\u00a0-3")])
def test_shard_and_lines_take_ascii_digits_only(scratch: Path, option: str, value: str) -> None:
    _tiny(scratch)
    before = listing(scratch)
    result = run([*BATCH, "-o", "b.csv", option, value], scratch)
    check(result, Probe([], code=2, contains="ASCII digits"), before, listing(scratch))
