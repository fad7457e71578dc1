"""N-goal benchmark: the coalition DP against the tree route, and the DP alone on a 64×64 grid.

1. On the 3×4 unit grid (start (0,1); goals (2,0), (2,3), (0,3); prior 1/2, 1/3, 1/6), at the
   largest horizon whose walk tree has at most ``--max-prefixes`` prefixes: ``V_H`` by the tree
   route (``game_value``: tree, compact LP with cvxpy + Clarabel, exact bracket; and the LP
   alone) and by the coalition DP (``coalition_value``), timed in the same run; the ratio is
   tree route / DP, and both values must agree exactly.
2. The DP alone on a 64×64 open 4-connected grid (start (63,0); goals (0,63), (0,0), (63,63),
   (32,32), (0,32), the first N of them; equal priors) at ``H = inf`` for N = 3, 4, 5: seconds
   and peak memory (max RSS of a fresh subprocess per N; it includes the imports of Python,
   numpy and cvxpy, which dominate it).

Run: ``.venv/bin/python benchmarks/bench_ngoal.py [--max-prefixes 60000] [--size 64]``.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
from fractions import Fraction

from _timing import timed

from dppverify.formats.movingai import GridMap, grid_document
from dppverify.game.instance import Instance, instance_from_json
from dppverify.structured.coalition import coalition_value
from dppverify.tree_route.tree import count_prefixes
from dppverify.tree_route.value_lp import game_value

GOALS64 = ((0, 63), (0, 0), (63, 63), (32, 32), (0, 32))


def small_grid() -> Instance:
    """The 3×4 unit grid with three goals."""
    return instance_from_json(grid_document(GridMap(3, 4, ("....", "....", "....")), (0, 1),
                                             [(2, 0), (2, 3), (0, 3)],
                                             [Fraction(1, 2), Fraction(1, 3), Fraction(1, 6)]))


def tree_vs_dp(max_prefixes: int) -> dict[str, object]:
    inst = small_grid()
    h = inst.hops[inst.start]
    while count_prefixes(inst, h + 1) <= max_prefixes:
        h += 1
    tree, t_tree = timed(game_value, inst, h, max_prefixes=max_prefixes)
    dp, t_dp = timed(coalition_value, inst, h)
    if not tree.bracket.closed or tree.bracket.exact != dp.value:
        raise SystemExit(f"routes disagree at H = {h}: {tree.bracket} vs {dp.value}")
    return {"H": h, "prefixes": tree.prefixes, "value": str(dp.value),
            "tree_seconds": round(t_tree, 3), "lp_seconds": round(tree.lp.seconds, 3),
            "dp_seconds": round(t_dp, 4), "ratio": round(t_tree / t_dp, 1)}


def single(n: int, size: int) -> dict[str, object]:
    rows = tuple("." * size for _ in range(size))
    goals = [(r * (size - 1) // 63, c * (size - 1) // 63) for r, c in GOALS64[:n]]
    inst = instance_from_json(grid_document(GridMap(size, size, rows), (size - 1, 0), goals,
                                             [Fraction(1, n)] * n))
    v, seconds = timed(coalition_value, inst, None)
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    return {"N": n, "cells": size * size, "layers": v.layers, "value": str(v.value),
            "seconds": round(seconds, 2), "max_rss_mib": round(rss, 1)}


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--max-prefixes", type=int, default=60_000)
    parser.add_argument("--size", type=int, default=64)
    parser.add_argument("--single", type=int, help=argparse.SUPPRESS)
    parser.add_argument("--quick", action="store_true",
                        help="tiny sizes, for the test suite (also DPP_BENCH_QUICK=1)")
    args = parser.parse_args()
    counts = (3, 4, 5)
    if not args.single and (args.quick or os.environ.get("DPP_BENCH_QUICK")):
        args.max_prefixes, args.size, counts = 500, 8, (3,)
    if args.single:
        print(json.dumps(single(args.single, args.size)))
        return
    r = tree_vs_dp(args.max_prefixes)
    print(f"3x4 grid, N = 3, H = {r['H']} ({r['prefixes']} prefixes): V_H = {r['value']} by "
          f"both routes; tree route {r['tree_seconds']} s (LP {r['lp_seconds']} s), coalition "
          f"DP {r['dp_seconds']} s: ratio {r['ratio']}x")
    for n in counts:
        out = subprocess.run([sys.executable, __file__, "--single", str(n), "--size",
                              str(args.size)], capture_output=True, text=True, check=True)
        s = json.loads(out.stdout)
        print(f"{args.size}x{args.size} open grid, N = {n}, H = inf: V = {s['value']} after "
              f"{s['layers']} layers, {s['seconds']} s, max RSS {s['max_rss_mib']} MiB")


if __name__ == "__main__":
    main()
