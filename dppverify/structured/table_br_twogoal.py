"""Best responses over ALL walks against a two-goal table Defender with a default
(proofs/TABLEBR.md): the ``dpp-profile/1`` table rule on the N-general backward induction of
:mod:`dppverify.structured.table_br` (the case N = 2).

A two-goal table lists ``P(allocate to goal | walk)`` for finitely many walks and plays its
``default`` on every other walk: a probability ``q`` or ``"progress"`` (the progress rule
towards the table's own ``goal``, eq. (7), with the running minimum ``c_t`` taken along the
whole walk). A constant default leaves the trie by :func:`~dppverify.structured.table_br.exit_costs`
(``q_θ = q`` for the type whose goal is the table's, ``1 − q`` for the other). Against
``"progress"`` the state off the trie is the node and the running minimum ``c`` of
``d(·, goal)``: a step to ``x`` makes progress ``Δ = c − min(c, d(x, goal))`` and costs ``Δ``
(same type) or ``w − Δ`` (the other), both ``>= 0`` (``Δ <= w`` by the triangle inequality,
since ``c <= d(v, goal)``). ``c`` only takes the values ``d(x, goal)`` and the exit states'
``c``, so an exact Dijkstra on the product graph (node, c) gives the cost-to-go; its size is
guarded (:data:`MAX_PRODUCT_STATES`).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from fractions import Fraction

from dppverify.errors import UndecidedError
from dppverify.exact import INF, Number, normalize
from dppverify.game.distances import multi_source_dijkstra, state_dijkstra
from dppverify.game.instance import Instance, Roles
from dppverify.game.profile import DefenderRule
from dppverify.structured.table_br import Step, exit_costs, trie_induction
from dppverify.structured.trie import WalkTrie, build_walk_trie

MAX_PRODUCT_STATES = 400_000
"""Largest (node, running minimum) product graph the ``"progress"`` default is solved on."""


@dataclass(frozen=True)
class TableMinima:
    """Each type's minimum cost over all walks of any length against a two-goal table Defender.

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

    def of(self, role: int) -> Number:
        """The minimum of type ``role`` (1 = primary, 2 = secondary)."""
        return self.primary if role == 1 else self.secondary


def _game_prefix(instance: Instance, walk: tuple[int, ...]) -> tuple[int, ...]:
    """The longest prefix of a listed walk the game can reach (a walk ends at its first goal
    and follows arcs); ``()`` when it does not start at ``s0``."""
    if not walk or walk[0] != instance.start:
        return ()
    for t in range(1, len(walk)):
        if instance.is_goal(walk[t - 1]) or instance.weight(walk[t - 1], walk[t]) is None:
            return walk[:t]
    return walk


def _undefined_walk(instance: Instance, rule: DefenderRule) -> tuple[int, ...] | None:
    """For a table without default: the first walk of the game it leaves undefined, in the
    order the message has always named it (longest trie prefixes first), or None."""
    s0 = instance.start
    trie: set[tuple[int, ...]] = {(s0,)}
    for walk in rule.entries:
        if walk and walk[0] == s0:
            for t in range(1, len(walk)):
                if instance.is_goal(walk[t - 1]) or instance.weight(walk[t - 1],
                                                                    walk[t]) is None:
                    break
                trie.add(tuple(walk[:t + 1]))
    for p in reversed(sorted(trie, key=len)):
        if instance.is_goal(p[-1]):
            continue
        for u, _ in instance.succ[p[-1]]:
            q = (*p, u)
            if (q not in trie or q not in rule.entries) and (
                    instance.is_goal(u) or any(d[u] != INF for d in instance.dist_to)):
                return q
    return None


def _progress_exit(instance: Instance, roles: Roles, goal: int, role: int, same: bool,
                   exits: set[tuple[int, Number]]) -> dict[tuple[int, Number], Number]:
    """Cost-to-go from the states ``(node, c)`` in ``exits`` against the progress rule towards
    ``goal`` (running minimum ``c``): exact Dijkstra on the product graph, backwards from the
    goal states."""
    index = instance.goals.index(goal)
    dg = instance.dist_to[index]
    dist = roles.dist(role)
    values = sorted({c for _, c in exits} | {x for x in dg if x != INF})
    n = instance.n_nodes
    states = sum(1 for x in range(n) for c in values if c <= dg[x])
    if states > MAX_PRODUCT_STATES:
        raise UndecidedError(
            f"the table Defender's \"progress\" default needs a (node, running minimum) "
            f"product graph of {states} states, above the limit of {MAX_PRODUCT_STATES}; a "
            f"constant \"default\" would decide the untruncated game, or --horizon H "
            f"certifies the game truncated at H")
    mode = instance.numbers

    def back(state: tuple[int, Number]) -> Iterable[tuple[tuple[int, Number], Number]]:
        """The arcs into ``(x, c2)``, reversed: predecessors ``(v, c)`` with
        ``min(c, d(x)) == c2`` and ``c <= d(v)``, and the step's cost."""
        x, c2 = state
        for v, w in instance.pred[x]:
            if instance.is_goal(v):
                continue
            if c2 < dg[x]:
                cands = [c2] if c2 <= dg[v] else []
            else:  # c2 == d(x): any c >= d(x) that v can hold
                cands = [c for c in values if c2 <= c <= dg[v]]
            for c in cands:
                delta = c - c2
                yield (v, c), (delta if same else mode.difference(w, delta))

    # goal states cost their terminal cost whatever c is
    best = state_dijkstra([((g, c), dist[g]) for g in instance.goals for c in values
                           if c <= dg[g]], back)
    return {s: best.get(s, INF) for s in exits}


def _constant_exit(instance: Instance, roles: Roles, share: Number, role: int) -> list[Number]:
    """Cost-to-go from each node against a constant allocation ``share`` to ``g^θ``
    (:func:`exit_costs`; float mode: the same Dijkstra on the float weights)."""
    index = instance.goals.index(roles.g1 if role == 1 else roles.g2)
    if instance.exact:
        return exit_costs(instance, Fraction(share), index)[0]
    pred = [[(u, w) for u, w in arcs if not instance.is_goal(u)] for arcs in instance.pred]
    dist = roles.dist(role)
    return multi_source_dijkstra(pred, [(g, dist[g]) for g in instance.goals],
                                 factor=share)[0]


def table_minima(instance: Instance, roles: Roles, rule: DefenderRule) -> TableMinima:
    """Both types' exact minimum cost over ALL walks against the two-goal ``rule``.

    Parameters
    ----------
    instance, roles : Instance, Roles
        The game, and which of its goals is ``g1``.
    rule : DefenderRule
        The Defender: ``P(allocate to rule.goal | walk)`` for listed walks, and a default (a
        probability, or the progress rule, eq. (7), with the running minimum ``c_t`` taken
        along the whole walk). Without a default it must list every walk of the game that
        goes on from its entries (e.g. on a finite DAG); otherwise the game is undecided.

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

    >>> from dppverify.game.examples import kite
    >>> from dppverify.game.profile import ProgressRule, TableRule
    >>> inst = kite()
    >>> r = inst.roles()
    >>> table_minima(inst, r, TableRule(goal=r.g1, entries={}, default=Fraction(1)))
    TableMinima(primary=2, secondary=0, trie_prefixes=1)
    >>> table_minima(inst, r, TableRule(goal=r.g1, entries={}, default=ProgressRule(r.g1)))
    TableMinima(primary=2, secondary=1, trie_prefixes=1)
    """
    mode = instance.numbers
    if not rule.defined_everywhere:
        missing = _undefined_walk(instance, rule)
        if missing is not None:
            raise UndecidedError(
                f"the untruncated game (H = inf) cannot be decided for this profile: its table "
                f"Defender has no \"default\" and no entry for the walk "
                f"{list(instance.labels(missing))}, so it is undefined there; a \"default\" (a "
                f"probability or \"progress\") would decide it, or --horizon H certifies the "
                f"game truncated at H")
    trie = build_walk_trie(instance, [_game_prefix(instance, w) for w in rule.entries])
    listed = {p: rule.entries[walk] for walk in rule.entries
              if (p := trie.find(walk)) is not None}
    # the running minimum c(p) towards the progress goal on the trie (parents come first)
    pgoal = rule.goal if rule.progress_goal is None else rule.progress_goal
    pindex = instance.goals.index(pgoal)
    dg = instance.dist_to[pindex]
    cmin: list[Number] = []
    for p in range(len(trie)):
        here = dg[trie.node[p]]
        cmin.append(here if trie.parent[p] < 0 else min(cmin[trie.parent[p]], here))
    out = [_type_minimum(instance, roles, rule, trie, listed, cmin, pgoal, role)
           for role in (1, 2)]
    return TableMinima(primary=mode.convert(out[0]) if out[0] != INF else INF,
                       secondary=mode.convert(out[1]) if out[1] != INF else INF,
                       trie_prefixes=len(trie))


def _type_minimum(instance: Instance, roles: Roles, rule: DefenderRule, trie: WalkTrie,
                  listed: Mapping[int, Fraction], cmin: list[Number], pgoal: int,
                  role: int) -> Number:
    """Type ``θ``'s minimum over all walks (1 = primary, 2 = secondary): the backward
    induction on the trie, leaving it against the table's default."""
    mode = instance.numbers
    index = instance.goals.index(pgoal)
    dg = instance.dist_to[index]
    mine = (roles.g1 if role == 1 else roles.g2) == rule.goal

    def share(sg: Number) -> Number:
        """``σ(g^θ | p)`` from ``σ(rule.goal | p)``."""
        return sg if mine else mode.difference(mode.one(), sg)

    leave: Step
    if rule.progress_goal is not None:
        same = (roles.g1 if role == 1 else roles.g2) == pgoal
        exits: set[tuple[int, Number]] = set()
        for p in range(len(trie)):
            v = trie.node[p]
            if trie.parent[p] >= 0 and instance.is_goal(v):
                continue
            for u, _ in instance.succ[v]:
                if trie.child(p, u) is None and not instance.is_goal(u):
                    exits.add((u, min(cmin[p], dg[u])))
        rest = _progress_exit(instance, roles, pgoal, role, same, exits) if exits else {}
        dist = roles.dist(role)

        def progress_leave(p: int, u: int, w: Number) -> Number | None:
            c = min(cmin[p], dg[u])
            delta = cmin[p] - c
            step = delta if same else mode.difference(w, delta)
            return step + (dist[u] if instance.is_goal(u) else rest[(u, c)])

        leave = progress_leave
    elif rule.constant is not None:
        off = share(rule.constant)
        const = _constant_exit(instance, roles, off, role)

        def constant_leave(p: int, u: int, w: Number) -> Number | None:
            return w * off + const[u]

        leave = constant_leave
    else:
        def undefined(p: int, u: int, w: Number) -> Number | None:
            return None  # never reached: _undefined_walk found every such walk

        leave = undefined

    def inside(p: int, c: int, w: Number) -> Number | None:
        sg: Number | None = listed.get(c)
        if sg is None:
            if not rule.defined_everywhere:
                return None
            sg = (mode.ratio(cmin[p] - min(cmin[p], dg[trie.node[c]]), w)
                  if rule.constant is None else rule.constant)
        return w * share(sg)

    J, _, _ = trie_induction(instance, trie, roles.dist(role), inside, leave)
    root = J[0]
    return root if root == INF or not mode.exact else normalize(root)
