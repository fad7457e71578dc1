"""Hostile probes, second round: each runs the real ``dpp`` in a session of its own under
CPU and memory limits and asserts its exit code, exactly one stderr line where an error is
expected, no traceback, untouched files, and no surviving process."""

from __future__ import annotations

import json
import os
import stat
from pathlib import Path

import pytest

from tests.hostile._harness import MAP, Probe, Setup, check, link, listing, run, run_probe

pytestmark = pytest.mark.hostile

TRI = ["tri.json"]


def _float_instance(w: list[float]) -> dict[str, object]:
    return {"graph": {"nodes": [{"id": "s"}, {"id": "a"}, {"id": "g1"}, {"id": "g2"}],
                      "edges": [{"source": "s", "target": "a", "weight": w[0]},
                                {"source": "a", "target": "g1", "weight": w[1]},
                                {"source": "s", "target": "g2", "weight": w[2]},
                                {"source": "g2", "target": "g1", "weight": w[1]}]},
            "start": "s", "goals": ["g1", "g2"], "prior": ["1/2", "1/2"], "numbers": "float"}


def _scaled(factor: str) -> Setup:
    def setup(d: Path) -> None:
        doc = json.loads((d / "tri.json").read_text())
        for e in doc["graph"]["edges"]:
            e["weight"] = f"{e['weight']}{factor}"
        (d / "scaled.json").write_text(json.dumps(doc))
    return setup


def _floats(*w: float) -> Setup:
    def setup(d: Path) -> None:
        (d / "f.json").write_text(json.dumps(_float_instance(list(w))))
    return setup


def _fifo(name: str) -> Setup:
    def setup(d: Path) -> None:
        os.mkfifo(d / name)
    return setup


def _big_map(h: int, w: int) -> Setup:
    def setup(d: Path) -> None:
        with open(d / "big.map", "w") as fh:
            fh.write(f"type octile\nheight {h}\nwidth {w}\nmap\n")
            row = "." * w + "\n"
            for _ in range(h):
                fh.write(row)
    return setup


def _folder(name: str, *files: str) -> Setup:
    def setup(d: Path) -> None:
        (d / name).mkdir()
        for f in files:
            (d / name / f).write_text("the user's own file\n")
    return setup


def _combine(*setups: Setup) -> Setup:
    def setup(d: Path) -> None:
        for s in setups:
            s(d)
    return setup


PROBES: list[tuple[str, Probe, Setup | None]] = []


def probe(name: str, args: list[str], setup: Setup | None = None, **kw: object) -> None:
    PROBES.append((name, Probe(args, **kw), setup))  # type: ignore[arg-type]


# --- outputs: never replace a non-regular file, never an input --------------------------
probe("solve -o /dev/null", ["solve", *TRI, "-o", "/dev/null"], code=0)
probe("solve -o fifo without reader", ["solve", *TRI, "-o", "ff"], _fifo("ff"),
      contains="FIFO")
probe("solve -o link to /dev/null", ["solve", *TRI, "-o", "ln"], link("ln", "/dev/null"),
      code=0)
probe("solve -o link to fifo", ["solve", *TRI, "-o", "ln"],
      _combine(_fifo("ff"), link("ln", "ff")), contains="FIFO")
probe("solve -o link to regular file", ["solve", *TRI, "-o", "ln"],
      _combine(lambda d: (d / "real.json").write_text("{}"), link("ln", "real.json")),
      code=0, changes=("real.json",))
probe("solve --save-instance /dev/null", ["solve", *TRI, "--save-instance", "/dev/null"],
      code=0, one_line=False)
probe("solve x -o x", ["solve", *TRI, "-o", "tri.json"], contains="input")
probe("solve x -o ./sub/../x", ["solve", *TRI, "-o", "sub/../tri.json"], _folder("sub"),
      contains="input")
probe("solve x --save-instance x", ["solve", *TRI, "--save-instance", "tri.json"],
      contains="input")
probe("solve --map m -o m", ["solve", *MAP, "-o", "paper10.map"], contains="input")
probe("solve x -o link-to-x", ["solve", *TRI, "-o", "ln"], link("ln", "tri.json"),
      contains="input")
probe("export-efg x -o x", ["export-efg", *TRI, "-H", "1", "-o", "tri.json"],
      contains="input")
probe("export-efg -o /dev/null", ["export-efg", *TRI, "-H", "1", "-o", "/dev/null"], code=0)
probe("export-efg -o fifo", ["export-efg", *TRI, "-H", "1", "-o", "ff"], _fifo("ff"),
      contains="FIFO")
probe("plot map -o fifo", ["plot", "map", "-o", "ff.png"], _fifo("ff.png"), contains="FIFO")
probe("compare --output-dir over a fifo file",
      ["experiment", "compare", "--output-dir", "out"],
      _combine(_folder("out"), _fifo("out/compare.csv")), contains="FIFO", one_line=True)
probe("solve -o existing folder", ["solve", *TRI, "-o", "sub"], _folder("sub", "keep.txt"))
probe("solve -o /dev/full", ["solve", *TRI, "-o", "/dev/full"], contains="cannot write")
# --- inputs that never end or never come --------------------------------------------------
probe("solve fifo input without writer", ["solve", "ff"], _fifo("ff"))
probe("certify fifo profile", ["certify", *TRI, "ff"], _fifo("ff"))
probe("value fifo instance", ["value", "ff", "-H", "1"], _fifo("ff"))
probe("solve --map fifo", ["solve", "--map", "ff", *MAP[2:]], _fifo("ff"))
probe("plot voi fifo", ["plot", "voi", "ff", "-o", "v.png"], _fifo("ff"))
probe("value /dev/null", ["value", "/dev/null", "-H", "1"])
probe("certify /dev/urandom profile", ["certify", *TRI, "/dev/urandom"])
probe("solve --map /dev/urandom", ["solve", "--map", "/dev/urandom", *MAP[2:]])
# --- numerics --------------------------------------------------------------------------
probe("float 2e-12 solve", ["solve", "f.json"], _floats(2e-12, 2e-12, 2e-12), code=0,
      one_line=False)
probe("float 2e-12 mixed 3e-12 solve", ["solve", "f.json", "-o", "p.json"],
      _floats(2e-12, 3e-12, 2e-12), code=0, changes=("p.json",))
probe("float 1e-300 solve", ["solve", "f.json"], _floats(1e-300, 1e-300, 1e-300),
      contains="10**200")
probe("float 1e-300 value", ["value", "f.json", "-H", "2"], _floats(1e-300, 1e-300, 1e-300),
      contains="10**200")
probe("float 1e300 solve", ["solve", "f.json"], _floats(1e300, 1, 1), contains="10**200")
probe("float 1e300 certify", ["certify", "--float", "f.json", "prof.json"],
      _floats(1e300, 1, 1), contains="10**200")
probe("float ratio 1e150 solve", ["solve", "f.json"], _floats(1e150, 1, 1),
      contains="10**6")
probe("float ratio 1e150 value", ["value", "f.json", "-H", "3"], _floats(1e150, 1, 1),
      contains="10**6")
probe("float ratio 1e7 certify", ["certify", "--float", "f.json", "prof.json"],
      _floats(1e7, 1, 1), contains="10**6")
probe("float ratio 1e150 export-efg", ["export-efg", "f.json", "-H", "1", "-o", "g.efg"],
      _floats(1e150, 1, 1), contains="10**6")
probe("float ratio 1e5 solve answers", ["solve", "f.json"], _floats(1e5, 1, 1), code=0,
      one_line=False)
probe("exact 1e12-scaled value tree", ["value", "scaled.json", "-H", "3", "--route", "tree"],
      _scaled("000000000000"), code=(0, 3), one_line=False)
probe("exact 1e12-scaled value structured",
      ["value", "scaled.json", "-H", "inf", "--route", "structured"],
      _scaled("000000000000"), code=0, one_line=False)
probe("exact 1e40-scaled value tree", ["value", "scaled.json", "-H", "3", "--route", "tree"],
      _scaled("0" * 40), code=(0, 3), one_line=False)
probe("exact 1e-12-scaled solve", ["solve", "scaled.json"], _scaled("/1000000000000"),
      code=0, one_line=False)
# --- sizes and budgets ---------------------------------------------------------------------
probe("5000x5000 map solve", ["solve", "--map", "big.map", "--start", "0,0", "--goals",
                              "4999,4999", "0,4999", "--prior", "1/2,1/2"],
      _big_map(5000, 5000), memory=1 << 30, contains="4000000")
probe("5000x5000 map value", ["value", "--map", "big.map", "--start", "0,0", "--goals",
                              "4999,4999", "0,4999", "--prior", "1/2,1/2", "-H", "inf"],
      _big_map(5000, 5000), memory=1 << 30, contains="4000000")
probe("2001x2000 map certify", ["certify", "--map", "big.map", "--start", "0,0", "--goals",
                                "1,1", "0,1", "--prior", "1/2,1/2", "prof.json"],
      _big_map(2001, 2000), memory=1 << 30, contains="limit")
for cmd in (["certify", *TRI, "prof.json"], ["value", *TRI, "-H", "1"],
            ["export-efg", *TRI, "-H", "1", "-o", "g.efg"], ["audit", "--solver", "json:loads"]):
    probe(f"{cmd[0]} --max-prefixes 10**12", [*cmd, "--max-prefixes", str(10**12)],
          contains="10000000")
probe("value --route tree too large", ["value", "--map", "paper10.map", "--start", "9,0",
                                       "--goals", "0,9", "0,0", "--prior", "0.6,0.4",
                                       "-H", "60", "--route", "tree"],
      contains="--route structured")
probe("value --route auto huge H decides fast",
      ["value", *MAP, "-H", "10000", "--route", "auto"], code=0, one_line=False, cpu=60)
probe("certify -H 10000 auto", ["certify", *MAP, "-H", "10000", "prof.json"],
      code=(0, 1, 2), one_line=False, cpu=60)


def _long_walks(steps: int) -> Setup:
    """A path graph of 2 * steps + 1 nodes, start in the middle, a goal at each end, and a
    profile whose two walks have ``steps`` steps each (written directly, not solved)."""
    def setup(d: Path) -> None:
        n = 2 * steps + 1
        doc = {"graph": {"nodes": [{"id": i} for i in range(n)],
                         "edges": [{"source": i, "target": i + 1} for i in range(n - 1)]},
               "start": steps, "goals": [0, n - 1], "prior": ["3/5", "2/5"]}
        (d / "path.json").write_text(json.dumps(doc))
        prof = {"format": "dpp-profile/1", "goals": {"primary": 0, "secondary": n - 1},
                "defender": {"rule": "progress", "goal": 0},
                "attacker": {"primary": [{"path": list(range(steps, -1, -1)),
                                          "probability": 1}],
                             "secondary": [{"path": list(range(steps, n)),
                                            "probability": 1}]}}
        (d / "path_profile.json").write_text(json.dumps(prof))
    return setup


probe("certify a 6,000-step walk, structured, in 1.5 GiB",
      ["certify", "path.json", "path_profile.json", "--route", "structured"],
      _long_walks(6_000), code=(0, 1), one_line=False, memory=3 << 29, cpu=60)
probe("certify a 60,000-step walk, structured, in 1.5 GiB",  # slow: the full-size campaign
      ["certify", "path.json", "path_profile.json", "--route", "structured"],
      _long_walks(60_000), code=(0, 1), one_line=False, memory=3 << 29, cpu=400)
probe("value on a 120,001-node path, auto route decides",
      ["value", "path.json", "-H", "10000", "--route", "auto"],
      _long_walks(60_000), code=(0, 2), one_line=False, memory=3 << 29, cpu=200)
# --- the command line: one line, exit 2, for every command ---------------------------------
for cmd in (["solve"], ["value"], ["certify"], ["export-efg"], ["audit"],
            ["experiment", "compare"], ["experiment", "density"], ["plot", "map"],
            ["plot", "beliefs"], ["plot", "voi"]):
    probe(f"{' '.join(cmd)} --bogus", [*cmd, "--bogus"])
for cmd in (["plot"], ["experiment"], []):
    probe(f"dpp {' '.join(cmd)} without command", cmd, contains="missing command")
probe("value -H without value", ["value", *TRI, "-H"])
probe("certify --route without value", ["certify", *TRI, "prof.json", "--route"])
probe("density --workers x", ["experiment", "density", "--workers", "x"])
probe("density --samples 10**12", ["experiment", "density", "--samples", str(10**12)])
probe("audit --timeout nan", ["audit", "--solver", "json:loads", "--timeout", "nan"])
probe("audit --timeout inf", ["audit", "--solver", "json:loads", "--timeout", "inf"])
probe("solve two instances", ["solve", "tri.json", "tri.json"])
probe("certify three files", ["certify", "tri.json", "prof.json", "prof.json"])
probe("value -H 1e3", ["value", *TRI, "-H", "1e3"])
probe("value -H ''", ["value", *TRI, "-H", ""])
probe("export-efg --max-nodes -1", ["export-efg", *TRI, "-H", "1", "-o", "g.efg",
                                    "--max-nodes", "-1"])
probe("certify --trials 10**12", ["certify", *TRI, "prof.json", "--trials", str(10**12)])
probe("audit --examples 10**12", ["audit", "--solver", "json:loads", "--examples",
                                  str(10**12)])
probe("audit --max-nodes 10**6", ["audit", "--solver", "json:loads", "--max-nodes", "1000000"])
probe("density --size 10**9", ["experiment", "density", "--size", str(10**9)])
probe("density --densities 100", ["experiment", "density", "--densities", "100",
                                  "--samples", "1", "--size", "4", "--workers", "1",
                                  "--output-dir", "dd"])
probe("density --densities -5", ["experiment", "density", "--densities=-5", "--samples", "1",
                                 "--workers", "1", "--output-dir", "dd"])
# --- audit: solvers that misbehave ----------------------------------------------------------


def _solver(script: str, **kw: object) -> list[str]:
    return ["audit", "--solver-cmd", f"../bin/{script} {{instance}} {{profile}}",
            "--examples", "2", "--no-shrink", "--timeout", "1.5", "--output-dir", "af"]


AUDIT_FAIL = {"code": 1, "one_line": False, "changes": ("af",)}
for script in ("fifo_exit.sh", "fifo_block.sh", "escape_exit.sh", "escape_hang.sh",
               "orphan.sh", "flood.sh", "stubborn.sh", "zero_link.sh", "dir_profile.sh",
               "empty.sh", "huge.sh", "killgroup.sh", "binary.sh", "slow.sh"):
    probe(f"audit solver {script}", _solver(script), memory=1 << 30, **AUDIT_FAIL)
probe("audit keeps the user's files in --output-dir",
      [*_solver("empty.sh")], _folder("af", "profile.json", "notes.txt", "certificate.json"),
      **AUDIT_FAIL)


SLOW_PROBES = {"certify a 60,000-step walk, structured, in 1.5 GiB"}
"""Probes of the ``slow`` run (``python3 dev.py test -m slow``); the default run has each one's
short version (the 6,000-step walk; the trie of a 60,000-step walk is linear:
tests/dppverify/tree_route/test_linear_memory.py)."""


@pytest.mark.parametrize("name, probe_, setup", [
    pytest.param(*p, marks=pytest.mark.slow) if p[0] in SLOW_PROBES else p for p in PROBES],
    ids=[p[0] for p in PROBES])
def test_probe(scratch: Path, name: str, probe_: Probe, setup: Setup | None) -> None:
    run_probe(scratch, name, probe_, setup)
    if name.startswith("audit keeps"):
        for f in ("profile.json", "notes.txt", "certificate.json"):
            assert (scratch / "af" / f).read_text() == "the user's own file\n", f


def test_enough_probes() -> None:
    assert len(PROBES) >= 60
    assert len({p[0] for p in PROBES}) == len(PROBES)


@pytest.mark.parametrize("via_link", [False, True])
def test_streams_into_a_fifo_with_a_reader(scratch: Path, via_link: bool) -> None:
    """``-o FIFO`` (or a symlink to one) with a reader: the profile streams through it and the
    FIFO stays a FIFO."""
    import threading

    os.mkfifo(scratch / "ff")
    target = "ff"
    if via_link:
        (scratch / "ln").symlink_to("ff")
        target = "ln"
    got: list[bytes] = []

    def read() -> None:
        with open(scratch / "ff", "rb") as fh:  # blocks until the probe opens it for writing
            got.append(fh.read())

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    before = listing(scratch)
    result = run(["solve", "tri.json", "-o", target], scratch)
    reader.join(60)
    check(result, Probe([], code=0), before, listing(scratch))
    assert json.loads(got[0])["format"] == "dpp-profile/1"
    assert stat.S_ISFIFO((scratch / "ff").lstat().st_mode)
