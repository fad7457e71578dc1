"""The exact guarantee sets of the N-goal game at ``H = inf``, on a refined set of facet normals.

For a finite set ``A`` of non-negative integer normals (every 0/1 vector among them, closed
under permutations of the goals) the *normal-restricted DP* (proofs/NGOAL.md NG.7) is, layer
by layer from the goals,

    m_a(g, k) = a·d(g, g^·)  at a goal g;     m_a(v, 0) = +inf elsewhere;
    s_a(v, k) = min_{(v,u)} [ w(v,u)·max(a) + m_a(u, k-1) ]                      (the step)
    m_a(v, k) = min { Σ_n c_n s_n(v, k) : c >= 0, Σ_n c_n n = a }               (the closure)

and ``F_v^k = {r : a·r <= m_a(v, k) ∀ a ∈ A}`` contains the exact set ``G_v^k``. Everything
here is exact integers at a common scale ``D`` (numpy int64, products in float64 only when
every partial sum is an integer below 2**53). The layers are computed incrementally (only the
tails of arcs into changed nodes are recomputed) until one repeats: the *fixpoint* ``m*`` (the
greatest fixpoint of the layer map), reached at layer ``K``. ``rank[a, v]`` is the layer at
which ``m_a(v)`` reached its final value; the Attacker of
:mod:`solver.coalitions.normal_attacker` walks down the ranks, so its walks have at most
``K`` steps (proofs/NEXACT.md NX.2).

:func:`guarantee_sets` finds ``A`` by *refinement*: the DP with the 0/1 normals, the arc test
``F_v ⊆ F_u + wΔ`` at its fixpoint (Farkas, on the packing polytope's directions,
:mod:`solver.coalitions.vertex_tables`); where it fails, the DP is re-run with the test at
every layer, and at the first failing layer ``k`` (every earlier layer then *is* the exact
set) the exact set ``G_v^k = ∩_u (F_u^{k-1} + wΔ)`` at a failing node is written out in
H-representation,
its facets that ``F_v^k`` violates are found (a candidate is a facet iff the other candidates
do not cover it as cheaply: one exact LP), and they join ``A`` with their permutations. Every
normal added is a facet normal of an exact layer set (or a permutation of one), so the
refinement stops whenever the exact layers repeat (proofs/NEXACT.md NX.6); a budget of rounds,
layers, normals and bases bounds it otherwise, and the caller reports the bracket.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from functools import cache, cached_property

import numpy as np

from solver.coalitions.block_fixpoint import block_fixpoint, fixpoint_ranks
from solver.coalitions.normal_cover import normal_cover_lp
from solver.coalitions.vertex_tables import (
    Direction,
    Normal,
    VertexTable,
    packing_vertices,
    primitive,
    vertex_table,
    zero_one_normals,
)
from solver.graph.distances import EXACT_FLOAT_LIMIT

INT_LIMIT = 2 ** 62


class BudgetExceeded(Exception):
    """The fixpoint or the normals were not found within the stated budget."""


@dataclass(frozen=True)
class Budget:
    """Limits of the refinement (``dpp solve`` states them when one is reached).

    Attributes
    ----------
    rounds : int
        Refinement rounds (each adds at least one facet normal).
    layers : int or None
        DP layers per run (None: ``20 · nodes + 200``).
    extra_normals : int
        Normals beyond the ``2^N - 1`` 0/1 vectors.
    bases : int
        Bases tried for one vertex table.
    """

    rounds: int = 12
    layers: int | None = None
    extra_normals: int = 80
    bases: int = 20_000_000

    def describe(self) -> str:
        """One phrase naming the limits.

        Examples
        --------
        >>> Budget().describe()
        '12 refinement rounds, 20·nodes + 200 layers, 80 extra normals, 20,000,000 bases'
        """
        layers = "20·nodes + 200" if self.layers is None else f"{self.layers:,}"
        return (f"{self.rounds} refinement rounds, {layers} layers, {self.extra_normals} extra "
                f"normals, {self.bases:,} bases")


@dataclass(frozen=True, eq=False)
class ArcGraph:
    """The walkable part of an N-goal game as arrays.

    Attributes
    ----------
    indptr, heads, weights : numpy.ndarray
        The arcs out of non-goal nodes, by tail (CSR); weights are int64 numerators over
        ``denominator``.
    denominator : int
        The weights' common denominator.
    goals : tuple of int
        Goal nodes, ``goals[θ]`` is type θ's goal.
    terminal : numpy.ndarray
        ``terminal[i, θ]``: ``d(goals[i], g^θ)`` as a numerator over ``denominator``.
    start : int
        The start node.
    """

    indptr: np.ndarray
    heads: np.ndarray
    weights: np.ndarray
    denominator: int
    goals: tuple[int, ...]
    terminal: np.ndarray
    start: int
    tails: np.ndarray = field(init=False, repr=False)
    rev_indptr: np.ndarray = field(init=False, repr=False)
    rev_tails: np.ndarray = field(init=False, repr=False)
    is_goal: np.ndarray = field(init=False, repr=False)

    def __post_init__(self) -> None:
        n = self.n_nodes
        tails = np.repeat(np.arange(n, dtype=np.int64), np.diff(self.indptr))
        order = np.argsort(self.heads, kind="stable")
        rev = np.zeros(n + 1, dtype=np.int64)
        np.add.at(rev, self.heads + 1, 1)
        object.__setattr__(self, "tails", tails)
        object.__setattr__(self, "rev_indptr", np.cumsum(rev))
        object.__setattr__(self, "rev_tails", tails[order])
        goal = np.zeros(n, dtype=bool)
        goal[list(self.goals)] = True
        object.__setattr__(self, "is_goal", goal)

    @property
    def n_nodes(self) -> int:
        """Number of nodes."""
        return len(self.indptr) - 1

    @property
    def n_goals(self) -> int:
        """``N``."""
        return len(self.goals)

    def arcs_of(self, nodes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The arc indices out of ``nodes`` (concatenated) and each node's first position."""
        lo, hi = self.indptr[nodes], self.indptr[nodes + 1]
        counts = hi - lo
        seg = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(np.int64)
        idx = np.arange(int(counts.sum()), dtype=np.int64) - np.repeat(seg - lo, counts)
        return idx, seg

    def tails_into(self, nodes: np.ndarray) -> np.ndarray:
        """The distinct tails of arcs into ``nodes``."""
        lo, hi = self.rev_indptr[nodes], self.rev_indptr[nodes + 1]
        counts = hi - lo
        if not counts.sum():
            return np.zeros(0, dtype=np.int64)
        seg = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(np.int64)
        idx = np.arange(int(counts.sum()), dtype=np.int64) - np.repeat(seg - lo, counts)
        return np.unique(self.rev_tails[idx])


def min_product(values: np.ndarray, scaled: np.ndarray) -> np.ndarray:
    """Row-wise ``min`` of ``values @ scaled`` for non-negative int64 data, exactly.

    float64 when every partial sum is provably an integer below 2**53, else Python integers.

    Examples
    --------
    >>> min_product(np.array([[2, 3, 4], [2, 3, 6]]), np.array([[1, 0], [1, 0], [0, 1]])
    ...             ).tolist()
    [4, 5]
    """
    if values.shape[0] == 0:
        return np.zeros(0, dtype=np.int64)
    top = int(values.max(initial=0))
    width = (top + 1) * (int(np.abs(scaled).sum(axis=0).max(initial=1)) + 1)
    if width < EXACT_FLOAT_LIMIT:
        return (values.astype(np.float64) @ scaled.astype(np.float64)).min(axis=1).astype(
            np.int64)
    out = (values.astype(object) @ scaled.astype(object)).min(axis=1)
    if max(int(x) for x in out) >= INT_LIMIT:
        raise BudgetExceeded("numbers beyond the exact int64 range")
    return out.astype(np.int64)


def symmetric_closure(normals: Sequence[Normal]) -> tuple[Normal, ...]:
    """The normals with every permutation of each, 0/1 vectors first (mask order), the others
    sorted decreasingly.

    Examples
    --------
    >>> symmetric_closure([(2, 2, 1)])
    ((1, 0, 0), (0, 1, 0), (1, 1, 0), (0, 0, 1), (1, 0, 1), (0, 1, 1), (1, 1, 1), (2, 2, 1), \
(2, 1, 2), (1, 2, 2))
    """
    n = len(normals[0])
    zo = zero_one_normals(n)
    extra = {p for a in normals for p in itertools.permutations(a)} - set(zo)
    return zo + tuple(sorted(extra, reverse=True))


@dataclass(frozen=True, eq=False)
class NormalSystem:
    """A normal set ``A`` with its tables: closures, packing directions, packing vertices.

    ``normals`` must be closed under permutations (:func:`symmetric_closure`); tables of
    permuted right-hand sides are shared. With ``dominated`` the closure of ``a`` uses only the
    normals ``n <= a`` (componentwise): the reading of ``docs/formats.md`` §2b by which the
    checker judges a written rule; its values need not be closed, so every direction of the
    packing polytope is tested, the 0/1 ones included.
    """

    normals: tuple[Normal, ...]
    dominated: bool = False
    tops: np.ndarray = field(init=False, repr=False)
    closures: tuple[VertexTable, ...] = field(init=False, repr=False)
    directions: tuple[Direction, ...] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "tops", np.array([max(a) for a in self.normals],
                                                  dtype=np.int64))
        if self.dominated:
            closures = tuple(_dominated_table(self.normals, a) for a in self.normals)
        else:
            closures = tuple(symmetric_table(self.normals, a) for a in self.normals)
        object.__setattr__(self, "closures", closures)
        object.__setattr__(self, "directions",
                           packing_directions_symmetric(self.normals, self.dominated))

    @property
    def n_goals(self) -> int:
        """``N``."""
        return len(self.normals[0])

    @property
    def lcm(self) -> int:
        """The lcm of the closure tables' denominators."""
        return math.lcm(1, *(t.lcm for t in self.closures))


def symmetric_table(normals: tuple[Normal, ...], rhs: Normal) -> VertexTable:
    """The cover table of ``rhs`` from that of its sorted permutation (normals closed under
    permutations).

    Examples
    --------
    >>> zo = zero_one_normals(3)
    >>> a = symmetric_table(zo, (1, 0, 1)).vertices()
    >>> b = vertex_table(zo, (1, 0, 1)).vertices()
    >>> sorted(sorted(v.items()) for v in a) == sorted(sorted(v.items()) for v in b)
    True
    """
    n = len(rhs)
    order = sorted(range(n), key=lambda i: (-rhs[i], i))  # sorted[k] = rhs[order[k]]
    base = vertex_table(normals, tuple(rhs[i] for i in order))
    inv = [0] * n
    for k, i in enumerate(order):
        inv[i] = k
    index = {v: j for j, v in enumerate(normals)}
    cols = tuple(index[tuple(normals[j][inv[i]] for i in range(n))] for j in base.columns)
    return VertexTable(columns=cols, scaled=base.scaled, lcm=base.lcm)


def _dominated_table(normals: tuple[Normal, ...], a: Normal) -> VertexTable:
    """The covers of ``a`` by the normals ``n <= a`` (``a`` itself included: the step)."""
    keep = [j for j, n in enumerate(normals) if all(x <= y for x, y in zip(n, a, strict=True))]
    sub = vertex_table(tuple(normals[j] for j in keep), a)
    return VertexTable(columns=tuple(keep[c] for c in sub.columns), scaled=sub.scaled,
                       lcm=sub.lcm)


@cache
def packing_directions_symmetric(normals: tuple[Normal, ...], every: bool = False
                                 ) -> tuple[Direction, ...]:
    """:func:`solver.coalitions.vertex_tables.packing_directions` with the cover tables shared
    by symmetry (``every``: the 0/1 directions too)."""
    out = []
    for d in packing_directions_raw(normals, every):
        s, y, lams, lcm = d
        cover = symmetric_table(normals, tuple(int(x * s) for x in y))
        out.append(Direction(y, s, cover, lams, lcm))
    return tuple(out)


@cache
def packing_directions_raw(normals: tuple[Normal, ...], every: bool = False
                           ) -> tuple[tuple[int, tuple[Fraction, ...], np.ndarray, int], ...]:
    """``(s, y, lam_lcm · λs, lam_lcm)`` per non-0/1 direction of the packing vertices (every
    non-zero direction with ``every``)."""
    n = len(normals[0])
    groups: dict[tuple[Fraction, ...], list[tuple[Fraction, ...]]] = {}
    for lam in packing_vertices(normals):
        y = tuple(sum((lam[j] * normals[j][i] for j in range(len(normals)) if lam[j]),
                      Fraction(0)) for i in range(n))
        if not any(y) or (not every and all(x in (0, 1) for x in y)):
            continue
        groups.setdefault(y, []).append(lam)
    out = []
    for y, lams in sorted(groups.items()):
        s = math.lcm(*(x.denominator for x in y))
        lcm = math.lcm(*(x.denominator for lam in lams for x in lam))
        arr = np.array([[int(x * lcm) for x in lam] for lam in lams], dtype=np.int64)
        out.append((s, y, arr, lcm))
    return tuple(out)


def failing_arcs(directions: Sequence[Direction], tail_vals: np.ndarray, head_vals: np.ndarray,
                 tail_pos: np.ndarray, head_pos: np.ndarray, w_scaled: np.ndarray
                 ) -> np.ndarray:
    """A mask over arcs violating ``F_v ⊆ F_u + wΔ`` (proofs/NGOAL.md NG.8(c)).

    ``tail_vals``/``head_vals`` are ``(|A|, k)`` numerators at one scale ``D`` (the distinct
    tails and heads), ``tail_pos``/``head_pos`` each arc's column in them, ``w_scaled`` the
    weights times ``D``. Only the non-0/1 directions are tested (the others hold by the step and
    the closure).
    """
    bad = np.zeros(len(tail_pos), dtype=bool)
    if not len(tail_pos):
        return bad
    for d in directions:
        cols = np.asarray(d.cover.columns, dtype=np.int64)
        hv = min_product(tail_vals[cols].T, d.cover.scaled)[tail_pos]
        mu = min_product(head_vals.T, d.lams.T)[head_pos]
        # h_v(y) <= w + λ·m_u:  hv / (lcm_T · s) <= w + mu / lcm_λ   (all at scale D)
        f_w, f_mu = d.cover.lcm * d.lam_lcm * d.scale, d.cover.lcm * d.scale
        top = max(int(hv.max(initial=0)) * d.lam_lcm,
                  int(w_scaled.max(initial=0)) * f_w + int(mu.max(initial=0)) * f_mu)
        if max(top, f_w, f_mu, d.lam_lcm) < INT_LIMIT:  # int64 holds every term exactly
            bad |= hv * d.lam_lcm > w_scaled * f_w + mu * f_mu
        else:
            lhs = hv.astype(object) * d.lam_lcm
            rhs = w_scaled.astype(object) * f_w + mu.astype(object) * f_mu
            bad |= np.asarray(lhs > rhs, dtype=bool)
    return bad


@dataclass(frozen=True, eq=False)
class Fixpoint:
    """A repeated layer of the normal-restricted DP.

    Attributes
    ----------
    system : NormalSystem
        The normals.
    m : numpy.ndarray
        ``(|A|, nodes)`` int64 numerators: ``m_a(v) = m[a, v] / scale`` where ``finite[v]``.
    scale : int
        The common denominator ``D``.
    finite : numpy.ndarray
        Whether a goal is reachable from the node.
    ranks : callable
        Gives :attr:`rank` (computed on first use: only the certified fixpoint's Attacker and
        ``K`` need them).
    """

    system: NormalSystem
    m: np.ndarray
    scale: int
    finite: np.ndarray
    ranks: Callable[[], np.ndarray] = field(repr=False)

    @cached_property
    def rank(self) -> np.ndarray:
        """``(|A|, nodes)``: the layer at which ``m_a(v)`` reached its final value."""
        return self.ranks()

    @cached_property
    def layers(self) -> int:
        """``K``: the last layer that changed something."""
        return int(self.rank.max(initial=0))

    def value(self, j: int, v: int) -> Fraction:
        """``m_{a_j}(v)`` exactly."""
        return Fraction(int(self.m[j, v]), self.scale)


@dataclass(frozen=True)
class LayerFailure:
    """The first layer ``k`` where ``F_v^k ⊄ F_u^{k-1} + wΔ``: its failing tails and the
    values of layers ``k`` (at the recomputed ``rows``) and ``k - 1`` (all nodes) at scale
    ``scale`` (``layer`` -1: the failures of a fixpoint, both layers the repeated one)."""

    layer: int
    tails: np.ndarray
    rows: np.ndarray
    new: np.ndarray
    old: np.ndarray
    old_finite: np.ndarray
    scale: int


def layered_dp(graph: ArcGraph, system: NormalSystem, *, check_layers: bool,
               max_layers: int) -> Fixpoint | LayerFailure:
    """The normal-restricted DP from the goals until a layer repeats (or, with
    ``check_layers``, until the first layer failing the arc test).

    Raises
    ------
    BudgetExceeded
        After ``max_layers`` layers, or when the numbers leave the exact range.
    """
    n = graph.n_nodes
    a = len(system.normals)
    den = graph.denominator
    scale = den
    m = np.zeros((a, n), dtype=np.int64)
    finite = np.zeros(n, dtype=bool)
    rank = np.zeros((a, n), dtype=np.int32)
    normals = np.array(system.normals, dtype=np.int64)  # (|A|, N)
    goals = np.asarray(graph.goals, dtype=np.int64)
    m[:, goals] = normals @ graph.terminal.T  # a·d(g, g^·), numerators over den
    finite[goals] = True
    changed = goals
    tops = system.tops
    top_all = int(tops.max())
    lcm_all = max(1, system.lcm)
    width_all = max(int(np.abs(t.scaled).sum(axis=0).max(initial=1)) + 1
                    for t in system.closures)
    trivial = [t.scaled.shape[1] == 1 for t in system.closures]
    mmax = int(m.max(initial=0))
    k = 0
    while True:
        k += 1
        if k > max_layers:
            raise BudgetExceeded(f"no repeated layer within {max_layers:,} layers")
        rows = graph.tails_into(changed)
        rows = rows[~graph.is_goal[rows]]
        if rows.size == 0:
            break
        arcs, seg = graph.arcs_of(rows)
        heads = graph.heads[arcs]
        fin_h = finite[heads]
        fin_rows = np.logical_or.reduceat(fin_h, seg)
        w_s = graph.weights[arcs] * (scale // den)
        big = mmax + int(w_s.max(initial=0)) * top_all + 1
        if big * lcm_all * 4 > INT_LIMIT:
            raise BudgetExceeded("numbers beyond the exact int64 range")
        cand = tops[:, None] * w_s[None, :] + m[:, heads]
        cand[:, ~fin_h] = big
        step = np.minimum.reduceat(cand, seg, axis=1)
        live = np.flatnonzero(fin_rows)
        new = np.zeros((a, rows.size), dtype=np.int64)
        sub = step[:, live]
        exact_float = (big + 1) * width_all < EXACT_FLOAT_LIMIT
        subf = sub.T.astype(np.float64) if exact_float else None
        closed: list[np.ndarray | None] = []
        for j, tab in enumerate(system.closures):
            if trivial[j]:
                closed.append(None)  # the only cover is a itself: the step value
            elif subf is not None:
                cols = np.asarray(tab.columns, dtype=np.int64)
                closed.append((subf[:, cols] @ tab.scaled.astype(np.float64)).min(axis=1)
                              .astype(np.int64))
            else:
                cols = np.asarray(tab.columns, dtype=np.int64)
                closed.append(min_product(sub[cols].T, tab.scaled))
        # back to scale D: grow D where a closure value is not a multiple of its table's lcm
        grow = 1
        for j, tab in enumerate(system.closures):
            x = closed[j]
            if x is None or tab.lcm == 1 or not np.any(x % tab.lcm):
                continue
            g = math.gcd(int(np.gcd.reduce(x, initial=0)), tab.lcm)
            grow = math.lcm(grow, tab.lcm // g)
        if grow > 1:
            scale *= grow
            m *= grow
            mmax *= grow
            sub = sub * grow
            if mmax * lcm_all * 4 > INT_LIMIT:
                raise BudgetExceeded("numbers beyond the exact int64 range")
        for j, tab in enumerate(system.closures):
            x = closed[j]
            new[j, live] = sub[j] if x is None else x * grow // tab.lcm
        if live.size:
            mmax = max(mmax, int(new[:, live].max()))
        if check_layers:
            t_arcs = fin_rows[np.repeat(np.arange(rows.size), np.diff(np.append(seg, len(arcs))))]
            keep = t_arcs & fin_h
            if keep.any():
                arc_tail = np.repeat(np.arange(rows.size), np.diff(np.append(seg, len(arcs))))
                bad = failing_arcs(system.directions, new, m, arc_tail[keep], heads[keep],
                                   graph.weights[arcs][keep] * (scale // den))
                if bad.any():
                    tails = np.unique(rows[arc_tail[keep][bad]])
                    return LayerFailure(k, tails, rows, new, m.copy(), finite.copy(), scale)
        old_fin = finite[rows]
        diff = (new != m[:, rows]) & fin_rows[None, :]
        diff |= (fin_rows & ~old_fin)[None, :]
        if np.any((new > m[:, rows]) & old_fin[None, :]):  # pragma: no cover - monotone map
            raise AssertionError("normal DP: a layer value increased")
        touched = rows[live]
        m[:, touched] = new[:, live]
        finite[touched] = True
        rank[:, rows] = np.where(diff, k, rank[:, rows])
        changed = rows[np.any(diff, axis=0)]
        if changed.size == 0:
            break
    return Fixpoint(system, m, scale, finite, lambda: rank)


def normal_dp(graph: ArcGraph, system: NormalSystem, max_layers: int) -> Fixpoint:
    """The fixpoint of the normal-restricted DP with the layered DP's ranks.

    By blocks of sourced shortest paths and a label-setting for the ranks
    (:mod:`solver.coalitions.block_fixpoint`, proofs/NEXACT.md NX.7): the same ``m*``, finite
    nodes, ranks and ``K`` as :func:`layered_dp` (only the common scale may differ), in a few
    rounds instead of ``K`` layers. Where that method does not apply it is
    :func:`layered_dp`.

    Raises
    ------
    BudgetExceeded
        As :func:`layered_dp`: no repeated layer within ``max_layers`` layers (the ranks give
        ``K``), or numbers beyond the exact range.

    Examples
    --------
    >>> graph = ArcGraph(indptr=np.array([0, 2, 2, 2]), heads=np.array([1, 2]),
    ...                  weights=np.array([1, 1]), denominator=1, goals=(1, 2),
    ...                  terminal=np.array([[0, 2], [2, 0]]), start=0)
    >>> fix = normal_dp(graph, NormalSystem(zero_one_normals(2)), 100)
    >>> [str(fix.value(j, 0)) for j in range(3)], fix.layers
    (['1', '1', '2'], 1)
    """
    normals = np.array(system.normals, dtype=np.int64)
    goal_values = normals @ graph.terminal.T
    found = block_fixpoint(graph.indptr, graph.heads, graph.weights, graph.denominator,
                           graph.goals, goal_values, system.tops, system.closures,
                           [sum(a) for a in system.normals], max_rounds=max_layers + 1)
    if found is None:
        fix = layered_dp(graph, system, check_layers=False, max_layers=max_layers)
        assert isinstance(fix, Fixpoint)
        return fix
    m, scale, finite, _ = found

    def ranks() -> np.ndarray:
        return fixpoint_ranks(graph.indptr, graph.heads,
                              graph.weights * (scale // graph.denominator), graph.goals,
                              system.tops, system.closures, m, finite)

    fix = Fixpoint(system, m, scale, finite, ranks)
    # K <= the number of (normal, inner node) pairs (the ranks take every value 0..K); below
    # that the budget of layers is checked on K itself, as the layered DP does
    inner = int(np.count_nonzero(finite)) - len(set(graph.goals))
    if max_layers <= len(system.normals) * inner and fix.layers >= max_layers:
        raise BudgetExceeded(f"no repeated layer within {max_layers:,} layers")
    return fix


def fixpoint_failures(graph: ArcGraph, fix: Fixpoint) -> np.ndarray:
    """The tails of walkable arcs violating ``F_v ⊆ F_u + wΔ`` at the fixpoint."""
    tails, heads = graph.tails, graph.heads
    keep = fix.finite[tails] & fix.finite[heads]
    w = graph.weights[keep] * (fix.scale // graph.denominator)
    bad = failing_arcs(fix.system.directions, fix.m, fix.m, tails[keep], heads[keep], w)
    return np.unique(tails[keep][bad])


def _local_facets(graph: ArcGraph, system: NormalSystem, fail: LayerFailure, v: int,
                  max_new: int) -> list[Normal]:
    """The facets of the exact ``G_v^k = ∩_u (F_u^{k-1} + wΔ)`` that ``F_v^k`` violates.

    ``F_u^{k-1} + wΔ = {r : y_λ·r <= w + λ·m(u)}`` over the vertices ``λ`` of ``P_A``
    (Farkas); a candidate ``p`` (primitive ``y_λ``) is a facet of the intersection iff the
    other candidates do not cover it at a cost ``<= β_p`` (LP duality), and it is violated by
    ``F_v^k`` iff the cover of ``p`` by ``A`` at ``v`` costs more than ``β_p``.
    """
    scale = fail.scale
    normals = system.normals
    lo, hi = int(graph.indptr[v]), int(graph.indptr[v + 1])
    bound: dict[Normal, Fraction] = {}
    lams = packing_vertices(normals)
    for arc in range(lo, hi):
        u = int(graph.heads[arc])
        if not fail.old_finite[u]:
            continue
        w = Fraction(int(graph.weights[arc]), graph.denominator)
        mu = [Fraction(int(x), scale) for x in fail.old[:, u]]
        for lam in lams:
            if not any(lam):
                continue
            y = [sum((lam[j] * normals[j][i] for j in range(len(normals)) if lam[j]),
                     Fraction(0)) for i in range(system.n_goals)]
            p = primitive(y)
            t = Fraction(p[next(i for i in range(len(p)) if p[i])]) / y[next(
                i for i in range(len(p)) if p[i])]
            b = t * (w + sum((lam[j] * mu[j] for j in range(len(normals)) if lam[j]),
                             Fraction(0)))
            if p not in bound or b < bound[p]:
                bound[p] = b
    col = int(np.flatnonzero(fail.rows == v)[0])
    at_v = [Fraction(int(x), scale) for x in fail.new[:, col]]
    cands = sorted(bound)
    known = set(normals)
    out: list[Normal] = []
    for p in cands:
        if p in known:
            continue
        here = normal_cover_lp(normals, at_v, [Fraction(x) for x in p]).value
        if here <= bound[p]:
            continue  # F_v^k satisfies this candidate
        others = [q for q in cands if q != p]
        alone = normal_cover_lp(others, [bound[q] for q in others],
                                [Fraction(x) for x in p]).value
        if alone > bound[p]:
            out.append(p)
            if len(out) >= max_new:
                break
    return out


@dataclass(frozen=True, eq=False)
class GuaranteeSets:
    """The certified fixpoint: normals, exact support numbers, ranks.

    Attributes
    ----------
    fixpoint : Fixpoint
        The repeated layer over the final normals; its sets satisfy the arc condition at
        every walkable arc (so they are the exact sets ``G_v`` of the untruncated game).
    rounds : int
        Refinement rounds used (0: the 0/1 normals sufficed).
    """

    fixpoint: Fixpoint
    rounds: int

    @property
    def normals(self) -> tuple[Normal, ...]:
        """``A``: the 0/1 vectors, then the extra normals."""
        return self.fixpoint.system.normals

    @property
    def extra_normals(self) -> tuple[Normal, ...]:
        """The normals that are not 0/1 vectors."""
        return tuple(a for a in self.normals if any(x > 1 for x in a))


@dataclass(frozen=True)
class Unreached:
    """What :func:`guarantee_sets` knows when the budget ends: an upper bound's DP (the last
    fixpoint found, an outer approximation) and why it stopped."""

    reason: str
    upper: Fixpoint | None


HEURISTIC_ROUNDS = 3
"""Rounds that take the missing facets at the fixpoint itself (fast, no termination proof);
after them every round takes them at the first failing layer (proofs/NEXACT.md NX.6)."""


def guarantee_sets(graph: ArcGraph, budget: Budget | None = None,
                   initial: Sequence[Normal] = ()) -> GuaranteeSets | Unreached:
    """The exact guarantee sets at ``H = inf``: the refined normal-restricted DP, certified.

    Each round runs the DP to its fixpoint and tests the arc condition at every walkable arc;
    where it fails, the facets of ``∩_u (F_u + wΔ)`` that ``F_v`` violates join the normals
    (with their permutations): for the first :data:`HEURISTIC_ROUNDS` rounds at the fixpoint,
    afterwards at the first failing layer of a run tested layer by layer, where every earlier
    layer is exact, so that each normal added is a facet of an exact layer set (NX.6).

    Returns :class:`GuaranteeSets` when a fixpoint passes the arc test at every walkable arc,
    else :class:`Unreached` with the reason (the budget) and the best outer DP found.
    ``initial`` normals (with their permutations) join the 0/1 vectors from the start.

    Examples
    --------
    Two goals one step from the start: the 0/1 normals suffice, no refinement:

    >>> graph = ArcGraph(indptr=np.array([0, 2, 2, 2]), heads=np.array([1, 2]),
    ...                  weights=np.array([1, 1]), denominator=1, goals=(1, 2),
    ...                  terminal=np.array([[0, 2], [2, 0]]), start=0)
    >>> found = guarantee_sets(graph)
    >>> found.rounds, found.extra_normals, [str(found.fixpoint.value(2, 0))]
    (0, (), ['2'])
    """
    budget = Budget() if budget is None else budget
    n_goals = graph.n_goals
    max_layers = budget.layers if budget.layers is not None else 20 * graph.n_nodes + 200
    system = NormalSystem(symmetric_closure([*zero_one_normals(n_goals), *initial]))
    best: Fixpoint | None = None
    rounds = 0
    while True:
        try:
            fix = normal_dp(graph, system, max_layers)
        except BudgetExceeded as exc:
            return Unreached(str(exc), best)
        best = fix
        failing = fixpoint_failures(graph, fix)
        if not failing.size:
            return GuaranteeSets(fix, rounds)
        if rounds >= budget.rounds:
            return Unreached(f"no certified fixpoint within {budget.rounds} refinement rounds",
                             best)
        rounds += 1
        new: list[Normal] = []
        if rounds <= HEURISTIC_ROUNDS:
            # the fixpoint's own failures (no layer: -1; its ranks are not needed)
            at_fix = LayerFailure(-1, failing, np.arange(graph.n_nodes), fix.m, fix.m,
                                  fix.finite, fix.scale)
            for v in failing[:8]:
                new += _local_facets(graph, system, at_fix, int(v), 8)
        if not new:  # the proved route: the first failing layer
            try:
                run = layered_dp(graph, system, check_layers=True, max_layers=max_layers)
            except BudgetExceeded as exc:
                return Unreached(str(exc), best)
            if isinstance(run, Fixpoint):  # pragma: no cover - NX.5: every layer exact
                return Unreached("a fixpoint whose layers all pass fails the arc test", best)
            for v in run.tails[:8]:
                new += _local_facets(graph, system, run, int(v), 8)
        if not new:  # pragma: no cover - a failing layer always misses a facet (NX.6)
            return Unreached("no missing facet found at a failing layer", best)
        normals = symmetric_closure(list(system.normals) + new)
        if len(normals) - (2 ** n_goals - 1) > budget.extra_normals:
            return Unreached(f"more than {budget.extra_normals} extra normals needed", best)
        try:
            system = NormalSystem(normals)
        except ValueError as exc:
            return Unreached(str(exc), best)


def dominated_failures(graph: ArcGraph, normals: tuple[Normal, ...], max_layers: int
                       ) -> tuple[Fixpoint, list[Normal]]:
    """The rule's sets under the format's dominated reading (``docs/formats.md`` §2b) and the
    primitive directions in which they fail the arc test at some walkable arc (empty: the
    written rule's sets pass).

    Raises
    ------
    BudgetExceeded
        When the dominated DP does not repeat a layer within ``max_layers``.
    """
    system = NormalSystem(normals, dominated=True)
    fix = normal_dp(graph, system, max_layers)
    tails, heads = graph.tails, graph.heads
    keep = fix.finite[tails] & fix.finite[heads]
    w = graph.weights[keep] * (fix.scale // graph.denominator)
    bad: list[Normal] = []
    for d in system.directions:
        if failing_arcs((d,), fix.m, fix.m, tails[keep], heads[keep], w).any():
            bad.append(primitive(d.y))
    return fix, bad
