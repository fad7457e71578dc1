"""Dragan et al.'s observer (paper eq. (17)) with path length as the cost functional.

``P(g^i | ξ[0:t]) = exp(-C[ξ[0:t]] - V_i(s_t)) / exp(-V_i(s_0)) · b^i_0 / Z`` with
``C`` = path length and ``V_i(s) = d(s, g^i)`` (full-graph distance, as the paper states).
The factor ``exp(-C)`` is common to both goals and cancels in ``Z``, so the belief depends on
the current node ``s_t`` and the prior only::

    b^1_t = b1 e^{-x1} / (b1 e^{-x1} + b2 e^{-x2}) = 1 / (1 + (b2/b1) e^{δ}),
    x_i = d(s_t, g^i) - d(s_0, g^i),   δ = x1 - x2   (an exact rational).

The belief is irrational in general. Two things are needed from it:

- the *comparison* ``b^1_t >= 1/2`` (the alternative Defender σ'), i.e.
  ``ln(b1/b2) >= δ``. For ``b1 = b2`` this is ``δ <= 0``, exact. Otherwise ``b1/b2`` is a
  rational ≠ 1, whose logarithm is irrational (Lindemann), hence never equal to ``δ``: it is
  decided with mpmath interval arithmetic, doubling the precision until the interval for
  ``ln(b1/b2)`` separates from ``δ`` (guaranteed to terminate);
- *values* (sums of beliefs for eqs. (18a)/(18b), plots): mpmath at :data:`DPS` digits.

A node from which ``g^i`` is unreachable has ``e^{-x_i} = 0`` (belief 0 in ``g^i``); a node
reaching neither goal keeps the prior.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from functools import cache

import mpmath
import numpy as np
from mpmath.ctx_iv import MPIntervalContext
from mpmath.ctx_mp import MPContext

from solver.graph.network import Network

DPS = 50
"""Decimal digits of the mpmath values of Dragan's belief."""

MP = MPContext()
MP.dps = DPS
HI = MPContext()
HI.dps = DPS + 10
"""Private mpmath contexts (results at ``DPS`` digits, intermediates at ``DPS + 10``). They
are never modified after import, so threads (e.g. a threaded Dask worker) can share them;
mpmath's global ``mp`` context is not used."""


def ln_at_least(ratio: Fraction, delta: Fraction) -> bool:
    """Decide ``ln(ratio) >= delta`` exactly, for a positive rational ``ratio``.

    Examples
    --------
    >>> ln_at_least(Fraction(3, 2), Fraction(0)), ln_at_least(Fraction(3, 2), Fraction(2, 5))
    (True, True)
    >>> ln_at_least(Fraction(3, 2), Fraction(41, 100))   # ln 1.5 = 0.405465...
    False
    >>> ln_at_least(Fraction(1), Fraction(0))
    True
    """
    if ratio <= 0:
        raise ValueError(f"ratio must be positive, got {ratio}")
    if ratio == 1:
        return delta <= 0
    return _ln_at_least(ratio.numerator, ratio.denominator, delta.numerator, delta.denominator)


@cache
def _ln_at_least(p: int, q: int, a: int, b: int) -> bool:
    prec = 64
    while True:
        iv = MPIntervalContext()  # a fresh context per precision: thread-safe
        iv.prec = prec
        log = iv.log(iv.mpf(p) / iv.mpf(q))
        d = iv.mpf(a) / iv.mpf(b)
        if log.a > d.b:
            return True
        if log.b < d.a:
            return False
        prec *= 2  # ln(p/q) is irrational and never equals a/b: this terminates


@dataclass(frozen=True, eq=False)
class DraganObserver:
    """Eq. (17) with path-length cost on a network: the belief ``b^1_t`` at any node.

    Parameters
    ----------
    network : Network
        The game graph.
    start, g1, g2 : int
        Node indices of ``s_0``, the primary and the secondary goal.
    d_to_g1, d_to_g2 : numpy.ndarray
        Stored distances ``d(v, g1)``, ``d(v, g2)`` (numerators over
        ``network.numbers.denominator`` in exact mode; ``inf`` when unreachable).
    b1, b2 : Fraction
        The prior (primary first).

    Examples
    --------
    A path s - a - g1 and a - g2 (unit weights), prior (3/5, 2/5). At ``a`` both goals
    are one step closer, so the belief is still the prior; at ``g2`` it drops.

    >>> import networkx as nx
    >>> from solver.graph.distances import distances_to
    >>> net = Network.from_networkx(nx.Graph([("s", "a"), ("a", "g1"), ("a", "g2")]))
    >>> obs = DraganObserver(net, 0, 2, 3, distances_to(net, 2), distances_to(net, 3),
    ...                      Fraction(3, 5), Fraction(2, 5))
    >>> obs.delta(1), obs.delta(3)
    (Fraction(0, 1), Fraction(2, 1))
    >>> [mpmath.nstr(b, 6) for b in obs.beliefs([0, 1, 3])]
    ['0.6', '0.6', '0.168747']
    >>> obs.favours_g1(1), obs.favours_g1(3)
    (True, False)
    """

    network: Network
    start: int
    g1: int
    g2: int
    d_to_g1: np.ndarray = field(repr=False)
    d_to_g2: np.ndarray = field(repr=False)
    b1: Fraction
    b2: Fraction

    def delta(self, v: int) -> Fraction | None:
        """``δ = x1 - x2`` at node ``v`` exactly; None when a goal is unreachable from ``v``."""
        d1, d2 = self.d_to_g1[v], self.d_to_g2[v]
        if d1 == np.inf or d2 == np.inf:
            return None
        raw = (d1 - self.d_to_g1[self.start]) - (d2 - self.d_to_g2[self.start])
        return Fraction(self.network.numbers.convert(raw))  # a float: its exact value

    def belief(self, v: int) -> mpmath.mpf:
        """``b^1_t`` at node ``v`` (mpmath, :data:`DPS` digits)."""
        delta = self.delta(v)
        if delta is None:
            return _limit_belief(self.d_to_g1[v] == np.inf, self.d_to_g2[v] == np.inf, self.b1)
        return _belief(self.b1, self.b2, delta)

    def beliefs(self, walk: Sequence[int]) -> list[mpmath.mpf]:
        """``b^1_t`` after each prefix ``ξ[0:t]``, ``t = 0..T``, of a walk."""
        return [self.belief(int(v)) for v in walk]

    def favours_g1(self, v: int) -> bool:
        """``b^1_t >= 1/2`` at node ``v``, decided exactly."""
        delta = self.delta(v)
        if delta is None:
            no1, no2 = self.d_to_g1[v] == np.inf, self.d_to_g2[v] == np.inf
            return bool(no2 or not no1)  # belief 1, or the prior (b1 >= b2): g1
        return ln_at_least(self.b1 / self.b2, delta)


def _limit_belief(no_g1: bool, no_g2: bool, b1: Fraction) -> mpmath.mpf:
    if no_g1 and not no_g2:
        return MP.mpf(0)
    if no_g2 and not no_g1:
        return MP.mpf(1)
    return MP.mpf(b1.numerator) / b1.denominator


def belief_hi(b1: Fraction, b2: Fraction, delta: Fraction) -> mpmath.mpf:
    """``1 / (1 + (b2/b1) e^δ)`` in the :data:`HI` context (``DPS + 10`` digits).

    Parameters
    ----------
    b1, b2 : Fraction
        The prior.
    delta : Fraction
        ``δ = x1 − x2`` (see :meth:`DraganObserver.delta`).

    Returns
    -------
    mpmath.mpf
        The belief in ``g1``.

    Examples
    --------
    ``δ = 0`` leaves the prior; ``δ = 2`` (two steps towards g2) lowers the belief in g1:

    >>> mpmath.nstr(belief_hi(Fraction(3, 5), Fraction(2, 5), Fraction(0)), 20)
    '0.6'
    >>> b = belief_hi(Fraction(3, 5), Fraction(2, 5), Fraction(2))
    >>> HI.nstr(b, 40), abs(b - 1 / (1 + HI.mpf(2) / 3 * HI.exp(2))) < HI.mpf(10) ** -50
    ('0.1687468256815759526704055690174413321859', True)
    """
    ratio = HI.mpf(b2.numerator * b1.denominator) / (b2.denominator * b1.numerator)
    return 1 / (1 + ratio * HI.exp(HI.mpf(delta.numerator) / delta.denominator))


@cache
def _belief(b1: Fraction, b2: Fraction, delta: Fraction) -> mpmath.mpf:
    return MP.mpf(belief_hi(b1, b2, delta))
