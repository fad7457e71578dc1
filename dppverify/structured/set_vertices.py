"""The vertices of a normal-described set ``F = { r : a·r <= m_a, a ∈ A }``, exactly.

``A`` holds non-negative integer normals, the unit vectors among them, so ``F`` is a pointed
polyhedron whose recession cone is ``-R^N_+``: ``F = conv(V) - R^N_+`` for its finite vertex
set ``V`` (Minkowski–Weyl). The arc test of the guarantee rule needs ``V`` only
(``proofs/NRULE.md`` NR.2(b)): a down-closed convex set contains ``F`` iff it contains ``V``,
and only the *maximal* vertices (none componentwise below another) need testing.

:func:`maximal_vertices` enumerates ``V`` by the double description method (Motzkin, Raiffa,
Thompson and Thrall, 1953; the adjacency test of Fukuda and Prodon, 1996) on the homogenised
cone ``{(x, t) : a·x <= m_a t, t >= 0}`` of ``R^{N+1}``, whose extreme rays are the vertices
``(r, 1)`` and the rays ``(-e_θ, 0)``:

- start from the unit normals: the cone ``x <= m t, t >= 0`` has the extreme rays
  ``(m_{e_1}, …, m_{e_N}, 1)`` and ``(-e_θ, 0)``;
- add each other normal ``a``: with ``s(g) = a·x - m_a t``, keep the rays with ``s <= 0`` and
  add ``s(p)·q - s(q)·p`` for every *adjacent* pair ``s(p) > 0 > s(q)``; ``p``, ``q`` are
  adjacent iff no third ray is tight at every constraint tight at both (the combinatorial
  test, valid because the list holds the extreme rays of a pointed cone, each once).

Integers throughout (each ray divided by the gcd of its entries), so the numbers stay the
minors Cramer's rule gives; a normal that is nowhere tight changes nothing but costs one
pass over the rays, so no redundancy LP is needed first.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from dppverify.structured.cover import Normal

SetVertex = tuple[tuple[int, ...], int, int]
"""A vertex ``r = x / t`` of ``F`` as ``(x, t, tight)``: integer ``x``, ``t > 0`` and the
bitmask (bit ``j``: normal ``j``) of the normals tight at ``r``."""


def _ray(vec: list[int]) -> tuple[int, ...]:
    g = math.gcd(*vec)
    return tuple(x // g for x in vec) if g > 1 else tuple(vec)


def maximal_vertices(normals: Sequence[Normal], values: Sequence[int]) -> tuple[SetVertex, ...]:
    """The maximal vertices of ``{ r : normals[j]·r <= values[j] ∀ j }``, exactly.

    Parameters
    ----------
    normals : sequence of Normal
        Non-negative integer vectors of one length ``N``, every unit vector among them.
    values : sequence of int
        The right-hand sides ``m_j`` (integers: callers pass numerators at a common scale,
        the vertices are then at that scale too).

    Returns
    -------
    tuple of SetVertex
        ``(x, t, tight)`` per maximal vertex ``r = x / t`` (``t > 0``, lowest terms), sorted.

    Examples
    --------
    The square ``r_1, r_2 <= 2`` cut by ``r_1 + r_2 <= 3`` has two vertices, ``(2, 1)`` and
    ``(1, 2)``; ``(2, 2)`` is cut off and nothing else is maximal:

    >>> [(x, t) for x, t, _ in maximal_vertices([(1, 0), (0, 1), (1, 1)], [2, 2, 3])]
    [((1, 2), 1), ((2, 1), 1)]
    >>> [(x, t) for x, t, _ in maximal_vertices([(1, 0), (0, 1), (2, 1)], [1, 1, 2])]
    [((1, 0), 1), ((1, 2), 2)]
    """
    n = len(normals[0])
    k = len(normals)
    unit: dict[int, int] = {}
    for j, a in enumerate(normals):
        if sum(a) == 1 and max(a) == 1:
            unit.setdefault(a.index(1), j)
    if len(unit) < n:
        raise ValueError("maximal_vertices: every unit vector must be among the normals")
    t_bit = 1 << k  # the constraint t >= 0
    start = (*(int(values[unit[i]]) for i in range(n)), 1)
    units = sum(1 << unit[i] for i in range(n))
    rays: list[tuple[tuple[int, ...], int]] = [(start, units)]
    for i in range(n):
        vec = (*(-int(c == i) for c in range(n)), 0)
        rays.append((vec, t_bit | (units & ~(1 << unit[i]))))
    done = set(unit.values())
    for j in range(k):
        if j in done:
            continue
        rays = _add_constraint(rays, (*(int(x) for x in normals[j]), -int(values[j])),
                               1 << j, n)
    verts = [(x[:n], x[n], z) for x, z in rays if x[n] > 0]
    out = [v for v in verts
           if not any(w is not v and all(a * w[1] <= b * v[1] for a, b in
                                         zip(v[0], w[0], strict=True))
                      for w in verts)]  # x_v / t_v <= x_w / t_w: v is below w
    return tuple(sorted(out))


def _add_constraint(rays: list[tuple[tuple[int, ...], int]], row: tuple[int, ...], bit: int,
                    n: int) -> list[tuple[tuple[int, ...], int]]:
    """One double-description step: the extreme rays of the cone cut by ``row·g <= 0``."""
    side = [sum(c * x for c, x in zip(row, g, strict=True)) for g, _ in rays]
    plus = [i for i, s in enumerate(side) if s > 0]
    if not plus:
        return [(g, z | bit) if side[i] == 0 else (g, z) for i, (g, z) in enumerate(rays)]
    minus = [i for i, s in enumerate(side) if s < 0]
    kept = [(g, z | bit) if side[i] == 0 else (g, z) for i, (g, z) in enumerate(rays)
            if side[i] <= 0]
    masks = [z for _, z in rays]
    for p in plus:
        gp, zp = rays[p]
        for q in minus:
            gq, zq = rays[q]
            common = zp & zq
            if common.bit_count() < n - 1:  # adjacent rays share a face of dimension 2
                continue
            if any(common & ~masks[i] == 0 for i in range(len(rays)) if i != p and i != q):
                continue
            sp, sq = side[p], side[q]
            kept.append((_ray([sp * b - sq * a for a, b in zip(gp, gq, strict=True)]),
                         common | bit))
    return kept
