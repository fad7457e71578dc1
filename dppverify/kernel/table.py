"""Table Defenders (the progress rule is the empty table with the progress default): the
Defender's memory automaton, its σ along a walk, and the product-graph inequalities of one
Attacker type (proofs/KERNEL.md K.0, K.2 item 5, K.3).

All labels are integers over the witness's denominator ``S``; ``inf`` is the kernel's
sentinel for +∞ of potentials and ``dinf`` (``3·inf``) that of distances.
"""

from __future__ import annotations

from fractions import Fraction
from itertools import compress
from operator import add, le
from typing import Any

from dppverify.kernel.graph import exact
from dppverify.kernel.profile import Table
from dppverify.kernel.reading import Instance
from dppverify.kernel.verdict import BadInput, Undecided

__all__ = ["Memory", "TableRule", "first_failure"]

Memory = tuple[int, Any]
"""The Defender's state after a prefix: ``(trie prefix or -1, running minimum c)``."""


def first_failure(xs: list[Any], ys: list[Any], skip: bytearray) -> int | None:
    """The first ``v`` with ``xs[v] > ys[v]`` and ``skip[v] == 0``, or None (C-speed scan).

    Examples
    --------
    >>> first_failure([1, 5, 9], [2, 4, 3], bytearray([0, 1, 0]))
    2
    """
    bad = [not ok for ok in map(le, xs, ys)]
    for v in compress(range(len(bad)), bad):
        if not skip[v]:
            return v
    return None


class TableRule:
    """A table Defender on an instance, with the verified distances ``D`` (scaled by ``S``)."""

    def __init__(self, inst: Instance, table: Table, D: list[list[Any]], S: int, inf: int
                 ) -> None:
        self.inst, self.table, self.D, self.S, self.inf = inst, table, D, S, inf
        self.dinf = 3 * inf
        self.children: dict[tuple[int, int], int] = {}
        self.progress = table.default == "progress"
        self.dg = D[table.goal]
        self.node, self.cmin = [inst.start], [self.dg[inst.start]]
        self.listed: dict[int, tuple[Fraction, ...]] = {}
        for w, dist in table.entries.items():
            p = 0
            for u in w[1:]:
                q = self.children.setdefault((p, u), len(self.node))
                if q == len(self.node):
                    self.node.append(u)
                    self.cmin.append(min(self.cmin[p], self.dg[u]))
                p = q
            self.listed[p] = dist

    def start(self) -> Memory:
        """The memory at the start."""
        return (0, self.cmin[0])

    def step(self, mem: Memory, v: int, u: int, w: Fraction) -> tuple[Memory, tuple[Any, ...]]:
        """The memory after the step ``v -> u`` and the step's σ (None where undefined)."""
        p, c = mem
        q = self.children.get((p, u)) if p >= 0 else None
        c2 = min(c, self.dg[u]) if self.progress else c
        sigma: Any = self.listed.get(q) if q is not None else None
        if sigma is None and self.progress:
            x = Fraction(c - c2) / (w * self.S)
            sigma = tuple(x if i == self.table.goal else 1 - x for i in range(2))
        elif sigma is None:
            sigma = self.table.default
        return (-1 if q is None else q, c2), sigma

    def labels(self, rec: Any, key: str, alive: list[bool]) -> list[Any]:
        """The witness's per-node list ``rec[key]``: ``inf`` at dead nodes and for ``null``."""
        xs = rec.get(key) if type(rec) is dict else None
        if type(xs) is not list or len(xs) != self.inst.graph.n or not set(map(type, xs)) <= {
                int, type(None)}:
            raise BadInput(f"witness: {key} must be a list of {self.inst.graph.n} integers")
        inf = self.inf
        return [inf if x is None or not a else x for x, a in zip(xs, alive, strict=True)]

    def check_type(self, theta: int, rec: Any, alive: list[bool], u_scaled: Fraction) -> None:
        """Type ``θ``'s inequalities (K.2 item 5); :class:`Undecided` names the first failing."""
        inst, S, inf, dg = self.inst, self.S, self.inf, self.dg
        graph, is_goal, Dt = inst.graph, inst.is_goal, self.D[theta]
        keys = {"trie"} | ({"P", "Q"} if self.progress and theta != self.table.goal else
                           set() if self.progress or self.table.default is None else {"exit"})
        if type(rec) is not dict or set(rec) != keys:
            raise BadInput(f"witness: types[{theta}] must have exactly the keys {sorted(keys)}")
        phi = rec["trie"]
        if type(phi) is not list or len(phi) != len(self.node) or not set(map(type, phi)) <= {
                int, type(None)}:
            raise BadInput(f"witness: types[{theta}].trie must be {len(self.node)} integers")
        phi = [inf if x is None else x for x in phi]
        same = theta == self.table.goal
        exit_phi: Any = None
        if self.progress and not same:
            P, Q = self.labels(rec, "P", alive), self.labels(rec, "Q", alive)
            self._arcs(theta, P, P, Fraction(1), "P(x) <= w + P(u)")
            self._arcs(theta, Q, Q, Fraction(1), "Q(x) <= w + Q(u)", goals=False)
            v = first_failure(Q, list(map(add, dg, P)), bytearray(not a for a in alive))
            if v is not None:
                raise Undecided(f"type {theta}, node {inst.show(v)}: Q(u) <= d(u, g) + P(u) "
                                "fails (the progress default's closed form)")

            def exit_phi(u: int, c2: Any) -> Any:
                return min(P[u], Q[u] - c2 if Q[u] < inf else inf)
        elif self.progress:
            def exit_phi(u: int, c2: Any) -> Any:
                return c2
        elif self.table.default is not None:
            E = self.labels(rec, "exit", alive)
            self._arcs(theta, E, E, self.table.default[theta], "E(x) <= w·q + E(u)")

            def exit_phi(u: int, c2: Any) -> Any:
                return E[u]
        for p, v in enumerate(self.node):
            if not alive[v]:
                continue
            if is_goal[v]:
                if not phi[p] <= Dt[v]:
                    raise Undecided(f"type {theta}, trie prefix {p} (goal {inst.show(v)}): "
                                    "phi <= terminal cost fails")
                continue
            for u, w in graph.arcs(v):
                if not alive[u]:
                    continue
                q = self.children.get((p, u))
                (_, c2), sigma = self.step((p, self.cmin[p]), v, u, w)
                if sigma is None or (q is None and exit_phi is None):
                    raise Undecided(f"the table Defender is undefined after the trie prefix {p} "
                                    f"steps to {inst.show(u)} (no entry, no default)")
                nxt = phi[q] if q is not None else exit_phi(u, c2)
                if not phi[p] <= exact(w * S * sigma[theta]) + nxt:
                    raise Undecided(f"type {theta}, trie prefix {p} -> node {inst.show(u)}: "
                                    "phi(p) <= cost + phi(next) fails")
        if not u_scaled <= phi[0]:
            raise Undecided(f"type {theta}: U <= phi(start) fails (U = {u_scaled / S}, phi = "
                            f"{Fraction(phi[0], S) if phi[0] < inf else 'inf'}); the witness "
                            "does not prove regret 0")

    def _arcs(self, theta: int, X: list[Any], Y: list[Any], k: Fraction, what: str,
              goals: bool = True) -> None:
        """``X(x) <= k·w·S + Y(u)`` on every live arc from an alive non-goal ``x``, and (with
        ``goals``) ``X(g) <= D_θ(g)`` at the goals."""
        inst = self.inst
        M = inst.graph.relax(Y, k * self.S, self.inf)
        v = first_failure(X, M, inst.is_goal)
        if v is not None:
            raise Undecided(f"type {theta}, node {inst.show(v)}: {what} fails on an arc")
        for g in inst.goals if goals else ():
            if not X[g] <= self.D[theta][g]:
                raise Undecided(f"type {theta}, goal {inst.show(g)}: the exit label <= "
                                "terminal cost fails")
