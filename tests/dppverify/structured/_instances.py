"""Random N-goal instances and normal sets for the guarantee rule's tests (seeded, small)."""

from __future__ import annotations

import itertools
import random
from fractions import Fraction
from typing import Any

from dppverify.game.examples import hub_document

__all__ = ["digraph", "extras", "grid", "instance_doc"]


def _prior(rng: random.Random, n_goals: int) -> list[str]:
    ws = [rng.randint(1, 6) for _ in range(n_goals)]
    return [str(Fraction(w, sum(ws))) for w in ws]


def digraph(rng: random.Random, n_goals: int, *, acyclic: bool = False) -> dict[str, Any]:
    """A random digraph (start ``s``, inner nodes ``x…``, goals ``g1 … gN``); ``acyclic``: the
    walkable arcs go forward in the order ``s, x…, goals`` (a finite game), plus a ring of arcs
    between the goals (never walked) so that the goals reach each other."""
    inner = [f"x{i}" for i in range(rng.randint(2, 5))]
    goals = [f"g{i + 1}" for i in range(n_goals)]
    order = ["s", *inner, *goals]
    arcs: dict[tuple[str, str], int] = {}
    for i, a in enumerate(order[:-n_goals]):
        for j, b in enumerate(order):
            if a == b or rng.random() >= 0.35 or (acyclic and j <= i):
                continue
            arcs[(a, b)] = rng.randint(1, 4)
    for a, b in zip(goals, goals[1:] + goals[:1], strict=False):
        arcs.setdefault((a, b), rng.randint(1, 4))
    for g in goals:
        if not any(b == g and a != g and a not in goals for a, b in arcs):
            arcs[(rng.choice(["s", *inner]), g)] = rng.randint(1, 4)
    for x in inner:
        if not any(a == "s" or b == x for a, b in arcs if b == x):
            arcs[("s", x)] = rng.randint(1, 3)
    return {"graph": {"directed": True, "nodes": [{"id": v} for v in order],
                      "edges": [{"source": a, "target": b, "weight": w}
                                for (a, b), w in arcs.items()]},
            "start": "s", "goals": goals, "prior": _prior(rng, n_goals)}


def grid(rng: random.Random, n_goals: int) -> dict[str, Any]:
    """A small undirected grid (3×3 to 4×4) with random weights and a few obstacles."""
    rows, cols = rng.randint(3, 4), rng.randint(3, 4)
    cells = [(i, j) for i in range(rows) for j in range(cols)]
    blocked = set(rng.sample(cells, rng.randint(0, 2)))
    free = [c for c in cells if c not in blocked]
    start, *goals = rng.sample(free, n_goals + 1)
    edges = []
    for (i, j) in free:
        for di, dj in ((0, 1), (1, 0)):
            x = (i + di, j + dj)
            if x in free:
                edges.append({"source": f"{i},{j}", "target": f"{x[0]},{x[1]}",
                              "weight": rng.randint(1, 3)})
    return {"graph": {"directed": False, "nodes": [{"id": f"{i},{j}"} for i, j in free],
                      "edges": edges},
            "start": f"{start[0]},{start[1]}", "goals": [f"{i},{j}" for i, j in goals],
            "prior": _prior(rng, n_goals)}


def instance_doc(rng: random.Random, n_goals: int, family: str) -> dict[str, Any]:
    """One instance of ``family``: ``digraph``, ``dag``, ``grid`` or ``hub``."""
    if family == "hub":
        return hub_document(rng, n_goals)
    if family == "grid":
        return grid(rng, n_goals)
    return digraph(rng, n_goals, acyclic=family == "dag")


def extras(rng: random.Random, n_goals: int, *, closed: bool | None = None
           ) -> list[tuple[int, ...]]:
    """A random set of extra normals: permutations of (2, 2, 2, 1, …) patterns (the facets
    seen on gadgets), all of them (``closed``) or a random subset, sometimes with an odd one
    such as (2, 1, 0, …) or (1, 2, 3, …)."""
    if n_goals < 3:
        return []
    pats = [(2, 2, 2, 1) + (0,) * (n_goals - 4), (2, 2, 2, 1) + (1,) * (n_goals - 4)] \
        if n_goals >= 4 else [(2, 1, 1), (2, 2, 1)]
    pat = rng.choice(pats)
    perms = sorted(set(itertools.permutations(pat)))
    if closed is None:
        closed = rng.random() < 0.4
    out = perms if closed else rng.sample(perms, rng.randint(1, min(4, len(perms))))
    if not closed and rng.random() < 0.3:
        odd = rng.choice([(2, 1), (1, 2, 3), (3, 1, 1)])
        cand = tuple(list(odd) + [0] * (n_goals - len(odd)))
        if cand not in out:
            out = [*out, cand]
    return list(out)
