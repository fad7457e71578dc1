"""The arc test ``F_v ⊆ F_u + wΔ`` by the vertices of ``F_v`` (the solver's own; proofs/NRULE.md
NR.2(b)).

``F = {r : a·r <= m_a ∀ a ∈ A}`` (non-negative integer normals, the unit vectors among them) is
``conv(V) - R^N_+`` for its vertex set ``V``, and ``F_u + wΔ`` is convex and down-closed, so the
arc condition holds iff every maximal vertex ``r`` of ``F_v`` lies in ``F_u + wΔ``, i.e. iff

    φ = min { 1·s : s >= 0, a·s >= a·r - m_a(u) ∀ a } <= w.

:func:`set_vertices` enumerates ``V`` by the double description method on the cone
``{(x, t) : a·x <= m_a t, t >= 0}`` (exact integers; the combinatorial adjacency test of
Fukuda and Prodon); :func:`gauge` solves the LP as the solver's cover LP
(:func:`solver.coalitions.normal_cover.normal_cover_lp`: ``max b·λ`` over the packing
polytope ``Σ λ_a a <= 1`` with the slacks as unit columns), whose dual is ``-s`` and whose
optimal ``λ`` names the most violated direction ``y_λ = Σ λ_a a`` when ``φ > w``.

Where the packing polytope has thousands of vertices (many extra normals) this is far cheaper
than the direction test of :mod:`solver.coalitions.guarantee_sets`: a set ``F_v`` has a few
dozen maximal vertices.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from fractions import Fraction

import numpy as np

from solver.coalitions.normal_cover import normal_cover_lp
from solver.coalitions.vertex_tables import Normal, primitive


def set_vertices(normals: Sequence[Normal], values: Sequence[int]
                 ) -> list[tuple[tuple[int, ...], int]]:
    """The maximal vertices ``x / t`` of ``{r : normals[j]·r <= values[j]}``, exactly.

    Examples
    --------
    >>> sorted(set_vertices([(1, 0), (0, 1), (1, 1)], [2, 2, 3]))
    [((1, 2), 1), ((2, 1), 1)]
    """
    n = len(normals[0])
    k = len(normals)
    unit = [next(j for j, a in enumerate(normals) if tuple(a) == tuple(int(i == c)
                                                                       for c in range(n)))
            for i in range(n)]
    t_bit = 1 << k
    all_units = sum(1 << j for j in unit)
    # generators (x_1..x_N, t) with the bitmask of the constraints tight at them
    gens: list[tuple[tuple[int, ...], int]] = [
        ((*(int(values[j]) for j in unit), 1), all_units)]
    for i in range(n):
        gens.append(((*(-int(c == i) for c in range(n)), 0), t_bit | (all_units ^ (1 << unit[i]))))
    for j in range(k):
        if j in unit:
            continue
        row = (*(int(x) for x in normals[j]), -int(values[j]))
        gens = _cut(gens, row, 1 << j, n)
    pts = [(g[:n], g[n]) for g, _ in gens if g[n] > 0]
    return [p for p in pts if not any(
        q != p and all(a * q[1] <= b * p[1] for a, b in zip(p[0], q[0], strict=True))
        for q in pts)]


def _cut(gens: list[tuple[tuple[int, ...], int]], row: tuple[int, ...], bit: int, n: int
         ) -> list[tuple[tuple[int, ...], int]]:
    vals = [sum(c * x for c, x in zip(row, g, strict=True)) for g, _ in gens]
    if max(vals) <= 0:
        return [(g, z | bit if v == 0 else z) for (g, z), v in zip(gens, vals, strict=True)]
    out = [(g, z | bit if v == 0 else z) for (g, z), v in zip(gens, vals, strict=True)
           if v <= 0]
    for p, (gp, zp) in enumerate(gens):
        if vals[p] <= 0:
            continue
        for q, (gq, zq) in enumerate(gens):
            if vals[q] >= 0:
                continue
            both = zp & zq
            if bin(both).count("1") < n - 1:
                continue
            if any(r != p and r != q and both & ~zr == 0 for r, (_, zr) in enumerate(gens)):
                continue  # not adjacent: a third generator is tight wherever both are
            new = [vals[p] * b - vals[q] * a for a, b in zip(gp, gq, strict=True)]
            g = math.gcd(*new)
            out.append((tuple(x // g for x in new), both | bit))
    return out


def gauge(normals: Sequence[Normal], b: Sequence[int]) -> tuple[Fraction, list[Fraction]]:
    """``φ = max {b·λ : λ >= 0, Σ_a λ_a a <= 1}`` and the ``y_λ`` of an optimal ``λ``, exactly.

    Examples
    --------
    >>> phi, y = gauge([(1, 0), (0, 1), (1, 1)], [1, 1, 3])
    >>> phi, [str(x) for x in y]
    (Fraction(3, 1), ['1', '1'])
    """
    n = len(normals[0])
    use = [j for j, x in enumerate(b) if x > 0]
    if not use:
        return Fraction(0), [Fraction(0)] * n
    cols = [tuple(normals[j]) for j in use] + [tuple(int(i == c) for c in range(n))
                                               for i in range(n)]
    costs = [Fraction(-int(b[j])) for j in use] + [Fraction(0)] * n
    lp = normal_cover_lp(cols, costs, [Fraction(1)] * n)
    s = [-x for x in lp.dual]
    # the certificate: s >= 0 and a·s >= b_a for every normal, with 1·s = φ
    phi = -lp.value
    if min(s) < 0 or sum(s) != phi or any(
            sum((a[i] * s[i] for i in range(n)), Fraction(0)) < b[j]
            for j, a in enumerate(normals) if b[j] > 0):  # pragma: no cover - LP duality
        raise AssertionError("arc test: the cover LP's dual is not a certificate")
    y = [sum((c * cols[j][i] for j, c in lp.cover.items() if j < len(use)), Fraction(0))
         for i in range(n)]
    return phi, y


def vertex_failures(normals: Sequence[Normal], tail_vals: np.ndarray, head_vals: np.ndarray,
                    tail_pos: np.ndarray, head_pos: np.ndarray, w_scaled: np.ndarray
                    ) -> tuple[np.ndarray, list[Normal]]:
    """A mask over arcs violating ``F_v ⊆ F_u + wΔ`` and the primitive directions violated.

    ``tail_vals``/``head_vals`` are ``(|A|, k)`` integer numerators at one scale (the distinct
    tails and heads), ``tail_pos``/``head_pos`` each arc's column in them, ``w_scaled`` the
    weights at that scale.

    Examples
    --------
    One arc of weight 1 into a node whose set is ``r_1, r_2 <= 1, r_1 + r_2 <= 1``; the tail's
    set ``r_1, r_2 <= 2, r_1 + r_2 <= 3`` has the vertex ``(2, 1)``, two away:

    >>> zo = [(1, 0), (0, 1), (1, 1)]
    >>> bad, ys = vertex_failures(zo, np.array([[2], [2], [3]]), np.array([[1], [1], [1]]),
    ...                          np.array([0]), np.array([0]), np.array([1]))
    >>> bad.tolist(), ys
    ([True], [(1, 1)])
    """
    n_arcs = len(tail_pos)
    bad = np.zeros(n_arcs, dtype=bool)
    found: dict[Normal, None] = {}
    verts: dict[int, list[tuple[tuple[int, ...], int]]] = {}
    for k in range(n_arcs):
        tp, hp = int(tail_pos[k]), int(head_pos[k])
        if tp not in verts:
            verts[tp] = set_vertices(normals, [int(x) for x in tail_vals[:, tp]])
        mu = [int(x) for x in head_vals[:, hp]]
        w = int(w_scaled[k])
        for x, t in verts[tp]:
            b = [sum(a[i] * x[i] for i in range(len(x)) if a[i]) - t * m
                 for a, m in zip(normals, mu, strict=True)]
            if max(b) <= 0:
                continue  # r ∈ F_u itself
            phi, y = gauge(normals, b)
            if phi > t * w:
                bad[k] = True
                found.setdefault(primitive(y), None)
    return bad, list(found)
