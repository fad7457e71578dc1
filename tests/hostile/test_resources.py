"""Hostile probes, third round: resources. Too few open files, a map too large for the
memory the process may use, a ``.scen`` file built to make a pre-pass quadratic, and a
``--dask`` port where no scheduler answers: each is one line and exit 2, in bounded time and
memory (enforced by the harness' kernel limits), never a traceback.
"""

from __future__ import annotations

import socket
import threading
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

from tests.hostile._harness import Probe, run_probe

pytestmark = pytest.mark.hostile

Setup = Callable[[Path], None]


def _map(name: str, h: int, w: int) -> Setup:
    def setup(d: Path) -> None:
        with open(d / name, "w") as fh:
            fh.write(f"type octile\nheight {h}\nwidth {w}\nmap\n")
            row = "." * w + "\n"
            for _ in range(h):
                fh.write(row)
    return setup


def _tiny(d: Path) -> None:
    (d / "tiny.map").write_text("type octile\nheight 3\nwidth 4\nmap\n....\n.@@.\n....\n")
    (d / "tiny.scen").write_text("version 1\n0\ttiny.map\t4\t3\t0\t0\t3\t2\t5\n"
                                 "0\ttiny.map\t4\t3\t3\t0\t0\t2\t5\n"
                                 "0\ttiny.map\t4\t3\t0\t2\t3\t0\t3\n")


def _quadratic_scen(lines_: int, size: int) -> Setup:
    """``lines_`` lines on one ``size`` x ``size`` map, every goal distinct: a pre-pass drawing
    each line's fake-goal candidates up front touches ``lines_ * size**2`` cells (3.6 * 10**9
    for the slow run's 60,000 lines on 300 x 300, beyond the CPU limit); all but two lines
    start on nothing (outside the map), so only two games are solved."""
    def setup(d: Path) -> None:
        _map("big.map", size, size)(d)
        s, far = size - 1, 2 * (size - 1)
        lines = ["version 1", f"0\tbig.map\t{size}\t{size}\t0\t0\t{s}\t{s}\t{far}",
                 f"0\tbig.map\t{size}\t{size}\t{s}\t0\t0\t{s}\t{far}"]
        lines += [f"0\tbig.map\t{size}\t{size}\t{size + 100}\t{size + 100}\t{k % size}"
                  f"\t{k // size % size}\t1" for k in range(lines_)]
        (d / "q.scen").write_text("\n".join(lines) + "\n")
    return setup


PROBES: list[tuple[str, Probe, Setup | None]] = []


def probe(name: str, args: list[str], setup: Setup | None = None, **kw: object) -> None:
    PROBES.append((name, Probe(args, **kw), setup))  # type: ignore[arg-type]


probe("batch --workers 2 with ulimit -n 20",
      ["batch", "tiny.scen", "-o", "b.csv", "--workers", "2", "--no-progress"], _tiny,
      nofile=20, contains="ulimit -n")
probe("density --workers 2 with ulimit -n 20",
      ["experiment", "density", "--samples", "4", "--size", "5", "--workers", "2",
       "--output-dir", "dd"], nofile=20, contains="ulimit -n")
probe("solve with ulimit -n 20", ["solve", "tri.json"], nofile=20, code=0, one_line=False)
probe("batch --workers 2 with ulimit -n 64",
      ["batch", "tiny.scen", "-o", "b.csv", "--workers", "2", "--no-progress"], _tiny,
      nofile=64, code=0, one_line=False, changes=("b.csv",))
for cmd in (["value"], ["certify", "prof.json"], ["export-efg", "-H", "1", "-o", "g.efg"]):
    probe(f"{cmd[0]} on a 4,000,000-cell map in 3 GiB",
          [*cmd, "--map", "big.map", "--start", "0,0", "--goals", "1999,1999", "0,1999",
           "--prior", "1/2,1/2"], _map("big.map", 2000, 2000), contains="memory", cpu=60)
probe("solve 3 goals on a 4,000,000-cell map in 3 GiB",
      ["solve", "--map", "big.map", "--start", "0,0", "--goals", "1999,1999", "0,1999",
       "1999,0", "--prior", "1/3,1/3,1/3"], _map("big.map", 2000, 2000), contains="memory",
      cpu=60)
QUADRATIC = {"": (6_000, 100), " (60,000 lines)": (60_000, 300)}
"""The short version (default run: 6,000 lines on 100 x 100) and the full campaign (``slow``:
60,000 lines on 300 x 300) of the quadratic .scen, as (lines, map side)."""
for _tag, (_n, _size) in QUADRATIC.items():
    probe(f"batch on a .scen built to be quadratic{_tag}",
          ["batch", "q.scen", "-o", "q.csv", "--no-progress"],
          _quadratic_scen(_n, _size), code=2, one_line=False, changes=("q.csv",), cpu=100)
    probe(f"audit --scen on a .scen built to be quadratic{_tag}",
          ["audit", "--solver", "solver.adapter:solve_json", "--map", "big.map", "--scen",
           "q.scen", "--no-shrink", "--output-dir", "af"], _quadratic_scen(_n, _size),
          code=(0, 1),
          one_line=False, changes=("af",), cpu=100)


@pytest.mark.parametrize("name, probe_, setup", [
    pytest.param(*p, marks=pytest.mark.slow) if "60,000 lines" in p[0] else p for p in PROBES],
    ids=[p[0] for p in PROBES])
def test_resource_probe(scratch: Path, name: str, probe_: Probe, setup: Setup | None) -> None:
    result = run_probe(scratch, name, probe_, setup)
    if name.startswith("batch on a .scen built"):
        rows = 60_002 if "60,000 lines" in name else 6_002
        assert result.stdout.startswith(f"{rows} rows: 2 ok"), result.stdout


@pytest.fixture
def silent_port() -> Iterator[int]:
    """A TCP port that accepts connections and never says a word (not a Dask scheduler)."""
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(8)
    held: list[socket.socket] = []
    stop = threading.Event()

    def accept() -> None:
        server.settimeout(0.2)
        while not stop.is_set():
            try:
                held.append(server.accept()[0])
            except OSError:
                continue

    t = threading.Thread(target=accept, daemon=True)
    t.start()
    yield server.getsockname()[1]
    stop.set()
    t.join(5)
    for s in (*held, server):
        s.close()


@pytest.mark.parametrize("cmd", [["batch", "tiny.scen", "-o", "b.csv", "--no-progress"],
                                 ["experiment", "density", "--samples", "2", "--size", "5",
                                  "--output-dir", "dd"]], ids=["batch", "density"])
def test_dask_port_without_a_scheduler(scratch: Path, silent_port: int,
                                       cmd: list[str]) -> None:
    """``--dask`` at a port where something listens but no scheduler greets: one line naming
    it (before the fix: a wait of 90 s, then another error)."""
    run_probe(scratch, "dask", Probe([*cmd, "--dask", f"tcp://127.0.0.1:{silent_port}"],
                                     contains="no greeting within 2 s",
                                     env={"DPP_DASK_CONNECT_SECONDS": "2"}), _tiny)


def test_enough_resource_probes() -> None:
    assert len(PROBES) >= 10
