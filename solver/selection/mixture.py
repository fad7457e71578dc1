"""Two goals: the goal-selection Defender as a per-prefix mixture of the two progress rules
(proofs/SELECT.md SELECT.5).

The progress rule toward goal ``g`` (the paper's σ* with ``g`` as primary, eq. (7)) puts
``(c_{t-1} − c_t)/w`` of each step on ``g`` and the rest on the other goal, ``c_t`` the running
minimum of ``d(s_t, g)``; against it type ``g`` pays ``d(s0, g)`` on every walk ending at ``g``
and the other type at least ``M − d(s0, g)`` (``M = min_v d(s0,v) + d(v,g1) + d(v,g2)``). The
mixture ``α·σ_1 + (1 − α)·σ_2`` (σ_i the progress rule toward ``goals[i]``) guarantees, walk by
walk, ``c(α) = α·(d1, M − d1) + (1 − α)·(M − d2, d2)``; ``α`` is chosen to put
``c(α) − r`` on the diagonal where the choice ``q*`` puts weight::

    α = (2·d2 − M + r1 − r2) / (2·(d1 + d2 − M)), clipped to [0, 1]

(``α = 1`` or ``0`` by ``q*`` when ``d1 + d2 = M``: the value is then linear in ``q``).
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from solver.formats.nodes import node_to_json
from solver.game.instance import Instance


@dataclass(frozen=True)
class TwoGoalMixture:
    """The two progress rules' per-prefix mixture with weight ``alpha`` on ``goals[0]``'s.

    Attributes
    ----------
    alpha : Fraction
        The weight of the progress rule toward ``goals[0]``.
    d1, d2, M : Fraction
        ``d(s0, goals[0])``, ``d(s0, goals[1])`` and ``M``.
    guaranteed : tuple of Fraction
        ``c(α)``: each type's guaranteed cost (its exact best-response cost).
    """

    alpha: Fraction
    d1: Fraction
    d2: Fraction
    M: Fraction
    guaranteed: tuple[Fraction, Fraction]

    method = "the per-prefix mixture of the two progress rules (proofs/SELECT.md SELECT.5)"

    def rule_json(self, game: Instance) -> dict[str, Any]:
        """``{"rule": "progress-mixture", "goal": goals[0], "alpha": α}``."""
        return {"rule": "progress-mixture", "goal": node_to_json(game.goals[0]),
                "alpha": str(self.alpha)}

    def describe(self, game: Instance) -> str:
        """The rule in words, for the summary line."""
        return (f"{self.alpha}·progress({game.goals[0]!r}) + {1 - self.alpha}·progress("
                f"{game.goals[1]!r}), per prefix")

    def sigma_along(self, game: Instance, walk: Sequence[int]) -> list[Fraction]:
        """The weight on ``goals[0]`` after every step of ``walk`` (game node indices).

        Examples
        --------
        >>> from solver.game.instance import triangle
        >>> game = triangle()   # s -> g2 (weight 2): progress 1 toward g1, 2 toward g2
        >>> mix = TwoGoalMixture(Fraction(1, 2), Fraction(3), Fraction(2), Fraction(4),
        ...                      (Fraction(5, 2), Fraction(5, 2)))
        >>> [str(x) for x in mix.sigma_along(game, [game.s0, game.targets[1]])]
        ['1/4']
        """
        c = [game.distance(0, walk[0]), game.distance(1, walk[0])]
        out = []
        for v, u in itertools.pairwise(walk):
            w = Fraction(int(game.network.arc_weight(v, u) or 0), game.denominator)
            new = [min(c[0], game.distance(0, u)), min(c[1], game.distance(1, u))]
            to_0 = (c[0] - new[0]) / w
            to_1 = (c[1] - new[1]) / w
            out.append(self.alpha * to_0 + (1 - self.alpha) * (1 - to_1))
            c = new
        return out

    def walk_cost(self, game: Instance, walk: Sequence[int], theta: int) -> Fraction:
        """Type ``θ``'s exact cost of ``walk`` against the mixture."""
        total = game.distance(theta, walk[-1])
        for k, s in enumerate(self.sigma_along(game, walk)):
            w = Fraction(int(game.network.arc_weight(walk[k], walk[k + 1]) or 0),
                         game.denominator)
            total += w * (s if theta == 0 else 1 - s)
        return total

    def check_costs(self, game: Instance, mixtures: dict[int, Any],
                    h: Sequence[Fraction]) -> None:
        """Every walk of type ``θ`` costs exactly ``h_θ`` against the mixture: the two
        constructions agree (proofs/SELECT.md SELECT.5); an AssertionError otherwise."""
        for theta, mix in mixtures.items():
            for walk, _ in mix:
                cost = self.walk_cost(game, walk, theta)
                if cost != h[theta]:  # pragma: no cover - SELECT.5
                    raise AssertionError(f"the progress mixture charges type {theta + 1} "
                                         f"{cost} on {walk}, the guarantee rule {h[theta]}")


def two_goal_mixture(game: Instance, values: Sequence[Fraction], m0: Sequence[Fraction],
                     choice: Sequence[Fraction], value: Fraction) -> TwoGoalMixture:
    """The mixture's ``α`` from ``d1 = m0[0]``, ``d2 = m0[1]`` and ``M = m0[2]`` (the coalition
    values of ``{1}``, ``{2}``, ``{1, 2}`` at the start).

    Examples
    --------
    paper10.map's numbers: ``d1 = 18``, ``d2 = 17``, ``M = 25``, ``V_sel = 25/2``:

    >>> from solver.game.instance import triangle
    >>> mix = two_goal_mixture(triangle(), [Fraction(0)] * 2,
    ...                        [Fraction(18), Fraction(17), Fraction(25)],
    ...                        [Fraction(1, 2)] * 2, Fraction(25, 2))
    >>> mix.alpha, mix.guaranteed
    (Fraction(9, 20), (Fraction(25, 2), Fraction(25, 2)))
    """
    d1, d2, m = (Fraction(x) for x in m0)
    r1, r2 = values
    gap = d1 + d2 - m
    if gap:
        alpha = min(Fraction(1), max(Fraction(0), (2 * d2 - m + r1 - r2) / (2 * gap)))
    else:  # V is linear in q: one progress rule, toward the goal chosen
        alpha = Fraction(1) if choice[0] >= choice[1] else Fraction(0)
    c = (m - d2 + alpha * gap, d2 - alpha * gap)
    for t in range(2):  # SELECT.5: on the diagonal where q* chooses, above it elsewhere
        slack = c[t] - values[t] - value
        if slack < 0 or (choice[t] and slack):  # pragma: no cover - SELECT.5
            raise AssertionError(f"the progress mixture with α = {alpha} guarantees {c}, not "
                                 f"V_sel = {value} + r on the chosen goals")
    return TwoGoalMixture(alpha, d1, d2, m, c)


def value_curve(d1: Fraction, d2: Fraction, m: Fraction, qs: Sequence[float]) -> list[float]:
    """``V(q)`` at the priors ``qs`` of ``goals[0]``, with values 0:
    ``max((1 − q)M + (2q − 1)d1, qM + (1 − 2q)d2)`` (proofs/SELECT.md SELECT.10).

    Examples
    --------
    >>> value_curve(Fraction(18), Fraction(17), Fraction(25), [0.0, 0.5, 1.0])
    [17.0, 12.5, 18.0]
    """
    a, b, c = float(d1), float(d2), float(m)
    return [max((1 - q) * c + (2 * q - 1) * a, q * c + (1 - 2 * q) * b) for q in qs]


def minimising_choices(d1: Fraction, d2: Fraction, m: Fraction, value: Fraction
                       ) -> tuple[Fraction, Fraction]:
    """The interval of priors ``q`` of ``goals[0]`` attaining ``V_sel = value`` (values 0): the
    hull of the binding normals' points, 1 for ``{g1}``, 0 for ``{g2}``, 1/2 for the pair
    (proofs/SELECT.md SELECT.A).

    Examples
    --------
    >>> minimising_choices(Fraction(6), Fraction(3), Fraction(6), Fraction(3))
    (Fraction(0, 1), Fraction(1, 2))
    """
    points = [q for q, x in ((Fraction(1), d1), (Fraction(0), d2), (Fraction(1, 2), m / 2))
              if x == value]
    return min(points), max(points)
