"""The N-goal construction: normal-coalition Attacker and exact guarantee rule (proofs/NEXACT.md).

- **Sets.** The exact guarantee sets at ``H = inf`` as the fixpoint of the normal-restricted DP
  over a refined set ``A`` of facet normals, certified by the arc test at every walkable arc
  (:mod:`solver.coalitions.guarantee_sets`); with the 0/1 normals alone this is the coalition DP.
- **Root and Attacker.** The cover LP at the start gives the value, the guarantee vector ``h``
  (its lexicographically largest optimal dual in the priority order) and the starting pieces;
  the pieces walk down the DP's ranks (:mod:`solver.coalitions.normal_attacker`).
- **Defender.** The guarantee rule with ``h`` and the extra normals,
  ``{"rule": "guarantee", "h": [...], "normals": [...]}`` (``docs/formats.md`` §2b;
  :mod:`solver.coalitions.guarantee_rule` evaluates it).

Every type pays exactly ``h_θ`` on each of its walks and at least ``h_θ`` on any walk
(proofs/NEXACT.md NX.4, NX.5), so ``U = b·h = V_inf``. Where the budget of the refinement ends
first, :func:`coalition_equilibrium` raises :class:`FixpointNotReached` with an exact value bracket.
"""

from __future__ import annotations

import itertools
import time
from collections import deque
from collections.abc import Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import numpy as np

from solver.coalitions.arc_graph import ArcGraph
from solver.coalitions.budget import Budget, BudgetExceeded
from solver.coalitions.guarantee_rule import priority_order, rule_step
from solver.coalitions.guarantee_sets import (
    GuaranteeSets,
    Unreached,
    dominated_failures,
    guarantee_sets,
)
from solver.coalitions.normal_attacker import normal_attacker
from solver.coalitions.normal_cover import normal_cover_lp
from solver.coalitions.normal_dp import Fixpoint
from solver.coalitions.vertex_tables import Normal
from solver.errors import DPPError
from solver.game.instance import Instance
from solver.game.profile_writing import per_goal_profile
from solver.game.walks import StrategyWalk

__all__ = ["CertifiedSets", "CoalitionEquilibrium", "FixpointNotReached", "SetsNotCertified",
           "arc_graph", "certified_sets", "coalition_equilibrium"]

DEFAULT_BUDGET = Budget()
DOMINATED_ROUNDS = 2
"""Rounds that add the failing directions of the written rule's (dominated) sets as normals."""
"""The refinement's limits for ``dpp solve`` (stated in its one-line answer when reached)."""
METHOD = ("normal-coalition Attacker and exact guarantee rule (proofs/NEXACT.md); the "
          "normal-restricted DP at H = inf over refined facet normals, certified by the arc "
          "test; steps preferred to splits, first cheapest arc")


class FixpointNotReached(DPPError):
    """The certified fixpoint was not reached within the budget: an exact bracket instead.

    Attributes
    ----------
    lower, upper : Fraction
        ``lower <= V_inf <= upper``.
    lower_source, upper_source : str
        Where each bound comes from.
    reason : str
        Which limit was reached.
    """

    def __init__(self, reason: str, lower: Fraction, lower_source: str, upper: Fraction | None,
                 upper_source: str) -> None:
        self.reason = reason
        self.lower, self.lower_source = lower, lower_source
        self.upper, self.upper_source = upper, upper_source
        hi = "unknown" if upper is None else str(upper)
        super().__init__(f"no certified fixpoint ({reason}); the value lies in [{lower}, {hi}] "
                         f"(lower: {lower_source}; upper: {upper_source})")


@dataclass(frozen=True, eq=False)
class CoalitionEquilibrium:
    """The N-goal profile the construction gives, with its exact values.

    Attributes
    ----------
    instance : Instance
        The game (exact weights).
    h : tuple of Fraction
        The Defender's guarantee vector (the root cover LP's canonical optimal dual).
    normals : tuple of tuple of int
        The extra facet normals of the rule (not 0/1 vectors); empty when the 0/1 normals
        suffice.
    cover : dict
        Normal (tuple) -> starting piece mass ``c_a``.
    mixtures : tuple
        ``mixtures[θ]``: ``((walk as node indices, probability), …)``.
    costs : tuple of Fraction
        ``U^θ``: type θ's expected cost against the rule (``h_θ``: every walk of type θ costs
        exactly ``h_θ``, proofs/NEXACT.md NX.4).
    guarded, walked : tuple of Fraction
        Type θ's expected stage cost ``E[Σ_t w_t σ_t(θ)] = h_θ − E[d(end, g^θ)]`` and expected
        walk length ``E[Σ_t w_t]``.
    U, U_bar, VoI, dp_value : Fraction
        ``Σ b_θ U^θ``; ``Σ b_θ d(s0, g^θ)``; ``(Ū − U)/Ū``; the DP's value ``h·b``.
    layers, rounds : int
        The fixpoint's layer ``K`` (the longest walk has at most ``K`` steps) and the
        refinement rounds used.
    feasible : bool
        Kept for callers: always true (the arc test passed at every walkable arc).
    seconds : float
        Solve time.
    """

    instance: Instance = field(repr=False)
    h: tuple[Fraction, ...]
    normals: tuple[Normal, ...]
    cover: dict[Normal, Fraction]
    mixtures: tuple[tuple[tuple[tuple[int, ...], Fraction], ...], ...]
    costs: tuple[Fraction, ...]
    guarded: tuple[Fraction, ...]
    walked: tuple[Fraction, ...]
    U: Fraction
    U_bar: Fraction
    VoI: Fraction
    dp_value: Fraction
    layers: int
    rounds: int
    feasible: bool
    seconds: float
    fixpoint: Fixpoint | None = field(default=None, repr=False)
    node_index: np.ndarray | None = field(default=None, repr=False)

    def rule_values(self, v: int) -> list[Fraction | None]:
        """``m_a(v)`` of the written rule (the format's dominated reading, docs/formats.md §2b)
        for every normal (0/1 vectors in mask order, then the extra normals) at the game's node
        ``v``; None where no goal is reachable or ``v`` is off the walks."""
        assert self.fixpoint is not None and self.node_index is not None
        i = int(self.node_index[v])
        fix = self.fixpoint
        if i < 0 or not fix.finite[i]:
            return [None] * len(fix.system.normals)
        return [fix.value(j, i) for j in range(len(fix.system.normals))]

    def defender_along(self, walk: Sequence[int]) -> list[tuple[Fraction, ...]]:
        """The rule's ``σ`` after every step of a walk (game node indices), exactly.

        Examples
        --------
        The triangle's step ``s → g2`` (weight 2) makes progress 1 toward ``g1``: σ* (N = 2).

        >>> from solver.game.instance import triangle
        >>> game = triangle()
        >>> eq = coalition_equilibrium(game)
        >>> [[str(x) for x in s] for s in eq.defender_along([game.s0, game.targets[1]])]
        [['1/2', '1/2']]
        """
        assert self.fixpoint is not None
        normals = self.fixpoint.system.normals
        order = priority_order(self.instance.prior)
        r = self.h
        out = []
        for v, u in itertools.pairwise(walk):
            inst = self.instance
            w = Fraction(int(inst.network.arc_weight(v, u) or 0), inst.denominator)
            sigma, _ = rule_step(r, normals, self.rule_values(u), w, order)
            out.append(sigma)
            r = tuple(x - w * y for x, y in zip(r, sigma, strict=True))
        return out

    @property
    def strategies(self) -> tuple[tuple[StrategyWalk, ...], ...]:
        """``strategies[θ]``: the mixed strategy of goal index θ, as walks with probabilities."""
        net = self.instance.network
        return tuple(tuple(StrategyWalk.along(net, walk, p) for walk, p in mix)
                     for mix in self.mixtures)

    def to_json(self) -> dict[str, Any]:
        """The ``dpp-ngoal-profile/1`` document with the guarantee rule (``docs/formats.md``
        §2b), written by :func:`~solver.game.profile_writing.per_goal_profile`.

        Examples
        --------
        >>> from solver.game.instance import triangle
        >>> out = coalition_equilibrium(triangle()).to_json()   # two goals: σ*'s value
        >>> out["defender"], out["value"]["U"]
        ({'rule': 'guarantee', 'h': ['3', '1']}, '12/5')
        """
        defender: dict[str, Any] = {"rule": "guarantee", "h": [str(x) for x in self.h]}
        if self.normals:  # only when there are extra ones
            defender["normals"] = [list(a) for a in self.normals]
        return per_goal_profile(
            self.instance, self.strategies, defender=defender,
            values={"U": str(self.U), "U_types": [str(x) for x in self.costs],
                    "U_bar": str(self.U_bar), "VoI": str(self.VoI)},
            method=METHOD,
            cover={",".join(map(str, a)): str(c)
                   for a, c in sorted(self.cover.items(), reverse=True)},
            layers=self.layers, refinement_rounds=self.rounds)



def arc_graph(game: Instance, *, whole: bool = False) -> tuple[ArcGraph, np.ndarray]:
    """The walkable part of ``game`` as arrays, and the game's node index of each node.

    The nodes are those on some walk: reachable from the start through non-goal nodes, and
    from which a goal is reachable, and every goal (with ``whole``: every node from which a
    goal is reachable, as the trusted kernel checks the DP). Arcs out of goals are dropped
    (walks end there).

    Examples
    --------
    >>> from solver.game.instance_reading import instance_from_json
    >>> doc = {"graph": {"nodes": [{"id": x} for x in "sabz"],
    ...        "edges": [{"source": "s", "target": "a"}, {"source": "s", "target": "b"},
    ...                  {"source": "a", "target": "z"}]},
    ...        "start": "s", "goals": ["a", "b"], "prior": ["1/2", "1/2"]}
    >>> graph, labels = arc_graph(instance_from_json(doc))
    >>> graph.n_nodes, [str(instance_from_json(doc).label(int(i))) for i in labels]
    (3, ['s', 'a', 'b'])
    """
    net = game.network
    n = net.n_nodes
    goal = np.zeros(n, dtype=bool)
    goal[list(game.targets)] = True
    seen = np.full(n, whole, dtype=bool)
    seen[game.s0] = True
    queue = deque([game.s0])
    while queue:  # forward: walks continue only from non-goal nodes
        v = queue.popleft()
        if goal[v]:
            continue
        for u in net.indices[net.indptr[v]:net.indptr[v + 1]].tolist():
            if not seen[u]:
                seen[u] = True
                queue.append(u)
    reach = np.zeros(n, dtype=bool)
    for d in game.dist_to:
        reach |= np.isfinite(d.astype(np.float64))
    keep = np.flatnonzero((seen & reach) | goal)  # every goal: its terminal costs
    new = np.full(n, -1, dtype=np.int64)
    new[keep] = np.arange(keep.size)
    indptr = [0]
    heads: list[int] = []
    weights: list[int] = []
    for v in keep.tolist():
        if not goal[v]:
            lo, hi = int(net.indptr[v]), int(net.indptr[v + 1])
            for u, w in zip(net.indices[lo:hi].tolist(), net.weights[lo:hi].tolist(),
                            strict=True):
                if new[u] >= 0:
                    heads.append(int(new[u]))
                    weights.append(int(w))
        indptr.append(len(heads))
    terminal = np.array([[int(game.dist_to[t][g]) for t in range(game.n_goals)]
                         for g in game.targets], dtype=np.int64)
    graph = ArcGraph(indptr=np.asarray(indptr, dtype=np.int64),
                     heads=np.asarray(heads, dtype=np.int64),
                     weights=np.asarray(weights, dtype=np.int64),
                     denominator=game.denominator,
                     goals=tuple(int(new[g]) for g in game.targets), terminal=terminal,
                     start=int(new[game.s0]))
    return graph, keep


def simple_lower_bound(game: Instance) -> tuple[Fraction, str]:
    """NG.9: the better of a Defender always guarding one goal and the uniform Defender.

    Examples
    --------
    >>> from solver.game.instance import triangle
    >>> simple_lower_bound(triangle())
    (Fraction(21, 10), 'a Defender always guarding goal 1 (proofs/NGOAL.md NG.9)')
    """
    d = [game.distance(t, game.s0) for t in range(game.n_goals)]
    guard = [b * x for b, x in zip(game.prior, d, strict=True)]
    best = max(range(game.n_goals), key=lambda t: guard[t])
    uniform = sum(guard, Fraction(0)) / game.n_goals
    if uniform > guard[best]:
        return uniform, "the uniform Defender (proofs/NGOAL.md NG.9)"
    return guard[best], f"a Defender always guarding goal {best + 1} (proofs/NGOAL.md NG.9)"


def _fixpoint_value(fix: Fixpoint, start: int, prior: tuple[Fraction, ...]) -> Fraction:
    costs = [fix.value(j, start) for j in range(len(fix.system.normals))]
    return normal_cover_lp(fix.system.normals, costs, list(prior)).value


@dataclass(frozen=True, eq=False)
class CertifiedSets:
    """The exact guarantee sets of a game at ``H = inf``, as the construction uses them.

    Attributes
    ----------
    graph : ArcGraph
        The walkable part of the game (:func:`arc_graph`).
    labels : numpy.ndarray
        The game's node index of each node of ``graph``.
    found : GuaranteeSets
        The certified fixpoint ``m*`` with its normals and ranks (proofs/NEXACT.md).
    written : Fixpoint
        The written rule's DP (the format's dominated reading, ``docs/formats.md`` §2b),
        which passes the arc test as well.
    """

    graph: ArcGraph
    labels: np.ndarray
    found: GuaranteeSets
    written: Fixpoint


class SetsNotCertified(Exception):
    """:func:`certified_sets` stopped before a certified fixpoint.

    Attributes
    ----------
    reason : str
        Which limit was reached.
    fixpoint : Fixpoint or None
        The DP at hand: the certified fixpoint when ``certified`` (the sets are exact, only the
        written rule failed), else the best outer DP found (an upper bound), or None.
    certified : bool
        Whether ``fixpoint`` is the certified one.
    start : int
        The start's index in ``fixpoint``.
    """

    def __init__(self, reason: str, fixpoint: Fixpoint | None, certified: bool, start: int
                 ) -> None:
        super().__init__(reason)
        self.reason, self.fixpoint, self.certified, self.start = (reason, fixpoint, certified,
                                                                  start)


def certified_sets(game: Instance, budget: Budget = DEFAULT_BUDGET) -> CertifiedSets:
    """The exact guarantee sets of ``game`` (any prior: the sets do not depend on it).

    Raises
    ------
    SetsNotCertified
        When the budget ends before a certified fixpoint whose written rule passes.

    Examples
    --------
    >>> from solver.game.instance import triangle
    >>> cs = certified_sets(triangle())
    >>> [str(cs.found.fixpoint.value(j, cs.graph.start)) for j in range(3)]
    ['3', '2', '4']
    """
    graph, labels = arc_graph(game)
    found = guarantee_sets(graph, budget)
    written = None
    for _ in range(DOMINATED_ROUNDS + 1):  # the written rule, under the format's reading
        if not isinstance(found, GuaranteeSets):
            break
        if not found.extra_normals:  # a cover of 1_S uses subsets of S only: the same DP
            written = found.fixpoint
            break
        max_layers = budget.layers if budget.layers is not None else 20 * graph.n_nodes + 200
        try:
            written, bad = dominated_failures(graph, found.normals, max_layers)
        except (BudgetExceeded, ValueError) as exc:
            found = Unreached(f"the written rule's sets: {exc}", found.fixpoint)
            break
        if not bad:
            break
        extra = [a for a in bad if a not in found.normals]
        if not extra or _ + 1 > DOMINATED_ROUNDS:
            raise SetsNotCertified(
                "the rule with these normals fails the arc test under the format's dominated "
                f"reading (docs/formats.md §2b) in direction {bad[0]}", found.fixpoint, True,
                graph.start)
        found = guarantee_sets(graph, budget, initial=[*found.extra_normals, *extra])
    if not isinstance(found, GuaranteeSets):
        raise SetsNotCertified(found.reason + f"; budget: {budget.describe()}", found.upper,
                               False, graph.start)
    assert written is not None
    return CertifiedSets(graph, labels, found, written)


def coalition_equilibrium(game: Instance, budget: Budget = DEFAULT_BUDGET
                          ) -> CoalitionEquilibrium:
    """The exact N-goal construction on ``game``: the entry :func:`solver.solve` calls for
    ``N >= 3`` (for two goals it gives σ*'s values).

    Raises
    ------
    FixpointNotReached
        When the budget ends before a certified fixpoint (with the value bracket).

    Examples
    --------
    >>> from solver.game.instance_reading import instance_from_json
    >>> doc = {"graph": {"nodes": [{"id": x} for x in "smabc"],
    ...        "edges": [{"source": "s", "target": "m"}, {"source": "m", "target": "a"},
    ...                  {"source": "m", "target": "b"}, {"source": "m", "target": "c"},
    ...                  {"source": "s", "target": "a", "weight": 2}]},
    ...        "start": "s", "goals": ["a", "b", "c"], "prior": ["1/2", "1/3", "1/6"]}
    >>> eq = coalition_equilibrium(instance_from_json(doc))
    >>> str(eq.U), str(eq.dp_value), eq.normals
    ('3/2', '3/2', ())
    """
    t0 = time.perf_counter()
    try:
        cs = certified_sets(game, budget)
    except SetsNotCertified as exc:
        if exc.certified:
            assert exc.fixpoint is not None
            v = _fixpoint_value(exc.fixpoint, exc.start, game.prior)
            src = "the certified fixpoint (proofs/NEXACT.md NX.5)"
            raise FixpointNotReached(exc.reason, v, src, v, src) from None
        lower, lo_src = simple_lower_bound(game)
        upper = None if exc.fixpoint is None else _fixpoint_value(exc.fixpoint, exc.start,
                                                                  game.prior)
        up_src = ("none (no fixpoint of the DP)" if exc.fixpoint is None else
                  f"the normal-restricted DP over {len(exc.fixpoint.system.normals)} normals "
                  "at its fixpoint (proofs/NGOAL.md NG.7)")
        raise FixpointNotReached(exc.reason, lower, lo_src, upper, up_src) from None
    graph, labels, found, written = cs.graph, cs.labels, cs.found, cs.written
    fix = found.fixpoint
    assert written is not None
    n = game.n_goals
    order = priority_order(game.prior)
    try:
        plan = normal_attacker(graph, fix, game.prior, order)
    except ValueError as exc:  # the plan's size limit
        v = _fixpoint_value(fix, graph.start, game.prior)
        src = "the certified fixpoint (proofs/NEXACT.md NX.5)"
        raise FixpointNotReached(str(exc), v, src, v, src) from None
    normals = fix.system.normals
    mix = plan.mixtures(normals, game.prior)
    h0 = plan.h
    type_cost = list(h0)  # NX.4: every walk of type θ costs exactly h_θ
    guarded = [Fraction(0)] * n
    walked = [Fraction(0)] * n
    den = game.denominator
    for theta in range(n):
        for walk, prob in mix[theta].items():
            length = Fraction(0)
            for k in range(1, len(walk)):
                length += Fraction(int(game.network.arc_weight(int(labels[walk[k - 1]]),
                                                                int(labels[walk[k]])) or 0),
                                   den)
            end = int(labels[walk[-1]])
            guarded[theta] += prob * (h0[theta] - game.distance(theta, end))
            walked[theta] += prob * length
    u_val = sum((b * c for b, c in zip(game.prior, type_cost, strict=True)), Fraction(0))
    u_bar = sum((game.prior[t] * game.distance(t, game.s0) for t in range(n)), Fraction(0))
    mixtures = tuple(tuple(sorted(((tuple(int(labels[v]) for v in w), p)
                                   for w, p in m.items()), key=lambda kv: (-kv[1], kv[0])))
                     for m in mix)
    return CoalitionEquilibrium(instance=game, h=h0, normals=found.extra_normals,
                        cover={normals[j]: c for j, c in plan.root_cover.items()},
                        mixtures=mixtures, costs=tuple(type_cost), guarded=tuple(guarded),
                        walked=tuple(walked), U=u_val, U_bar=u_bar,
                        VoI=(u_bar - u_val) / u_bar if u_bar else Fraction(0),
                        dp_value=plan.value, layers=fix.layers, rounds=found.rounds,
                        feasible=True, seconds=time.perf_counter() - t0, fixpoint=written,
                        node_index=_inverse(labels, game.network.n_nodes))


def _inverse(labels: np.ndarray, n: int) -> np.ndarray:
    out = np.full(n, -1, dtype=np.int64)
    out[labels] = np.arange(labels.size)
    return out
