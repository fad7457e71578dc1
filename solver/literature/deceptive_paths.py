"""Exaggeration and ambiguity paths of Dragan et al. (paper eqs. (18a)/(18b)), exact DP.

For type θ (true goal ``g^θ``, fake goal ``g^{-θ}``) over the paths ``Ξ^θ(s0)`` from ``s0``
to ``g^θ``::

    ξ^{θ,ex} ∈ argmin Σ_{t=0..T} P(g^θ | ξ[0:t])                          (18a)
    ξ^{θ,am} ∈ argmin Σ_{t=0..T} |P(g^θ | ξ[0:t]) − P(g^{−θ} | ξ[0:t])|   (18b)

with ``P`` Dragan's belief (eq. (17), path-length cost; :mod:`solver.literature.dragan_belief`).

The DP and its horizon
----------------------
A DP over (node, elapsed cost) is not needed: with path length as the cost, ``exp(-C)``
cancels in eq. (17), so the belief — and each summand — is a function of the current node
``s_t`` alone. The objective is then a sum of node terms ``τ(s_t) >= 0`` (``> 0`` for 18a):
a shortest-path problem with node costs, solved by Dijkstra backwards from ``g^θ``
(``D(v) = τ(v) + min_{v→u} D(u)``, ``D(g^θ) = τ(g^θ)``), a DP over the node alone.

- **Walks are allowed, there is no horizon**: the minimum is over all walks from ``s0`` that
  reach ``g^θ`` without visiting ``g^{−θ}`` (the game would end there; ``Ξ^θ`` as in the
  paper's Definition 4). Removing a cycle from a walk removes non-negative terms, so the
  minimum over walks equals the minimum over simple paths and is attained by one; the
  returned path is simple.
- **Numbers**: each distinct term is computed by mpmath at 60 digits
  (``solver.literature.dragan_belief.HI``) and rounded to a fixed point integer with
  :data:`SCALE_BITS` fractional bits; sums are then exact integers.
  Paths whose objectives differ by at most :data:`TIE_UNITS` units (``2^-136 ≈ 1.1e-41``)
  are treated as tied. Genuinely tied paths (same multiset of ``δ`` values, common on grids)
  get bit-identical sums. Rounding moves a path sum by at most ``T/2`` units, below the
  tolerance for any path of fewer than ``2^25`` steps.
- **Tie-break** (deterministic): among (near-)optimal paths, the fewest steps; then at each
  step the lowest node index (instance node order; row-major on grids).
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass
from fractions import Fraction
from functools import cache
from typing import Literal

import mpmath
import numpy as np

from solver.graph.distances import costs_to
from solver.graph.network import Network
from solver.literature.dragan_belief import HI, MP, DraganObserver, belief_hi

Kind = Literal["exaggeration", "ambiguity"]
KINDS: tuple[Kind, Kind] = ("exaggeration", "ambiguity")

SCALE_BITS = 160
"""Fixed-point resolution of the objective: one unit is ``2**-160``."""

TIE_UNITS = 2**24
"""Objectives within this many units (``2**-136``) count as tied."""


@dataclass(frozen=True)
class DeceptivePath:
    """An exaggeration or ambiguity path of one type.

    Attributes
    ----------
    walk : tuple of int
        Node indices ``s0 .. g^θ``.
    theta : int
        1 (primary) or 2 (secondary): whose true goal the path reaches.
    kind : str
        ``"exaggeration"`` or ``"ambiguity"``.
    objective : mpmath.mpf
        The value of eq. (18a) or (18b) along ``walk`` (fixed point, see the module notes).
    """

    walk: tuple[int, ...]
    theta: int
    kind: Kind
    objective: mpmath.mpf


def node_terms(observer: DraganObserver, theta: int, kind: Kind) -> list[int]:
    """The summand of eq. (18a)/(18b) at every node, in fixed point (``2**-SCALE_BITS``).

    Examples
    --------
    >>> import networkx as nx
    >>> from solver.graph.distances import distances_to
    >>> from solver.graph.network import Network
    >>> net = Network.from_networkx(nx.Graph([("s", "g1"), ("s", "g2")]))
    >>> obs = DraganObserver(net, 0, 1, 2, distances_to(net, 1), distances_to(net, 2),
    ...                      Fraction(1, 2), Fraction(1, 2))
    >>> [round(t / 2**SCALE_BITS, 6) for t in node_terms(obs, 1, "exaggeration")]
    [0.5, 0.880797, 0.119203]
    """
    if theta not in (1, 2):
        raise ValueError(f"theta must be 1 or 2, got {theta}")
    if kind not in KINDS:
        raise ValueError(f"kind must be one of {KINDS}, got {kind!r}")
    out = []
    for v in range(observer.network.n_nodes):
        delta = observer.delta(v)
        if delta is None:
            out.append(_scaled(observer.belief(v), theta, kind))
        else:
            out.append(_term(observer.b1, observer.b2, delta, theta, kind))
    return out


@cache
def _term(b1: Fraction, b2: Fraction, delta: Fraction, theta: int, kind: Kind) -> int:
    return _scaled(belief_hi(b1, b2, delta), theta, kind)


def _scaled(belief_g1: mpmath.mpf, theta: int, kind: Kind) -> int:
    b = HI.mpf(belief_g1)
    value = abs(2 * b - 1) if kind == "ambiguity" else (b if theta == 1 else 1 - b)
    return int(HI.nint(HI.ldexp(value, SCALE_BITS)))


def objective(observer: DraganObserver, walk: list[int] | tuple[int, ...], theta: int,
              kind: Kind) -> mpmath.mpf:
    """Eq. (18a)/(18b) summed along ``walk`` from its node terms (fixed point).

    Parameters
    ----------
    observer : DraganObserver
        The observer's beliefs (eq. (17)).
    walk : sequence of int
        Node indices.
    theta : int
        1 (primary) or 2 (secondary).
    kind : {"exaggeration", "ambiguity"}
        Eq. (18a) (the belief in the true goal) or eq. (18b) (``|2 b^1_t − 1|``).

    Returns
    -------
    mpmath.mpf
        The sum, accurate to ``2**-SCALE_BITS`` per node.

    Examples
    --------
    A path s - a - g1 and a - g2 (unit weights), prior (3/5, 2/5): the primary's
    exaggeration objective is the sum of the beliefs in g1 along its walk.

    >>> import networkx as nx
    >>> from solver.graph.distances import distances_to
    >>> net = Network.from_networkx(nx.Graph([("s", "a"), ("a", "g1"), ("a", "g2")]))
    >>> obs = DraganObserver(net, 0, 2, 3, distances_to(net, 2), distances_to(net, 3),
    ...                      Fraction(3, 5), Fraction(2, 5))
    >>> walk = [0, 1, 2]                                   # s, a, g1
    >>> ex = objective(obs, walk, 1, "exaggeration")
    >>> mpmath.nstr(ex, 6), abs(ex - sum(obs.beliefs(walk))) < mpmath.mpf(2) ** -100
    ('2.11724', True)
    >>> mpmath.nstr(objective(obs, walk, 1, "ambiguity"), 6)  # |2b - 1|: 0.2 + 0.2 + 0.83
    '1.23449'
    """
    terms = node_terms(observer, theta, kind)
    return _unscale(sum(terms[v] for v in walk))


def _unscale(units: int) -> mpmath.mpf:
    return MP.ldexp(MP.mpf(units), -SCALE_BITS)


def deceptive_path(observer: DraganObserver, theta: int, kind: Kind) -> DeceptivePath:
    """ξ^{θ,ex} or ξ^{θ,am}: the minimiser of eq. (18a)/(18b) (see the module notes).

    Raises
    ------
    ValueError
        If ``g^θ`` cannot be reached from ``s0`` without passing ``g^{−θ}``.

    Examples
    --------
    A 3×3 grid, start bottom-left, g1 top-right, g2 top-left, prior (3/5, 2/5). The primary's
    exaggeration path heads to g2's side first; its ambiguity path keeps the belief near 1/2.

    >>> from solver import Instance
    >>> from solver.graph.distances import distances_to
    >>> inst = Instance.from_grid(np.zeros((3, 3), bool), (2, 0), ((0, 2), (0, 0)),
    ...                           ("3/5", "2/5"))
    >>> net = inst.network
    >>> obs = DraganObserver(net, 6, 2, 0, distances_to(net, 2), distances_to(net, 0),
    ...                      inst.b1, inst.b2)
    >>> [net.labels[v] for v in deceptive_path(obs, 1, "exaggeration").walk]
    [(2, 0), (1, 0), (1, 1), (0, 1), (0, 2)]
    """
    net = observer.network
    goal, fake = (observer.g1, observer.g2) if theta == 1 else (observer.g2, observer.g1)
    s0 = observer.start
    terms = node_terms(observer, theta, kind)
    if s0 == goal:
        return DeceptivePath((s0,), theta, kind, _unscale(terms[s0]))
    found = costs_to(net, goal, lambda u, v, w: None if u == fake else terms[u],
                     start=terms[goal])
    inf = -1  # "unreached" marker (values are non-negative)
    dist = [found.get(v, inf) for v in range(net.n_nodes)]
    if dist[s0] == inf:
        raise ValueError(f"goal {net.labels[goal]!r} is unreachable from "
                         f"{net.labels[s0]!r} without passing {net.labels[fake]!r}")
    path = _trace(net, s0, goal, fake, dist, terms)
    return DeceptivePath(path, theta, kind, _unscale(dist[s0]))


def _trace(net: Network, s0: int, goal: int, fake: int, dist: list[int],
           terms: list[int]) -> tuple[int, ...]:
    """Follow tight arcs (``|τ(u) + D(v) − D(u)| <= TIE_UNITS``) from ``s0``: fewest steps
    first (BFS depth in the tight subgraph), then the lowest node index."""
    rev = net.reverse

    def tight(u: int, v: int) -> bool:
        return (u != fake and v != fake and dist[u] >= 0 and dist[v] >= 0
                and abs(terms[u] + dist[v] - dist[u]) <= TIE_UNITS)

    hops = np.full(net.n_nodes, -1, dtype=np.int64)
    hops[goal] = 0
    queue = deque([goal])
    while queue:  # BFS backwards from the goal over tight arcs
        v = queue.popleft()
        if v == s0:
            break
        for u in rev.out_arcs(v)[0].tolist():
            if hops[u] < 0 and u != goal and tight(u, v):
                hops[u] = hops[v] + 1
                queue.append(u)
    path = [s0]
    u = s0
    while u != goal:
        heads = net.out_arcs(u)[0].tolist()
        u = next(v for v in heads if hops[v] == hops[u] - 1 and tight(u, v))
        path.append(u)
    return tuple(path)
