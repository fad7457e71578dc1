"""A deliberately naive, independent model of the DPP game on an instance document.

Exact rationals throughout, plain dict adjacency, Dijkstra on Fractions, σ* straight from
eq. (7), costs straight from eq. (3), and exhaustive enumeration of simple paths and walks.
Used as the brute-force reference of the property tests; imports neither package.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Hashable, Iterator, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

Node = Hashable
INF = math.inf


def key(x: Any) -> Node:
    """JSON node id -> hashable id (lists become tuples)."""
    return tuple(key(y) for y in x) if isinstance(x, list) else x


def number(x: Any) -> Fraction:
    """An exact number of the instance format (ints, ``"p/q"``, decimals read exactly)."""
    if isinstance(x, float):
        return Fraction(repr(x))
    return Fraction(x) if not isinstance(x, str) else Fraction(x.strip())


@dataclass(frozen=True)
class Game:
    """An instance document as a plain weighted digraph with primary/secondary goals."""

    nodes: tuple[Node, ...]
    succ: dict[Node, tuple[tuple[Node, Fraction], ...]]
    start: Node
    g1: Node
    g2: Node
    b1: Fraction
    b2: Fraction
    d1: dict[Node, Fraction]
    d2: dict[Node, Fraction]

    @classmethod
    def from_doc(cls, doc: dict[str, Any], *, swap_at_tie: bool = False) -> Game:
        """Parse ``doc``; the primary goal has the larger prior (``goals[0]`` at a tie, or
        ``goals[1]`` with ``swap_at_tie``)."""
        g = doc["graph"]
        nodes = tuple(key(n["id"]) for n in g["nodes"])
        succ: dict[Node, list[tuple[Node, Fraction]]] = {v: [] for v in nodes}
        for e in g.get("edges", g.get("links", [])):
            u, v, w = key(e["source"]), key(e["target"]), number(e.get("weight", 1))
            succ[u].append((v, w))
            if not g.get("directed", False) and u != v:
                succ[v].append((u, w))
        goals = [key(x) for x in doc["goals"]]
        prior = [number(p) for p in doc["prior"]]
        i = 1 if prior[1] > prior[0] or (prior[0] == prior[1] and swap_at_tie) else 0
        frozen = {u: tuple(a) for u, a in succ.items()}
        return cls(nodes, frozen, key(doc["start"]), goals[i], goals[1 - i], prior[i],
                   prior[1 - i], _dist_to(frozen, goals[i]), _dist_to(frozen, goals[1 - i]))

    # ------------------------------------------------------------------ distances
    def d_to(self, v: Node, goal: Node) -> Fraction | float:
        """``d(v, goal)`` for ``goal`` in ``{g1, g2}`` (``inf`` when unreachable)."""
        table = self.d1 if goal == self.g1 else self.d2
        return table.get(v, INF)

    def weight(self, u: Node, v: Node) -> Fraction:
        """Weight of the arc ``u -> v``."""
        return next(w for x, w in self.succ[u] if x == v)

    @property
    def M(self) -> Fraction | float:
        """``min_v d(s0,v) + d(v,g1) + d(v,g2)`` (proofs/XI2.md)."""
        d0 = _dist_from(self.succ, self.start)
        return min(d0[v] + self.d_to(v, self.g1) + self.d_to(v, self.g2) for v in d0)

    # ------------------------------------------------------------------ σ* and costs
    def sigma(self, walk: Sequence[Node]) -> list[Fraction]:
        """σ*(g1) after each step of ``walk`` (eq. (7), running minimum ``c_t``)."""
        c = self.d_to(walk[0], self.g1)
        out = []
        for u, v in itertools.pairwise(walk):
            c_new = min(c, self.d_to(v, self.g1))
            out.append(Fraction(0) if c_new == c else Fraction(c - c_new) / self.weight(u, v))
            c = c_new
        return out

    def cost(self, walk: Sequence[Node], theta: int) -> Fraction | float:
        """Type ``theta``'s cost of ``walk`` against σ* (U^θ, eq. (3)): allocations + terminal."""
        sig = self.sigma(walk)
        paid = sum((self.weight(u, v) * (s if theta == 1 else 1 - s)
                    for (u, v), s in zip(itertools.pairwise(walk), sig, strict=True)),
                   Fraction(0))
        return paid + self.d_to(walk[-1], self.g1 if theta == 1 else self.g2)

    def phases(self, walk: Sequence[Node]) -> tuple[int, int, int]:
        """``(t_I, t_II, T)`` of ``walk`` read off σ* (proofs/L5.md)."""
        sig = self.sigma(walk)
        t_i = 0
        while t_i < len(sig) and sig[t_i] == 1:
            t_i += 1
        positive = [t for t, s in enumerate(sig, start=1) if s > 0]
        return t_i, max([t_i, *positive]), len(sig)

    # ------------------------------------------------------------------ enumeration
    def is_goal(self, v: Node) -> bool:
        """True at ``g1`` and ``g2``."""
        return v == self.g1 or v == self.g2

    def simple_paths(self) -> Iterator[tuple[Node, ...]]:
        """Every simple path from ``s0`` ending at the first goal it reaches."""
        yield from self._walks([self.start], simple=True, steps=len(self.nodes))

    def walks(self, horizon: int) -> Iterator[tuple[Node, ...]]:
        """Every walk from ``s0`` with at most ``horizon`` steps ending at its first goal."""
        yield from self._walks([self.start], simple=False, steps=horizon)

    def _walks(self, walk: list[Node], *, simple: bool, steps: int) -> Iterator[tuple[Node, ...]]:
        if self.is_goal(walk[-1]):
            yield tuple(walk)
            return
        if len(walk) - 1 == steps:
            return
        for v, _ in self.succ[walk[-1]]:
            if simple and v in walk:
                continue
            walk.append(v)
            yield from self._walks(walk, simple=simple, steps=steps)
            walk.pop()

    def best_secondary(self) -> tuple[Fraction | float, list[tuple[Node, ...]]]:
        """Minimum type-2 cost over all simple paths, and every path attaining it."""
        costs = [(self.cost(p, 2), p) for p in self.simple_paths()]
        best = min(c for c, _ in costs)
        return best, [p for c, p in costs if c == best]


def _dist_to(succ: dict[Node, tuple[tuple[Node, Fraction], ...]], target: Node
             ) -> dict[Node, Fraction]:
    pred: dict[Node, list[tuple[Node, Fraction]]] = {v: [] for v in succ}
    for u, arcs in succ.items():
        for v, w in arcs:
            pred[v].append((u, w))
    return _shortest(pred, target)


def _dist_from(succ: dict[Node, tuple[tuple[Node, Fraction], ...]], source: Node
               ) -> dict[Node, Fraction]:
    return _shortest({u: list(a) for u, a in succ.items()}, source)


def _shortest(adj: dict[Node, list[tuple[Node, Fraction]]] | dict[Node, Any], source: Node
              ) -> dict[Node, Fraction]:
    """Exact shortest distances from ``source`` by Bellman–Ford (relax every arc until nothing
    changes): slower than both packages' Dijkstra and sharing nothing with it."""
    dist: dict[Node, Fraction] = {source: Fraction(0)}
    changed = True
    while changed:
        changed = False
        for u in list(dist):
            for v, w in adj[u]:
                if v not in dist or dist[u] + w < dist[v]:
                    dist[v] = dist[u] + w
                    changed = True
    return dist


def to_float_doc(doc: dict[str, Any]) -> dict[str, Any]:
    """The same instance in float mode: every weight a binary float, ``"numbers": "float"``."""
    g = doc["graph"]
    edges = [{**e, "weight": float(number(e.get("weight", 1)))}
             for e in g.get("edges", g.get("links", []))]
    graph = {k: v for k, v in g.items() if k != "links"}
    return {**doc, "graph": {**graph, "edges": edges}, "numbers": "float"}


def adjacent(doc: dict[str, Any], u: Any, v: Any) -> bool:
    """True when there is an arc ``u -> v`` in the instance document."""
    game = Game.from_doc(doc)
    return any(x == key(v) for x, _ in game.succ[key(u)])
