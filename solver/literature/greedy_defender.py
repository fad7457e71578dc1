"""The alternative Defender σ' of Sec. VII-B: greedy on Dragan's belief (eq. (17)).

After the Attacker's step to ``s_t``, σ' allocates to ``g1`` if ``b^1_t >= 1/2`` and to
``g2`` otherwise (Lemma 3: greedy on the belief; at exactly 1/2 it picks ``g1``, as the
paper says). Every allocation is 0 or 1 and is decided exactly
(:meth:`solver.literature.dragan_belief.DraganObserver.favours_g1`), so evaluations against σ'
are exact ``Fraction`` values.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from fractions import Fraction

from solver.literature.dragan_belief import DraganObserver

_ONE, _ZERO = Fraction(1), Fraction(0)


@dataclass(frozen=True, eq=False)
class DraganDefender:
    """σ': ``σ'(g1 | ξ[0:t]) = 1`` iff Dragan's ``b^1_t >= 1/2``.

    Examples
    --------
    >>> import networkx as nx
    >>> from solver.graph.distances import distances_to
    >>> from solver.graph.network import Network
    >>> net = Network.from_networkx(nx.Graph([("s", "a"), ("a", "g1"), ("a", "g2")]))
    >>> obs = DraganObserver(net, 0, 2, 3, distances_to(net, 2), distances_to(net, 3),
    ...                      Fraction(3, 5), Fraction(2, 5))
    >>> [str(x) for x in DraganDefender(obs).schedule([0, 1, 3])]
    ['1', '0']
    """

    observer: DraganObserver
    _cache: dict[int, bool] = field(default_factory=dict, repr=False)

    def allocates_g1(self, v: int) -> bool:
        """Whether σ' allocates to ``g1`` right after the Attacker arrives at ``v``."""
        hit = self._cache.get(v)
        if hit is None:
            hit = self._cache[v] = self.observer.favours_g1(v)
        return hit

    def schedule(self, walk: Sequence[int]) -> list[Fraction]:
        """σ'(g1) after each step ``t = 1..T`` of ``walk`` (node indices from ``s0``)."""
        return [_ONE if self.allocates_g1(int(v)) else _ZERO for v in walk[1:]]
