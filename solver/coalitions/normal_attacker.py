"""The normal-coalition Attacker and the root of the exact guarantee rule (proofs/NEXACT.md).

Given a certified fixpoint of the normal-restricted DP
(:mod:`solver.coalitions.guarantee_sets`: normals ``A``, support numbers ``m*``, ranks):

- **Root.** The cover LP ``min Σ_a c_a m*_a(s0)`` s.t. ``Σ_a c_a a = b`` gives the value, the
  starting pieces (normal ``a`` with mass ``c_a``) and, as its lexicographically largest
  optimal dual in the priority order, the Defender's guarantee vector ``h``.
- **Pieces.** A piece is a normal ``a`` with a mass ``μ``; it carries ``μ·a_θ`` of type θ's
  prior mass. A piece at a non-goal node ``v`` with rank ``ρ = rank[a, v]`` takes a cover
  ``Σ_n c_n n = a`` (a vertex of the closure table) and an arc ``(v, u_n)`` per normal ``n``
  with ``rank[n, u_n] <= ρ - 1`` such that ``Σ_n c_n (w(v, u_n)·max n + m*_n(u_n)) = m*_a(v)``
  (one exists: proofs/NEXACT.md NX.2); the piece ``(n, μ·c_n)`` steps to ``u_n``. The trivial
  cover (the whole piece steps) is preferred, then the first cheapest vertex, the first
  cheapest arc. A piece stops at a goal. Ranks strictly decrease along a piece's walk, so
  every walk has at most ``K`` steps.
- **Mixtures.** Type θ plays a walk with probability (the type-θ mass of the pieces ending on
  it) / ``b_θ``.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from solver.coalitions.arc_graph import ArcGraph
from solver.coalitions.normal_cover import normal_cover_lp
from solver.coalitions.normal_dp import Fixpoint

__all__ = ["AttackerPlan", "normal_attacker", "piece_walks"]

Walk = tuple[int, ...]


@dataclass(frozen=True)
class AttackerPlan:
    """The root and the Attacker's walks.

    Attributes
    ----------
    h : tuple of Fraction
        The Defender's guarantee vector (``h·a <= m*_a(s0)`` for every normal, ``h·b`` = value).
    value : Fraction
        ``min Σ_a c_a m*_a(s0)`` = ``h·b``.
    root_cover : dict
        Normal index -> starting mass ``c_a``.
    leaves : tuple
        ``(walk, {normal index: mass})`` for every walk the pieces end on.
    """

    h: tuple[Fraction, ...]
    value: Fraction
    root_cover: dict[int, Fraction]
    leaves: tuple[tuple[Walk, dict[int, Fraction]], ...]

    def mixtures(self, normals: Sequence[Sequence[int]], prior: Sequence[Fraction]
                 ) -> tuple[dict[Walk, Fraction], ...]:
        """Type θ's mixed strategy: walk -> probability (exact, summing to 1)."""
        out: list[dict[Walk, Fraction]] = [{} for _ in prior]
        for walk, pieces in self.leaves:
            for j, mass in pieces.items():
                for t, x in enumerate(normals[j]):
                    if x:
                        out[t][walk] = out[t].get(walk, Fraction(0)) + mass * x / prior[t]
        return tuple(out)


def normal_attacker(graph: ArcGraph, fix: Fixpoint, prior: Sequence[Fraction],
                    order: Sequence[int], max_walks: int = 200_000) -> AttackerPlan:
    """The root cover, ``h`` and the pieces' walks on a certified fixpoint.

    Raises
    ------
    ValueError
        If the plan would list more than ``max_walks`` walks.

    Examples
    --------
    >>> import numpy as np
    >>> from solver.coalitions.guarantee_sets import guarantee_sets
    >>> graph = ArcGraph(indptr=np.array([0, 2, 2, 2]), heads=np.array([1, 2]),
    ...                  weights=np.array([1, 1]), denominator=1, goals=(1, 2),
    ...                  terminal=np.array([[0, 2], [2, 0]]), start=0)
    >>> fix = guarantee_sets(graph).fixpoint
    >>> plan = normal_attacker(graph, fix, [Fraction(1, 2)] * 2, (0, 1))
    >>> str(plan.value), [w for w, _ in plan.leaves]
    ('1', [(0, 1), (0, 2)])
    """
    normals = fix.system.normals
    s0 = graph.start
    costs = [fix.value(j, s0) for j in range(len(normals))]
    root = normal_cover_lp(normals, costs, list(prior), order)
    leaves = piece_walks(graph, fix, root.cover, max_walks)
    return AttackerPlan(tuple(root.dual), root.value, dict(root.cover), leaves)


def piece_walks(graph: ArcGraph, fix: Fixpoint, pieces: dict[int, Fraction],
                max_walks: int = 200_000) -> tuple[tuple[Walk, dict[int, Fraction]], ...]:
    """The walks of the pieces ``pieces`` (normal index -> mass) started at the start: every
    walk they end on with the masses ending there, sorted (proofs/NEXACT.md NX.2).

    Raises
    ------
    ValueError
        If the pieces end on more than ``max_walks`` walks.

    Examples
    --------
    >>> from solver.coalitions.guarantee_sets import guarantee_sets
    >>> graph = ArcGraph(indptr=np.array([0, 2, 2, 2]), heads=np.array([1, 2]),
    ...                  weights=np.array([1, 1]), denominator=1, goals=(1, 2),
    ...                  terminal=np.array([[0, 2], [2, 0]]), start=0)
    >>> fix = guarantee_sets(graph).fixpoint
    >>> piece_walks(graph, fix, {2: Fraction(1)})   # the pair (1, 1) splits at the start
    (((0, 1), {0: Fraction(1, 1)}), ((0, 2), {1: Fraction(1, 1)}))
    """
    memo: dict[tuple[int, int], list[tuple[int, Fraction, int]]] = {}
    leaves: list[tuple[Walk, dict[int, Fraction]]] = []
    stack: list[tuple[Walk, dict[int, Fraction]]] = [((graph.start,), dict(pieces))]
    while stack:
        walk, at = stack.pop()
        v = walk[-1]
        if graph.is_goal[v]:
            leaves.append((walk, at))
            if len(leaves) > max_walks:
                raise ValueError(f"the Attacker's plan exceeds {max_walks:,} walks")
            continue
        nxt: dict[int, dict[int, Fraction]] = {}
        for j, mass in sorted(at.items()):
            key = (j, v)
            if key not in memo:
                memo[key] = _moves(graph, fix, j, v)
            for j2, coef, u in memo[key]:
                d = nxt.setdefault(u, {})
                d[j2] = d.get(j2, Fraction(0)) + mass * coef
        for u in sorted(nxt, reverse=True):
            stack.append(((*walk, u), nxt[u]))
    leaves.sort()
    return tuple(leaves)


def _moves(graph: ArcGraph, fix: Fixpoint, j: int, v: int) -> list[tuple[int, Fraction, int]]:
    """How a piece of normal ``j`` at ``v`` moves: ``(normal, coefficient, head)`` triples."""
    system = fix.system
    rho = int(fix.rank[j, v])
    lo, hi = int(graph.indptr[v]), int(graph.indptr[v + 1])
    heads = graph.heads[lo:hi]
    ok = fix.finite[heads] & (fix.rank[:, heads] <= rho - 1)  # (|A|, arcs)
    w_s = graph.weights[lo:hi] * (fix.scale // graph.denominator)
    vals = w_s[None, :] * system.tops[:, None] + fix.m[:, heads]
    big = int(vals.max(initial=0)) + 1
    vals = np.where(ok, vals, big)
    best_arc = np.argmin(vals, axis=1)  # the first cheapest arc per normal
    best = vals[np.arange(len(system.normals)), best_arc]
    target = int(fix.m[j, v])
    if int(best[j]) == target:  # the whole piece steps
        return [(j, Fraction(1), int(heads[best_arc[j]]))]
    tab = system.closures[j]
    cols = np.asarray(tab.columns, dtype=np.int64)
    for scaled, lcm in tab.parts:
        totals = best[cols].astype(object) @ scaled.astype(object)
        k = next((i for i, x in enumerate(totals) if x == target * lcm), None)
        if k is None:
            continue
        out = []
        for pos, col in enumerate(tab.columns):
            c = int(scaled[pos, k])
            if c:
                if int(best[col]) >= big:  # pragma: no cover - NX.2
                    raise AssertionError("normal Attacker: a cover uses an unrealised normal")
                out.append((col, Fraction(c, lcm), int(heads[best_arc[col]])))
        return out
    raise AssertionError("normal Attacker: no ranked cover attains m*")  # pragma: no cover
