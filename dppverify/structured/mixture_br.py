"""Two goals: every type's exact best response over all walks to the per-prefix mixture of the
two progress rules (:class:`~dppverify.game.mixture_rule.ProgressMixture`; proofs/SELECT.md
SELECT.7).

Best response of type ``θ`` over all walks, exactly:

1. *Lower bound* (SELECT.7(a)). A walk's cost is ``α`` times its cost against ``σ_g`` plus
   ``1 − α`` times its cost against ``σ_{g'}``, so every walk costs at least
   ``α·min_g + (1 − α)·min_{g'}``, the minima over all walks against each progress rule
   (proofs/WALKBR.md; :func:`~dppverify.twogoal.progress_br.walk_minima`). A profile walk at that
   bound is a best response: decided without search.
2. *Exact search* (SELECT.7(b)). Otherwise the cost of a continuation depends only on the node
   and the two running minima, which take finitely many values: an exact Dijkstra on the
   states ``(v, c_g, c_{g'})`` (every step cost is ``>= 0``) gives the minimum over all walks and
   a walk attaining it, within a budget of states.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from fractions import Fraction

from dppverify.exact import INF, Number, normalize
from dppverify.game.distances import state_dijkstra_via
from dppverify.game.instance import Instance
from dppverify.game.mixture_rule import ProgressMixture
from dppverify.twogoal.progress_br import walk_minima

MAX_STATES = 400_000
"""The exact search's budget of states per type (an undecided check beyond it)."""

State = tuple[int, Number, Number]


@dataclass(frozen=True)
class MixtureResponse:
    """Type ``theta``'s best response to a :class:`ProgressMixture` over all walks.

    Attributes
    ----------
    theta : int
        The goal index.
    value : Number or None
        The minimum over all walks (None: undecided within the budget).
    walk : tuple of int or None
        A walk attaining it (None when decided by the lower bound alone).
    lower : Number
        The lower bound ``α·min_g + (1 − α)·min_{g'}``.
    states : int
        States the exact search settled (0 when the bound decided).
    how : str
        How it was decided.
    """

    theta: int
    value: Number | None
    walk: tuple[int, ...] | None
    lower: Number
    states: int
    how: str


class _Budget(Exception):
    pass


def mixture_response(instance: Instance, mix: ProgressMixture, theta: int, cost: Number,
                     max_states: int = MAX_STATES) -> MixtureResponse:
    """Type ``theta``'s exact minimum over all walks against ``mix``; ``cost`` is its profile
    cost (the lower bound decides when ``cost`` attains it).

    Examples
    --------
    The triangle, α = 1/2: type g2 pays 3/4·2 = 3/2 on ``s -> g2`` and 1/2·3 + 2 = 7/2 via
    ``g1``; the bound 1/2·2 + 1/2·1 = 3/2 (``d(s, g2)`` against its own rule, ``M − d(s, g1)``
    against the other) is attained:

    >>> from dppverify.game.examples import triangle
    >>> r = mixture_response(triangle(), ProgressMixture(0, Fraction(1, 2)), 1, Fraction(3, 2))
    >>> r.value, r.lower, r.how
    (Fraction(3, 2), Fraction(3, 2), "the mixture of the two progress rules' minima (SELECT.7(a))")
    >>> mixture_response(triangle(), ProgressMixture(0, Fraction(1, 2)), 1, 2).walk
    (0, 2)
    """
    g, o = instance.goals[mix.goal], instance.goals[1 - mix.goal]
    own = theta == mix.goal
    toward_g, toward_o = walk_minima(instance, g), walk_minima(instance, o)
    lower = normalize(mix.alpha * Fraction(toward_g.same if own else toward_g.other)
                      + (1 - mix.alpha) * Fraction(toward_o.other if own else toward_o.same))
    if cost == lower:
        return MixtureResponse(theta, lower, None, lower, 0,
                               "the mixture of the two progress rules' minima (SELECT.7(a))")
    try:
        value, walk, states = _search(instance, mix, theta, max_states)
    except _Budget:
        return MixtureResponse(theta, None, None, lower, max_states,
                               f"the exact search exceeded {max_states:,} states")
    return MixtureResponse(theta, value, walk, lower, states,
                           "an exact search over (node, running minima) (SELECT.7(b))")


def _search(instance: Instance, mix: ProgressMixture, theta: int, max_states: int
            ) -> tuple[Number, tuple[int, ...], int]:
    """The exact Dijkstra on ``(v, c_g, c_o)`` with the terminal costs at the goals."""
    goals = set(instance.goals)
    start = (instance.start, *mix.start(instance, instance.start))
    expanded = [0]
    sink = (-1, 0, 0)

    def arcs(x: State) -> Iterable[tuple[State, Number]]:
        v, cg, co = x
        if v < 0:
            return []
        if v in goals:
            return [(sink, instance.dist_to[theta][v])]
        expanded[0] += 1
        if expanded[0] > max_states:
            raise _Budget
        out = []
        for u, w in instance.succ[v]:
            if instance.hops[u] < 0:
                continue  # no goal from u: no strategy enters it
            dist, new = mix.step(instance, (cg, co), u, w)
            out.append(((u, new[0], new[1]), normalize(Fraction(w) * dist[theta])))
        return out

    dist, via = state_dijkstra_via([(start, 0)], arcs)
    value = dist.get(sink, INF)
    assert value != INF  # every goal is reachable from the start
    walk = []
    x = via[sink]
    while True:
        walk.append(x[0])
        if x == start:
            break
        x = via[x]
    return value, tuple(reversed(walk)), expanded[0]
