"""The deceptive path-planning strategies π_d1–π_d4 of Masters & Sardina (IJCAI 2017).

Masters and Sardina, "Deceptive Path-Planning", IJCAI 2017, Sec. 5; reference code: the p4
simulator fork ``ssardina-research/p4-simulator-gr`` (``src/deceptor.py``,
``src/agents/agent_ds1.py`` … ``agent_ds4.py``), read to check this reading, not copied.
Each type θ plans for its real goal ``g_r = g^θ`` with the other goal as the bogus goal
``g_b = g^{-θ}``; distances are the game's (``d``, exact on rational instances):

- ``costdif(v, g) = d(v, g) − d(s0, g)``; a node ``v`` is **truthful** when ``v ≠ g_b`` and
  ``costdif(v, g_r) < costdif(v, g_b)`` (the observer of the paper's cost-difference goal
  recogniser then ranks ``g_r`` strictly first at ``v``).
- **Radius of maximum probability** ``rmp = (d(g_b, g_r) + d(s0, g_r) − d(s0, g_b)) / 2``.
- **Last deceptive point** ``t``: on a shortest path from ``g_b`` to ``g_r``, the first node
  at distance ≥ ``d(g_b, g_r) − rmp`` from ``g_b`` (i.e. within ``rmp`` of ``g_r``); then,
  while that node is truthful, one node back towards ``g_b`` (the reference code's
  ``findTarget``). ``g_b`` itself is never truthful, so ``t`` exists.

The strategies (each type's path is deterministic):

- **π_d1** (simulation, "showing the false"): a shortest path to ``g_b``, then to ``g_r``.
- **π_d2** (dissimulation, "hiding the real"): a shortest path to ``t``, then to ``g_r``.
- **π_d3**: like π_d2, but the leg to ``t`` avoids truthful-looking steps softly: a step onto
  a node nearer to ``g_r`` than to ``g_b`` costs 3/2 of its weight (the reference code
  inflates its A* heuristic by 1.5 on such nodes; a step cost makes the path independent of
  A*'s tie-breaking). The leg is the shortest path under those costs.
- **π_d4**: like π_d2, but the leg to ``t`` uses no truthful node (the reference code prunes
  them) and passes no goal (the game would end there); the shortest such path. When none
  exists, π_d4 falls back to π_d2's leg (``MSPath.fallback``).

In this game a walk ends at the first goal it reaches, where type θ pays the terminal cost
``d(end, g^θ)``: so π_d1 ends at ``g_b`` and the rest of its route (a shortest path from
``g_b`` to ``g_r``) is exactly that terminal cost; any other path is cut at the first goal
it reaches. Shortest-path ties follow the solver's rule (lowest node index,
:mod:`solver.graph.shortest_paths`).

Examples
--------
A corridor ``s – a – b`` with ``g1`` beyond ``b`` and ``g2`` one step off ``a``:

>>> import networkx as nx
>>> from fractions import Fraction
>>> from solver.game.instance import Instance
>>> g = nx.Graph([("s", "a"), ("a", "b"), ("b", "g1"), ("a", "g2")])
>>> plans = plan_all(Instance(g, "s", ("g1", "g2"), ("1/2", "1/2")))
>>> for name in STRATEGIES:  # the primary type's paths
...     print(name, plans[name][0].nodes)
pi_d1 ('s', 'a', 'g2')
pi_d2 ('s', 'a', 'b', 'g1')
pi_d3 ('s', 'a', 'b', 'g1')
pi_d4 ('s', 'a', 'b', 'g1')
"""

from __future__ import annotations

from collections.abc import Callable, Hashable, Sequence
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from solver.game.instance import Instance
from solver.graph.distances import costs_to, distances_to
from solver.graph.network import Network
from solver.graph.shortest_paths import path_to_target

STRATEGIES = ("pi_d1", "pi_d2", "pi_d3", "pi_d4")
"""The four strategies, as CSV/CLI names."""

LABELS = {"pi_d1": "π_d1", "pi_d2": "π_d2", "pi_d3": "π_d3", "pi_d4": "π_d4"}
"""How text outputs and figures spell them."""

_PENALTY = Fraction(3, 2)


@dataclass(frozen=True)
class MSPath:
    """One type's path under a strategy.

    Attributes
    ----------
    walk : tuple of int
        Node indices from ``s0`` to the first goal reached.
    nodes : tuple
        The same as node ids.
    target : Hashable
        ``g_b`` (π_d1) or the last deceptive point ``t`` (π_d2–π_d4), as a node id.
    fallback : bool
        π_d4 only: no path to ``t`` through deceptive nodes existed, π_d2's leg was used.
    """

    walk: tuple[int, ...]
    nodes: tuple[Hashable, ...]
    target: Hashable
    fallback: bool = False


@dataclass(frozen=True)
class _Game:
    net: Network
    s0: int
    goals: tuple[int, int]            # (g1, g2) as indices
    d_to: tuple[np.ndarray, np.ndarray]  # d(v, g1), d(v, g2)

    @classmethod
    def of(cls, inst: Instance) -> _Game:
        net = inst.network
        s0, g1, g2 = (net.index_of(x) for x in (inst.start, inst.primary, inst.secondary))
        assert s0 is not None and g1 is not None and g2 is not None
        return cls(net, s0, (g1, g2), (distances_to(net, g1), distances_to(net, g2)))


def _lt(net: Network, a: object, b: object) -> bool:
    """``a < b`` on stored numbers (exact integers, or floats within the tolerance)."""
    return not net.numbers.at_most(b, a)


def truthful(net: Network, v: int, s0: int, real: int, bogus: int, d_to_real: np.ndarray,
             d_to_bogus: np.ndarray) -> bool:
    """Whether node ``v`` is truthful for the real goal (see the module docstring).

    Examples
    --------
    >>> import networkx as nx
    >>> net = Network.from_networkx(nx.path_graph(5))  # 0 - 1 - 2 - 3 - 4
    >>> dr, db = distances_to(net, 4), distances_to(net, 0)
    >>> [truthful(net, v, 2, 4, 0, dr, db) for v in range(5)]
    [False, False, False, True, True]
    """
    if v == bogus:
        return False
    dif_real = d_to_real[v] - d_to_real[s0]
    dif_bogus = d_to_bogus[v] - d_to_bogus[s0]
    return _lt(net, dif_real, dif_bogus)


def last_deceptive_point(net: Network, s0: int, real: int, bogus: int, d_to_real: np.ndarray,
                         d_to_bogus: np.ndarray) -> int:
    """The last deceptive point ``t`` for the real goal (see the module docstring).

    Examples
    --------
    On the path 0 – 1 – 2 – 3 – 4 – 5 – 6 with the start at 3, the real goal 6 and the bogus
    goal 0: rmp = (6 + 3 − 3) / 2 = 3, so ``t`` is first the node 3 steps from 6 (node 3),
    which is not truthful (both goals look equally likely there):

    >>> import networkx as nx
    >>> net = Network.from_networkx(nx.path_graph(7))
    >>> last_deceptive_point(net, 3, 6, 0, distances_to(net, 6), distances_to(net, 0))
    3
    >>> last_deceptive_point(net, 2, 6, 0, distances_to(net, 6), distances_to(net, 0))
    2
    """
    path = path_to_target(net, bogus, real, d_to_real, net.numbers)
    total = d_to_real[bogus]
    twice_rmp = d_to_real[bogus] + d_to_real[s0] - d_to_bogus[s0]
    # walk from g_b until 2 * cost_so_far >= 2 * d(g_b, g_r) - 2 rmp
    weights = net.path_weights(path)
    k, so_far = 0, weights[:0].sum()
    while k < len(path) - 1 and _lt(net, 2 * so_far, 2 * total - twice_rmp):
        so_far = so_far + weights[k]
        k += 1
    while k > 0 and truthful(net, path[k], s0, real, bogus, d_to_real, d_to_bogus):
        k -= 1
    return int(path[k])


Stored = Fraction | float
"""A stored weight or distance: an exact integer numerator, or a float (float mode)."""


def _leg(net: Network, source: int, target: int, cost: Callable[[int, int, Stored], Stored],
         allowed: Callable[[int], bool]) -> list[int] | None:
    """Least-cost path ``source -> target`` under ``cost(u, v, w)`` through ``allowed``
    nodes (``source`` and ``target`` always allowed); ties: lowest node index at each step
    (a backward Dijkstra to ``target``, then the tight arcs from ``source``)."""
    def step(u: int, v: int, w: Stored) -> Stored | None:
        return cost(u, v, w) if u == source or allowed(u) else None

    dist = costs_to(net, target, step, lambda a, b: _lt(net, a, b))
    if source not in dist:
        return None
    path = [source]
    u = source
    while u != target:
        heads, ws = net.out_arcs(u)
        nxt = None
        for v, w in sorted(zip(heads.tolist(), ws.tolist(), strict=True)):
            if v in dist and (v == target or allowed(v)) and net.numbers.equal(
                    cost(u, v, w) + dist[v], dist[u]):
                nxt = v
                break
        assert nxt is not None  # a tight arc exists along a Dijkstra tree
        path.append(nxt)
        u = nxt
    return path


def _cut(walk: Sequence[int], goals: tuple[int, int]) -> tuple[int, ...]:
    for k, v in enumerate(walk):
        if v in goals:
            return tuple(walk[:k + 1])
    return tuple(walk)


def plan(inst: Instance, strategy: str, theta: int, *, game: _Game | None = None) -> MSPath:
    """Type ``theta``'s path (1: true goal ``g1``, 2: ``g2``) under ``strategy``.

    Examples
    --------
    >>> import networkx as nx
    >>> g = nx.Graph([("s", "a"), ("a", "b"), ("b", "g1"), ("a", "g2")])
    >>> p = plan(Instance(g, "s", ("g1", "g2"), ("1/2", "1/2")), "pi_d1", 2)
    >>> p.nodes, p.target
    (('s', 'a', 'b', 'g1'), 'g1')
    """
    if strategy not in STRATEGIES:
        raise ValueError(f"unknown strategy {strategy!r}; expected one of {STRATEGIES}")
    gm = game if game is not None else _Game.of(inst)
    net, s0 = gm.net, gm.s0
    real, bogus = (gm.goals[0], gm.goals[1]) if theta == 1 else (gm.goals[1], gm.goals[0])
    d_real, d_bogus = (gm.d_to[0], gm.d_to[1]) if theta == 1 else (gm.d_to[1], gm.d_to[0])
    fallback = False
    if strategy == "pi_d1":
        target = bogus
        walk = path_to_target(net, s0, bogus, d_bogus, net.numbers)
    else:
        target = last_deceptive_point(net, s0, real, bogus, d_real, d_bogus)
        if strategy == "pi_d2":
            first = path_to_target(net, s0, target, distances_to(net, target), net.numbers)
        elif strategy == "pi_d3":
            def cost(u: int, v: int, w: Stored) -> Stored:
                near_real = _lt(net, d_real[v], d_bogus[v])
                return w * _PENALTY if near_real else w
            leg = _leg(net, s0, target, cost, lambda v: True)
            assert leg is not None  # t is reachable from s0 (it lies on a g_b-g_r path)
            first = leg
        else:
            leg = _leg(net, s0, target, lambda u, v, w: w,
                       lambda v: v not in gm.goals and not truthful(net, v, s0, real, bogus,
                                                                     d_real, d_bogus))
            if leg is None:
                fallback = True
                leg = path_to_target(net, s0, target, distances_to(net, target), net.numbers)
            first = leg
        walk = first + path_to_target(net, target, real, d_real, net.numbers)[1:]
    cut = _cut(walk, gm.goals)
    labels = net.labels
    return MSPath(cut, tuple(labels[v] for v in cut), labels[target], fallback)


def plan_all(inst: Instance) -> dict[str, tuple[MSPath, MSPath]]:
    """Both types' paths under each of :data:`STRATEGIES` (primary type first).

    Examples
    --------
    >>> from solver.experiments.compare import paper10_instance
    >>> plans = plan_all(paper10_instance())
    >>> sorted(plans) == list(STRATEGIES)
    True
    """
    gm = _Game.of(inst)
    return {s: (plan(inst, s, 1, game=gm), plan(inst, s, 2, game=gm)) for s in STRATEGIES}
