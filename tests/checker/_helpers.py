"""Instance builders and brute-force references shared by the checker tests.

The references here are deliberately naive (enumerate every walk by depth-first search on a
plain dict adjacency) so that tests recompute results from the input rather than trusting
the checker's tree or backward induction.
"""

from __future__ import annotations

import json
from collections.abc import Hashable, Iterator, Sequence
from fractions import Fraction
from pathlib import Path
from typing import Any

DATA = Path(__file__).resolve().parents[1] / "data"

Edge = tuple[Any, Any, Any]


def make_doc(edges: Sequence[Edge], start: Any, goals: Sequence[Any], prior: Sequence[Any],
             *, directed: bool = False, nodes: Sequence[Any] | None = None) -> dict[str, Any]:
    """An instance document from ``(u, v, weight)`` triples."""
    ids: list[Any] = list(nodes) if nodes is not None else []
    for u, v, _ in edges:
        for x in (u, v):
            if x not in ids:
                ids.append(x)
    for x in (start, *goals):
        if x not in ids:
            ids.append(x)
    return {"graph": {"directed": directed, "multigraph": False, "graph": {},
                      "nodes": [{"id": x} for x in ids],
                      "edges": [{"source": u, "target": v, "weight": w} for u, v, w in edges]},
            "start": start, "goals": list(goals), "prior": [str(Fraction(p)) for p in prior]}


def triangle_doc(prior: tuple[str, str] = ("7/10", "3/10")) -> dict[str, Any]:
    """NOTES §3 / formats.md: s–g2 (2), g2–g1 (2), s–g1 (3)."""
    return make_doc([("s", "g2", 2), ("g2", "g1", 2), ("s", "g1", 3)], "s", ["g1", "g2"], prior)


def grid_doc(rows: int, cols: int, start: tuple[int, int], goals: Sequence[tuple[int, int]],
             prior: Sequence[Any], blocked: Sequence[tuple[int, int]] = ()) -> dict[str, Any]:
    """A 4-connected unit grid; node ids are ``[row, col]`` lists."""
    free = [(r, c) for r in range(rows) for c in range(cols) if (r, c) not in set(blocked)]
    edges = []
    for r, c in free:
        for dr, dc in ((0, 1), (1, 0)):
            if (r + dr, c + dc) in free:
                edges.append(([r, c], [r + dr, c + dc], 1))
    return make_doc(edges, list(start), [list(g) for g in goals], prior,
                    nodes=[[r, c] for r, c in free])


def load_cases() -> list[dict[str, Any]]:
    """The conformance cases (tests/data/conformance_cases.json)."""
    cases: list[dict[str, Any]] = json.loads((DATA / "conformance_cases.json").read_text())
    return cases


def _key(x: Any) -> Hashable:
    return tuple(_key(y) for y in x) if isinstance(x, list) else x


def adjacency(doc: dict[str, Any]) -> dict[Hashable, list[tuple[Hashable, Fraction]]]:
    """Plain adjacency of an instance document (independent of dppverify's parser)."""
    g = doc["graph"]
    adj: dict[Hashable, list[tuple[Hashable, Fraction]]] = {_key(n["id"]): [] for n in g["nodes"]}
    for e in g.get("edges", g.get("links", [])):
        u, v, w = _key(e["source"]), _key(e["target"]), Fraction(str(e.get("weight", 1)))
        adj[u].append((v, w))
        if not g.get("directed", False) and u != v:
            adj[v].append((u, w))
    return adj


def all_walks(doc: dict[str, Any], horizon: int) -> Iterator[tuple[Hashable, ...]]:
    """Every walk from the start with at most ``horizon`` steps that ends at its first goal."""
    adj = adjacency(doc)
    goals = {_key(g) for g in doc["goals"]}
    start = _key(doc["start"])

    def dfs(walk: list[Hashable]) -> Iterator[tuple[Hashable, ...]]:
        if walk[-1] in goals:
            yield tuple(walk)
            return
        if len(walk) - 1 == horizon:
            return
        for v, _ in adj[walk[-1]]:
            walk.append(v)
            yield from dfs(walk)
            walk.pop()

    yield from dfs([start])


def distances_to(doc: dict[str, Any], target: Any) -> dict[Hashable, Fraction]:
    """Bellman-Ford distances to ``target`` (a second, slow, independent reference)."""
    adj = adjacency(doc)
    t = _key(target)
    dist: dict[Hashable, Fraction] = {t: Fraction(0)}
    for _ in range(len(adj)):
        changed = False
        for u, arcs in adj.items():
            for v, w in arcs:
                if v in dist and (u not in dist or dist[v] + w < dist[u]):
                    dist[u] = dist[v] + w
                    changed = True
        if not changed:
            break
    return dist
