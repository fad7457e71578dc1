"""The normal-restricted DP of the structured route (``proofs/NGOAL.md`` NG.7).

One number ``m_n(v, k)`` per node, steps left and normal ``n`` of a fixed finite set ``M`` of
non-negative integer vectors containing every 0/1 vector::

    a_n(v) = min_u [ w(v, u)·max(n) + m_n(u, k-1) ]                         (step)
    m_n(v) = min { Σ_{n'} c_{n'} a_{n'}(v) : c >= 0, Σ_{n'} c_{n'} n' = n }   (closure)

It describes outer sets ``F_v^k = { r : n·r <= m_n(v, k) ∀ n ∈ M }`` ⊇ ``G_v^k`` (an upper
bound on ``V_H``, NG.2/NG.7); with ``M`` the 0/1 vectors it is the coalition DP. The closure
takes the cheapest cover over the vertex tables of :mod:`dppverify.structured.cover`; each
layer is certified by :mod:`dppverify.structured.dp_certificate` (NG.8).
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

from dppverify.errors import HorizonError
from dppverify.game.instance import Instance
from dppverify.structured.coalition import CoalitionRunner
from dppverify.structured.cover import (
    Normal,
    cheapest,
    min_cover_vectors,
    symmetric_table,
    zero_one_normals,
)
from dppverify.structured.dp_certificate import Arc, direction_checks, failing_arcs


class BeyondExactRange(Exception):
    """The normal-restricted DP's numbers left the range of exact float64/int64 arithmetic."""


class NormalDP:
    """The normal-restricted DP (NG.7), vectorised over nodes, in exact integers at scale ``D``.

    A layer is ``(m, finite, D)``: ``m[j, v] = D · m_{n_j}(v)`` (Python-int exact, int64
    storage), ``finite[v]`` whether ``v`` reaches a goal (all normals are finite together).
    After every closure the scale is reduced to the least multiple of the weights' common
    denominator that keeps every value integral, so equal layers have equal representations.

    Examples
    --------
    With the 0/1 normals it is the coalition DP:

    >>> from dppverify.game.examples import star3
    >>> dp = NormalDP(star3(), zero_one_normals(3))
    >>> dp.value(dp.step(dp.step(dp.layer0())))
    Fraction(3, 2)
    """

    def __init__(self, inst: Instance, normals: tuple[Normal, ...]) -> None:
        self.inst = inst
        self.normals = normals
        self.tops = [max(x) for x in normals]
        self.tables = [symmetric_table(normals, x) for x in normals]
        self.checks = direction_checks(normals)
        goal = np.zeros(inst.n_nodes, dtype=bool)
        goal[list(inst.goals)] = True
        self.goal = goal
        src, dst, wts = [], [], []
        for v in range(inst.n_nodes):
            if not goal[v]:
                for u, w in inst.succ[v]:
                    src.append(v)
                    dst.append(u)
                    wts.append(Fraction(w))
        self.src = np.asarray(src, dtype=np.int64)
        self.dst = np.asarray(dst, dtype=np.int64)
        self.w = wts
        self.wden = math.lcm(1, *(w.denominator for w in wts))
        self.active = np.unique(self.src)
        self.seg = np.searchsorted(self.src, self.active)
        self.term = {g: [sum((Fraction(x[t]) * Fraction(inst.dist_to[t][g])
                              for t in range(inst.n_goals)), Fraction(0)) for x in normals]
                     for g in inst.goals}
        self.cut = math.lcm(1, *(t.lcm for t in self.tables))

    def weights(self, scale: int) -> np.ndarray:
        return np.asarray([int(w * scale) for w in self.w], dtype=np.int64)

    def _goals(self, m: np.ndarray, scale: int) -> None:
        for g, vals in self.term.items():
            m[:, g] = [int(x * scale) for x in vals]

    def layer0(self) -> tuple[np.ndarray, np.ndarray, int]:
        scale = math.lcm(self.wden, *(x.denominator for vals in self.term.values()
                                      for x in vals))
        m = np.zeros((len(self.normals), self.inst.n_nodes), dtype=np.int64)
        self._goals(m, scale)
        return m, self.goal.copy(), scale

    def _reduce(self, m: np.ndarray, finite: np.ndarray, scale: int
                ) -> tuple[np.ndarray, np.ndarray, int]:
        g = math.gcd(int(np.gcd.reduce(m[:, finite].ravel(), initial=0)), scale // self.wden)
        if g > 1:
            m = m // g
            scale //= g
        m[:, ~finite] = 0
        return m, finite, scale

    def close(self, a: np.ndarray, rows: np.ndarray, scale: int
              ) -> tuple[np.ndarray, int]:
        """Closure (NG.7) of the step values ``a`` (``|M| × rows``) at scale ``scale``."""
        out = np.zeros_like(a)
        if 2 ** 62 // max(1, self.cut) < int(a.max(initial=0)) + 1:
            raise BeyondExactRange
        for j, tab in enumerate(self.tables):
            cols = np.asarray(tab.columns, dtype=np.int64)
            best = cheapest(a[cols].T, tab.scaled)
            out[j] = np.asarray(best, dtype=object) * (self.cut // tab.lcm)
        return out, scale * self.cut

    def step(self, state: tuple[np.ndarray, np.ndarray, int]
             ) -> tuple[np.ndarray, np.ndarray, int]:
        m, finite, scale = state
        n = self.inst.n_nodes
        new_fin = self.goal.copy()
        if self.src.size:
            fin_dst = finite[self.dst]
            reach = np.logical_or.reduceat(fin_dst, self.seg)
            rows = self.active[reach]
            new_fin[rows] = True
            wts = self.weights(scale)
            big = int(m[:, finite].max(initial=0)) * 2 + int(wts.max(initial=0)) * max(
                self.tops) * 2 + 1
            if big > 2 ** 61:
                raise BeyondExactRange
            a = np.empty((len(self.normals), rows.size), dtype=np.int64)
            for j, top in enumerate(self.tops):
                cand = wts * top + np.where(fin_dst, m[j][self.dst], big)
                a[j] = np.minimum.reduceat(cand, self.seg)[reach]
            closed, new_scale = self.close(a, rows, scale)
        else:
            rows = np.zeros(0, dtype=np.int64)
            closed, new_scale = np.zeros((len(self.normals), 0), dtype=np.int64), scale
        out = np.zeros((len(self.normals), n), dtype=np.int64)
        out[:, rows] = closed
        self._goals(out, new_scale)
        return self._reduce(out, new_fin, new_scale)

    def certify(self, new: tuple[np.ndarray, np.ndarray, int],
                old: tuple[np.ndarray, np.ndarray, int]) -> list[Arc]:
        (a, fa, sa), (b, fb, sb) = new, old
        scale = math.lcm(sa, sb)
        return failing_arcs(self.checks, a * (scale // sa), fa, b * (scale // sb), fb, self.src,
                        self.dst, self.weights(scale))

    def value(self, state: tuple[np.ndarray, np.ndarray, int]) -> Fraction:
        m, finite, scale = state
        s0 = self.inst.start
        if not finite[s0]:
            raise HorizonError("no walk from the start reaches a goal within the horizon")
        costs = [Fraction(int(x), scale) for x in m[:, s0]]
        return min_cover_vectors(self.normals, costs, self.inst.prior).value

    def warm(self, run: CoalitionRunner, layer: dict[int, np.ndarray]
             ) -> tuple[np.ndarray, np.ndarray, int]:
        """A start above a DP layer (NG.8(b)): the coalition fixpoint, extras by 0/1 covers."""
        zo = zero_one_normals(self.inst.n_goals)
        arr, finite = run.stacked(layer)
        m = np.zeros((len(self.normals), self.inst.n_nodes), dtype=np.int64)
        m[:len(zo)] = np.where(finite, arr, 0)
        rows = np.flatnonzero(finite)
        cut = math.lcm(1, *(symmetric_table(zo, x).lcm for x in self.normals[len(zo):]))
        m *= cut
        for j in range(len(zo), len(self.normals)):
            tab = symmetric_table(zo, self.normals[j])
            best = cheapest(arr[np.asarray(tab.columns)][:, rows].T, tab.scaled)
            m[j, rows] = np.asarray(best, dtype=object) * (cut // tab.lcm)
        return self._reduce(m, finite, run.scale * cut)


def normal_dp_value(inst: Instance, extras: list[Normal], horizon: int | None,
                    max_layers: int, start: tuple[CoalitionRunner, dict[int, np.ndarray]] | None
                    ) -> tuple[Fraction, int, list[Arc]]:
    """The DP over the 0/1 normals and ``extras``: its value, layers and failing arcs (NG.8).

    Finite ``H``: ``H`` layers from the goals, certified at every layer. ``H = inf``
    (``horizon=None``): started from the coalition fixpoint ``start`` (NG.8(b)) until a layer
    repeats, within ``max_layers``, certified there.

    Raises
    ------
    HorizonError
        If ``H = inf`` does not converge within ``max_layers`` layers.
    BeyondExactRange
        If the numbers leave the range of exact float64/int64 arithmetic.

    Examples
    --------
    The hub's value 12/7 with the four permutations of (2, 2, 2, 1), certified:

    >>> from dppverify.game.examples import hub4
    >>> extras = [(2, 2, 2, 1), (2, 2, 1, 2), (2, 1, 2, 2), (1, 2, 2, 2)]
    >>> normal_dp_value(hub4(), extras, 3, 100, None)
    (Fraction(12, 7), 3, [])
    """
    normals = zero_one_normals(inst.n_goals) + tuple(extras)
    dp = NormalDP(inst, normals)
    if horizon is not None:
        layer = dp.layer0()
        fails: list[Arc] = []
        for _ in range(horizon):
            nxt = dp.step(layer)
            if not fails:
                fails = dp.certify(nxt, layer)
            layer = nxt
        return dp.value(layer), horizon, fails
    assert start is not None
    layer = dp.warm(*start)
    for k in range(1, max_layers + 1):
        nxt = dp.step(layer)
        if nxt[2] == layer[2] and np.array_equal(nxt[1], layer[1]) and np.array_equal(
                nxt[0], layer[0]):
            return dp.value(nxt), k, dp.certify(nxt, nxt)
        layer = nxt
    raise HorizonError(f"the refined DP did not converge within {max_layers} layers")
