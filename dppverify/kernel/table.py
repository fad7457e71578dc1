"""Table Defenders (the progress rule is the empty table with the progress default): the
Defender's memory automaton, the cost of each step, and the product-graph inequalities of one
Attacker type (proofs/KERNEL.md K.0, K.2 item 5, K.3).

Labels are integers over the witness's denominator ``S`` (+∞ is :data:`INF`); a step's costs
are ``S·w·σ(θ)`` for every type θ, so that σ itself is never divided out.
"""

from __future__ import annotations

from fractions import Fraction
from operator import add, le
from typing import Any

from dppverify.kernel.graph import exact
from dppverify.kernel.profile import Table
from dppverify.kernel.reading import INF, Instance, labels
from dppverify.kernel.verdict import BadInput, Beyond, Undecided

Memory = tuple[int, Any]
"""The Defender's state after a prefix: ``(trie prefix or -1, running minimum c)``."""


def first_failure(xs: list[Any], ys: list[Any], skip: Any = ()) -> int | None:
    """The first ``v`` not in ``skip`` with ``xs[v] > ys[v]``, or None (C-speed when none).

    Examples
    --------
    >>> first_failure([1, 5, 9], [2, 4, 3], (1,))
    2
    """
    for v in skip:  # ys is the caller's fresh list
        ys[v] = INF
    return None if all(map(le, xs, ys)) else next(v for v in range(len(xs)) if not xs[v] <= ys[v])


class TableRule:
    """A table Defender on an instance, with the verified distances ``D`` (scaled by ``S``)."""

    def __init__(self, inst: Instance, table: Table, D: list[list[Any]], S: int) -> None:
        self.inst, self.table, self.D, self.S = inst, table, D, S
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

    def step(self, mem: Memory, v: int, u: int, w: Fraction) -> tuple[Memory, Any]:
        """The memory after the step ``v -> u`` and the step's costs ``S·w·σ(θ)`` (None where
        the table is undefined)."""
        p, c = mem
        q = self.children.get((p, u)) if p >= 0 else None
        c2 = min(c, self.dg[u]) if self.progress else c
        sigma = self.listed.get(q) if q is not None else None
        mem2 = (-1 if q is None else q, c2)
        if sigma is None and self.progress:
            j, full = self.table.goal, exact(w * self.S)
            return mem2, tuple(c - c2 if i == j else full - (c - c2) for i in range(2))
        sigma = sigma or self.table.default  # type: ignore[assignment]
        return mem2, None if sigma is None else tuple(exact(w * self.S * x) for x in sigma)

    def check_type(self, theta: int, rec: Any, dead: list[int], u_scaled: Fraction) -> None:
        """Type ``θ``'s inequalities (K.2 item 5); :class:`Undecided` names the first failing."""
        inst, n, dg = self.inst, self.inst.graph.n, self.dg
        other = self.progress and theta != self.table.goal
        keys = {"trie"} | ({"P", "Q"} if other else set() if self.progress or
                           self.table.default is None else {"exit"})
        if type(rec) is not dict or set(rec) != keys:
            raise BadInput(f"witness: types[{theta}] must have exactly the keys {sorted(keys)}")
        phi = labels(rec["trie"], len(self.node), f"types[{theta}].trie")
        exit_phi: Any = None
        if other:
            P, Q = (labels(rec[k], n, f"types[{theta}].{k}", dead) for k in ("P", "Q"))
            self._arcs(theta, P, Fraction(1), "P(x) <= w + P(u)")
            self._arcs(theta, Q, Fraction(1), "Q(x) <= w + Q(u)", goals=False)
            if (v := first_failure(Q, list(map(add, dg, P)))) is not None:
                raise Undecided(f"type {theta}, node {inst.show(v)}: Q(u) <= d(u, g) + P(u) "
                                "fails (the progress default's closed form)")
            exit_phi = lambda u, c2: min(P[u], Q[u] - c2)  # noqa: E731 (closed form, K.3)
        elif self.progress:
            exit_phi = lambda u, c2: c2  # noqa: E731
        elif self.table.default is not None:
            E = labels(rec["exit"], n, f"types[{theta}].exit", dead)
            self._arcs(theta, E, self.table.default[theta], "E(x) <= w·q + E(u)")  # type: ignore[arg-type]
            exit_phi = lambda u, c2: E[u]  # noqa: E731
        alive = self.inst.alive
        for p, v in enumerate(self.node):
            if alive[v] and inst.is_goal[v] and not phi[p] <= self.D[theta][v]:
                raise Undecided(f"type {theta}, trie prefix {p} (goal {inst.show(v)}): "
                                "phi <= terminal cost fails")
            for u, w in inst.graph.arcs(v) if alive[v] and not inst.is_goal[v] else ():
                if not alive[u]:
                    continue
                q = self.children.get((p, u))
                (_, c2), cost = self.step((p, self.cmin[p]), v, u, w)
                if cost is None or (q is None and exit_phi is None):
                    raise Beyond(f"the table Defender is undefined after the trie prefix {p} "
                                    f"steps to {inst.show(u)} (no entry, no default)")
                nxt = phi[q] if q is not None else exit_phi(u, c2)
                if not phi[p] <= cost[theta] + nxt:
                    raise Undecided(f"type {theta}, trie prefix {p} -> node {inst.show(u)}: "
                                    "phi(p) <= cost + phi(next) fails")
        if not u_scaled <= phi[0]:
            at = phi[0] / Fraction(self.S) if phi[0] < INF else INF
            raise Undecided(f"type {theta}: U <= phi(start) fails (U = {u_scaled / self.S}, phi = "
                            f"{at}); the witness does not prove regret 0")

    def _arcs(self, theta: int, X: list[Any], k: Fraction, what: str, goals: bool = True
              ) -> None:
        """``X(x) <= k·w·S + X(u)`` on every live arc from an alive non-goal ``x``, and (with
        ``goals``) ``X(g) <= D_θ(g)`` at the goals."""
        inst = self.inst
        if (v := first_failure(X, inst.graph.relax(X, k * self.S, INF), inst.goals)) is not None:
            raise Undecided(f"type {theta}, node {inst.show(v)}: {what} fails on an arc")
        if goals and (g := next((g for g in inst.goals if X[g] > self.D[theta][g]), -1)) >= 0:
            raise Undecided(f"type {theta}, goal {inst.show(g)}: the exit label <= terminal cost "
                            "fails")
