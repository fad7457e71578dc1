"""Solver benchmarks, reported as ratios measured in one run.

1. A 1000x1000 grid with 20% random obstacles: ``solve`` (from the boolean obstacle array,
   CSR construction included) against ONE ``scipy.sparse.csgraph.dijkstra`` from the start on
   the free cells' graph (built by ``_grids.free_cell_graph``, not by the solver). Target:
   ratio <= 5 (``bench_scale.py`` has the tighter target, <= 3.5). Also the peak traced
   memory of ``solve``.
2. Small random graphs: ``solve`` against brute-force enumeration of all simple paths for
   the secondary's best response (what the closed form replaces).

Run: ``.venv/bin/python benchmarks/bench_solver.py [--size 1000] [--repeat 5]``
"""

from __future__ import annotations

import argparse
import itertools
import os
import tracemalloc
from fractions import Fraction

import networkx as nx
import numpy as np
from _grids import free_cell_graph, random_grid
from _timing import best, timed
from scipy.sparse.csgraph import connected_components, dijkstra

from solver import Instance
from solver.graph.distances import distances_to
from solver.twogoal.equilibrium import paper_equilibrium


def grid_instance(size: int, density: float, seed: int) -> tuple[np.ndarray, tuple[int, int],
                                                                 tuple[tuple[int, int], ...]]:
    """Random obstacles; start and goals are corners of the largest free component."""
    blocked = random_grid(size, density, seed)
    mat, node = free_cell_graph(blocked)
    _, comp = connected_components(mat, directed=False)
    big = np.bincount(comp).argmax()
    cells = np.argwhere((node >= 0) & (comp[np.maximum(node, 0)] == big))
    rows, cols = cells[:, 0], cells[:, 1]

    def pick(score: np.ndarray) -> tuple[int, int]:
        k = int(np.argmin(score))
        return (int(rows[k]), int(cols[k]))

    start = pick(rows + cols)                      # near the top-left corner
    g1 = pick((size - rows) + (size - cols))       # near the bottom-right corner
    g2 = pick(rows + (size - cols))                # near the top-right corner
    return blocked, start, (g1, g2)


def bench_grid(size: int, repeat: int) -> None:
    blocked, start, goals = grid_instance(size, 0.2, seed=0)
    prior = ("3/5", "2/5")
    mat, node = free_cell_graph(blocked)  # the baseline graph: free cells only (_grids.py)
    s = int(node[start])
    t_dij, t_solve = float("inf"), float("inf")
    for _ in range(repeat):  # interleaved, so both see the same machine load
        t_dij = min(t_dij, timed(dijkstra, mat, directed=True, indices=s)[1])
        t_solve = min(t_solve, timed(
            lambda: paper_equilibrium(Instance.from_grid(blocked, start, goals, prior)))[1])
    tracemalloc.start()
    eq = paper_equilibrium(Instance.from_grid(blocked, start, goals, prior))
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    print(f"grid {size}x{size}, 20% obstacles: {mat.shape[0]:,} free cells, {mat.nnz:,} arcs; "
          f"xi2 has {eq.phases.T} steps, phases {eq.phases}")
    print(f"  one scipy dijkstra      {t_dij * 1e3:8.1f} ms")
    print(f"  solve (incl. CSR build) {t_solve * 1e3:8.1f} ms   ratio {t_solve / t_dij:.2f}x "
          "(target <= 5x)")
    print(f"  peak traced memory of solve: {peak / 2**20:.0f} MiB "
          f"({peak / blocked.size:.0f} bytes per cell)")


def brute_force_u2(inst: Instance) -> Fraction:
    """min over simple paths ending at their first goal of the secondary's cost against σ*."""
    eq = paper_equilibrium(inst)  # only for σ* (the progress rule) and the distance field
    net, sigma = inst.network, eq.defender
    g1, g2 = net.index_of(inst.primary), net.index_of(inst.secondary)
    s0 = net.index_of(inst.start)
    d_to_g2 = distances_to(net, g2)  # type: ignore[arg-type]
    best: Fraction | None = None
    stack: list[list[int]] = [[s0]]  # type: ignore[list-item]
    while stack:
        path = stack.pop()
        end = path[-1]
        if end in (g1, g2):
            sched = sigma.schedule(path)
            cost = sum((net.numbers.convert(net.arc_weight(u, v)) * (1 - s)  # type: ignore[arg-type]
                        for (u, v), s in zip(itertools.pairwise(path), sched, strict=True)),
                       Fraction(0)) + net.numbers.convert(d_to_g2[end])
            best = cost if best is None or cost < best else best
            continue
        heads, _ = net.out_arcs(end)
        stack.extend([*path, int(h)] for h in heads if int(h) not in path)
    assert best is not None
    return best  # type: ignore[return-value]


def bench_small(repeat: int, sizes: tuple[int, ...] = (8, 10, 12, 14, 16)) -> None:
    rng = np.random.default_rng(1)
    print("small random graphs (G(n, p=0.35), integer weights 1..5): solve vs enumerating "
          "simple paths")
    for n in sizes:
        while True:
            g = nx.gnp_random_graph(n, 0.35, seed=int(rng.integers(1 << 30)))
            if nx.is_connected(g):
                break
        for u, v in g.edges:
            g[u][v]["weight"] = int(rng.integers(1, 6))
        inst = Instance(g, 0, (n - 1, n - 2), ("3/5", "2/5"))
        t_brute = timed(brute_force_u2, inst)[1]
        t_solve = best(lambda inst=inst: paper_equilibrium(inst), repeat)[0]  # type: ignore[misc]
        assert brute_force_u2(inst) == paper_equilibrium(inst).U2
        print(f"  n={n:2d} m={g.number_of_edges():3d}: enumeration {t_brute * 1e3:9.1f} ms, "
              f"solve {t_solve * 1e3:6.2f} ms, speed-up {t_brute / t_solve:9.0f}x "
              "(same U2)")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", type=int, default=1000)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--quick", action="store_true",
                    help="tiny sizes, for the test suite (also DPP_BENCH_QUICK=1)")
    args = ap.parse_args()
    quick = bool(args.quick or os.environ.get("DPP_BENCH_QUICK"))
    if quick:
        args.size, args.repeat = 60, 1
    bench_grid(args.size, args.repeat)
    bench_small(args.repeat, (8,) if quick else (8, 10, 12, 14, 16))


if __name__ == "__main__":
    main()
