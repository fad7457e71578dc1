"""V_H benchmark: our compact LP against the same LP in scipy's HiGHS, and the peers.

On the 3×4 grid (start (0,1), goals (2,0) and (2,3), prior 3/5-2/5, unit weights), for each
horizon H it reports:

- the walk tree's size and ``V_H`` exactly (``dppverify.game_value``'s bracket);
- our value LP (``dppverify.tree_route.value_lp.solve_value_lp``: cvxpy + Clarabel, wall time
including
  cvxpy's problem construction) and the SAME LP assembled as sparse matrices and solved by
  ``scipy.optimize.linprog(method="highs")`` in the same run, as a ratio (target <= 3);
- OpenSpiel (``load_efg_game`` + ``sequence_form_lp`` with HiGHS) and Gambit
  (``read_efg`` + ``nash.lp_solve(rational=True)``) on the exported ``.efg`` game, each run in
  a subprocess with a time limit and an address-space limit, so that a hang or a memory
  blow-up cannot take the benchmark down; once a peer fails or exceeds the limit at some H,
  larger H are skipped for it.

Run: ``.venv/bin/python benchmarks/bench_value.py [--hmin 3] [--hmax 12] [--peer-timeout 60]``
(the peers need ``pip install -e '.[peers]'``; without them their columns say so).
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np
import scipy.sparse as sp
from _timing import timed
from scipy.optimize import linprog

from dppverify.game.instance import Instance, Roles, instance_from_json
from dppverify.tree_route.efg import efg_size, tree_to_efg
from dppverify.tree_route.lp import flow_matrix
from dppverify.tree_route.tree import WalkTree, build_tree
from dppverify.tree_route.value_lp import exact_bracket, solve_value_lp

MAX_PEER_NODES = 2_000_000
"""Games larger than this are not even exported for the peers."""


def grid_instance() -> Instance:
    """The 3×4 unit grid of docs/checker.md."""
    rows, cols = 3, 4
    cells = [(r, c) for r in range(rows) for c in range(cols)]
    edges = [{"source": [r, c], "target": [r + dr, c + dc], "weight": 1}
             for r, c in cells for dr, dc in ((0, 1), (1, 0)) if (r + dr, c + dc) in cells]
    return instance_from_json({
        "graph": {"directed": False, "nodes": [{"id": [r, c]} for r, c in cells],
                  "edges": edges},
        "start": [0, 1], "goals": [[2, 0], [2, 3]], "prior": ["3/5", "2/5"]})


def highs_value_lp(tree: WalkTree, roles: Roles) -> tuple[float, float]:
    """The compact LP of value_lp.py as sparse matrices, solved by scipy's HiGHS.

    Variables ``[x1 (n), x2 (n), z (n-1)]``; returns ``(value, wall seconds)`` (assembly
    included, like the cvxpy time).
    """
    t0 = time.perf_counter()
    n = tree.n_prefixes
    leaf = tree.is_leaf_mask()
    node = tree.node
    d1 = np.where(leaf, np.array([float(roles.d1[int(v)]) for v in node]), 0.0)
    d2 = np.where(leaf, np.array([float(roles.d2[int(v)]) for v in node]), 0.0)
    b1, b2 = float(roles.b1), float(roles.b2)
    c = np.concatenate([b1 * d1, b2 * d2, tree.weight_float[1:]])
    flow = flow_matrix(tree)
    root = sp.csr_matrix(([1.0], ([0], [0])), shape=(1, n))
    blk = sp.vstack([root, flow])
    zero = sp.csr_matrix((blk.shape[0], n))
    zz = sp.csr_matrix((blk.shape[0], n - 1))
    a_eq = sp.vstack([sp.hstack([blk, zero, zz]), sp.hstack([zero, blk, zz])]).tocsr()
    b_eq = np.zeros(a_eq.shape[0])
    b_eq[0] = b_eq[blk.shape[0]] = 1.0
    pick = sp.hstack([sp.csr_matrix((n - 1, 1)), sp.identity(n - 1, format="csr")])
    eye = sp.identity(n - 1, format="csr")
    none = sp.csr_matrix((n - 1, n))
    a_ub = sp.vstack([sp.hstack([b1 * pick, none, -eye]),
                      sp.hstack([none, b2 * pick, -eye])]).tocsr()
    bounds = [(0, None)] * (2 * n) + [(None, None)] * (n - 1)
    res = linprog(c, A_ub=a_ub, b_ub=np.zeros(a_ub.shape[0]), A_eq=a_eq, b_eq=b_eq,
                  bounds=bounds, method="highs")
    seconds = time.perf_counter() - t0
    if res.status != 0:
        raise RuntimeError(f"HiGHS: {res.message}")
    return float(res.fun), seconds


# --- peers, each in a subprocess -------------------------------------------------------------

def _peer_openspiel(path: str) -> dict[str, Any]:
    import cvxpy as cp
    import pyspiel
    from open_spiel.python.algorithms import lp_solver, sequence_form_lp

    lp_solver.LinearProgram.solve.__defaults__ = (cp.HIGHS, {})  # ECOS is gone from cvxpy 1.9
    t0 = time.perf_counter()
    game = pyspiel.load_efg_game(Path(path).read_text())
    v0, v1, _, _ = sequence_form_lp.solve_zero_sum_game(game, solver=cp.HIGHS)
    return {"value": float(v1), "value_p0": float(v0), "seconds": time.perf_counter() - t0}


def _peer_gambit(path: str) -> dict[str, Any]:
    import pygambit as gbt

    t0 = time.perf_counter()
    game = gbt.read_efg(path)
    eq = gbt.nash.lp_solve(game, rational=True).equilibrium
    value = Fraction(eq.payoffs["Defender"])
    return {"value": str(value), "seconds": time.perf_counter() - t0}


PEERS = {"openspiel": _peer_openspiel, "gambit": _peer_gambit}


def _limit_memory(gib: float) -> None:
    limit = int(gib * 2**30)
    resource.setrlimit(resource.RLIMIT_AS, (limit, limit))


def run_peer(name: str, path: str, timeout: float, memory_gib: float) -> dict[str, Any]:
    """Run one peer in a subprocess: ``{"value", "seconds"}`` or ``{"error"}``."""
    t0 = time.perf_counter()
    try:
        proc = subprocess.run([sys.executable, __file__, "--run-peer", name, path],
                              capture_output=True, text=True, timeout=timeout,
                              preexec_fn=lambda: _limit_memory(memory_gib))
    except subprocess.TimeoutExpired:
        return {"error": f"> {timeout:g} s", "seconds": time.perf_counter() - t0}
    if proc.returncode != 0:
        tail = (proc.stderr.strip().splitlines() or ["?"])[-1][:80]
        if "MemoryError" in proc.stderr or "bad_alloc" in proc.stderr:
            tail = f"out of memory (> {memory_gib:g} GiB)"
        if "No module named" in proc.stderr:
            tail = "not installed"
        return {"error": tail, "seconds": time.perf_counter() - t0}
    out: dict[str, Any] = json.loads(proc.stdout.strip().splitlines()[-1])
    return out


# --- the benchmark ---------------------------------------------------------------------------

def bench(hmin: int, hmax: int, peer_timeout: float, memory_gib: float,
          peers: list[str]) -> list[dict[str, Any]]:
    inst = grid_instance()
    roles = inst.roles()
    alive = dict.fromkeys(peers, True)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for h in range(hmin, hmax + 1):
            tree, t_tree = timed(build_tree, inst, h)
            lp, t_ours = timed(solve_value_lp, tree, roles)
            v_highs, t_highs = highs_value_lp(tree, roles)
            bracket, t_exact = timed(exact_bracket, tree, roles, lp)
            size = efg_size(tree)
            row: dict[str, Any] = {
                "H": h, "prefixes": tree.n_prefixes, "efg_nodes": size.nodes,
                "exact": str(bracket.exact) if bracket.closed else
                f"[{bracket.lower}, {bracket.upper}]",
                "ours": lp.value, "ours_s": t_ours, "ours_solver_s": lp.stats.seconds,
                "highs": v_highs, "highs_s": t_highs, "tree_s": t_tree, "exact_s": t_exact}
            path = os.path.join(tmp, f"grid_H{h}.efg")
            if any(alive.values()) and size.nodes <= MAX_PEER_NODES:
                Path(path).write_text(tree_to_efg(tree, max_nodes=MAX_PEER_NODES))
            for name in peers:
                if not alive[name]:
                    row[name] = {"error": "skipped"}
                    continue
                if size.nodes > MAX_PEER_NODES:
                    row[name] = {"error": f"> {MAX_PEER_NODES} nodes"}
                    alive[name] = False
                    continue
                res = run_peer(name, path, peer_timeout, memory_gib)
                row[name] = res
                if "error" in res or res["seconds"] > peer_timeout:
                    alive[name] = False
            if os.path.exists(path):
                os.unlink(path)
            rows.append(row)
            print(json.dumps(row), file=sys.stderr, flush=True)
    return rows


def _peer_cell(res: dict[str, Any] | None, exact: str) -> str:
    if res is None:
        return "-"
    if "error" in res:
        return res["error"]
    val = res["value"]
    if isinstance(val, str):  # Gambit: exact
        mark = "= V_H" if val == exact else f"{val} ≠ V_H"
    else:
        mark = f"Δ {abs(val - float(Fraction(exact))):.0e}"
    return f"{res['seconds']:.2f} s ({mark})"


def table(rows: list[dict[str, Any]], peers: list[str]) -> str:
    head = ["H", "prefixes", "V_H (exact)", "ours: cvxpy+Clarabel", "HiGHS (same LP)",
            "ours / HiGHS", "|ours − HiGHS|", "exact bracket", ".efg nodes",
            *[{"openspiel": "OpenSpiel", "gambit": "Gambit (exact)"}[p] for p in peers]]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in rows:
        cells = [str(r["H"]), f"{r['prefixes']:,}", r["exact"], f"{r['ours_s']:.3f} s",
                 f"{r['highs_s']:.3f} s", f"{r['ours_s'] / r['highs_s']:.2f}",
                 f"{abs(r['ours'] - r['highs']):.0e}", f"{r['exact_s']:.2f} s",
                 f"{r['efg_nodes']:,}", *[_peer_cell(r.get(p), r["exact"]) for p in peers]]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--hmin", type=int, default=3)
    ap.add_argument("--hmax", type=int, default=12)
    ap.add_argument("--peer-timeout", type=float, default=60.0,
                    help="seconds per peer run; larger H are skipped after one exceeds it")
    ap.add_argument("--peer-memory", type=float, default=8.0,
                    help="address-space limit of a peer subprocess, GiB")
    ap.add_argument("--peers", default="openspiel,gambit",
                    help="comma-separated subset of openspiel,gambit ('' for none)")
    ap.add_argument("--json", help="also write the rows as JSON to this file")
    ap.add_argument("--run-peer", nargs=2, metavar=("PEER", "EFG"), help=argparse.SUPPRESS)
    ap.add_argument("--quick", action="store_true",
                    help="tiny sizes, for the test suite (also DPP_BENCH_QUICK=1)")
    args = ap.parse_args()
    if not args.run_peer and (args.quick or os.environ.get("DPP_BENCH_QUICK")):
        args.hmin, args.hmax, args.peers = 3, 4, ""
    if args.run_peer:
        print(json.dumps(PEERS[args.run_peer[0]](args.run_peer[1])))
        return
    peers = [p for p in args.peers.split(",") if p]
    rows = bench(args.hmin, args.hmax, args.peer_timeout, args.peer_memory, peers)
    print(table(rows, peers))
    large = [r["ours_s"] / r["highs_s"] for r in rows if r["prefixes"] >= 1000]
    if large:
        print(f"\nworst ours/HiGHS ratio at >= 1000 prefixes: {max(large):.2f} (target <= 3)")
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=2))


if __name__ == "__main__":
    main()
