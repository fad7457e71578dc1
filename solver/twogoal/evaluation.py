"""Exact evaluation of any (Defender, Attacker) pair on an instance (paper eqs. (3)-(4), (16)).

A *Defender* is given by its schedule: a function mapping a walk (node indices from
``s0``) to the probability of allocating to ``g1`` after each step — σ*, the alternative
Defender σ' and any other prefix-based Defender fit. An *Attacker* is a mixed strategy over
finite paths per type (the paper's Γ_mix). Beliefs follow Bayes' rule (eq. (2)) from the
Attacker's mixture and are independent of the Defender.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Hashable, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from functools import cached_property
from itertools import pairwise

import numpy as np

from solver.game.walks import StrategyWalk
from solver.graph.network import Network
from solver.numbers import Number

Schedule = Callable[[Sequence[int]], list[Number]]
"""A Defender: walk (node indices) -> probability of allocating to g1 after each step."""


@dataclass(frozen=True)
class Trajectory:
    """One Attacker path with everything that happens along it.

    Attributes
    ----------
    theta : int
        The Attacker type θ: 1 (primary, true goal ``g1``) or 2 (secondary, ``g2``).
    label : str
        Name of the path (``xi2``, ``xi1_I``, ...).
    probability : Fraction
        Probability that this type takes this path.
    walk : tuple of int
        Node indices ``s_0 .. s_T``.
    nodes : tuple
        The same as node ids.
    sigma_g1 : tuple
        Defender's probability of allocating to ``g1`` after steps ``1..T``.
    belief_g1 : tuple of Fraction
        Bayes belief ``b^1_t`` that ``g1`` is true after steps ``0..T`` (Bayes' rule, eq. (2)).
    allocation : tuple
        Cumulative expected allocation to this type's true goal after steps ``0..T``.
    terminal : Number
        Terminal cost ``d(s_T, g^θ)``.
    cost : Number
        ``allocation[-1] + terminal``: this path's cost for its type.
    """

    theta: int
    label: str
    probability: Fraction
    walk: tuple[int, ...]
    nodes: tuple[Hashable, ...]
    sigma_g1: tuple[Number, ...]
    belief_g1: tuple[Fraction, ...]
    allocation: tuple[Number, ...]
    terminal: Number
    cost: Number


@dataclass(frozen=True)
class _WalkRun:
    """One Attacker walk evaluated against the Defender (internal)."""

    theta: int
    strategy: StrategyWalk
    sigma: tuple[Number, ...]
    weights: tuple[Number, ...]
    terminal: Number
    cost: Number


@dataclass(frozen=True, eq=False)
class Evaluation:
    """Type costs ``U1, U2``, overall ``U``, complete-information ``U_bar`` and ``VoI``.

    ``trajectories`` (per-step σ, beliefs and cumulative allocations of every path) is
    computed on first access.
    """

    U1: Number
    U2: Number
    U: Number
    U_bar: Number
    VoI: Number
    _runs: tuple[_WalkRun, ...] = field(repr=False)
    _prior: tuple[Fraction, Fraction] = field(repr=False)

    @cached_property
    def trajectories(self) -> tuple[Trajectory, ...]:
        """Per walk: σ(g1), Bayes beliefs ``b^1_t`` (eq. (2)) and cumulative allocation."""
        all_paths = [(r.theta, r.strategy) for r in self._runs]
        out = []
        for run in self._runs:
            alloc: list[Number] = [run.cost - run.cost]  # a zero of the right type
            for w, s in zip(run.weights, run.sigma, strict=True):
                alloc.append(alloc[-1] + w * (s if run.theta == 1 else 1 - s))
            out.append(Trajectory(run.theta, run.strategy.label, run.strategy.probability,
                                  run.strategy.walk, run.strategy.nodes, run.sigma,
                                  _beliefs_along(run.strategy.walk, all_paths, self._prior),
                                  tuple(alloc), run.terminal, run.cost))
        return tuple(out)


def evaluate(
    net: Network,
    schedule: Schedule,
    primary: Sequence[StrategyWalk],
    secondary: Sequence[StrategyWalk],
    *,
    prior: tuple[Fraction, Fraction],
    goals: tuple[int, int],
    d_to: tuple[np.ndarray, np.ndarray],
    d_from_start: np.ndarray,
) -> Evaluation:
    """Evaluate a Defender schedule against a mixed Attacker, exactly.

    ``U^θ = Σ_ξ γ(ξ|θ) [Σ_t w(e_t) σ_t(g^θ) + d(s_T, g^θ)]`` (eq. (3)),
    ``U = b1 U1 + b2 U2`` (eq. (4)), ``VoI = (Ū − U)/Ū`` with ``Ū = b1 d(s0,g1) + b2 d(s0,g2)``;
    ``prior`` is ``(b1, b2)``, ``goals`` the node indices ``(g1, g2)``, ``d_to`` the distance
    fields ``(d(·, g1), d(·, g2))``.

    Examples
    --------
    >>> from solver.graph.distances import distances_from, distances_to
    >>> from solver.game.instance import triangle
    >>> net = triangle().network   # s=0, g2=1, g1=2
    >>> always_g1 = lambda walk: [Fraction(1)] * (len(walk) - 1)
    >>> direct = [StrategyWalk.along(net, walk, Fraction(1), "direct") for walk in ((0, 2), (0, 1))]
    >>> ev = evaluate(net, always_g1, direct[:1], direct[1:],
    ...               prior=(Fraction(7, 10), Fraction(3, 10)), goals=(2, 1),
    ...               d_to=(distances_to(net, 2), distances_to(net, 1)),
    ...               d_from_start=distances_from(net, 0))
    >>> str(ev.U1), str(ev.U2), str(ev.U), str(ev.VoI)
    ('3', '0', '21/10', '2/9')
    >>> [str(x) for x in ev.trajectories[0].allocation]
    ['0', '3']
    """
    (b1, b2), (g1, g2), (d_to_g1, d_to_g2) = prior, goals, d_to
    runs = []
    numbers = net.numbers
    convert = functools.cache(numbers.convert)  # a walk's weights take few distinct values
    u_theta = {1: numbers.zero(), 2: numbers.zero()}
    for theta, mixture in ((1, primary), (2, secondary)):
        for sp in mixture:
            sigma = tuple(schedule(sp.walk))
            raw = net.path_weights(sp.walk).tolist()
            paid = _allocation_total(net, raw, sigma, to_g1=theta == 1)
            terminal = numbers.convert((d_to_g1 if theta == 1 else d_to_g2)[sp.walk[-1]])
            cost = paid + terminal
            runs.append(_WalkRun(theta, sp, sigma, tuple(map(convert, raw)), terminal, cost))
            u_theta[theta] = u_theta[theta] + sp.probability * cost
    u1, u2 = u_theta[1], u_theta[2]
    value = b1 * u1 + b2 * u2
    u_bar = b1 * numbers.convert(d_from_start[g1]) + b2 * numbers.convert(d_from_start[g2])
    return Evaluation(u1, u2, value, u_bar, (u_bar - value) / u_bar, tuple(runs), (b1, b2))


def _allocation_total(net: Network, raw_weights: Sequence[int | float],
                      sigma: Sequence[Number], *, to_g1: bool) -> Number:
    """``Σ_t w_t σ_t(g^θ)``. Steps with σ in {0, 1} (most steps on grids) are summed as
    stored integers; only fractional steps need rational arithmetic."""
    whole: int | float = 0
    part: Number = net.numbers.zero()
    for w, s in zip(raw_weights, sigma, strict=True):
        share = s if to_g1 else 1 - s
        if share == 1:
            whole += w
        elif share != 0:
            part += net.numbers.convert(w) * share
    return net.numbers.convert(whole) + part


def _beliefs_along(walk: Sequence[int], all_paths: Sequence[tuple[int, StrategyWalk]],
                   prior: tuple[Fraction, Fraction]) -> tuple[Fraction, ...]:
    """Bayes belief in g1 at each prefix of ``walk`` (Bayes' rule, eq. (2), unrolled): the
    prior-weighted mass of primary paths sharing the prefix over the total mass sharing it. The
    belief can change only where another path leaves this one, so it is computed once per
    segment."""
    shared = [(theta, sp.probability, _common_prefix(walk, sp.walk)) for theta, sp in all_paths]
    out: list[Fraction] = []
    for t0, t1 in pairwise([0, *sorted({n for _, _, n in shared if 0 < n < len(walk)}),
                            len(walk)]):
        mass = [sum((p for th, p, n in shared if n > t0 and th == theta), Fraction(0))
                for theta in (1, 2)]
        num = prior[0] * mass[0]
        out.extend([num / (num + prior[1] * mass[1])] * (t1 - t0))
    return tuple(out)


def _common_prefix(a: Sequence[int], b: Sequence[int]) -> int:
    """Number of leading nodes ``a`` and ``b`` share."""
    n = min(len(a), len(b))
    x = np.asarray(a[:n]) != np.asarray(b[:n])
    return int(np.argmax(x)) if x.any() else n
