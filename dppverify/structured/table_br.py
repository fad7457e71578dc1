"""Best responses over ALL walks against a two-goal table Defender with a default
(proofs/TABLEBR.md).

A table Defender lists ``P(allocate to goal | walk)`` for finitely many walks and plays its
``default`` on every other walk: a probability ``q`` or ``"progress"`` (the progress rule
towards the table's own ``goal``, eq. (7), with the running minimum ``c_t`` taken along the
whole walk). Let the *trie* be the prefix closure of the listed walks. A walk of the game that
leaves the trie never comes back (the trie is prefix-closed), so its cost is the trie part plus
the cheapest way to finish from the state in which it left, against the default alone:

- constant default ``q``: the state is the node; a step of weight ``w`` costs type θ
  ``w·q_θ`` (``q_θ = q`` for the type whose goal is the table's, ``1 − q`` for the other), so
  the rest is a shortest path to the first goal reached plus its terminal cost ``d(goal, g^θ)``
  (one exact reverse Dijkstra per type);
- ``"progress"``: the state is the node and the running minimum ``c`` of ``d(·, goal)``; a
  step to ``x`` makes progress ``Δ = c − min(c, d(x, goal))`` and costs ``Δ`` (same type) or
  ``w − Δ`` (the other), both ``>= 0`` (``Δ <= w`` by the triangle inequality, since
  ``c <= d(v, goal)``). ``c`` only takes the values ``d(x, goal)`` and the exit states' ``c``,
  so an exact Dijkstra on the product graph (node, c) gives the cost-to-go; its size is
  guarded (:data:`MAX_PRODUCT_STATES`).

Backward induction on the finite trie then gives the minimum over all walks of any length
(exact; the same construction as the N-goal route, proofs/NWALKBR.md NW.1).
"""

from __future__ import annotations

import heapq
from collections.abc import Mapping
from dataclasses import dataclass
from itertools import count

from dppverify.errors import UndecidedError
from dppverify.exact import INF, Number, normalize
from dppverify.game.instance import Instance, Roles
from dppverify.game.profile import ProgressRule, TableRule

__all__ = ["MAX_PRODUCT_STATES", "TableMinima", "table_minima"]

MAX_PRODUCT_STATES = 400_000
"""Largest (node, running minimum) product graph the ``"progress"`` default is solved on."""


@dataclass(frozen=True)
class TableMinima:
    """Each type's minimum cost over all walks of any length against a table Defender.

    Attributes
    ----------
    primary, secondary : Number
        ``min`` over walks of ``U¹`` and ``U²`` (``INF`` when no goal can be reached).
    trie_prefixes : int
        Prefixes of the listed walks' trie (root included).
    """

    primary: Number
    secondary: Number
    trie_prefixes: int

    def of(self, theta: int) -> Number:
        """The minimum of type ``theta`` (1 = primary, 2 = secondary)."""
        return self.primary if theta == 1 else self.secondary


def _trie(instance: Instance, entries: Mapping[tuple[int, ...], object]) -> list[tuple[int, ...]]:
    """The prefix closure of the listed walks that the game can reach (a walk ends at its
    first goal: prefixes continuing past a goal are dropped), root first, by length."""
    s0 = instance.start
    out: set[tuple[int, ...]] = {(s0,)}
    for walk in entries:
        if not walk or walk[0] != s0:
            continue
        for t in range(1, len(walk)):
            if instance.is_goal(walk[t - 1]) or instance.weight(walk[t - 1], walk[t]) is None:
                break
            out.add(tuple(walk[:t + 1]))
    return sorted(out, key=len)


def _share(rule: TableRule, roles: Roles, theta: int, sigma_goal: Number,
           instance: Instance) -> Number:
    """``σ(g^θ | p)`` from ``σ(rule.goal | p)``."""
    if (roles.g1 if theta == 1 else roles.g2) == rule.goal:
        return sigma_goal
    return instance.numbers.difference(instance.numbers.one(), sigma_goal)


def _constant_exit(instance: Instance, roles: Roles, share: Number, theta: int) -> list[Number]:
    """Cost-to-go from each node against a constant allocation ``share`` to ``g^θ``: a reverse
    Dijkstra from the goals (each worth its terminal cost), never passing through a goal."""
    dist = roles.dist(theta)
    n = instance.n_nodes
    best: list[Number] = [INF] * n
    heap: list[tuple[Number, int, int]] = []
    tie = count()
    for g in instance.goals:
        best[g] = dist[g]
        heapq.heappush(heap, (dist[g], next(tie), g))
    done = [False] * n
    while heap:
        d, _, x = heapq.heappop(heap)
        if done[x] or d != best[x]:
            continue
        done[x] = True
        for v, w in instance.pred[x]:
            if instance.is_goal(v):
                continue  # a walk ends at its first goal: never continue from one
            nd = d + w * share
            if nd < best[v]:
                best[v] = nd
                heapq.heappush(heap, (nd, next(tie), v))
    return best


def _progress_exit(instance: Instance, roles: Roles, goal: int, theta: int, same: bool,
                   exits: set[tuple[int, Number]]) -> dict[tuple[int, Number], Number]:
    """Cost-to-go from the states ``(node, c)`` in ``exits`` against the progress rule towards
    ``goal`` (running minimum ``c``): exact Dijkstra on the product graph, backwards from the
    goal states."""
    slot = instance.goal_index(goal)
    assert slot is not None
    dg = instance.dist_to[slot]
    dist = roles.dist(theta)
    values = sorted({c for _, c in exits} | {x for x in dg if x != INF})
    n = instance.n_nodes
    states = sum(1 for x in range(n) for c in values if c <= dg[x])
    if states > MAX_PRODUCT_STATES:
        raise UndecidedError(
            f"the table Defender's \"progress\" default needs a (node, running minimum) "
            f"product graph of {states} states, above the limit of {MAX_PRODUCT_STATES}; a "
            f"constant \"default\" would decide the untruncated game, or --horizon H "
            f"certifies the game truncated at H")
    # c_at[x]: the c values a state at x can hold (c <= d(x, goal)); goal states cost their
    # terminal cost whatever c is
    best: dict[tuple[int, Number], Number] = {}
    heap: list[tuple[Number, int, int, Number]] = []
    tie = count()
    for g in instance.goals:
        for c in values:
            if c <= dg[g]:
                best[(g, c)] = dist[g]
                heapq.heappush(heap, (dist[g], next(tie), g, c))
    mode = instance.numbers
    while heap:
        d, _, x, c2 = heapq.heappop(heap)
        if best.get((x, c2)) != d:
            continue
        for v, w in instance.pred[x]:
            if instance.is_goal(v):
                continue
            # predecessors (v, c) with min(c, d(x)) == c2 and c <= d(v)
            if c2 < dg[x]:
                cands = [c2] if c2 <= dg[v] else []
            else:  # c2 == d(x): any c >= d(x) that v can hold
                cands = [c for c in values if c2 <= c <= dg[v]]
            for c in cands:
                delta = c - c2
                step = delta if same else mode.difference(w, delta)
                nd = d + step
                key = (v, c)
                if nd < best.get(key, INF):
                    best[key] = nd
                    heapq.heappush(heap, (nd, next(tie), v, c))
    return {s: best.get(s, INF) for s in exits}


def _reaches_a_goal(instance: Instance, u: int) -> bool:
    """True when some walk of the game goes on from ``u`` (a goal is reachable from it)."""
    return instance.is_goal(u) or any(d[u] != INF for d in instance.dist_to)


def _undefined(instance: Instance, walk: tuple[int, ...]) -> str:
    return (f"the untruncated game (H = inf) cannot be decided for this profile: its table "
            f"Defender has no \"default\" and no entry for the walk "
            f"{list(instance.labels(walk))}, so it is undefined there; a \"default\" (a "
            f"probability or \"progress\") would decide it, or --horizon H certifies the game "
            f"truncated at H")


def table_minima(instance: Instance, roles: Roles, rule: TableRule) -> TableMinima:
    """Both types' exact minimum cost over ALL walks against ``rule`` (it needs a default).

    Parameters
    ----------
    instance : Instance
        The game.
    roles : Roles
        The labelling (which goal is ``g1``).
    rule : TableRule
        The Defender. Without a default it must list every walk of the game that goes on
        from its entries (e.g. on a finite DAG); otherwise the game is undecided.

    Returns
    -------
    TableMinima

    Raises
    ------
    UndecidedError
        A table without default that leaves a walk of the game unlisted (the message names
        it), or a ``"progress"`` default whose product graph is above
        :data:`MAX_PRODUCT_STATES`.

    Examples
    --------
    On the kite (``s–g1``, ``s–g2`` of weight 2, ``s–a`` 1, ``a–g1``, ``a–g2`` 1, prior
    3/5), a table that guards g1 everywhere (default 1) lets the secondary walk ``s a g2`` free:

    >>> from fractions import Fraction
    >>> from dppverify.game.examples import kite
    >>> inst = kite()
    >>> r = inst.roles()
    >>> table_minima(inst, r, TableRule(goal=r.g1, entries={}, default=Fraction(1)))
    TableMinima(primary=2, secondary=0, trie_prefixes=1)
    >>> table_minima(inst, r, TableRule(goal=r.g1, entries={}, default=ProgressRule(r.g1)))
    TableMinima(primary=2, secondary=1, trie_prefixes=1)
    """
    mode = instance.numbers
    trie = _trie(instance, rule.entries)
    in_trie = set(trie)
    progress = isinstance(rule.default, ProgressRule)
    # σ(rule.goal | p) and the running minimum c(p) towards the progress goal on the trie
    pgoal = rule.default.goal if isinstance(rule.default, ProgressRule) else rule.goal
    pslot = instance.goal_index(pgoal)
    assert pslot is not None
    dg = instance.dist_to[pslot]
    out: list[Number] = []
    for theta in (1, 2):
        same = (roles.g1 if theta == 1 else roles.g2) == pgoal
        dist = roles.dist(theta)
        # exit states: (trie prefix p, next node u) with p·u off the trie
        const_exit: list[Number] | None = None
        if rule.default is not None and not progress:
            assert not isinstance(rule.default, ProgressRule)
            const_exit = _constant_exit(instance, roles,
                                        _share(rule, roles, theta, rule.default, instance), theta)
        cmin: dict[tuple[int, ...], Number] = {}
        for p in trie:
            cmin[p] = dg[p[0]] if len(p) == 1 else min(cmin[p[:-1]], dg[p[-1]])
        exits: set[tuple[int, Number]] = set()
        if progress:
            for p in trie:
                if len(p) > 1 and instance.is_goal(p[-1]):
                    continue
                for u, _ in instance.succ[p[-1]]:
                    if (*p, u) not in in_trie and not instance.is_goal(u):
                        exits.add((u, min(cmin[p], dg[u])))
        prog_exit = (_progress_exit(instance, roles, pgoal, theta, same, exits)
                     if progress and exits else {})
        J: dict[tuple[int, ...], Number] = {}
        for p in reversed(trie):
            v = p[-1]
            if instance.is_goal(v):
                J[p] = dist[v]
                continue
            best: Number = INF
            for u, w in instance.succ[v]:
                q = (*p, u)
                if q in in_trie:
                    sg = rule.entries.get(q)
                    if sg is None and rule.default is None:  # a listed walk's unlisted prefix
                        if _reaches_a_goal(instance, u):
                            raise UndecidedError(_undefined(instance, q))
                        continue
                    if sg is None:
                        sg = (mode.ratio(cmin[p] - min(cmin[p], dg[u]), w) if progress
                              else rule.default)  # type: ignore[assignment]
                    assert sg is not None and not isinstance(sg, ProgressRule)
                    cost = w * _share(rule, roles, theta, sg, instance) + J[q]
                elif rule.default is None:
                    if _reaches_a_goal(instance, u):
                        raise UndecidedError(_undefined(instance, q))
                    continue  # no walk of the game goes on from q: nothing to define
                elif progress:
                    delta = cmin[p] - min(cmin[p], dg[u])
                    step = delta if same else mode.difference(w, delta)
                    rest = dist[u] if instance.is_goal(u) else prog_exit[(u, min(cmin[p], dg[u]))]
                    cost = step + rest
                else:
                    assert const_exit is not None and not isinstance(rule.default, ProgressRule)
                    share = _share(rule, roles, theta, rule.default, instance)
                    cost = w * share + const_exit[u]
                if cost < best:
                    best = cost
            J[p] = best
        root = J[(instance.start,)]
        out.append(root if root == INF or not mode.exact else normalize(root))
    return TableMinima(primary=mode.convert(out[0]) if out[0] != INF else INF,
                       secondary=mode.convert(out[1]) if out[1] != INF else INF,
                       trie_prefixes=len(trie))
