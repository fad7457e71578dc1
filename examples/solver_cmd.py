#!/usr/bin/env python3
"""A command-line DPP solver in plain Python (standard library only), to show
``dpp audit --solver-cmd``:

    python examples/solver_cmd.py INSTANCE.json PROFILE.json
    dpp audit --solver-cmd 'python examples/solver_cmd.py {instance} {profile}'

It reads an instance document (docs/formats.md §1) and writes a dpp-profile/1 document
(§2), rebuilding the paper's equilibrium from scratch with exact fractions: σ* (eq. (7)), ξ²
through the minimiser v* of d(s0,v) + d(v,g1) + d(v,g2) cut at the first goal (proofs/XI2.md),
the phases, and the primary's mixture of eq. (15). Any program in any language that does the
same file-in/file-out can be audited the same way.
"""

from __future__ import annotations

import heapq
import itertools
import json
import math
import sys
from fractions import Fraction
from typing import Any


def key(x: Any) -> Any:
    """JSON node id -> hashable (grid cells [r, c] become tuples)."""
    return tuple(key(y) for y in x) if isinstance(x, list) else x


def out(v: Any) -> Any:
    """Hashable node id -> JSON."""
    return list(v) if isinstance(v, tuple) else v


def dijkstra(adj: dict[Any, list[tuple[Any, Fraction]]], source: Any) -> dict[Any, Fraction]:
    dist = {source: Fraction(0)}
    heap = [(Fraction(0), 0, source)]
    tick = 0
    while heap:
        d, _, u = heapq.heappop(heap)
        if d > dist[u]:
            continue
        for v, w in adj[u]:
            if v not in dist or d + w < dist[v]:
                dist[v] = d + w
                tick += 1
                heapq.heappush(heap, (dist[v], tick, v))
    return dist


def solve(doc: dict[str, Any]) -> dict[str, Any]:
    g = doc["graph"]
    nodes = [key(n["id"]) for n in g["nodes"]]
    succ: dict[Any, list[tuple[Any, Fraction]]] = {v: [] for v in nodes}
    pred: dict[Any, list[tuple[Any, Fraction]]] = {v: [] for v in nodes}
    for e in g.get("edges", g.get("links", [])):
        u, v, w = key(e["source"]), key(e["target"]), Fraction(str(e.get("weight", 1)))
        arcs = [(u, v), (v, u)] if not g.get("directed", False) else [(u, v)]
        for a, b in arcs:
            succ[a].append((b, w))
            pred[b].append((a, w))
    goals = [key(x) for x in doc["goals"]]
    prior = [Fraction(str(p)) for p in doc["prior"]]
    i = 1 if prior[1] > prior[0] else 0      # the primary goal; goals[0] at a tie
    g1, g2, b1, b2 = goals[i], goals[1 - i], prior[i], prior[1 - i]
    s0 = key(doc["start"])

    d0, d1, d2 = dijkstra(succ, s0), dijkstra(pred, g1), dijkstra(pred, g2)
    inf = math.inf

    def tight_path(u: Any, target: Any, dist: dict[Any, Fraction]) -> list[Any]:
        path = [u]
        while path[-1] != target:
            x = path[-1]
            path.append(next(v for v, w in succ[x] if w + dist.get(v, inf) == dist[x]))
        return path

    # ξ²: through the first minimiser v* of d(s0,v) + d(v,g1) + d(v,g2), cut at a goal
    pivot = min((v for v in nodes if v in d0 and v in d1 and v in d2),
                key=lambda v: d0[v] + d1[v] + d2[v])
    head = [pivot]
    while head[-1] != s0:
        x = head[-1]
        head.append(next(u for u, w in pred[x] if u in d0 and d0[u] + w == d0[x]))
    walk = head[::-1] + tight_path(pivot, g2, d2)[1:]
    xi2 = walk[:next(t for t, v in enumerate(walk) if v in (g1, g2)) + 1]

    # σ* along ξ² (eq. (7)) and the phases
    weight = {(u, v): w for u in nodes for v, w in succ[u]}
    c, sigma = d1[s0], []
    for u, v in itertools.pairwise(xi2):
        c_new = min(c, d1.get(v, inf))
        sigma.append((c - c_new) / weight[u, v])
        c = c_new
    t_i = 0
    while t_i < len(sigma) and sigma[t_i] == 1:
        t_i += 1
    t_ii = max([t_i] + [t + 1 for t, s in enumerate(sigma) if s > 0])

    def branch(t: int) -> list[Any]:
        return xi2 if t == len(xi2) - 1 else xi2[:t] + tight_path(xi2[t], g1, d1)

    p_ii = b2 / b1
    path_i, path_ii = branch(t_i), branch(t_ii)
    mix = [(path_i, Fraction(1))] if path_i == path_ii else [
        (p, q) for p, q in ((path_i, 1 - p_ii), (path_ii, p_ii)) if q > 0]
    entry = lambda p, q: {"path": [out(v) for v in p], "probability": str(q)}  # noqa: E731
    return {
        "format": "dpp-profile/1",
        "goals": {"primary": out(g1), "secondary": out(g2)},
        "defender": {"rule": "progress", "goal": out(g1)},
        "attacker": {"primary": [entry(p, q) for p, q in mix],
                     "secondary": [entry(xi2, 1)]},
        "phases": {"t_I": t_i, "t_II": t_ii, "T": len(xi2) - 1},
        "solver": {"name": "examples/solver_cmd.py"},
    }


def main(argv: list[str]) -> int:
    if len(argv) != 2:
        print("usage: solver_cmd.py INSTANCE.json PROFILE.json", file=sys.stderr)
        return 2
    with open(argv[0]) as f:
        doc = json.loads(f.read(), parse_float=Fraction)
    with open(argv[1], "w") as f:
        json.dump(solve(doc), f)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
