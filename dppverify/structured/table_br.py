"""Best responses over ALL walks against a table Defender with a default, for any number of goals
(proofs/NWALKBR.md; the two-goal forms of the default, proofs/TABLEBR.md).

A table Defender lists ``σ(· | walk) ∈ Δ^N`` for finitely many walks and plays its
``default`` on every other walk. Let the *trie* be the prefix closure of the listed walks
(:mod:`dppverify.structured.trie`). A walk that leaves the trie never comes back (the trie is
prefix-closed), so its cost is the trie part plus the cheapest way to finish from the state in
which it left, against the default alone. Inside the trie, backward induction
(:func:`trie_induction`)::

    J(p) = d(v, g^θ)                                          (p ends at a goal v)
    J(p) = min over arcs (v, u):  w(v,u)·σ(p·u)[θ] + J(p·u)   (p·u in the trie)
                                  cost of leaving at p·u       (p·u off the trie)

``J(s0)`` is type θ's minimum over every walk of the game of any length (NW.1), exactly. A game
walk ends at the FIRST goal it reaches, and a type may end at any goal (paying the terminal
cost ``d(goal, g^θ)``); walks that never reach a goal are not strategies, so nodes from which
no goal is reachable cost ``+inf``. The cost of leaving depends on the default:

- a constant distribution (any N; a probability ``q`` for two goals): the state is the node; a
  step of weight ``w`` costs type θ ``w·default[θ]``, so the rest is a shortest path to the
  first goal reached plus its terminal cost (:func:`exit_costs`, one exact Dijkstra per type);
- ``"progress"`` (two goals, :mod:`dppverify.structured.table_br_twogoal`): the state is the
  node and the running minimum of ``d(·, goal)``, and an exact Dijkstra on that product graph
  gives the cost-to-go.

Without a default the Defender is undefined on every walk outside the table: unless the table
lists every prefix of every walk of the game, no best response exists; the N-goal
:func:`walk_best_response` then names one walk where the Defender is undefined, the two-goal
``table_minima`` raises :class:`~dppverify.errors.UndecidedError` naming one.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from fractions import Fraction

from dppverify.exact import INF, Number, normalize
from dppverify.game.distances import common_denominator, multi_source_dijkstra
from dppverify.game.instance import Instance
from dppverify.structured.trie import WalkTrie, build_walk_trie

GoalFreePred = tuple[int, list[list[tuple[int, int]]]]
"""``(W, pred)``: ``W`` the common denominator of the weights and ``pred[x]`` the arcs
``(u, W·w(u, x))`` entering ``x`` from non-goal nodes (:func:`goal_free_pred`)."""


@dataclass(frozen=True, eq=False)
class TableDefender:
    """A table Defender on a trie: ``sigma[p]`` for listed prefixes, ``default`` elsewhere.

    Attributes
    ----------
    trie : WalkTrie
        Contains every listed walk (and usually the profile's walks).
    sigma : Mapping
        Prefix id -> goal distribution (indexed by goal index θ), for the table's walks.
    default : tuple or None
        The distribution at every walk the table does not list.
    instance : Instance
        The game the walks are walks of.
    """

    trie: WalkTrie
    sigma: Mapping[int, tuple[Fraction, ...]]
    default: tuple[Fraction, ...] | None
    instance: Instance
    _exit_graph: list[GoalFreePred] = field(default_factory=list, init=False, repr=False)

    def at(self, p: int) -> tuple[Fraction, ...] | None:
        """``σ(· | p)`` at trie prefix ``p`` (None: undefined, no entry and no default)."""
        return self.sigma.get(p, self.default)

    def exit_graph(self) -> GoalFreePred:
        """:func:`goal_free_pred` of the instance, built once per Defender (for every type)."""
        if not self._exit_graph:
            self._exit_graph.append(goal_free_pred(self.instance))
        return self._exit_graph[0]


def table_defender(instance: Instance,
                   entries: Mapping[tuple[int, ...], tuple[Fraction, ...]],
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
    return TableDefender(instance=instance, trie=trie, sigma=sigma,
                         default=None if default is None else tuple(default))


def goal_free_pred(instance: Instance) -> GoalFreePred:
    """The arcs entering each node from non-goal nodes (a walk never leaves a goal), weights
    scaled to integers: the graph :func:`exit_costs` runs on. Exact instances only.

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> goal_free_pred(star3())[1][:2]        # into s (from m), into m (from s)
    [[(1, 1)], [(0, 1)]]
    """
    den = common_denominator({w for arcs in instance.succ for _, w in arcs})
    scaled: dict[Number, int] = {}
    pred = []
    for arcs in instance.pred:
        row = []
        for u, w in arcs:
            if instance.is_goal(u):
                continue
            if w not in scaled:
                scaled[w] = int(Fraction(w) * den)
            row.append((u, scaled[w]))
        pred.append(row)
    return den, pred


def exit_costs(instance: Instance, share: Fraction, theta: int,
               arcs: GoalFreePred | None = None) -> tuple[list[Number], list[int]]:
    """``D_θ(u)``: the cheapest way from ``u`` to the end of the game when every step costs
    ``w·share`` (the default's weight on ``g^θ``), plus the terminal cost ``d(goal, g^θ)``.

    Walks stop at the first goal (``D_θ(goal) = d(goal, g^θ)``); ``+inf`` where no goal is
    reachable. Returns the costs and, for each non-goal node, the next node of a cheapest walk
    (``-1`` where none). Exact: one Dijkstra on Python integers
    (:func:`~dppverify.game.distances.multi_source_dijkstra`); ``arcs`` may pass
    :func:`goal_free_pred` computed once for several calls.

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> inst = star3()                      # nodes s, m, a, b, c = 0..4
    >>> exit_costs(inst, Fraction(0), 1)[0]   # free steps: walk to b from anywhere
    [0, 0, 2, 0, 2]
    >>> exit_costs(inst, Fraction(1), 0)      # full price: d(·, a)
    ([2, 1, 0, 2, 2], [2, 2, -1, -1, -1])
    """
    big, pred = arcs if arcs is not None else goal_free_pred(instance)
    unit = big * share.denominator  # every step costs (W·w)·num / (W·q)
    term = instance.dist_to[theta]
    sources = [(g, int(term[g] * unit)) for g in instance.goals if term[g] != INF]
    keys, via = multi_source_dijkstra(pred, sources, factor=share.numerator)
    costs: list[Number] = [INF if k == INF else normalize(Fraction(int(k), unit)) for k in keys]
    return costs, via


Step = Callable[[int, int, Number], Number | None]
"""``(p, x, w) -> cost``: a step of weight ``w`` from trie prefix ``p`` (to the trie child
``x``, or off the trie to node ``x``); None where the Defender is undefined."""


def trie_induction(instance: Instance, trie: WalkTrie, terminal: Sequence[Number],
                   inside: Step, leave: Step
                   ) -> tuple[list[Number], list[tuple[int, int] | None], tuple[int, ...] | None]:
    """Backward induction on ``trie`` (deepest prefixes first): ``J``, the choices, and the
    shortest walk of the game where the Defender is undefined (None when there is none).

    ``J[p]`` is the minimum cost from prefix ``p`` on: ``terminal[v]`` at a goal ``v``;
    else the least ``inside(p, c, w) + J[c]`` over trie children ``c`` and ``leave(p, u, w)``
    over arcs leaving the trie (towards nodes from which a goal is reachable). ``choice[p]``
    is the minimising ``(node, trie child or -1)``.

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> inst = star3()
    >>> t = build_walk_trie(inst, [(0, 1, 2)])
    >>> J, choice, _ = trie_induction(inst, t, inst.dist_to[0], lambda p, c, w: w,
    ...                               lambda p, u, w: None)
    >>> J[0], choice[0]
    (2, (1, 1))
    """
    n = len(trie)
    J: list[Number] = [INF] * n
    choice: list[tuple[int, int] | None] = [None] * n
    undefined: tuple[int, ...] | None = None
    for p in sorted(range(n), key=lambda q: -trie.depth[q]):
        v = trie.node[p]
        if instance.is_goal(v):
            J[p] = terminal[v]
            continue
        best: Number = INF
        pick: tuple[int, int] | None = None
        for u, w in instance.succ[v]:
            c = trie.child(p, u)
            if c is not None:
                step = inside(p, c, w)
                if step is None:
                    if J[c] != INF:
                        undefined = _shorter(undefined, trie.walk(c))
                    continue
                cost = step + J[c]
            else:
                if not (instance.is_goal(u) or instance.hops[u] >= 0):
                    continue  # no goal reachable: not part of any walk of the game
                out = leave(p, u, w)
                if out is None:
                    undefined = _shorter(undefined, (*trie.walk(p), u))
                    continue
                cost = out
            if cost < best:
                best, pick = cost, (u, -1 if c is None else c)
        J[p] = normalize(best) if best != INF else INF
        choice[p] = pick
    return J, choice, undefined


def _shorter(a: tuple[int, ...] | None, b: tuple[int, ...]) -> tuple[int, ...]:
    return b if a is None or len(b) < len(a) else a


@dataclass(frozen=True)
class WalkBestResponse:
    """Type θ's best response over all walks against a table Defender.

    Attributes
    ----------
    theta : int
        The goal index of the type (0-based).
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


def walk_best_response(defender: TableDefender, theta: int,
                       exits: tuple[list[Number], list[int]] | None = None) -> WalkBestResponse:
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
    inst = defender.instance
    default = defender.default
    if exits is None and default is not None:
        exits = exit_costs(inst, default[theta], theta, defender.exit_graph())

    def inside(p: int, c: int, w: Number) -> Number | None:
        s = defender.at(c)
        return None if s is None else w * s[theta]

    def leave(p: int, u: int, w: Number) -> Number | None:
        if default is None or exits is None:
            return None
        return w * default[theta] + exits[0][u]

    J, choice, undefined = trie_induction(inst, trie, inst.dist_to[theta], inside, leave)
    if undefined is not None:
        return WalkBestResponse(theta=theta, value=None, walk=(), undefined=undefined)
    if J[0] == INF:
        return WalkBestResponse(theta=theta, value=INF, walk=())
    walk = [trie.node[0]]
    p = 0
    step = choice[p]
    while step is not None:
        u, c = step
        walk.append(u)
        if c < 0:
            assert exits is not None
            x = u
            while not inst.is_goal(x):
                x = exits[1][x]
                walk.append(x)
            break
        p = c
        step = choice[p]
    return WalkBestResponse(theta=theta, value=J[0], walk=tuple(walk))

