"""The normal-restricted DP of the N-goal game at ``H = inf`` and its fixpoint.

For a finite set ``A`` of non-negative integer normals (every 0/1 vector among them, closed
under permutations of the goals) the *normal-restricted DP* (proofs/NGOAL.md NG.7) is, layer
by layer from the goals,

    m_a(g, k) = a·d(g, g^·)  at a goal g;     m_a(v, 0) = +inf elsewhere;
    s_a(v, k) = min_{(v,u)} [ w(v,u)·max(a) + m_a(u, k-1) ]                      (the step)
    m_a(v, k) = min { Σ_n c_n s_n(v, k) : c >= 0, Σ_n c_n n = a }               (the closure)

and ``F_v^k = {r : a·r <= m_a(v, k) ∀ a ∈ A}`` contains the exact set ``G_v^k``. Everything
here is exact integers at a common scale ``D`` (numpy int64, products in float64 only when
every partial sum is an integer below 2**53, Python integers over the parts of a large cover
table). :func:`layered_dp` computes the layers incrementally (only the tails of arcs into
changed nodes) until one repeats: the *fixpoint* ``m*`` (the greatest fixpoint of the layer
map), reached at layer ``K``; :func:`normal_dp` gets the same fixpoint by blocks of sourced
shortest paths (:mod:`solver.coalitions.block_fixpoint`). ``rank[a, v]`` is the layer at which
``m_a(v)`` reached its final value; the Attacker of :mod:`solver.coalitions.normal_attacker`
walks down the ranks, so its walks have at most ``K`` steps (proofs/NEXACT.md NX.2).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from fractions import Fraction
from functools import cached_property

import numpy as np

from solver.coalitions.arc_graph import ArcGraph
from solver.coalitions.arc_test import arc_failures
from solver.coalitions.block_fixpoint import block_fixpoint, fixpoint_ranks
from solver.coalitions.budget import BudgetExceeded
from solver.coalitions.cover_totals import cover_minimum
from solver.coalitions.normal_system import NormalSystem

INT_LIMIT = 2 ** 62

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


def _gcd_mod(num: np.ndarray, den: int) -> int:
    """``gcd(den, num mod den)`` over every entry (int64 or Python integers)."""
    if num.dtype != object and den < INT_LIMIT:
        return math.gcd(den, int(np.gcd.reduce(num % den, initial=0)))
    return math.gcd(den, *(int(v) % den for v in num))


def _rescaled(num: np.ndarray, grow: int, den: int) -> np.ndarray:
    """``num · grow / den`` (exact division) as int64, or :class:`BudgetExceeded`."""
    if num.dtype != object and int(np.abs(num).max(initial=0)) * grow < INT_LIMIT:
        return num * grow // den
    vals = [int(v) * grow // den for v in num]
    if vals and max(vals) >= INT_LIMIT:
        raise BudgetExceeded("numbers beyond the exact int64 range")
    return np.asarray(vals, dtype=np.int64)


def _closures(system: NormalSystem, trivial: list[bool], sub: np.ndarray
              ) -> tuple[list[tuple[np.ndarray, int] | None], int]:
    """Every normal's closure ``min_c Σ_n c_n s_n`` over its cover table at the rows of the
    steps ``sub`` (``(|A|, rows)``), as ``(numerators, denominator)`` (None: the only cover is
    the normal itself), and the factor by which the common scale must grow to hold them."""
    closed: list[tuple[np.ndarray, int] | None] = []
    rows = sub.shape[1]
    for j, tab in enumerate(system.closures):
        if trivial[j]:
            closed.append(None)  # the only cover is a itself: the step value
            continue
        cols = np.asarray(tab.columns, dtype=np.int64)
        found = cover_minimum(sub[cols].T, np.zeros((rows, cols.size), dtype=bool), tab)
        assert found is not None  # a itself is a vertex
        closed.append((found[0], found[1]))
    grow = 1
    for x in closed:  # grow D where a closure value is not a multiple of its table's lcm
        if x is not None and x[1] > 1:
            grow = math.lcm(grow, x[1] // _gcd_mod(x[0], x[1]))
    return closed, grow


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
    den = scale = graph.denominator
    m, finite, rank = np.zeros((a, n), dtype=np.int64), np.zeros(n, dtype=bool), np.zeros(
        (a, n), dtype=np.int32)
    changed = goals = np.asarray(graph.goals, dtype=np.int64)
    # a·d(g, g^·) at the goals, numerators over den
    m[:, goals] = np.array(system.normals, dtype=np.int64) @ graph.terminal.T
    finite[goals] = True
    tops = system.tops
    top_all = int(tops.max())
    trivial = [t.n_vertices == 1 for t in system.closures]
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
        if big * 4 > INT_LIMIT:
            raise BudgetExceeded("numbers beyond the exact int64 range")
        cand = tops[:, None] * w_s[None, :] + m[:, heads]
        cand[:, ~fin_h] = big
        step = np.minimum.reduceat(cand, seg, axis=1)
        live, new = np.flatnonzero(fin_rows), np.zeros((a, rows.size), dtype=np.int64)
        sub = step[:, live]
        closed, grow = _closures(system, trivial, sub)
        if grow > 1:
            scale *= grow
            m *= grow
            mmax *= grow
            sub = sub * grow
            if mmax * 4 > INT_LIMIT:
                raise BudgetExceeded("numbers beyond the exact int64 range")
        for j, x in enumerate(closed):
            new[j, live] = sub[j] if x is None else _rescaled(x[0], grow, x[1])
        if live.size:
            mmax = max(mmax, int(new[:, live].max()))
        if check_layers:
            arc_tail = np.repeat(np.arange(rows.size), np.diff(np.append(seg, len(arcs))))
            keep = fin_rows[arc_tail] & fin_h
            bad, _ = arc_failures(system, new, m, arc_tail[keep], heads[keep],
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
    >>> from solver.coalitions.vertex_tables import zero_one_normals
    >>> fix = normal_dp(graph, NormalSystem(zero_one_normals(2)), 100)
    >>> [str(fix.value(j, 0)) for j in range(3)], fix.layers
    (['1', '1', '2'], 1)
    """
    found = block_fixpoint(graph, system, max_rounds=max_layers + 1)
    if found is None:
        fix = layered_dp(graph, system, check_layers=False, max_layers=max_layers)
        assert isinstance(fix, Fixpoint)
        return fix
    m, scale, finite, _ = found

    def ranks() -> np.ndarray:
        return fixpoint_ranks(graph, system, scale, m, finite)

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
    bad, _ = arc_failures(fix.system, fix.m, fix.m, tails[keep], heads[keep], w)
    return np.unique(tails[keep][bad])
