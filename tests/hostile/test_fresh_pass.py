"""Hostile probes, third round: what a fresh hostile pass over every command found
(besides the classes of the other files). Each was reproduced before its fix; the classes are
listed in the issue's closing note."""

from __future__ import annotations

import socket
from collections.abc import Callable
from pathlib import Path

import pytest

from tests.hostile._harness import Probe, run_probe

pytestmark = pytest.mark.hostile

Setup = Callable[[Path], None]

MAP = ["--map", "paper10.map", "--start", "9,0", "--goals", "0,9", "0,0", "--prior", "0.6,0.4"]


def _tiny(d: Path) -> None:
    (d / "tiny.map").write_text("type octile\nheight 3\nwidth 4\nmap\n....\n.@@.\n....\n")
    (d / "tiny.scen").write_text("version 1\n0\ttiny.map\t4\t3\t0\t0\t3\t2\t5\n"
                                 "0\ttiny.map\t4\t3\t3\t0\t0\t2\t5\n")


def _socket(name: str) -> Setup:
    def setup(d: Path) -> None:
        s = socket.socket(socket.AF_UNIX)
        s.bind(str(d / name))
        s.close()  # the socket file stays
    return setup


PROBES: list[tuple[str, Probe, Setup | None]] = []


def probe(name: str, args: list[str], setup: Setup | None = _tiny, **kw: object) -> None:
    PROBES.append((name, Probe(args, **kw), setup))  # type: ignore[arg-type]


# a file of another kind as SCEN: refused, not a CSV of error rows
probe("batch SCEN = a .map", ["batch", "tiny.map", "-o", "b.csv"], contains="not a .scen file")
probe("batch SCEN = an instance JSON", ["batch", "tri.json", "-o", "b.csv"],
      contains="not a .scen file")
# an option value that could never give a row
probe("batch --route tree", ["batch", "tiny.scen", "-o", "b.csv", "--route", "tree"],
      contains="--route")
probe("batch --route both", ["batch", "tiny.scen", "-o", "b.csv", "--route", "both"],
      contains="--route")
# --dask with a protocol the client cannot use as is: one line, not an internal error
probe("batch --dask tls://", ["batch", "tiny.scen", "-o", "b.csv", "--dask",
                              "tls://127.0.0.1:1"], contains="Dask scheduler")
probe("density --dask tls://", ["experiment", "density", "--samples", "2", "--size", "5",
                                "--dask", "tls://127.0.0.1:1", "--output-dir", "dd"],
      contains="Dask scheduler")
# a hint that names an option the command has
probe("export-efg tree too large", ["export-efg", *MAP, "-H", "30", "-o", "g.efg"],
      contains="lower the horizon")
# an output that is a socket is named as one
probe("solve -o a socket", ["solve", "tri.json", "-o", "s.sock"], _socket("s.sock"),
      contains="socket")
probe("export-efg -o a socket", ["export-efg", "tri.json", "-H", "1", "-o", "s.sock"],
      _socket("s.sock"), contains="socket")
# a trailing slash names a folder: never a file of that name
for cmd in (["solve", "tri.json"], ["value", "tri.json"], ["certify", "tri.json", "prof.json"],
            ["batch", "tiny.scen"]):
    probe(f"{cmd[0]} -o new/ (a trailing slash)", [*cmd, "-o", "new/"], contains="folder")


@pytest.mark.parametrize("name, probe_, setup", PROBES, ids=[p[0] for p in PROBES])
def test_fresh_probe(scratch: Path, name: str, probe_: Probe, setup: Setup | None) -> None:
    result = run_probe(scratch, name, probe_, setup)
    if name == "export-efg tree too large":
        assert "--route" not in result.stderr  # export-efg has no --route


def test_enough_fresh_probes() -> None:
    assert len(PROBES) >= 12
    assert len({p[0] for p in PROBES}) == len(PROBES)
