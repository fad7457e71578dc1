"""The structured route: ``V_H`` of the N-goal game by the coalition DP over goal subsets.

For every node ``v``, steps left ``k`` and non-empty goal subset ``S`` the DP keeps one number,
``m_S(v, k)``: the cheapest cost of a pooled "coalition" in which every type of ``S`` starts at
``v`` with unit weighted mass (``proofs/NGOAL.md``). By increasing ``|S|``::

    m_S(g, k) = Σ_{θ ∈ S} d(g, g^θ)                           (goals are terminal)
    m_S(v, k) = min( min_u [ w(v, u) + m_S(u, k-1) ],           (walk on together)
                     min { Σ_{T ⊊ S} c_T m_T(v, k) : c >= 0, Σ_T c_T 1_T = 1_S } )   (split)
    m_S(v, k) = +inf when no goal is reachable from v within k steps,

    V_H = min { Σ_S c_S m_S(s0, H) : c >= 0, Σ_S c_S 1_S = (b_1, …, b_N) }.

The split is an LP over the fractional partitions of ``S``; its optimum is attained at a vertex,
and those vertices are the minimal balanced collections of ``S``
(:func:`dppverify.structured.cover.balanced_vertices`: 1, 5, 41, 1291 for ``|S|`` = 2 … 5), so the
split is one exact integer matrix product per (k, S) over all nodes. The final cover LP is
solved by the exact simplex of :func:`dppverify.structured.cover.min_cover`.

Exactness: weights are scaled to integers by the lcm ``W`` of their denominators; a split
multiplies by coefficients with denominators dividing ``L`` (the lcm over the vertex tables),
and ``m_S`` has a denominator dividing ``L^(|S|-1)``, so ``W·L^(N-1)·m`` is an integer for
every ``(v, k, S)``. The DP runs on those integers (numpy int64 when a bound proves there is no
overflow, Python integers otherwise; the split products in float64 BLAS when the same bound
proves every partial sum is an integer below 2^53, so that float64 arithmetic on them is exact),
and every division by ``L`` is checked to be exact.
Cost ``O(H·(2^N·E + n·Σ_S |vertices of S|))``. ``H = inf`` iterates until a layer repeats
(then every later layer is the same).

For two goals ``m_{1} = D1``, ``m_{2} = D2`` and ``m_{12} = min(step, D1 + D2)``: the
three-field DP of ``proofs/HORIZON.md``'s two-goal value. The DP is an upper bound on the
truncated game's value, equal to it for ``N <= 3`` (``proofs/NGOAL.md`` NG.3, NG.4) and not
always for ``N >= 4`` (the hub of :func:`dppverify.game.examples.hub4`);
:func:`dppverify.structured.proved_value.nvalue` certifies it or brackets the value.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from dppverify.errors import HorizonError, OptionError
from dppverify.exact import INF, Number, normalize
from dppverify.game.distances import EXACT_FLOAT_LIMIT
from dppverify.game.instance import Instance
from dppverify.structured.cover import MAX_BALANCED, balanced_vertices, members, min_cover, popcount


@dataclass(frozen=True)
class CoalitionValue:
    """The coalition DP at ``H`` (an upper bound on ``V_H``; the value for N <= 3).

    Attributes
    ----------
    horizon : int or None
        ``H`` (None for ``H = inf``).
    value : Number
        The DP's value exactly (``V_H`` for N <= 3; an upper bound for N >= 4).
    layers : int
        Number of DP layers computed (for ``H = inf``: the first ``k`` whose layer repeats).
    coalition_costs : Mapping
        Subset mask -> ``m_S(s0, H)`` exactly.
    cover : Mapping
        Subset mask -> ``c_S > 0``: the optimal pooling of the prior at the start.
    """

    horizon: int | None
    value: Number
    layers: int
    coalition_costs: Mapping[int, Number]
    cover: Mapping[int, Fraction]


@dataclass(frozen=True)
class Split:
    """The split of one goal subset ``S``: its minimal balanced collections as a vertex table.

    Attributes
    ----------
    mask : int
        ``S`` (``|S| >= 2``).
    columns : numpy.ndarray
        The masks of the proper subsets of ``S``, in the table's column order.
    scaled : numpy.ndarray
        ``(n_columns, n_vertices)`` integer vertex coordinates times ``lcm``.
    lcm : int
        The common denominator of the vertex coordinates.
    """

    mask: int
    columns: np.ndarray
    scaled: np.ndarray
    lcm: int


def splits(n_goals: int) -> list[Split]:
    """The split of every goal subset with at least two goals, by increasing ``|S|``, then mask.

    Raises
    ------
    OptionError
        Beyond the tabulated balanced collections (more than five goals).

    Examples
    --------
    >>> [(s.mask, s.columns.tolist(), s.lcm) for s in splits(2)]
    [(3, [1, 2], 1)]
    >>> len(splits(3)), splits(3)[-1].mask
    (4, 7)
    """
    if not 2 <= n_goals <= MAX_BALANCED:
        raise OptionError(too_many_goals(n_goals))
    out = []
    for size in range(2, n_goals + 1):
        table = balanced_vertices(size)
        for mask in range(1, 1 << n_goals):
            if popcount(mask) != size:
                continue
            elems = members(mask)
            glob = [sum(1 << elems[i] for i in members(local)) for local in table.columns]
            out.append(Split(mask, np.asarray(glob, dtype=np.int64), table.scaled, table.lcm))
    return out


def coalition_scale(instance: Instance, tables: list[Split]) -> int:
    """``Q = W·L^(N-1)``: every ``m_S(v, k)`` of the coalition DP times ``Q`` is an integer.

    ``W`` is the lcm of the weights' denominators, ``L`` the lcm over the split tables.

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> coalition_scale(star3(), splits(3))
    4
    """
    lcm_split = math.lcm(1, *(s.lcm for s in tables))
    wden = math.lcm(1, *(Fraction(w).denominator for arcs in instance.succ for _, w in arcs))
    return wden * lcm_split ** (instance.n_goals - 1)


def too_many_goals(n_goals: int) -> str:
    """The one-line refusal for an instance beyond the coalition DP's reach.

    Examples
    --------
    >>> too_many_goals(6)  # doctest: +ELLIPSIS
    'the coalition DP handles 2 to 5 goals, not 6 (...); give a finite --horizon for the tree route'
    """
    return (f"the coalition DP handles 2 to {MAX_BALANCED} goals, not {n_goals} (it enumerates "
            "the minimal balanced collections of the goals: 1,291 for 5 goals, about 200,000 "
            "for 6); give a finite --horizon for the tree route")


class CoalitionRunner:
    """The coalition DP's state: arcs in scaled integers; a layer is ``{S: m[S][v] · scale}``.

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> run = CoalitionRunner(star3())
    >>> layer = run.step(run.layer0(), 1)
    >>> run.value(layer, 1, 1).value, same_layer(layer, run.step(layer, 2))
    (2, False)
    """

    def __init__(self, inst: Instance) -> None:
        n_goals = inst.n_goals
        self.inst = inst
        self.splits = splits(n_goals)
        lcm_split = math.lcm(1, *(s.lcm for s in self.splits))
        weights = [w for arcs in inst.succ for _, w in arcs]
        self.scale = coalition_scale(inst, self.splits)
        n = inst.n_nodes
        max_w = max((Fraction(w) for w in weights), default=Fraction(0))
        max_d = max(Fraction(d) for row in inst.dist_to for d in row if d != INF)
        bound = n_goals * ((n + 1) * max_w + max_d) * self.scale
        width = (1 << n_goals) * max(1, lcm_split) * (bound + 1)
        self.big = int(bound) * 4 + 4  # above every finite value
        self.dtype: type | np.dtype = (np.dtype(np.int64) if width * 8 < 2 ** 62
                                       and self.big * 2 < 2 ** 62 else object)
        # Every partial sum of a split product is an integer below ``width``: below 2**53 the
        # float64 (BLAS) product of the integer matrices is exact, and much faster.
        self.float_exact = self.dtype == np.dtype(np.int64) and width < EXACT_FLOAT_LIMIT
        goal = np.zeros(n, dtype=bool)
        goal[list(inst.goals)] = True
        self.goal = goal
        self.hops = np.asarray(inst.hops, dtype=np.int64)
        src, dst, wts = [], [], []
        for u in range(n):
            if goal[u]:
                continue  # goals are terminal: their arcs are never walked
            for v, w in inst.succ[u]:
                src.append(u)
                dst.append(v)
                wts.append(int(Fraction(w) * self.scale))
        self.src = np.asarray(src, dtype=np.int64)
        self.dst = np.asarray(dst, dtype=np.int64)
        self.wts = np.asarray(wts, dtype=self.dtype)
        self.active = np.zeros(n, dtype=bool)  # non-goal nodes with an arc: they take a step
        self.active[self.src] = True
        self.seg = np.searchsorted(self.src, np.flatnonzero(self.active))
        self.terminal: dict[int, np.ndarray] = {}
        for mask in range(1, 1 << n_goals):
            vals = np.full(n, self.big, dtype=self.dtype)
            for g in inst.goals:
                vals[g] = int(sum(Fraction(inst.dist_to[t][g]) for t in members(mask))
                              * self.scale)
            self.terminal[mask] = vals

    def layer0(self) -> dict[int, np.ndarray]:
        return {mask: vals.copy() for mask, vals in self.terminal.items()}

    def step(self, prev: dict[int, np.ndarray], k: int) -> dict[int, np.ndarray]:
        finite = self.goal | ((self.hops >= 0) & (self.hops <= k))
        rows = np.flatnonzero(finite & ~self.goal)
        out: dict[int, np.ndarray] = {}
        for mask, old in prev.items():
            new = self.terminal[mask].copy()
            if self.seg.size:
                cand = self.wts + old[self.dst]
                best = np.minimum.reduceat(cand, self.seg)
                new[self.active] = np.minimum(best, self.big)
            new[~finite] = self.big
            out[mask] = new
        for sp in self.splits:  # increasing |S|: the columns are final already
            if rows.size == 0:
                break
            mat = np.stack([out[int(c)][rows] for c in sp.columns], axis=1)
            if self.float_exact:
                tot = (mat.astype(np.float64) @ sp.scaled.astype(np.float64)).astype(np.int64)
            else:
                tot = mat @ sp.scaled.astype(self.dtype)
            best = tot.min(axis=1)
            if np.any(best % sp.lcm != 0):  # pragma: no cover - guaranteed by the scaling
                raise AssertionError("coalition DP: a split is not a multiple of 1/scale")
            vals = out[sp.mask]
            vals[rows] = np.minimum(vals[rows], best // sp.lcm)
        return out

    def fixpoint(self, max_layers: int | None) -> tuple[dict[int, np.ndarray], int]:
        """The first layer ``k`` (beyond the farthest goal) equal to layer ``k - 1``, and ``k``.

        Every later layer is the same: it is the DP at ``H = inf``.

        Raises
        ------
        HorizonError
            If no layer repeats within ``max_layers`` layers.
        """
        layer = self.layer0()
        k = 0
        while True:
            k += 1
            if max_layers is not None and k > max_layers:
                raise HorizonError(f"the coalition DP did not converge within {max_layers} "
                                   f"layers")
            nxt = self.step(layer, k)
            if k > max(self.inst.hops) and same_layer(nxt, layer):
                return nxt, k
            layer = nxt

    def stacked(self, layer: dict[int, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
        """A layer as one ``(2^N - 1, nodes)`` array (row ``mask - 1``) and its finite nodes."""
        arr = np.stack([layer[m] for m in range(1, 1 << self.inst.n_goals)])
        return arr, layer[1] < self.big

    def value(self, layer: dict[int, np.ndarray], horizon: int | None,
              layers: int) -> CoalitionValue:
        s0 = self.inst.start
        costs: dict[int, Fraction] = {}
        for mask, vals in layer.items():
            x = int(vals[s0])
            if x >= self.big:
                raise HorizonError(f"no walk from the start reaches a goal within H = {horizon}"
                                   f" steps (the nearest goal is {self.inst.hops[s0]} steps "
                                   f"away)")
            costs[mask] = Fraction(x, self.scale)
        lp = min_cover(costs, self.inst.prior)
        return CoalitionValue(horizon=horizon, value=normalize(lp.value), layers=layers,
                              coalition_costs={m: normalize(c) for m, c in costs.items()},
                              cover=dict(lp.cover))


def same_layer(a: dict[int, np.ndarray], b: dict[int, np.ndarray]) -> bool:
    """True when two layers of the coalition DP are equal (then every later layer is too).

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> run = CoalitionRunner(star3())
    >>> one = run.step(run.layer0(), 1)
    >>> same_layer(run.layer0(), one), same_layer(one, one)
    (False, True)
    """
    return all(np.array_equal(a[m], b[m]) for m in a)


def coalition_value(instance: Instance, horizon: int | None, *,
                    max_layers: int | None = None) -> CoalitionValue:
    """The coalition DP of the N-goal game (``horizon=None`` for ``H = inf``).

    An upper bound on ``V_H``, equal to it for N <= 3 (``proofs/NGOAL.md``); use
    :func:`dppverify.structured.proved_value.nvalue` for the certified value or bracket.

    Parameters
    ----------
    instance : Instance
        The game (2 to 5 goals).
    horizon : int or None
        ``H >= 0``, or None: iterate until a layer repeats (``V_inf = lim V_H``).
    max_layers : int, optional
        For ``H = inf``: give up (``HorizonError``) after this many layers.

    Raises
    ------
    HorizonError
        If ``horizon`` is negative, or no goal is reachable within it.

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> v = coalition_value(star3(), 2)
    >>> v.value, v.coalition_costs[0b111]
    (Fraction(3, 2), 4)
    >>> coalition_value(star3(), None).value
    Fraction(3, 2)
    """
    if horizon is not None and horizon < 0:
        raise HorizonError(f"the horizon must be a non-negative integer, got {horizon}")
    run = CoalitionRunner(instance)
    if horizon is not None:
        layer = run.layer0()
        for k in range(1, horizon + 1):
            layer = run.step(layer, k)
        return run.value(layer, horizon, horizon)
    fixpoint, k = run.fixpoint(max_layers)
    return run.value(fixpoint, None, k)
