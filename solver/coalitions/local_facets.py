"""The facets of an exact layer set that the DP's outer set violates (the refinement's new
normals, proofs/NEXACT.md NX.6)."""

from __future__ import annotations

from fractions import Fraction

import numpy as np

from solver.coalitions.arc_graph import ArcGraph
from solver.coalitions.normal_cover import normal_cover_lp
from solver.coalitions.normal_dp import LayerFailure
from solver.coalitions.normal_system import NormalSystem
from solver.coalitions.vertex_tables import Normal, packing_vertices, primitive


def local_facets(graph: ArcGraph, system: NormalSystem, fail: LayerFailure, v: int,
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
