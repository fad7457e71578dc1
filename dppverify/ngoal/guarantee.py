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
(:mod:`dppverify.ngoal.coalition`). The sets are the true ones — and the DP value is ``V_H`` —
as soon as every arc satisfies ``F_v^k ⊆ F_u^{k-1} + w·Δ^N`` (NG.8). By Farkas' lemma that
holds iff for every vertex ``λ`` of the packing polytope ``P_M = { λ >= 0 : Σ_n λ_n n <= 1 }``

    h_{F_v}(y_λ) <= w + Σ_n λ_n m_n(u),          y_λ = Σ_n λ_n n,

where ``h_{F_v}(y)`` is the cheapest cover of ``y`` by the normals at ``v``. Vertices with
``y_λ`` a 0/1 vector satisfy it automatically (step and closure), so only the few others are
checked: none for N = 3 (which proves NG.4: the coalition DP is the value), the four
permutations of (1, 1, 1, 1/2) for N = 4 and 45 vectors for N = 5.

:func:`nvalue` runs the coalition DP, certifies it (``H = inf``: at the repeated layer, NG.8
then gives ``V_H`` for every ``H`` from that layer on; finite ``H``: at every layer) and, when
an arc fails, adds the failing directions ``y_λ`` to ``M`` and re-runs the general DP in exact
rationals (a few rounds, small instances). Where no certificate is found it returns a bracket
naming both bounds. Everything is exact: integer scaling and exact divisibility for the
coalition layers, ``Fraction`` arithmetic in the general DP, vertices by exact integer
determinants (no polyhedral library: the normals form a fixed small table, so every basis is
enumerated once per table).
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
from dppverify.exact import INF, Number, normalize
from dppverify.ngoal.coalition import CoalitionValue, _Runner, _same, too_many_goals
from dppverify.ngoal.cover import MAX_BALANCED, _dets, min_cover_vectors
from dppverify.ngoal.instance import NInstance

__all__ = ["NValue", "Table", "basic_solutions", "extra_directions", "lower_bound_simple",
           "nvalue", "packing_vertices", "zero_one_normals"]

Normal = tuple[int, ...]

MAX_ROUNDS = 4
"""Refinement rounds of the general DP (each adds the failing directions as normals)."""

MAX_GENERAL_WORK = 4_000_000
"""Rough limit on (nodes × layers × table entries) for the exact general DP."""


@dataclass(frozen=True)
class Table:
    """The vertices of ``{c >= 0 : Σ_j c_j columns[j] = rhs}``, scaled to integers.

    Attributes
    ----------
    columns : tuple of int
        Indices of the columns (into the caller's list) that may be positive.
    scaled : numpy.ndarray
        ``lcm · c`` for every vertex: shape ``(len(columns), n_vertices)``, int64.
    lcm : int
        Common denominator of every vertex coordinate.
    """

    columns: tuple[int, ...]
    scaled: np.ndarray
    lcm: int

    @property
    def vertices(self) -> list[tuple[Fraction, ...]]:
        """The vertices as exact fractions (one entry per column)."""
        return [tuple(Fraction(int(x), self.lcm) for x in col) for col in self.scaled.T]


def basic_solutions(columns: Sequence[Sequence[int]], rhs: Sequence[int]) -> Table:
    """Every vertex of ``{c >= 0 : Σ_j c_j columns[j] = rhs}`` (non-negative integer data).

    Rows outside the support of ``rhs`` force the columns that use them to 0; on the
    support, the unit vectors must be among the columns (full row rank). The vertices are the
    basic feasible solutions: every choice of ``|support|`` columns with a non-zero exact
    integer determinant, solved by Cramer's rule, kept when non-negative, de-duplicated.

    Examples
    --------
    The fractional covers of (1, 1, 1) by the non-empty subsets of three goals (as 0/1
    columns): the five minimal balanced collections plus the whole set itself.

    >>> cols = [tuple((s >> i) & 1 for i in range(3)) for s in range(1, 8)]
    >>> t = basic_solutions(cols, (1, 1, 1))
    >>> t.scaled.shape[1], t.lcm
    (6, 2)
    """
    rhs = tuple(int(x) for x in rhs)
    return _basic_solutions(tuple(tuple(int(x) for x in c) for c in columns), rhs)


@cache
def _basic_solutions(columns: tuple[Normal, ...], rhs: Normal) -> Table:
    rows = [i for i, x in enumerate(rhs) if x != 0]
    keep = [j for j, c in enumerate(columns)
            if any(c) and all(c[i] == 0 for i in range(len(rhs)) if rhs[i] == 0)]
    m = len(rows)
    if m == 0:
        return Table(columns=(), scaled=np.zeros((0, 1), dtype=np.int64), lcm=1)
    mat = np.array([[columns[j][i] for j in keep] for i in rows], dtype=np.int64)
    b = np.array([rhs[i] for i in rows], dtype=np.int64)
    found: list[np.ndarray] = []
    dens: list[int] = []
    all_combos = itertools.combinations(range(len(keep)), m)
    while True:
        chunk = np.array(list(itertools.islice(all_combos, 200_000)), dtype=np.int64)
        if chunk.size == 0:
            break
        entries = [[np.ascontiguousarray(mat[r, chunk[:, c]]) for c in range(m)]
                   for r in range(m)]
        det = _dets(entries)
        ok = det != 0
        chunk, det = chunk[ok], det[ok]
        entries = [[e[ok] for e in row] for row in entries]
        if not chunk.size:
            continue
        numer = np.empty((chunk.shape[0], m), dtype=np.int64)
        for i in range(m):  # Cramer: column i replaced by the right-hand side
            numer[:, i] = _dets([[np.full(chunk.shape[0], b[r]) if c == i else entries[r][c]
                                  for c in range(m)] for r in range(m)])
        sign = np.sign(det)[:, None]
        feas = np.all(numer * sign >= 0, axis=1)
        chunk, det, numer = chunk[feas], det[feas], numer[feas]
        common = int(np.lcm.reduce(np.abs(det))) if det.size else 1
        dense = np.zeros((chunk.shape[0], len(keep)), dtype=np.int64)
        idx = np.arange(chunk.shape[0])
        for i in range(m):
            dense[idx, chunk[:, i]] = numer[:, i] * (common // det)
        found.append(dense)
        dens.append(common)
    lcm = math.lcm(1, *dens)
    stacked = np.concatenate([d * (lcm // c) for d, c in zip(found, dens, strict=True)]) \
        if found else np.zeros((0, len(keep)), dtype=np.int64)
    unique = np.unique(stacked, axis=0)
    g = int(np.gcd.reduce(np.append(unique.ravel(), lcm)))
    return Table(columns=tuple(keep), scaled=np.ascontiguousarray((unique // g).T),
                 lcm=lcm // g)


def zero_one_normals(n_goals: int) -> tuple[Normal, ...]:
    """The 0/1 normals ``1_S`` in mask order (``mask = 1 … 2^N - 1``).

    Examples
    --------
    >>> zero_one_normals(2)
    ((1, 0), (0, 1), (1, 1))
    """
    return tuple(tuple((s >> i) & 1 for i in range(n_goals)) for s in range(1, 1 << n_goals))


@cache
def packing_vertices(normals: tuple[Normal, ...]) -> tuple[tuple[tuple[Fraction, ...],
                                                                tuple[Fraction, ...]], ...]:
    """The vertices ``λ`` of ``{λ >= 0 : Σ_n λ_n n <= 1}`` with ``y_λ = Σ_n λ_n n`` not 0/1.

    Returned as pairs ``(λ, y_λ)``. Vertices whose ``y_λ`` is a 0/1 vector are left out: the
    arc condition holds for them automatically (``proofs/NGOAL.md`` NG.8).

    Examples
    --------
    >>> len(packing_vertices(zero_one_normals(3)))
    0
    >>> sorted({y for _, y in packing_vertices(zero_one_normals(4))})[0]
    (Fraction(1, 2), Fraction(1, 1), Fraction(1, 1), Fraction(1, 1))
    """
    n = len(normals[0])
    slack = tuple(tuple(int(i == j) for i in range(n)) for j in range(n))
    table = basic_solutions(normals + slack, (1,) * n)
    out = []
    for v in table.vertices:
        lam = [Fraction(0)] * len(normals)
        for pos, col in enumerate(table.columns):
            if col < len(normals):
                lam[col] = v[pos]
        y = tuple(sum((lam[j] * normals[j][i] for j in range(len(normals))), Fraction(0))
                  for i in range(n))
        if any(x not in (0, 1) for x in y):
            out.append((tuple(lam), y))
    return tuple(sorted(set(out)))


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
    """The arc test for one direction ``y`` (0/1 normals): cover table of ``s·y``, ``λ``s."""

    scale: int  # s: s·y is an integer vector
    cover: Table  # vertices of {c >= 0 : Σ_T c_T 1_T = s·y}, columns = mask - 1
    lams: np.ndarray  # (n_lambda, 2^N - 1): lcm_l · λ
    lam_lcm: int
    y: tuple[Fraction, ...]


@cache
def _checks01(n_goals: int) -> tuple[_Check, ...]:
    normals = zero_one_normals(n_goals)
    groups: dict[tuple[Fraction, ...], list[tuple[Fraction, ...]]] = {}
    for lam, y in packing_vertices(normals):
        groups.setdefault(y, []).append(lam)
    out = []
    for y, lams in sorted(groups.items()):
        s = math.lcm(*(x.denominator for x in y))
        cover = basic_solutions(normals, tuple(int(x * s) for x in y))
        lcm = math.lcm(*(x.denominator for lam in lams for x in lam))
        arr = np.array([[int(x * lcm) for x in lam] for lam in lams], dtype=np.int64)
        out.append(_Check(s, cover, arr, lcm, y))
    return tuple(out)


def _matmin(mat: np.ndarray, table: np.ndarray, exact_float: bool) -> np.ndarray:
    """Row-wise ``min`` of ``mat @ table`` (integers; float64 BLAS when provably exact)."""
    if exact_float:
        return (mat.astype(np.float64) @ table.astype(np.float64)).min(axis=1).astype(np.int64)
    return (mat.astype(object) @ table.astype(object)).min(axis=1)


def _certify01(run: _Runner, new: dict[int, np.ndarray], old: dict[int, np.ndarray]
               ) -> tuple[int, int, tuple[Fraction, ...]] | None:
    """The first arc ``(v, u)`` violating ``F_v ⊆ F_u + wΔ`` (new layer at v, old at u)."""
    checks = _checks01(run.inst.n_goals)
    if not checks or run.src.size == 0:
        return None
    n_masks = (1 << run.inst.n_goals) - 1
    big = run.big
    finite_new = new[1] < big
    finite_old = old[1] < big
    arcs = finite_new[run.src] & finite_old[run.dst]
    if not arcs.any():
        return None
    src, dst, wts = run.src[arcs], run.dst[arcs], run.wts[arcs]
    nodes_v = np.unique(src)
    nodes_u = np.unique(dst)
    mnew = np.stack([new[m][nodes_v] for m in range(1, n_masks + 1)], axis=1)
    mold = np.stack([old[m][nodes_u] for m in range(1, n_masks + 1)], axis=1)
    bound = int(max(int(mnew.max()), int(mold.max()), 1))
    for chk in checks:
        tab = chk.cover.scaled
        cols = np.asarray(chk.cover.columns, dtype=np.int64)
        width = bound * int(np.abs(tab).sum(axis=0).max(initial=1)) + 1
        hv = _matmin(mnew[:, cols], tab, width < 2 ** 53)
        width_l = bound * int(chk.lams.sum(axis=1).max(initial=1)) + 1
        mu = _matmin(mold, chk.lams.T, width_l < 2 ** 53)
        hv_arc = hv[np.searchsorted(nodes_v, src)].astype(object)
        mu_arc = mu[np.searchsorted(nodes_u, dst)].astype(object)
        # h_v(y) <= w + λ·m_u, all at the DP scale: h_v(y) = hv / (lcm_T · s)
        lhs = hv_arc * chk.lam_lcm
        rhs = (wts.astype(object) * chk.cover.lcm * chk.lam_lcm * chk.scale
               + mu_arc * chk.cover.lcm * chk.scale)
        bad = np.flatnonzero(lhs > rhs)
        if bad.size:
            i = int(bad[0])
            return int(src[i]), int(dst[i]), chk.y
    return None


def _coalition_certified(inst: NInstance, horizon: int | None, max_layers: int | None
                         ) -> tuple[CoalitionValue, str | None, list[tuple[Fraction, ...]]]:
    """Coalition DP value, layers, and the first failure (None: certified) with its y's."""
    run = _Runner(inst)
    layer = run.layer0()
    fails: list[tuple[Fraction, ...]] = []
    reason: str | None = None

    def check(new: dict[int, np.ndarray], old: dict[int, np.ndarray], k: int) -> None:
        nonlocal reason
        if inst.n_goals <= 3:
            return  # NG.4: the coalition DP is the value
        bad = _certify01(run, new, old)
        if bad is not None:
            v, u, y = bad
            fails.append(y)
            if reason is None:
                reason = (f"arc {inst.nodes[v]!r} -> {inst.nodes[u]!r} (layer {k}) fails the "
                          f"certificate in direction ({', '.join(str(x) for x in y)})")

    if horizon is not None:
        for k in range(1, horizon + 1):
            nxt = run.step(layer, k)
            check(nxt, layer, k)
            layer = nxt
        return run.value(layer, horizon, horizon), reason, fails
    k = 0
    while True:
        k += 1
        if max_layers is not None and k > max_layers:
            raise HorizonError(f"the coalition DP did not converge within {max_layers} layers")
        nxt = run.step(layer, k)
        if k > max(inst.hops) and _same(nxt, layer):
            check(nxt, nxt, k)
            return run.value(nxt, None, k), reason, fails
        layer = nxt


# -- the general DP (any normals), exact rationals ---------------------------------------------

def _cover_min(tab: Table, costs: Sequence[Number]) -> Number:
    """``min`` over the table's vertices ``c`` of ``Σ_j c_j costs[columns[j]]`` (inf-aware)."""
    best: Number = INF
    vals = [costs[c] for c in tab.columns]
    for vert in tab.scaled.T:
        if any(x and vals[i] == INF for i, x in enumerate(vert)):
            continue
        tot = sum((int(x) * vals[i] for i, x in enumerate(vert) if x), Fraction(0))
        best = min(best, tot / tab.lcm)
    return best


def _multiple(y: Sequence[Fraction]) -> Fraction:
    """``k`` with ``extra_directions([y])[0] = k·y``."""
    i = next(i for i, x in enumerate(y) if x)
    return Fraction(extra_directions([y])[0][i]) / y[i]


class _General:
    """The normal-restricted DP in exact rationals (``math.inf`` off the reachable set)."""

    def __init__(self, inst: NInstance, normals: tuple[Normal, ...]) -> None:
        self.inst = inst
        self.normals = normals
        self.tops = [max(n) for n in normals]
        self.closure = [basic_solutions(normals, n) for n in normals]
        self.checks = packing_vertices(normals)
        self.covers = {y: basic_solutions(normals, extra_directions([y])[0])
                       for _, y in self.checks}
        self.goal = set(inst.goals)
        self.arcs = [(v, u, Fraction(w)) for v in range(inst.n_nodes) if v not in self.goal
                     for u, w in inst.succ[v]]
        self.term = {g: [sum((Fraction(n[t]) * Fraction(inst.dist_to[t][g])
                              for t in range(inst.n_goals)), Fraction(0)) for n in normals]
                     for g in inst.goals}

    def layer0(self) -> list[list[Number]]:
        inf: list[Number] = [INF] * len(self.normals)
        return [list(self.term[v]) if v in self.goal else list(inf)
                for v in range(self.inst.n_nodes)]

    def _close(self, a: list[Number]) -> list[Number]:
        return [_cover_min(tab, a) for tab in self.closure]

    def step(self, prev: list[list[Number]]) -> list[list[Number]]:
        nxt: list[list[Number]] = [list(r) for r in prev]
        best: dict[int, list[Number]] = {}
        for v, u, w in self.arcs:
            cand = [w * t + x for t, x in zip(self.tops, prev[u], strict=True)]
            row = best.setdefault(v, [INF] * len(self.normals))
            for j, c in enumerate(cand):
                if c < row[j]:
                    row[j] = c
        for v in range(self.inst.n_nodes):
            if v not in self.goal:
                nxt[v] = self._close(best[v]) if v in best else [INF] * len(self.normals)
        return nxt

    def h(self, m: list[Number], y: tuple[Fraction, ...]) -> Number:
        """The cheapest cover of ``y`` by the normals with costs ``m``."""
        return _cover_min(self.covers[y], m) / _multiple(y)

    def certify(self, new: list[list[Number]], old: list[list[Number]]
                ) -> list[tuple[int, int, tuple[Fraction, ...]]]:
        bad = []
        seen: set[tuple[Fraction, ...]] = set()
        hs: dict[tuple[int, tuple[Fraction, ...]], Number] = {}
        for v, u, w in self.arcs:
            if new[v][0] == INF or old[u][0] == INF:
                continue
            for lam, y in self.checks:
                if y in seen:
                    continue
                key = (v, y)
                if key not in hs:
                    hs[key] = self.h(new[v], y)
                mu = sum((x * old[u][j] for j, x in enumerate(lam) if x), Fraction(0))
                if hs[key] > w + mu:
                    bad.append((v, u, y))
                    seen.add(y)
        return bad

    def value(self, layer: list[list[Number]]) -> Fraction:
        costs = layer[self.inst.start]
        if costs[0] == INF:
            raise HorizonError("no walk from the start reaches a goal within the horizon")
        lp = min_cover_vectors(self.normals, [Fraction(c) for c in costs], self.inst.prior)
        return lp.value


def _general(inst: NInstance, extras: list[Normal], horizon: int | None,
             max_layers: int) -> tuple[Fraction, int, list[tuple[int, int, tuple[Fraction, ...]]]]:
    normals = zero_one_normals(inst.n_goals) + tuple(extras)
    dp = _General(inst, normals)
    layer = dp.layer0()
    fails: list[tuple[int, int, tuple[Fraction, ...]]] = []
    if horizon is not None:
        for _ in range(horizon):
            nxt = dp.step(layer)
            fails += dp.certify(nxt, layer)
            layer = nxt
        return dp.value(layer), horizon, fails
    k = 0
    while True:
        k += 1
        if k > max_layers:
            raise HorizonError(f"the general DP did not converge within {max_layers} layers")
        nxt = dp.step(layer)
        if k > max(inst.hops) and nxt == layer:
            return dp.value(nxt), k, dp.certify(nxt, nxt)
        layer = nxt


def nvalue(instance: NInstance, horizon: int | None, *, max_layers: int | None = None
           ) -> NValue:
    """``V_H`` of an N-goal instance (2 to 5 goals), exact where proved, else a bracket.

    For N <= 3 the coalition DP is the value (NG.3, NG.4). For N = 4, 5 the coalition DP is
    certified (NG.8) and, where it fails, refined with the failing directions as extra facet
    normals (general DP, exact rationals, small instances). ``horizon=None`` is ``H = inf``.

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
    coal, reason, fails = _coalition_certified(inst, horizon, max_layers)
    upper, layers = Fraction(coal.value), coal.layers
    n = inst.n_goals
    src = ("coalition DP (NG.3: the value for two goals)" if n == 2 else
           "coalition DP (NG.4: the value for three goals)" if n == 3 else
           "coalition DP, certified at every arc (NG.8)")
    if reason is None:
        return NValue(horizon, normalize(upper), normalize(upper), src, src, layers, (), None,
                      coal)
    up_src = "coalition DP (NG.2: an upper bound)"
    extras: list[Normal] = []
    cap = max_layers if max_layers is not None else 50 * inst.n_nodes + 100
    work = inst.n_nodes * (layers + 1)
    for _ in range(MAX_ROUNDS):
        new = [d for d in extra_directions(_permutations(fails)) if d not in extras]
        if not new:
            break
        extras += sorted(new, reverse=True)
        size = sum(basic_solutions(zero_one_normals(n) + tuple(extras), e).scaled.size
                   for e in extras)
        if work * size > MAX_GENERAL_WORK:
            reason += f"; the refined DP ({len(extras)} extra normals) is beyond its size limit"
            break
        try:
            val, layers_g, bad = _general(inst, extras, horizon, cap)
        except HorizonError as exc:
            reason += f"; the refined DP: {exc}"
            break
        if val < upper:
            upper, layers, up_src = (val, layers_g, f"DP over {len(extras)} extra facet "
                                     "normals (NG.7: an upper bound)")
        if not bad:
            src = f"DP over {len(extras)} extra facet normals, certified at every arc (NG.8)"
            return NValue(horizon, normalize(val), normalize(val), src, src, layers_g,
                          tuple(extras), None, coal)
        v, u, y = bad[0]
        reason = (f"arc {inst.nodes[v]!r} -> {inst.nodes[u]!r} fails the certificate of the "
                  f"DP with {len(extras)} extra normals in direction "
                  f"({', '.join(str(x) for x in y)})")
        fails = [b[2] for b in bad]
    lower, lo_src = lower_bound_simple(inst)
    return NValue(horizon, normalize(lower), normalize(upper), lo_src, up_src, layers,
                  tuple(extras), reason, coal)


def _permutations(ys: list[tuple[Fraction, ...]]) -> list[tuple[Fraction, ...]]:
    """Every permutation of every direction (the goals are symmetric in the tables)."""
    out: dict[tuple[Fraction, ...], None] = {}
    for y in ys:
        for p in itertools.permutations(y):
            out[p] = None
    return list(out)
