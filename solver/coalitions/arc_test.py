"""The arc test ``F_v ⊆ F_u + wΔ`` of the normal-restricted DP's sets (proofs/NGOAL.md NG.8(c),
proofs/NRULE.md NR.2): by the packing polytope's directions (vectorised over the arcs) or, where
that polytope is large, by the vertices of the tails' sets
(:mod:`solver.coalitions.arc_vertices`).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from solver.coalitions.arc_vertices import vertex_failures
from solver.coalitions.budget import BudgetExceeded
from solver.coalitions.normal_system import NormalSystem
from solver.coalitions.vertex_tables import Direction, Normal, primitive
from solver.graph.distances import EXACT_FLOAT_LIMIT

INT_LIMIT = 2 ** 62

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


def arc_failures(system: NormalSystem, tail_vals: np.ndarray, head_vals: np.ndarray,
                 tail_pos: np.ndarray, head_pos: np.ndarray, w_scaled: np.ndarray
                 ) -> tuple[np.ndarray, list[Normal]]:
    """A mask over arcs violating ``F_v ⊆ F_u + wΔ`` and the primitive directions violated.

    By the vertices of the tails' sets (:func:`solver.coalitions.arc_vertices.vertex_failures`,
    proofs/NRULE.md NR.2(b)) when :attr:`NormalSystem.by_vertices`, else by the packing
    directions (:func:`failing_arcs`, NG.8(c)). ``tail_vals``/``head_vals`` are ``(|A|, k)``
    numerators at one scale ``D`` (the distinct tails and heads), ``tail_pos``/``head_pos``
    each arc's column in them, ``w_scaled`` the weights times ``D``.
    """
    if not len(tail_pos):
        return np.zeros(0, dtype=bool), []
    if system.by_vertices:
        return vertex_failures(system.normals, tail_vals, head_vals, tail_pos, head_pos,
                               w_scaled)
    bad = np.zeros(len(tail_pos), dtype=bool)
    dirs: list[Normal] = []
    for d in system.directions:
        hit = failing_arcs((d,), tail_vals, head_vals, tail_pos, head_pos, w_scaled)
        if hit.any():
            bad |= hit
            dirs.append(primitive(d.y))
    return bad, dirs


def failing_arcs(directions: Sequence[Direction], tail_vals: np.ndarray, head_vals: np.ndarray,
                 tail_pos: np.ndarray, head_pos: np.ndarray, w_scaled: np.ndarray
                 ) -> np.ndarray:
    """A mask over arcs violating ``F_v ⊆ F_u + wΔ`` in the given directions (proofs/NGOAL.md
    NG.8(c)): ``h_{F_v}(y) > w + λ·m(u)`` for the cheapest cover at ``v`` and the cheapest
    packing vertex ``λ`` of ``y`` at ``u``.

    Arguments as :func:`arc_failures`. ``h_{F_v}(y)`` is the least over the cover table's
    parts, so an arc fails in ``y`` iff it fails for every part.
    """
    bad = np.zeros(len(tail_pos), dtype=bool)
    if not len(tail_pos):
        return bad
    for d in directions:
        mu = _min_product_exact(head_vals.T, d.lams.T)[head_pos]
        fails = np.ones(len(tail_pos), dtype=bool)
        cols = np.asarray(d.cover.columns, dtype=np.int64)
        for scaled, lcm in d.cover.parts:
            hv = _min_product_exact(tail_vals[cols].T, scaled)[tail_pos]
            # h_v(y) <= w + λ·m_u:  hv / (lcm_T · s) <= w + mu / lcm_λ   (all at scale D)
            f_w, f_mu = lcm * d.lam_lcm * d.scale, lcm * d.scale
            lhs = hv.astype(object) * d.lam_lcm
            rhs = w_scaled.astype(object) * f_w + mu.astype(object) * f_mu
            fails &= np.asarray(lhs > rhs, dtype=bool)
        bad |= fails
    return bad


def _min_product_exact(values: np.ndarray, scaled: np.ndarray) -> np.ndarray:
    """:func:`min_product` in Python integers where it would leave int64."""
    try:
        return min_product(values, scaled)
    except BudgetExceeded:
        return (values.astype(object) @ scaled.astype(object)).min(axis=1)
