"""The two-goal Defender that mixes the two progress rules per prefix (``docs/formats.md``
§2d; proofs/SELECT.md SELECT.7, SELECT.8).

``{"rule": "progress-mixture", "goal": g, "alpha": α}``: after a walk prefix the Defender puts
``α·σ_g + (1 − α)·σ_{g'}`` on the goals, ``σ_g`` the progress rule toward ``g`` (eq. (7) with
``g`` as primary: ``(c_{t-1} − c_t)/w`` on ``g``, the rest on the other goal ``g'``, ``c_t`` the
running minimum of ``d(s_t, g)``). ``{"rule": "progress", "goal": g}`` of a goal-selection
profile is ``α = 1``. Its best responses over all walks are
:mod:`dppverify.structured.mixture_br`'s.
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from types import MappingProxyType

from dppverify.exact import Number
from dppverify.game.instance_type import Instance


@dataclass(frozen=True)
class ProgressMixture:
    """The two progress rules mixed per prefix: ``alpha`` on the rule toward goal index ``goal``.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> mix = ProgressMixture(0, Fraction(1, 2))
    >>> mix.along(triangle(), [0, 2])   # s -> g2: progress 1 of 2 toward g1, 2 of 2 toward g2
    [(Fraction(1, 4), Fraction(3, 4))]
    """

    goal: int
    alpha: Fraction
    kind = "progress-mixture"
    table = False
    defined_everywhere = True
    progress_goal = None

    @property
    def entries(self) -> Mapping[tuple[int, ...], tuple[Fraction, ...]]:
        """No walk is listed: the rule is defined everywhere."""
        return MappingProxyType({})

    def listed_along(self, walk: Sequence[int]) -> Mapping[int, tuple[Fraction, ...]]:
        """No prefix is listed."""
        return MappingProxyType({})

    def step(self, instance: Instance, c: tuple[Number, Number], u: int, w: Number
             ) -> tuple[tuple[Fraction, Fraction], tuple[Number, Number]]:
        """The distribution over goal indices (0, 1) on a step into ``u`` of weight ``w``
        from running minima ``c`` (toward ``goal``, then toward the other), and the new minima."""
        g, o = self.goal, 1 - self.goal
        new = (min(c[0], instance.dist_to[g][u]), min(c[1], instance.dist_to[o][u]))
        to_g = self.alpha * Fraction(c[0] - new[0]) / Fraction(w)
        to_g += (1 - self.alpha) * (1 - Fraction(c[1] - new[1]) / Fraction(w))
        dist = [Fraction(0), Fraction(0)]
        dist[g], dist[o] = to_g, 1 - to_g
        return (dist[0], dist[1]), new

    def start(self, instance: Instance, v: int) -> tuple[Number, Number]:
        """The running minima at the start ``v``."""
        return (instance.dist_to[self.goal][v], instance.dist_to[1 - self.goal][v])

    def along(self, instance: Instance, walk: Sequence[int]
              ) -> list[tuple[Fraction, Fraction]]:
        """The Defender's distribution after every step of ``walk``."""
        c = self.start(instance, walk[0])
        out = []
        for v, u in itertools.pairwise(walk):
            w = instance.weight(v, u)
            assert w is not None  # a validated walk
            dist, c = self.step(instance, c, u, w)
            out.append(dist)
        return out

    def describe(self, instance: Instance) -> str:
        """The rule in words (goals by node id)."""
        g, o = (instance.nodes[instance.goals[t]] for t in (self.goal, 1 - self.goal))
        return f"{self.alpha}·progress({g!r}) + {1 - self.alpha}·progress({o!r}) per prefix"
