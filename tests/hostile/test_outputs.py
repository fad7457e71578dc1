"""Hostile probes, third round: the outputs of every command.

An output never names an input (by any path or link); a legal long name, a path past
PATH_MAX and a non-UTF-8 name are written or refused in one line; standard output that is a
closed pipe, ``/dev/full``, a closed descriptor or a Latin-1 terminal ends the command with one
line (a closed pipe: quietly, exit 141) or works; a full disk leaves all outputs or none.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from tests.hostile._harness import MAP, Probe, Setup, link, run_probe

pytestmark = pytest.mark.hostile

LONG = "a" * 246  # + a 4-character suffix: 250 bytes, a legal name
DEEP = "/".join(["d" * 200] * 25)  # past PATH_MAX (4096)
ODD = os.fsdecode(b"b\xff")  # not UTF-8


def _copy(source: str, target: str) -> Setup:
    def setup(d: Path) -> None:
        (d / target).parent.mkdir(parents=True, exist_ok=True)
        (d / target).write_bytes((d / source).read_bytes())
    return setup


def _density_csv(d: Path) -> None:
    (d / "density.csv").write_text(
        "density,sample,attempts,obstacles,defender,attacker,U1,U2,U,U_bar,VoI,VoI_float\n"
        "0,0,1,0,sigma*,gamma*,6,0,18/5,24/5,1/4,0.25\n")


PROBES: list[tuple[str, Probe, Setup | None]] = []


def probe(name: str, args: list[str], setup: Setup | None = None, **kw: object) -> None:
    PROBES.append((name, Probe(args, **kw), setup))  # type: ignore[arg-type]


# --- an output is never an input -----------------------------------------------------------
probe("plot map -o a .png link to its instance", ["plot", "map", "i.json", "-o", "ln.png"],
      lambda d: (_copy("tri.json", "i.json")(d), link("ln.png", "i.json")(d)),
      contains="input")
probe("plot map -o its instance named .png", ["plot", "map", "i.png", "-o", "i.png"],
      _copy("tri.json", "i.png"), contains="input")
probe("plot map -o a link to its map", ["plot", "map", *MAP, "-o", "m.png"],
      link("m.png", "paper10.map"), contains="input")
probe("plot beliefs -o a link to its map", ["plot", "beliefs", *MAP, "-o", "m.svg"],
      link("m.svg", "paper10.map"), contains="input")
probe("plot voi -o a link to its CSV", ["plot", "voi", "density.csv", "-o", "v.pdf"],
      lambda d: (_density_csv(d), link("v.pdf", "density.csv")(d)), contains="input")
probe("compare --output-dir over its instance", ["experiment", "compare", "od/compare.csv",
                                                 "--output-dir", "od"],
      _copy("tri.json", "od/compare.csv"), contains="input")
probe("compare --output-dir over its map", ["experiment", "compare", "--map", "od/compare.txt",
                                            *MAP[2:], "--output-dir", "od"],
      _copy("paper10.map", "od/compare.txt"), contains="input")
probe("ngoal --output-dir over its map", ["experiment", "ngoal", "--map", "nd/ngoal.png",
                                          "--max-goals", "2", "--output-dir", "nd"],
      _copy("paper10.map", "nd/ngoal.png"), contains="input")
# --- names: legal and long, past PATH_MAX, not UTF-8 ----------------------------------------
for cmd, out in ((["solve", "tri.json", "-o"], ".json"),
                 (["solve", "tri.json", "--save-instance"], ".json"),
                 (["certify", "tri.json", "prof.json", "-o"], ".json"),
                 (["value", "tri.json", "-o"], ".json"),
                 (["export-efg", "tri.json", "-H", "1", "-o"], ".efg"),
                 (["plot", "map", "-o"], ".png")):
    label = " ".join(c for c in cmd if not c.endswith(".json"))
    probe(f"{label} a legal 250-byte name", [*cmd, LONG + out], code=0, one_line=False,
          changes=(LONG + out,))
    probe(f"{label} past PATH_MAX", [*cmd, f"{DEEP}/x{out}"], contains="too long")
    probe(f"{label} a non-UTF-8 name", [*cmd, ODD + out], code=0, one_line=False,
          changes=(ODD + out,))
probe("compare --output-dir a legal 250-byte name", ["experiment", "compare", "--output-dir",
                                                     LONG + ".out"], code=0, one_line=False,
      changes=(LONG + ".out",))
probe("compare --output-dir past PATH_MAX", ["experiment", "compare", "--output-dir", DEEP],
      contains="too long", one_line=False)
probe("certify -o records a non-UTF-8 input name", ["certify", ODD + ".json", "prof.json",
                                                     "-o", "c.json"],
      _copy("tri.json", ODD + ".json"), code=0, changes=("c.json",))
# --- standard output -------------------------------------------------------------------------
for cmd in (["solve", "tri.json"], ["certify", "tri.json", "prof.json"],
            ["value", "tri.json", "--json"], ["experiment", "compare"], ["solve", "--help"],
            ["--version"], ["--help"]):
    label = " ".join(c for c in cmd if not c.endswith(".json"))
    probe(f"{label} > closed pipe", cmd, code=141, one_line=False, stdout="closed-pipe")
    probe(f"{label} > /dev/full", cmd, contains="standard output", stdout="full")
    probe(f"{label} >&- (closed)", cmd, code=0, one_line=False, stdout="closed")
    probe(f"{label} on a Latin-1 terminal", cmd, code=0, one_line=False,
          env={"PYTHONIOENCODING": "iso-8859-1"})
probe("batch summary > /dev/full", ["batch", "tiny.scen", "-o", "b.csv", "--no-progress"],
      lambda d: ((d / "tiny.map").write_text("type octile\nheight 1\nwidth 3\nmap\n...\n"),
                 (d / "tiny.scen").write_text("version 1\n0\ttiny.map\t3\t1\t0\t0\t2\t0\t2\n"
                                              "0\ttiny.map\t3\t1\t2\t0\t1\t0\t1\n")),
      stdout="full", one_line=False, contains="standard output", code=2, changes=("b.csv",))
probe("solve -o writes nothing to a closed stdout", ["solve", "tri.json", "-o", "p.json"],
      code=0, stdout="closed", changes=("p.json",))
# --- a full disk: all outputs or none -------------------------------------------------------
probe("solve -o and --save-instance on a full disk",
      ["solve", *MAP, "-o", "p.json", "--save-instance", "i.json"], fsize=2000,
      contains="cannot write")
probe("certify -o on a full disk", ["certify", "tri.json", "prof.json", "-o", "c.json"],
      fsize=2000, contains="cannot write")
probe("value -o on a full disk", ["value", "tri.json", "-o", "v.json"], fsize=100,
      contains="cannot write")
probe("export-efg -o on a full disk", ["export-efg", "tri.json", "-H", "2", "-o", "g.efg"],
      fsize=500, contains="cannot write")
probe("compare --output-dir on a full disk", ["experiment", "compare", "--output-dir", "cd"],
      fsize=1000, contains="cannot write", one_line=True, stdout="closed")
probe("plot map on a full disk", ["plot", "map", "-o", "m.png"], fsize=10_000,
      contains="cannot write")
probe("density --output-dir on a full disk",
      ["experiment", "density", "--samples", "2", "--size", "5", "--densities", "0",
       "--workers", "1", "--output-dir", "dd"], fsize=1000, contains="cannot write",
      stdout="closed")
probe("baselines --output-dir on a full disk",
      ["experiment", "baselines", "--samples", "0", "--no-maps", "--output-dir", "bd"],
      fsize=3000, contains="cannot write", stdout="closed")


@pytest.mark.parametrize("name, probe_, setup", PROBES, ids=[p[0] for p in PROBES])
def test_output_probe(scratch: Path, name: str, probe_: Probe, setup: Setup | None) -> None:
    result = run_probe(scratch, name, probe_, setup)
    if probe_.stdout == "closed-pipe":
        assert result.lines == [], result.stderr  # quietly, like any Unix filter
    if "Latin-1" in name:
        assert result.lines == [] or "error" not in result.stderr, result.stderr
    if name.startswith("certify -o records"):
        text = (scratch / "c.json").read_text(encoding="utf-8")  # valid UTF-8, name escaped
        assert "b\\udcff.json" in text


def test_enough_output_probes() -> None:
    assert len(PROBES) >= 50
    assert len({p[0] for p in PROBES}) == len(PROBES)
