"""Hostile probes, third round: ``dpp batch`` and the user's files.

The rule under test (``solver/experiments/batch_output.py``): the batch appends only to a file
that is provably a batch CSV of the same configuration; everything else is refused, one line
and exit 2, before a byte is written. Every probe runs the real ``dpp`` under CPU and memory
limits; the scratch folder is compared before and after (only the listed entries may change).
"""

from __future__ import annotations

import csv
import os
import subprocess
from collections.abc import Callable
from pathlib import Path

import pytest

from tests.hostile._harness import Probe, check, listing, run, run_probe

pytestmark = pytest.mark.hostile

Setup = Callable[[Path], None]

TINY_MAP = "type octile\nheight 3\nwidth 4\nmap\n....\n.@@.\n....\n"
TINY_SCEN = ("version 1\n"
             "0\ttiny.map\t4\t3\t0\t0\t3\t2\t5\n"
             "0\ttiny.map\t4\t3\t3\t0\t0\t2\t5\n"
             "0\ttiny.map\t4\t3\t0\t2\t3\t0\t3\n")
"""Three lines on a 4 x 3 map, every one a game (verdict pass)."""
BATCH = ["batch", "tiny.scen", "--no-progress"]


def _tiny(d: Path) -> None:
    (d / "tiny.map").write_text(TINY_MAP)
    (d / "tiny.scen").write_text(TINY_SCEN)


def _with(*setups: Setup) -> Setup:
    def setup(d: Path) -> None:
        _tiny(d)
        for s in setups:
            s(d)
    return setup


def _file(name: str, text: str | bytes) -> Setup:
    def setup(d: Path) -> None:
        p = d / name
        p.parent.mkdir(parents=True, exist_ok=True)
        if isinstance(text, bytes):
            p.write_bytes(text)
        else:
            p.write_text(text)
    return setup


def _link(name: str, target: str) -> Setup:
    def setup(d: Path) -> None:
        (d / name).symlink_to(target)
    return setup


def _fifo(name: str) -> Setup:
    def setup(d: Path) -> None:
        os.mkfifo(d / name)
    return setup


def _batch_csv(name: str, edit: Callable[[str], str] = lambda text: text,
               extra: list[str] | None = None) -> Setup:
    """``name``: the CSV a run of BATCH writes (made by running it), then edited."""
    def setup(d: Path) -> None:
        env = {**os.environ, "PYTHONPATH": str(Path(__file__).resolve().parents[2])}
        subprocess.run([os.sys.executable, "-m", "dpp", *BATCH, "-o", name,  # type: ignore[attr-defined]
                        *(extra or [])], cwd=d, env=env, capture_output=True, check=False)
        p = d / name
        p.write_text(edit(p.read_text()))
    return setup


def _no_newline_scen(d: Path) -> None:
    (d / "tiny.map").write_text(TINY_MAP)
    (d / "tiny.scen").write_text(TINY_SCEN.rstrip("\n"))  # its last line has no newline


PROBES: list[tuple[str, Probe, Setup | None]] = []


def probe(name: str, args: list[str], setup: Setup | None = _tiny, **kw: object) -> None:
    PROBES.append((name, Probe(args, **kw), setup))  # type: ignore[arg-type]


# --- 1. the user's files: refused before a byte is written -------------------------------
probe("batch -o the user's JSON (no newline)", [*BATCH, "-o", "notes.json"],
      _with(_file("notes.json", '{"my": "notes"}')), contains="not a dpp batch CSV")
probe("batch -o its own .scen (no newline)", [*BATCH, "-o", "tiny.scen"], _no_newline_scen,
      contains="input")
probe("batch -o the .map it reads", [*BATCH, "-o", "tiny.map"], contains="input")
probe("batch -o a link to the .scen", [*BATCH, "-o", "ln.csv"],
      _with(_link("ln.csv", "tiny.scen")), contains="input")
probe("batch -o an empty-looking text file", [*BATCH, "-o", "t.txt"],
      _with(_file("t.txt", "line")), contains="not a dpp batch CSV")
probe("batch -o a CSV of another configuration", [*BATCH, "-o", "b.csv", "--seed", "1"],
      _with(_batch_csv("b.csv")), contains="another configuration")
probe("batch -o a batch CSV the user appended a note to", [*BATCH, "-o", "b.csv"],
      _with(_batch_csv("b.csv", lambda t: t + "my notes about this run\n")),
      contains="not a dpp batch CSV")
probe("batch -o a batch CSV with a huge field", [*BATCH, "-o", "b.csv"],
      _with(_batch_csv("b.csv", lambda t: t.replace("pass", "pass" + "x" * 300_000, 1))),
      contains="not a dpp batch CSV")
probe("batch -o a batch CSV with a bad number", [*BATCH, "-o", "b.csv"],
      _with(_batch_csv("b.csv", lambda t: t.replace(",structured,", ",structured,zero", 1))),
      contains="not a number")
probe("batch -o a batch CSV with a 5000-digit line", [*BATCH, "-o", "b.csv"],
      _with(_batch_csv("b.csv", lambda t: t.replace("\n2,", "\n" + "9" * 5000 + ",", 1))),
      contains="not a line number")
probe("batch -o a batch CSV with a line the .scen lacks", [*BATCH, "-o", "b.csv"],
      _with(_batch_csv("b.csv", lambda t: t.replace("\n2,", "\n77,", 1))),
      contains="line 77")
probe("batch -o a batch CSV with a line twice", [*BATCH, "-o", "b.csv"],
      _with(_batch_csv("b.csv", lambda t: t + t.splitlines()[1] + "\n")),
      contains="twice")
probe("batch -o a batch CSV with a huge exponent", [*BATCH, "-o", "b.csv"],
      _with(_batch_csv("b.csv", lambda t: t.replace(",structured,", ",structured,1e999999999",
                                                    1))), contains="not a number")
probe("batch dangling link, run fails before a row", ["batch", "missing.scen", "-o", "dl"],
      _with(_link("dl", "target.csv")))
probe("batch dangling link into a missing folder", ["batch", "missing.scen", "-o", "dl"],
      _with(_link("dl", "nowhere/x.csv")))
probe("batch dangling link: the file it names is made", [*BATCH, "-o", "dl"],
      _with(_link("dl", "target.csv")), code=0, one_line=False, changes=("target.csv",))
probe("batch -o in a missing folder, run fails before a row",
      ["batch", "missing.scen", "-o", "new/dir/b.csv"])
probe("batch -o in a missing folder", [*BATCH, "-o", "new/dir/b.csv"], code=0, one_line=False,
      changes=("new",))
probe("batch resumes after a torn row", [*BATCH, "-o", "b.csv"],
      _with(_batch_csv("b.csv", lambda t: "\n".join(t.splitlines()[:2]) + "\n3,ok,tiny.m")),
      code=0, one_line=False, changes=("b.csv",))
probe("batch resumes an empty file", [*BATCH, "-o", "b.csv"], _with(_file("b.csv", "")),
      code=0, one_line=False, changes=("b.csv",))
# --- 2. outputs that are not files, names, a full disk ----------------------------------
probe("batch -o /dev/zero", [*BATCH, "-o", "/dev/zero"], memory=1 << 30,
      contains="not a regular file")
probe("batch -o /dev/null", [*BATCH, "-o", "/dev/null"], contains="not a regular file")
probe("batch -o /dev/full", [*BATCH, "-o", "/dev/full"], contains="not a regular file")
probe("batch -o a FIFO without reader", [*BATCH, "-o", "ff"], _with(_fifo("ff")),
      contains="FIFO")
probe("batch -o a folder", [*BATCH, "-o", "sub"], _with(lambda d: (d / "sub").mkdir()),
      contains="directory")
probe("batch -o a 300-byte name", [*BATCH, "-o", "a" * 300 + ".csv"], contains="too long")
probe("batch -o a legal 250-byte name", [*BATCH, "-o", "a" * 246 + ".csv"], code=0,
      one_line=False, changes=("a" * 246 + ".csv",))
probe("batch -o past PATH_MAX", [*BATCH, "-o", "/".join(["d" * 200] * 25) + "/b.csv"],
      contains="too long")
probe("batch -o a non-UTF-8 name", [*BATCH, "-o", os.fsdecode(b"b\xff.csv")], code=0,
      one_line=False, changes=(os.fsdecode(b"b\xff.csv"),))
probe("batch --maps a 300-byte name", [*BATCH, "-o", "b.csv", "--maps", "m" * 300],
      contains="--maps")
probe("batch --maps past PATH_MAX", [*BATCH, "-o", "b.csv", "--maps", "/".join(["m" * 200] * 25)],
      contains="--maps")
probe("batch full disk at the first row", [*BATCH, "-o", "b.csv"], fsize=400,
      contains="nothing was written")
probe("batch full disk on a resumed file", [*BATCH, "-o", "b.csv"],
      _with(_batch_csv("b.csv", lambda t: "\n".join(t.splitlines()[:2]) + "\n")),
      fsize=300, one_line=False, contains="run the same command again",
      changes=("b.csv",))  # its time changes (rolled back); its rows are checked below
# --- 7. exit codes and the summary ---------------------------------------------------------
probe("batch where every line fails", ["batch", "bad.scen", "-o", "b.csv", "--no-progress"],
      _with(_file("bad.scen", "version 1\n" + "0\tnowhere.map\t4\t3\t0\t0\t3\t2\t5\n" * 4)),
      code=2, one_line=False, changes=("b.csv",))


@pytest.mark.parametrize("name, probe_, setup", PROBES, ids=[p[0] for p in PROBES])
def test_batch_probe(scratch: Path, name: str, probe_: Probe, setup: Setup | None) -> None:
    result = run_probe(scratch, name, probe_, setup)
    if name.startswith("batch dangling"):
        assert (scratch / "dl").is_symlink(), "the link was replaced"
    if name == "batch dangling link: the file it names is made":
        text = (scratch / "target.csv").read_text(encoding="utf-8")
        rows = list(csv.DictReader(text.splitlines()))
        assert [r["verdict"] for r in rows] == ["pass"] * 3
    if name.startswith("batch full disk on a resumed"):
        text = (scratch / "b.csv").read_text()  # rolled back: its header and first row only
        lines = text.splitlines()
        assert text.endswith("\n") and len(lines) == 2 and lines[1].startswith("2,ok,")
    if name == "batch where every line fails":
        assert result.stdout.startswith("4 rows: 0 ok, 4 errors (first: line 2: unknown map "
                                        "'nowhere.map'"), result.stdout
        assert "no VoI (no ok row)" in result.stdout and "nan" not in result.stdout
    if name.startswith("batch resumes"):
        text = (scratch / "b.csv").read_text(encoding="utf-8")
        rows = list(csv.DictReader(text.splitlines()))
        assert sorted(int(r["line"]) for r in rows) == [2, 3, 4]


def test_enough_batch_probes() -> None:
    assert len(PROBES) >= 30
    assert len({p[0] for p in PROBES}) == len(PROBES)


def test_full_disk_on_a_real_file_system(scratch: Path) -> None:
    """A tmpfs of 12 KiB fills up in the middle of a batch: the file keeps whole rows only,
    the run says so in one line (exit 2), and a run with room continues it. Needs root (to
    mount); skipped otherwise."""
    disk = scratch.parent / "disk"
    disk.mkdir()
    if os.geteuid() != 0 or subprocess.run(["mount", "-t", "tmpfs", "-o", "size=12k", "tmpfs",
                                             str(disk)], capture_output=True).returncode != 0:
        pytest.skip("cannot mount a tmpfs here (needs root)")
    try:
        _tiny(scratch)
        long_scen = "version 1\n" + "".join(TINY_SCEN.splitlines(keepends=True)[1:]) * 40
        (scratch / "tiny.scen").write_text(long_scen)
        before = listing(scratch)
        result = run([*BATCH, "-o", str(disk / "b.csv"), "--chunk", "1"], scratch)
        check(result, Probe([], code=2, contains="No space left"), before, listing(scratch))
        text = (disk / "b.csv").read_text()
        assert text.endswith("\n") and 2 < text.count("\n") < 121
        assert [p.name for p in disk.iterdir()] == ["b.csv"]  # no temporary file
    finally:
        subprocess.run(["umount", str(disk)], check=False)
