"""Best responses over ALL walks against a table Defender with a default (proofs/NWALKBR.md).

A ``dpp-ngoal-profile/1`` Defender is a table ``walk -> σ(· | walk) ∈ Δ^N`` plus an optional
``default`` for every walk the table does not list. Let the *trie* be the prefix closure of the
listed walks (the table's walks and the profile's own walks): a finite set of prefixes. A walk
that leaves the trie never comes back (every extension of a prefix outside the trie is outside
it), so from there on the Defender plays ``default`` at every step, and type ``θ`` pays
``w(e)·default[θ]`` per step: the rest of its cheapest walk is a shortest path, to the first goal
it reaches, in arc costs ``w·default[θ]``, plus the terminal cost ``d(goal, g^θ)``
(:func:`exit_costs`, one exact Dijkstra from the goals). Inside the trie, backward induction
(:func:`walk_best_response`)::

    J(p) = d(v, g^θ)                                            (p ends at a goal v)
    J(p) = min over arcs (v, u):  w(v,u)·σ(p·u)[θ] + J(p·u)     (p·u in the trie)
                                  w(v,u)·default[θ] + D_θ(u)   (p·u leaves the trie)

``J(s0)`` is type θ's minimum over every walk of the game of any length (NW.1), exactly:
distances run on Python integers (the weights scaled by their common denominator and by the
denominator of ``default[θ]``), the trie on fractions. A game walk ends at the FIRST goal it
reaches, and a type may end at any goal (paying the terminal cost), as in the paper's game;
walks that never reach a goal are not strategies (admissible Attackers terminate), so nodes
from which no goal is reachable cost ``+inf``.

Without a default the Defender is undefined on every walk outside the table: unless the table
lists every prefix of every walk of the game, no best response exists; :func:`walk_best_response`
then names one walk where the Defender is undefined.
"""

from __future__ import annotations

import heapq
import math
import weakref
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from fractions import Fraction

from dppverify.exact import INF, Number, normalize
from dppverify.game.instance import Instance

__all__ = ["NWalkBR", "TableDefender", "WalkTrie", "build_walk_trie", "exit_costs",
           "table_defender", "walk_best_response"]


@dataclass(eq=False)
class WalkTrie:
    """Prefixes of a finite set of walks, numbered in insertion order (0 is ``(s0,)``).

    Attributes
    ----------
    instance : Instance
        The game.
    node, parent, depth : list of int
        Last node, parent prefix (``-1`` at the root) and steps of each prefix.
    children : list of dict
        ``children[p][v]``: the prefix ``p·v``.

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> t = build_walk_trie(star3(), [(0, 1, 2), (0, 1, 3)])
    >>> len(t), t.find((0, 1, 3)), t.walk(3), t.find((0, 2))
    (4, 3, (0, 1, 3), None)
    """

    instance: Instance
    node: list[int] = field(default_factory=list)
    parent: list[int] = field(default_factory=list)
    depth: list[int] = field(default_factory=list)
    children: list[dict[int, int]] = field(default_factory=list)

    def __len__(self) -> int:
        return len(self.node)

    def insert(self, walk: Sequence[int]) -> int:
        """Add ``walk`` (which starts at ``s0``) and its prefixes; return its prefix id."""
        if not self.node:
            self.node.append(self.instance.start)
            self.parent.append(-1)
            self.depth.append(0)
            self.children.append({})
        p = 0
        for v in walk[1:]:
            c = self.children[p].get(v)
            if c is None:
                c = len(self.node)
                self.node.append(v)
                self.parent.append(p)
                self.depth.append(self.depth[p] + 1)
                self.children.append({})
                self.children[p][v] = c
            p = c
        return p

    def find(self, walk: Sequence[int]) -> int | None:
        """The prefix id of ``walk``, or None when it is not in the trie."""
        if not walk or not self.node or walk[0] != self.node[0]:
            return None
        p: int | None = 0
        for v in walk[1:]:
            assert p is not None
            p = self.children[p].get(v)
            if p is None:
                return None
        return p

    def walk(self, p: int) -> tuple[int, ...]:
        """The walk (node indices) of prefix ``p``."""
        out = []
        while p >= 0:
            out.append(self.node[p])
            p = self.parent[p]
        return tuple(reversed(out))


def build_walk_trie(instance: Instance, walks: Iterable[Sequence[int]]) -> WalkTrie:
    """The trie of ``walks`` (each starting at ``s0``); the root is always present.

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> len(build_walk_trie(star3(), []))
    1
    """
    t = WalkTrie(instance)
    t.insert((instance.start,))
    for w in walks:
        t.insert(w)
    return t


@dataclass(frozen=True, eq=False)
class TableDefender:
    """A table Defender on a trie: ``sigma[p]`` for listed prefixes, ``default`` elsewhere.

    Attributes
    ----------
    trie : WalkTrie
        Contains every listed walk (and usually the profile's walks).
    sigma : Mapping
        Prefix id -> goal distribution, for the table's walks.
    default : tuple or None
        The distribution at every walk the table does not list.
    """

    trie: WalkTrie
    sigma: Mapping[int, tuple[Fraction, ...]]
    default: tuple[Fraction, ...] | None

    def at(self, p: int) -> tuple[Fraction, ...] | None:
        """``σ(· | p)`` at trie prefix ``p`` (None: undefined, no entry and no default)."""
        return self.sigma.get(p, self.default)


def table_defender(instance: Instance, entries: Mapping[tuple[int, ...], tuple[Fraction, ...]],
                   default: tuple[Fraction, ...] | None,
                   walks: Iterable[Sequence[int]] = ()) -> TableDefender:
    """The table Defender on the trie of its entries and ``walks`` (the profile's walks).

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> one = (Fraction(1), Fraction(0), Fraction(0))
    >>> d = table_defender(star3(), {(0, 1, 3): (Fraction(0), Fraction(1), Fraction(0))}, one)
    >>> d.at(d.trie.find((0, 1, 3))), d.at(d.trie.find((0, 1))) == one
    ((Fraction(0, 1), Fraction(1, 1), Fraction(0, 1)), True)
    """
    trie = build_walk_trie(instance, walks)
    sigma = {trie.insert(w): tuple(d) for w, d in entries.items()}
    return TableDefender(trie=trie, sigma=sigma, default=None if default is None
                         else tuple(default))


_ARCS: weakref.WeakKeyDictionary[Instance, tuple[int, list[list[tuple[int, int]]]]] = (
    weakref.WeakKeyDictionary())


def _scaled_pred(instance: Instance) -> tuple[int, list[list[tuple[int, int]]]]:
    """``(W, pred)``: ``W`` the lcm of the weights' denominators and, for every node ``x``, the
    arcs ``(u, W·w(u, x))`` entering it from non-goal nodes (built once per instance)."""
    if instance not in _ARCS:
        den = 1
        for d in {Fraction(w).denominator for arcs in instance.succ for _, w in arcs}:
            den = math.lcm(den, d)
        goal = set(instance.goals)
        scaled: dict[Number, int] = {}
        pred = []
        for arcs in instance.pred:
            row = []
            for u, w in arcs:
                if u in goal:
                    continue  # a walk never leaves a goal
                if w not in scaled:
                    scaled[w] = int(Fraction(w) * den)
                row.append((u, scaled[w]))
            pred.append(row)
        _ARCS[instance] = (den, pred)
    return _ARCS[instance]


def exit_costs(instance: Instance, share: Fraction, theta: int
               ) -> tuple[list[Number], list[int]]:
    """``D_θ(u)``: the cheapest way from ``u`` to the end of the game when every step costs
    ``w·share`` (the default's weight on ``g^θ``), plus the terminal cost ``d(goal, g^θ)``.

    Walks stop at the first goal (``D_θ(goal) = d(goal, g^θ)``); ``+inf`` where no goal is
    reachable. Returns the costs and, for each non-goal node, the next node of a cheapest walk
    (``-1`` where none). Exact: one Dijkstra on Python integers.

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> inst = star3()                      # nodes s, m, a, b, c = 0..4
    >>> exit_costs(inst, Fraction(0), 1)[0]   # free steps: walk to b from anywhere
    [0, 0, 2, 0, 2]
    >>> exit_costs(inst, Fraction(1), 0)      # full price: d(·, a)
    ([2, 1, 0, 2, 2], [2, 2, -1, -1, -1])
    """
    inst = instance
    big, pred = _scaled_pred(inst)
    num = share.numerator  # every step costs (W·w)·num / (W·q)
    unit = big * share.denominator
    n = inst.n_nodes
    best: list[int | None] = [None] * n
    nxt = [-1] * n
    heap: list[tuple[int, int]] = []
    for g in inst.goals:
        t = inst.dist_to[theta][g]
        if t != INF:
            key = int(Fraction(t) * unit)
            best[g] = key
            heap.append((key, g))
    heapq.heapify(heap)
    done = [False] * n
    pop, push = heapq.heappop, heapq.heappush
    while heap:
        k, x = pop(heap)
        if done[x]:
            continue
        done[x] = True
        for u, wi in pred[x]:
            if done[u]:
                continue
            nk = k + wi * num
            b = best[u]
            if b is None or nk < b:
                best[u] = nk
                nxt[u] = x
                push(heap, (nk, u))
    costs: list[Number] = [INF if b is None else normalize(Fraction(b, unit)) for b in best]
    return costs, nxt


@dataclass(frozen=True)
class NWalkBR:
    """Type θ's best response over all walks against a table Defender.

    Attributes
    ----------
    theta : int
        The type (0-based).
    value : Number or None
        The minimum cost over every walk (``+inf`` if no walk ends; None when undefined).
    walk : tuple of int
        A minimising walk (empty when ``value`` is None or infinite).
    undefined : tuple of int or None
        A walk of the game where the Defender is undefined (no entry, no default); then
        ``value`` is None.
    """

    theta: int
    value: Number | None
    walk: tuple[int, ...]
    undefined: tuple[int, ...] | None = None


def _shorter(a: tuple[int, ...] | None, b: tuple[int, ...]) -> tuple[int, ...]:
    return b if a is None or len(b) < len(a) else a


def walk_best_response(defender: TableDefender, theta: int,
                       exits: tuple[list[Number], list[int]] | None = None) -> NWalkBR:
    """Type ``θ``'s exact minimum over ALL walks of the game against ``defender``.

    ``exits`` may pass a precomputed :func:`exit_costs` for ``defender.default[θ]``.

    Examples
    --------
    Against the hub profile's Defender (guard ``a`` off its table), type ``b`` loops
    ``s m s m b`` for free, cheaper than its profile walk ``s m b`` (cost 1):

    >>> from dppverify.game.examples import star3
    >>> inst = star3()
    >>> one, b = (Fraction(1), Fraction(0), Fraction(0)), (Fraction(0), Fraction(1), Fraction(0))
    >>> d = table_defender(inst, {(0, 1, 3): b}, one, walks=[(0, 1, 2), (0, 1, 3)])
    >>> br = walk_best_response(d, 1)
    >>> br.value, inst.labels(br.walk)
    (0, ('s', 'm', 's', 'm', 'b'))
    >>> walk_best_response(table_defender(inst, {(0, 1, 3): b}, None), 1).undefined
    (0, 1)
    """
    trie = defender.trie
    inst = trie.instance
    default = defender.default
    if exits is None and default is not None:
        exits = exit_costs(inst, default[theta], theta)
    term = inst.dist_to[theta]
    n = len(trie)
    J: list[Number] = [INF] * n
    choice: list[tuple[int, int] | None] = [None] * n  # (node, trie child or -1)
    undefined: tuple[int, ...] | None = None
    order = sorted(range(n), key=lambda p: -trie.depth[p])
    for p in order:
        v = trie.node[p]
        if inst.is_goal(v):
            J[p] = term[v]
            continue
        best: Number = INF
        pick: tuple[int, int] | None = None
        kids = trie.children[p]
        for u, w in inst.succ[v]:
            c = kids.get(u)
            if c is not None:
                s = defender.at(c)
                if s is None:
                    if J[c] != INF:
                        undefined = _shorter(undefined, trie.walk(c))
                    continue
                cost = w * s[theta] + J[c]
            else:
                if not (inst.is_goal(u) or inst.hops[u] >= 0):
                    continue  # no goal reachable: not part of any walk of the game
                if default is None or exits is None:
                    undefined = _shorter(undefined, (*trie.walk(p), u))
                    continue
                cost = w * default[theta] + exits[0][u]
            if cost < best:
                best, pick = cost, (u, -1 if c is None else c)
        J[p] = normalize(best) if best != INF else INF
        choice[p] = pick
    if undefined is not None:
        return NWalkBR(theta=theta, value=None, walk=(), undefined=undefined)
    if J[0] == INF:
        return NWalkBR(theta=theta, value=INF, walk=())
    walk = [trie.node[0]]
    p = 0
    while choice[p] is not None:
        u, c = choice[p]  # type: ignore[misc]
        walk.append(u)
        if c < 0:
            assert exits is not None
            x = u
            while not inst.is_goal(x):
                x = exits[1][x]
                walk.append(x)
            break
        p = c
    return NWalkBR(theta=theta, value=J[0], walk=tuple(walk))
