"""Density sweep benchmark: the paper's full sweep must finish in under 60 s.

Runs ``run_density`` with the default configuration (20×20 grids, densities 0-40 %, 200
samples each, 6 strategy pairs per grid) on local processes and reports the wall time, the
time per grid, and — measured in the same run — the ratio of one grid's full work (sampling,
equilibrium, σ', four Dragan paths, six exact evaluations) to ``solve`` alone on the same
grids.

Run: ``.venv/bin/python benchmarks/bench_density.py [--samples 200] [--workers N]``
"""

from __future__ import annotations

import argparse
import os
import time

from _timing import timed

from solver import Instance, solve
from solver.experiments.density import DensityConfig, Task, run_density, run_task
from solver.experiments.sampling import sample_grid

TARGET_SECONDS = 60.0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--samples", type=int, default=200)
    ap.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--quick", action="store_true",
                    help="tiny sizes, for the test suite (also DPP_BENCH_QUICK=1)")
    args = ap.parse_args()
    if args.quick or os.environ.get("DPP_BENCH_QUICK"):
        args.samples, args.workers = 2, 1
    cfg = DensityConfig(samples=args.samples)
    grids = cfg.samples * len(cfg.densities)
    rows, wall = timed(run_density, cfg, workers=args.workers)
    print(f"full sweep: {grids} grids x 6 pairs = {len(rows)} rows, {args.workers} workers, "
          f"{wall:.2f} s wall ({1000 * wall / grids:.1f} ms/grid); target < {TARGET_SECONDS:.0f} s:"
          f" {'MET' if wall < TARGET_SECONDS else 'MISSED'}")
    # one density, in this process: full task vs solve() alone on the same grids
    probe = Task(cfg, 30, 0, min(40, cfg.samples))
    _, full = timed(run_task, probe)
    t0 = time.perf_counter()
    for k in range(probe.count):
        s = sample_grid(cfg.size, 30, k, cfg.seed, cfg.start, cfg.goals)
        solve(Instance.from_grid(s.blocked, cfg.start, cfg.goals, cfg.prior))
    alone = time.perf_counter() - t0
    print(f"30% density, {probe.count} grids in one process: full task {full:.3f} s, "
          f"sampling + solve alone {alone:.3f} s, ratio {full / alone:.1f}")


if __name__ == "__main__":
    main()
