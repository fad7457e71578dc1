"""How often `dpp solve` still answers "could not decide" for N goals, and why.

Draws ``--per`` instances per family (random digraphs, small grids with obstacles, hub gadgets:
``tests/solver/_ngoal_families.py``, seeds ``0 … per-1``) and N = 2..5, solves each with
:func:`solver.coalitions.construction.coalition_equilibrium` (the default budget) and counts:
solved, solved with extra facet normals (the 0/1 coalition sets did not suffice: the
instances the old construction refused), refused (the budget ended first: exit 3 with a
bracket), with the reasons of the refusals and the time per instance.

Run: ``.venv/bin/python benchmarks/bench_ngoal_refusals.py [--per 50] [--goals 4 5]``.
"""

from __future__ import annotations

import argparse
import collections
import os
import time

from solver.coalitions.construction import FixpointNotReached, coalition_equilibrium
from solver.game.instance_reading import instance_from_json
from tests.solver._ngoal_families import FAMILIES, draw


def main() -> None:
    """Print one line per (family, N) and the refusals."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--per", type=int, default=50)
    ap.add_argument("--goals", nargs="+", type=int, default=[2, 3, 4, 5])
    ap.add_argument("--families", nargs="+", default=list(FAMILIES))
    ap.add_argument("--quick", action="store_true",
                    help="two instances, N = 3, for the test suite (also DPP_BENCH_QUICK=1)")
    args = ap.parse_args()
    if args.quick or os.environ.get("DPP_BENCH_QUICK"):
        args.per, args.goals = 2, [3]
    print(f"{'family':8} {'N':>2} {'drawn':>6} {'solved':>7} {'normals':>8} {'refused':>8} "
          f"{'seconds':>8}")
    total: collections.Counter[str] = collections.Counter()
    for family in args.families:
        for n in args.goals:
            c: collections.Counter[str] = collections.Counter()
            t0 = time.perf_counter()
            for seed in range(args.per):
                game = instance_from_json(draw(family, seed, n))
                c["drawn"] += 1
                try:
                    eq = coalition_equilibrium(game)
                except FixpointNotReached as exc:
                    c["refused"] += 1
                    print(f"  refused: {family} seed {seed} N = {n}: {exc}", flush=True)
                    continue
                c["solved"] += 1
                c["normals"] += bool(eq.normals)
            total.update(c)
            print(f"{family:8} {n:>2} {c['drawn']:>6} {c['solved']:>7} {c['normals']:>8} "
                  f"{c['refused']:>8} {time.perf_counter() - t0:>8.1f}", flush=True)
    print(f"{'all':8} {'':>2} {total['drawn']:>6} {total['solved']:>7} {total['normals']:>8} "
          f"{total['refused']:>8}")


if __name__ == "__main__":
    main()
