"""Every type's exact best response over ALL walks against the guarantee rule (``proofs/NRULE.md``).

The rule (:mod:`dppverify.structured.guarantee`) is a deterministic function of the walk with
state ``r`` (``r = h`` at the start, ``r <- r - wσ`` on every step). Type θ's cost on a walk
telescopes: ``J^θ = h_θ - r_{T,θ} + d(g_T, g^θ)`` (NR.3). Its minimum over every walk of any
length is decided by two exact arguments:

- **the guarantee** (NR.2, the extension of NSOLVE.1): from a state ``(v, r)`` with
  ``r ∈ F_v`` such that the arc condition ``F_x ⊆ F_u + wΔ`` holds on every walkable arc a
  walk from ``v`` can take, every continuation ends with ``r_{T,θ} <= d(g_T, g^θ)``: the
  whole walk costs at least ``h_θ``. At the start with ``h ∈ F_{s0}`` this bounds every walk.
- **a label-setting search over the states** ``(v, r)`` (NR.4): ``c = h_θ - r_θ`` (the cost so
  far) never decreases, so a Dijkstra on ``c`` over the states reachable from ``(s0, h)``
  pops the goal states in the order of their costs; a state is cut when a lower bound on
  every continuation (the cheapest terminal cost reachable, and the guarantee above) is at
  least the bound ``B`` asked for. A coordinate ``η != θ`` whose every alive normal is
  slack at every later step (``a·r <= min_u m_a(u)``: ``a·r`` only decreases along a walk)
  no longer influences the rule and is dropped from the state (NR.4's abstraction), so
  identical futures are explored once. The first goal state popped below ``B`` is an exact
  best response (a *witness* walk); an exhausted queue proves that no walk costs less
  than ``B``.

The search stops after :data:`MAX_STATES` states; the caller reports that as undecided
(exit 3), naming the budget.
"""

from __future__ import annotations

import heapq
import itertools
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction

from dppverify.game.instance import Instance
from dppverify.game.rules import GuaranteeRule
from dppverify.structured.arc_condition import ArcCondition, arc_condition, walkable_arcs
from dppverify.structured.lexmin import lexmin
from dppverify.structured.normal_fixpoint import NormalSets


def _dot(a: tuple[int, ...], r: State) -> Fraction | None:
    """``a·r``, or None when ``a`` involves a dropped coordinate (NR.4(b))."""
    total = Fraction(0)
    for ai, x in zip(a, r, strict=True):
        if ai:
            if x is None:
                return None
            total += ai * x
    return total


MAX_STATES = 200_000
"""States the search of one type may expand before it gives up (reported as undecided)."""

State = tuple[Fraction | None, ...]
"""The rule's state ``r`` with dropped (never again binding) coordinates as None."""
Key = tuple[int, State, int]
"""A search state: node, abstract ``r`` and steps taken (0 when the walks are unbounded)."""


@dataclass(frozen=True)
class RuleResponse:
    """Type θ's minimum over all walks against the rule, as far as it matters for a bound ``B``.

    Attributes
    ----------
    theta : int
    bound : Fraction
        ``B``: the cost to beat (the type's profile cost).
    value : Fraction or None
        The exact minimum over all walks when it is below ``B`` (else None: every walk costs
        at least ``B``, proved), also None when undecided.
    walk : tuple of int or None
        A walk attaining ``value``.
    decided : bool
        False when the search hit :data:`MAX_STATES`.
    states : int
        States expanded.
    how : str
        How the answer was obtained (for the record's message).
    """

    theta: int
    bound: Fraction
    value: Fraction | None
    walk: tuple[int, ...] | None
    decided: bool
    states: int
    how: str


class RuleSearch:
    """The search context of one rule on one instance (shared by the types).

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> from dppverify.structured.guarantee import guarantee_sets
    >>> inst = star3()
    >>> rule = GuaranteeRule((Fraction(2), Fraction(1), Fraction(1)))
    >>> rs = RuleSearch(inst, rule, guarantee_sets(inst))
    >>> rs.arc.holds, rs.in_start
    (True, True)
    >>> r = rs.best(1, Fraction(1))
    >>> r.value, r.decided, r.how
    (None, True, 'the guarantee h_θ (NR.2)')
    """

    def __init__(self, instance: Instance, rule: GuaranteeRule, sets: NormalSets, *,
                 max_states: int = MAX_STATES) -> None:
        inst = instance
        self.inst = inst
        self.rule = rule
        self.sets = sets
        self.n = inst.n_goals
        self.order = tuple(sorted(range(self.n), key=lambda t: (-inst.prior[t], t)))
        self.max_states = max_states
        self.normals = sets.normals
        self.arc: ArcCondition = arc_condition(sets, inst.start)
        s0 = inst.start
        col = sets.column(s0)
        self.in_start = col is not None and all(
            sum((Fraction(x) * y for x, y in zip(a, rule.h, strict=True)), Fraction(0)) <= m
            for a, m in zip(sets.normals, col, strict=True))
        tails, heads, weights = walkable_arcs(sets, s0)
        self.succ: dict[int, list[tuple[int, Fraction]]] = {}
        for v, u, w in zip(tails, heads, weights, strict=True):
            self.succ.setdefault(v, []).append((u, Fraction(w)))
        nodes = set(tails) | set(heads) | {s0}
        self.nodes = sorted(nodes)
        # μ_a: the least m_a over every node a later step can enter
        self.mu = [min(Fraction(int(row[u]), sets.scale) for u in self.nodes if sets.finite[u])
                   if any(sets.finite[u] for u in self.nodes) else Fraction(0)
                   for row in sets.rows]
        # safe nodes: every walkable arc reachable from them satisfies the arc condition
        self.safe = self._safe_nodes(tails, heads)
        self._col: dict[int, list[Fraction] | None] = {}

    def _safe_nodes(self, tails: list[int], heads: list[int]) -> set[int]:
        bad_tails = {v for v, _ in self.arc.failing}
        pred: dict[int, list[int]] = {}
        for v, u in zip(tails, heads, strict=True):
            pred.setdefault(u, []).append(v)
        unsafe = set(bad_tails)
        stack = list(bad_tails)
        while stack:
            x = stack.pop()
            for y in pred.get(x, ()):
                if y not in unsafe:
                    unsafe.add(y)
                    stack.append(y)
        return {v for v in self.nodes if v not in unsafe}

    def column(self, v: int) -> list[Fraction] | None:
        """``m_a(v)`` for every normal (cached)."""
        if v not in self._col:
            self._col[v] = self.sets.column(v)
        return self._col[v]

    # ------------------------------------------------------------------ the rule's step
    def step(self, r: State, u: int, w: Fraction) -> tuple[State, tuple[Fraction, ...]]:
        """The rule on a step into ``u`` of weight ``w`` from the (abstract) state ``r``."""
        n = self.n
        m_u = self.column(u)
        rows: list[tuple[tuple[int, ...], Fraction]] = []
        if m_u is not None:
            for a, m in zip(self.normals, m_u, strict=True):
                total = _dot(a, r)
                if total is None:
                    continue
                need = (total - m) / w
                if need > 0:
                    rows.append((a, need))
        sigma = lexmin(rows, n, self.order)
        if sigma is None:
            sigma = tuple(Fraction(int(i == self.order[0])) for i in range(n))
        new = tuple(None if x is None else x - w * s for x, s in zip(r, sigma, strict=True))
        return new, sigma

    def abstract(self, r: State, theta: int) -> State:
        """Drop the coordinates ``η != θ`` that no alive normal involves (NR.4)."""
        n = self.n
        alive_coord = [False] * n
        for a, mu in zip(self.normals, self.mu, strict=True):
            total = _dot(a, r)
            if total is None or total <= mu:
                continue
            for i in range(n):
                if a[i]:
                    alive_coord[i] = True
        return tuple(x if (i == theta or alive_coord[i]) else None for i, x in enumerate(r))

    def in_sets(self, r: State, v: int) -> bool:
        """``r ∈ F_v`` (dropped coordinates only occur in slack normals)."""
        col = self.column(v)
        if col is None:
            return False
        for a, m in zip(self.normals, col, strict=True):
            total = Fraction(0)
            for i in range(self.n):
                if a[i]:
                    x = r[i]
                    if x is None:
                        break
                    total += a[i] * x
            else:
                if total > m:
                    return False
        return True

    # ------------------------------------------------------------------ the search
    def terminal_floor(self, theta: int) -> dict[int, Fraction]:
        """``T_θ(v)``: the least terminal cost ``d(g, g^θ)`` over the goals a walk from ``v``
        can end at (a lower bound on the rest of any walk from ``v``: ``σ >= 0``)."""
        inst = self.inst
        pred: dict[int, list[int]] = {}
        for v, arcs in self.succ.items():
            for u, _ in arcs:
                pred.setdefault(u, []).append(v)
        floor: dict[int, Fraction] = {}
        goals = sorted((Fraction(inst.dist_to[theta][g]), g) for g in inst.goals
                       if g in set(self.nodes))
        for d, g in goals:  # by increasing terminal cost: the first to reach a node is least
            if g in floor:
                continue
            floor[g] = d
            stack = [g]
            while stack:
                x = stack.pop()
                for y in pred.get(x, ()):
                    if y not in floor:
                        floor[y] = d
                        stack.append(y)
        return floor

    def best(self, theta: int, bound: Fraction, max_steps: int | None = None) -> RuleResponse:
        """Type ``theta``'s exact minimum over all walks if below ``bound``, else a proof that
        no walk costs less than ``bound`` (or undecided beyond :attr:`max_states`).

        ``max_steps``: only walks of at most that many steps (the truncated game).
        """
        inst = self.inst
        h = tuple(Fraction(x) for x in self.rule.h)
        guarantee = self.in_start and self.arc.holds
        if guarantee and h[theta] >= bound:
            return RuleResponse(theta, bound, None, None, True, 0, "the guarantee h_θ (NR.2)")
        floor = self.terminal_floor(theta)
        s0 = inst.start
        if s0 not in floor:  # pragma: no cover - the instance reaches a goal from s0
            return RuleResponse(theta, bound, None, None, True, 0, "no walk")
        root = self.abstract(h, theta)
        tick = itertools.count()
        hops = inst.hops
        heap: list[tuple[Fraction, int, int, State | None, int, Key | None]] = [
            (Fraction(0), next(tick), s0, root, 0, None)]
        parent: dict[Key, Key | None] = {}
        expanded = 0
        goals = set(inst.goals)
        while heap:
            c, _, v, r, k, par = heapq.heappop(heap)
            if r is None:  # a goal's terminal entry: the first one popped is the minimum
                assert par is not None
                walk = self._walk(parent, par)
                return RuleResponse(theta, bound, c, walk, True, expanded,
                                    "an exact search over the rule's states (NR.4)")
            key = (v, r, k if max_steps is not None else 0)
            if key in parent:
                continue
            parent[key] = par
            expanded += 1
            if expanded > self.max_states:
                return RuleResponse(theta, bound, None, None, False, expanded,
                                    f"the search stopped after {self.max_states:,} states")
            if v in goals:
                total = c + Fraction(inst.dist_to[theta][v])
                if total < bound:
                    heapq.heappush(heap, (total, next(tick), v, None, k, key))
                continue
            if max_steps is not None and k >= max_steps:
                continue
            for u, w in self.succ.get(v, ()):
                if max_steps is not None and k + 1 + max(hops[u], 0) > max_steps:
                    continue
                new, _ = self.step(r, u, w)
                new = self.abstract(new, theta)
                x = new[theta]
                assert x is not None
                c2 = h[theta] - x
                if c2 + floor.get(u, bound) >= bound:
                    continue
                k2 = k + 1 if max_steps is not None else 0
                if (u, new, k2) in parent:
                    continue
                if bound <= h[theta] and u in self.safe and self.in_sets(new, u):
                    continue  # NR.2 from (u, new): every continuation costs at least h_θ
                heapq.heappush(heap, (c2, next(tick), u, new, k + 1, key))
        return RuleResponse(theta, bound, None, None, True, expanded,
                            "an exhaustive search over the rule's states (NR.4)")

    def _walk(self, parent: dict[Key, Key | None], key: Key) -> tuple[int, ...]:
        out = []
        cur: Key | None = key
        while cur is not None:
            out.append(cur[0])
            cur = parent[cur]
        return tuple(reversed(out))


def rule_response(instance: Instance, rule: GuaranteeRule, sets: NormalSets,
                  bounds: Sequence[Fraction], *, max_states: int = MAX_STATES,
                  max_steps: int | None = None) -> tuple[list[RuleResponse], RuleSearch]:
    """Every type's :meth:`RuleSearch.best` against its bound (its profile cost).

    Examples
    --------
    The hub with the 0/1 normals only and ``h`` from the coalition DP: the arc condition
    fails at ``u -> u1``, ``F`` is empty on that step, the rule's fallback guards goal 1
    only, and type 2 walks to its goal unguarded:

    >>> from dppverify.game.examples import hub4
    >>> from dppverify.structured.guarantee import guarantee_sets
    >>> inst = hub4()
    >>> rule = GuaranteeRule(tuple(Fraction(x) for x in ("5/2", "5/2", "5/2", "5/4")))
    >>> out, _ = rule_response(inst, rule, guarantee_sets(inst), rule.h)
    >>> [(r.theta, r.value) for r in out if r.value is not None][:1]
    [(1, Fraction(0, 1))]
    """
    rs = RuleSearch(instance, rule, sets, max_states=max_states)
    return [rs.best(t, Fraction(b), max_steps) for t, b in enumerate(bounds)], rs
