"""Exact N-goal values: the guarantee-set recursion, certified on a finite set of facet normals.

``proofs/NGOAL.md`` (NG.6) proves that the value of the truncated N-goal game is
``V_H = max { b·r : r ∈ G_{s0}^H }`` for the *guarantee sets*

    G_g = { r : r <= d(g, g^·) }  at a goal g,     G_v^0 = R^N  elsewhere,
    G_v^k = ∩_{(v,u)} ( G_u^{k-1} + w(v,u)·Δ^N ),

and that a *normal-restricted* DP — one number ``m_n(v, k)`` per node, steps left and normal
``n`` of a fixed finite set ``M`` of non-negative integer vectors containing every 0/1 vector —

    a_n(v) = min_u [ w(v, u)·max(n) + m_n(u, k-1) ]                         (step)
    m_n(v) = min { Σ_{n'} c_{n'} a_{n'}(v) : c >= 0, Σ_{n'} c_{n'} n' = n }   (closure)

describes outer sets ``F_v^k = { r : n·r <= m_n(v, k) ∀ n ∈ M }`` ⊇ ``G_v^k`` (an upper bound on
``V_H``, NG.2/NG.7). With ``M`` the 0/1 vectors it is the coalition DP
(:mod:`dppverify.structured.coalition`). The sets are the true ones — and the DP value is ``V_H`` —
as soon as every arc satisfies ``F_v^k ⊆ F_u^{k-1} + w·Δ^N`` (NG.8). By Farkas' lemma that
holds iff for every vertex ``λ`` of the packing polytope ``P_M = { λ >= 0 : Σ_n λ_n n <= 1 }``

    h_{F_v}(y_λ) <= w + Σ_n λ_n m_n(u),          y_λ = Σ_n λ_n n,

where ``h_{F_v}(y)`` is the cheapest cover of ``y`` by the normals at ``v``. Vertices with
``y_λ`` a 0/1 vector satisfy it automatically (step and closure), so only the few others are
checked: none for N = 3 (which proves NG.4: the coalition DP is the value), the four
permutations of (1, 1, 1, 1/2) for N = 4 and 45 vectors for N = 5.

:func:`nvalue` runs the coalition DP, certifies it (``H = inf``: at the repeated layer, NG.8
then gives ``V_H`` for every ``H`` from that layer on; finite ``H``: at every layer) and, when
an arc fails, adds the failing direction ``y_λ`` and its permutations to ``M`` as primitive
integer normals and re-runs the DP (vectorised, exact integers at a reduced common scale; for
``H = inf`` started from the coalition fixpoint), a few rounds. Where no certificate is found
it returns a bracket naming both bounds: the best DP above, and below the better of two simple
Defenders (NG.9) and the coalition fixpoint's sets translated into a sub-fixpoint (NG.10).
Everything is exact; vertices come from exact integer determinants of every basis (no
polyhedral library: the normals form a fixed small table, so each basis is enumerated once per
table, and tables of permuted right-hand sides are shared by symmetry).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from functools import cache

import numpy as np

from dppverify.errors import HorizonError, OptionError
from dppverify.exact import Number, normalize
from dppverify.ngoal.instance import NInstance
from dppverify.structured.coalition import (
    CoalitionRunner,
    CoalitionValue,
    same_layer,
    too_many_goals,
)
from dppverify.structured.cover import (
    MAX_BALANCED,
    Normal,
    Table,
    cheapest,
    min_cover_vectors,
    packing_vertices,
    symmetric_table,
    zero_one_normals,
)

__all__ = [
    "NValue",
    "coalition_nvalue",
    "extra_directions",
    "lower_bound_simple",
    "nvalue",
]

MAX_ROUNDS = 4
"""Refinement rounds of the general DP (each adds the failing directions as normals)."""

MAX_BASES = 1_000_000
"""Limit on the bases enumerated for the vertices of a refined normal set's tables."""


def extra_directions(ys: Sequence[Sequence[Fraction]]) -> list[Normal]:
    """The primitive integer vectors along the directions ``ys`` (new normals).

    Examples
    --------
    >>> extra_directions([(Fraction(1), Fraction(1), Fraction(1), Fraction(1, 2))])
    [(2, 2, 2, 1)]
    """
    out = []
    for y in ys:
        den = math.lcm(*(Fraction(x).denominator for x in y))
        ints = [int(Fraction(x) * den) for x in y]
        g = math.gcd(*ints)
        out.append(tuple(x // g for x in ints))
    return out


def lower_bound_simple(instance: NInstance) -> tuple[Fraction, str]:
    """A cheap exact lower bound on every ``V_H`` (and ``V_inf``) from two simple Defenders.

    A Defender that always guards goal ``θ`` makes type ``θ`` pay at least ``d(s0, g^θ)``
    (the walk's weight plus the terminal cost); the uniform Defender makes every type ``θ``
    pay at least ``d(s0, g^θ)/N``. The bound is the better of ``max_θ b_θ d(s0, g^θ)`` and
    ``Σ_θ b_θ d(s0, g^θ) / N`` (``proofs/NGOAL.md`` NG.9).

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> lower_bound_simple(star3())
    (Fraction(1, 1), 'a Defender that always guards goal 1 (NG.9)')
    """
    inst = instance
    d = [Fraction(inst.dist_to[t][inst.start]) for t in range(inst.n_goals)]
    guard = [inst.prior[t] * d[t] for t in range(inst.n_goals)]
    best = max(range(inst.n_goals), key=lambda t: guard[t])
    uniform = sum(guard, Fraction(0)) / inst.n_goals
    if uniform > guard[best]:
        return uniform, "the uniform Defender (NG.9)"
    return guard[best], f"a Defender that always guards goal {best + 1} (NG.9)"


@dataclass(frozen=True)
class NValue:
    """``V_H`` of an N-goal instance by the guarantee sets: exact, or a named bracket.

    Attributes
    ----------
    horizon : int or None
        ``H`` (None for ``H = inf``).
    lower, upper : Number
        Exact bounds ``lower <= V_H <= upper``; equal when the value is proved.
    lower_source, upper_source : str
        Where each bound comes from.
    layers : int
        DP layers of the run that gave ``upper``.
    normals : tuple of tuple of int
        The facet normals beyond the 0/1 vectors that the final DP used (empty for the
        coalition DP).
    reason : str or None
        Why the value is not proved (None when it is).
    coalition : CoalitionValue
        The coalition DP at ``H`` (its cover and coalition costs at the start).
    """

    horizon: int | None
    lower: Number
    upper: Number
    lower_source: str
    upper_source: str
    layers: int
    normals: tuple[Normal, ...]
    reason: str | None
    coalition: CoalitionValue

    @property
    def exact(self) -> bool:
        """True when ``V_H`` is proved: the bounds meet."""
        return self.lower == self.upper

    @property
    def value(self) -> Number | None:
        """``V_H`` when proved, else None."""
        return self.upper if self.exact else None


# -- the coalition DP (0/1 normals), certified ------------------------------------------------

@dataclass(frozen=True)
class _Check:
    """The arc test for one direction ``y``: cover table of ``s·y`` and the ``λ``s."""

    scale: int  # s: s·y is an integer vector
    cover: Table  # vertices of {c >= 0 : Σ_n c_n n = s·y}, columns index the normals
    lams: np.ndarray  # (n_lambda, |M|): lcm_l · λ
    lam_lcm: int
    y: tuple[Fraction, ...]


@cache
def _checks(normals: tuple[Normal, ...]) -> tuple[_Check, ...]:
    groups: dict[tuple[Fraction, ...], list[tuple[Fraction, ...]]] = {}
    for lam, y in packing_vertices(normals):
        groups.setdefault(y, []).append(lam)
    out = []
    for y, lams in sorted(groups.items()):
        s = math.lcm(*(x.denominator for x in y))
        cover = symmetric_table(normals, tuple(int(x * s) for x in y))
        lcm = math.lcm(*(x.denominator for lam in lams for x in lam))
        arr = np.array([[int(x * lcm) for x in lam] for lam in lams], dtype=np.int64)
        out.append(_Check(s, cover, arr, lcm, y))
    return tuple(out)


Arc = tuple[int, int, tuple[Fraction, ...]]


def _certify(checks: tuple[_Check, ...], new: np.ndarray, fin_new: np.ndarray,
             old: np.ndarray, fin_old: np.ndarray, src: np.ndarray, dst: np.ndarray,
             wts: np.ndarray) -> list[Arc]:
    """Arcs violating ``F_v ⊆ F_u + wΔ`` (NG.8(c)), the first one per failing direction.

    ``new``/``old`` are ``(|M|, nodes)`` integer numerators at one scale ``D`` (``new`` at the
    arcs' tails, ``old`` at their heads), ``wts`` the arc weights times ``D``.
    """
    if not checks:
        return []
    arcs = fin_new[src] & fin_old[dst]
    if not arcs.any():
        return []
    src, dst, wts = src[arcs], dst[arcs], wts[arcs]
    nodes_v, nodes_u = np.unique(src), np.unique(dst)
    mnew, mold = new[:, nodes_v].T, old[:, nodes_u].T
    out: list[Arc] = []
    for chk in checks:
        cols = np.asarray(chk.cover.columns, dtype=np.int64)
        hv = cheapest(mnew[:, cols], chk.cover.scaled)
        mu = cheapest(mold, chk.lams.T)
        hv_arc = hv[np.searchsorted(nodes_v, src)].astype(object)
        mu_arc = mu[np.searchsorted(nodes_u, dst)].astype(object)
        # h_v(y) <= w + λ·m_u at scale D: h_v(y) = hv / (lcm_T · s), λ·m_u = mu / lcm_λ
        lhs = hv_arc * chk.lam_lcm
        rhs = (wts.astype(object) * chk.cover.lcm * chk.lam_lcm * chk.scale
               + mu_arc * chk.cover.lcm * chk.scale)
        bad = np.flatnonzero(lhs > rhs)
        if bad.size:
            i = int(bad[0])
            out.append((int(src[i]), int(dst[i]), chk.y))
    return out


def _coalition_certified(inst: NInstance, horizon: int | None, max_layers: int | None, *,
                         certify: bool = True
                         ) -> tuple[CoalitionValue, list[Arc],
                                    tuple[CoalitionRunner, dict[int, np.ndarray]] | None]:
    """Coalition DP value, the failing arcs (empty: certified), and the H = inf fixpoint."""
    run = CoalitionRunner(inst)
    layer = run.layer0()
    fails: list[Arc] = []
    checks = (_checks(zero_one_normals(inst.n_goals)) if inst.n_goals > 3 and certify
              else ())

    def check(new: dict[int, np.ndarray], old: dict[int, np.ndarray]) -> None:
        if checks and not fails:  # NG.4: nothing to check for N <= 3
            a, fa = run.stacked(new)
            b, fb = (a, fa) if new is old else run.stacked(old)
            fails.extend(_certify(checks, a, fa, b, fb, run.src, run.dst, run.wts))

    if horizon is not None:
        for k in range(1, horizon + 1):
            nxt = run.step(layer, k)
            check(nxt, layer)
            layer = nxt
        return run.value(layer, horizon, horizon), fails, None
    k = 0
    while True:
        k += 1
        if max_layers is not None and k > max_layers:
            raise HorizonError(f"the coalition DP did not converge within {max_layers} layers")
        nxt = run.step(layer, k)
        if k > max(inst.hops) and same_layer(nxt, layer):
            check(nxt, nxt)
            return run.value(nxt, None, k), fails, (run, nxt)
        layer = nxt


# -- the general DP (any normals), exact integers at a common scale ----------------------------

class _TooLarge(Exception):
    """The general DP's numbers left the range of exact float64/int64 arithmetic."""


class _General:
    """The normal-restricted DP (NG.7), vectorised over nodes, in exact integers at scale ``D``.

    A layer is ``(m, finite, D)``: ``m[j, v] = D · m_{n_j}(v)`` (Python-int exact, int64
    storage), ``finite[v]`` whether ``v`` reaches a goal (all normals are finite together).
    After every closure the scale is reduced to the least multiple of the weights' common
    denominator that keeps every value integral, so equal layers have equal representations.
    """

    def __init__(self, inst: NInstance, normals: tuple[Normal, ...]) -> None:
        self.inst = inst
        self.normals = normals
        self.tops = [max(x) for x in normals]
        self.tables = [symmetric_table(normals, x) for x in normals]
        self.checks = _checks(normals)
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
            raise _TooLarge
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
                raise _TooLarge
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
        return _certify(self.checks, a * (scale // sa), fa, b * (scale // sb), fb, self.src,
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


def _general(inst: NInstance, extras: list[Normal], horizon: int | None, max_layers: int,
             start: tuple[CoalitionRunner, dict[int, np.ndarray]] | None
             ) -> tuple[Fraction, int, list[Arc]]:
    normals = zero_one_normals(inst.n_goals) + tuple(extras)
    dp = _General(inst, normals)
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


def _deflated_lower(run: CoalitionRunner, layer: dict[int, np.ndarray]) -> Fraction | None:
    """NG.10: ``DP_inf - t(s0)`` for the least translations ``t`` making ``F - t·1`` a sub-fixpoint.

    ``F`` are the coalition DP's sets at its fixpoint ``layer``. With ``F'_v = F_v - t_v·1``
    (``t >= 0``, ``t = 0`` at goals) the arc condition for ``(v, u)`` reads
    ``t_v - t_u >= ℓ(v, u)``, the largest ``(h_{F_v}(y_λ) - w - λ·m_u) / (1·y_λ)`` over the vertices
    ``λ`` of the packing polytope (the 0/1 ones give ``(m_A(v) - w - m_A(u)) / |A|``). The least
    such ``t`` is a longest-path fixpoint (Bellman-Ford from ``t = 0``); None if it does not
    settle within ``n + 1`` rounds (a positive cycle).
    """
    inst = run.inst
    arr, finite = run.stacked(layer)
    keep = finite[run.src] & finite[run.dst]
    src, dst, wts = run.src[keep], run.dst[keep], run.wts[keep].astype(object)
    scale = run.scale
    frac = np.frompyfunc(lambda num, den: Fraction(int(num), int(den)), 2, 1)
    ell: np.ndarray | None = None
    for mask in range(1, 1 << inst.n_goals):
        size = bin(mask).count("1")
        e = arr[mask - 1][src].astype(object) - wts - arr[mask - 1][dst].astype(object)
        cand = frac(e, scale * size)
        ell = cand if ell is None else np.maximum(ell, cand)
    zo = zero_one_normals(inst.n_goals)
    for chk in _checks(zo):
        cols = np.asarray(chk.cover.columns, dtype=np.int64)
        hv = np.asarray(cheapest(arr[cols][:, src].T, chk.cover.scaled), dtype=object)
        mu = np.asarray(cheapest(arr[:, dst].T, chk.lams.T), dtype=object)
        num = (hv * chk.lam_lcm - wts * chk.cover.lcm * chk.scale * chk.lam_lcm
               - mu * chk.cover.lcm * chk.scale)
        ones = sum(chk.y, Fraction(0))
        den = scale * chk.cover.lcm * chk.scale * chk.lam_lcm
        cand = frac(num, den) / ones
        ell = cand if ell is None else np.maximum(ell, cand)
    if ell is None or src.size == 0:
        return Fraction(0)
    tails = np.unique(src)
    seg = np.searchsorted(src, tails)
    den = math.lcm(1, *{int(x.denominator) for x in ell})
    nums = [int(x * den) for x in ell]
    bound = (max(abs(x) for x in nums) + 1) * (inst.n_nodes + 2)
    lengths = np.asarray(nums, dtype=np.int64 if bound < 2 ** 62 else object)
    t = np.zeros(inst.n_nodes, dtype=lengths.dtype)  # t · den, exact integers
    for _ in range(inst.n_nodes + 1):
        best = np.maximum.reduceat(t[dst] + lengths, seg)
        new = t.copy()
        new[tails] = np.maximum(best, 0)
        if np.array_equal(new, t):
            return Fraction(int(t[inst.start]), den)
        t = new
    return None


def coalition_nvalue(coal: CoalitionValue, n_goals: int) -> NValue:
    """The proved value of an instance with ``n_goals <= 3`` from its coalition DP, already run.

    For two and three goals the coalition DP is the value (NG.3, NG.4), so a caller that has
    the DP (e.g. the guarantee rule's label-setting fixpoint, proofs/NSOLVE.md NSOLVE.3) need
    not run :func:`nvalue` again.

    Raises
    ------
    ValueError
        ``n_goals > 3``: there the DP is only an upper bound (NG.2); use :func:`nvalue`.

    Examples
    --------
    >>> from dppverify.structured.coalition import coalition_value
    >>> from dppverify.ngoal.examples import star3
    >>> coalition_nvalue(coalition_value(star3(), None), 3).value
    Fraction(3, 2)
    """
    if n_goals > 3:
        raise ValueError(f"the coalition DP is the value only for N <= 3 goals, not {n_goals}")
    src = ("coalition DP (NG.3: the value for two goals)" if n_goals == 2 else
           "coalition DP (NG.4: the value for three goals)")
    v = normalize(Fraction(coal.value))
    return NValue(coal.horizon, v, v, src, src, coal.layers, (), None, coal)


def nvalue(instance: NInstance, horizon: int | None, *, max_layers: int | None = None
           ) -> NValue:
    """``V_H`` of an N-goal instance (2 to 5 goals), exact where proved, else a bracket.

    For N <= 3 the coalition DP is the value (NG.3, NG.4). For N = 4, 5 the coalition DP is
    certified (NG.8) and, where it fails, refined with the failing directions (and their
    permutations) as extra facet normals, a few rounds (NG.7, NG.8; for ``H = inf`` started
    from the coalition fixpoint). ``horizon=None`` is ``H = inf``.

    Raises
    ------
    HorizonError
        If ``horizon`` is negative or no goal is reachable within it.
    OptionError
        For more than five goals.

    Examples
    --------
    >>> from dppverify.ngoal.examples import hub4, star3
    >>> nvalue(star3(), None).value
    Fraction(3, 2)
    >>> v = nvalue(hub4(), None)
    >>> v.value, v.normals
    (Fraction(12, 7), ((2, 2, 2, 1), (2, 2, 1, 2), (2, 1, 2, 2), (1, 2, 2, 2)))
    """
    inst = instance
    if not 2 <= inst.n_goals <= MAX_BALANCED:
        raise OptionError(too_many_goals(inst.n_goals))
    if horizon is not None and horizon < 0:
        raise HorizonError(f"the horizon must be a non-negative integer, got {horizon}")
    coal, fails, start = _coalition_certified(inst, horizon, max_layers)
    upper, layers = Fraction(coal.value), coal.layers
    n = inst.n_goals
    src = ("coalition DP (NG.3: the value for two goals)" if n == 2 else
           "coalition DP (NG.4: the value for three goals)" if n == 3 else
           "coalition DP, certified at every arc (NG.8)")
    if not fails:
        return NValue(horizon, normalize(upper), normalize(upper), src, src, layers, (), None,
                      coal)
    up_src = "coalition DP (NG.2: an upper bound)"
    reason = _fail_reason(inst, fails[0], "the coalition DP")
    lower, lo_src = lower_bound_simple(inst)
    fixpoint = start  # the coalition fixpoint, for NG.10 (it bounds every H)
    if fixpoint is None:
        fix = _coalition_certified(inst, None, max_layers, certify=False)
        fixpoint, dp_inf = fix[2], Fraction(fix[0].value)
    else:
        dp_inf = upper
    assert fixpoint is not None
    shift = _deflated_lower(*fixpoint)
    if shift is not None and dp_inf - shift > lower:
        lower, lo_src = dp_inf - shift, ("the coalition DP's fixpoint sets translated into a "
                                         "sub-fixpoint (NG.10)")
    if lower == upper:
        src = "coalition DP (NG.2) meeting the translated fixpoint bound (NG.10)"
        return NValue(horizon, normalize(upper), normalize(upper), src, src, layers, (), None,
                      coal)
    extras: list[Normal] = []
    up_normals: tuple[Normal, ...] = ()
    cap = max_layers if max_layers is not None else 50 * inst.n_nodes + 100
    for _ in range(MAX_ROUNDS):
        new = [d for d in extra_directions(_permutations([fails[0][2]])) if d not in extras]
        if not new:
            break
        extras += sorted(new, reverse=True)
        normals = zero_one_normals(n) + tuple(extras)
        if math.comb(len(normals) + n, n) > MAX_BASES:
            reason += (f"; refining needs {len(extras)} extra normals, beyond the vertex "
                       f"enumeration's limit ({MAX_BASES:,} bases)")
            break
        try:
            val, layers_g, fails = _general(inst, extras, horizon, cap, start)
        except (HorizonError, _TooLarge) as exc:
            reason += f"; the refined DP: {exc or 'numbers beyond exact float64 range'}"
            break
        if val < upper:
            upper, layers, up_normals = val, layers_g, tuple(extras)
            up_src = f"DP over {len(extras)} extra facet normals (NG.7: an upper bound)"
        if not fails:
            src = f"DP over {len(extras)} extra facet normals, certified at every arc (NG.8)"
            return NValue(horizon, normalize(val), normalize(val), src, src, layers_g,
                          tuple(extras), None, coal)
        if lower == upper:
            src = f"{up_src[:-1]}) meeting {lo_src}"
            return NValue(horizon, normalize(upper), normalize(upper), src, src, layers,
                          up_normals, None, coal)
        reason = _fail_reason(inst, fails[0], f"the DP with {len(extras)} extra normals")
    return NValue(horizon, normalize(lower), normalize(upper), lo_src, up_src, layers,
                  up_normals, reason, coal)


def _fail_reason(inst: NInstance, arc: Arc, what: str) -> str:
    v, u, y = arc
    return (f"arc {inst.nodes[v]!r} -> {inst.nodes[u]!r} fails the certificate of {what} in "
            f"direction ({', '.join(str(x) for x in y)})")


def _permutations(ys: list[tuple[Fraction, ...]]) -> list[tuple[Fraction, ...]]:
    """Every permutation of every direction (the goals are symmetric in the tables)."""
    out: dict[tuple[Fraction, ...], None] = {}
    for y in ys:
        for p in itertools.permutations(y):
            out[p] = None
    return list(out)
