"""Symbolic checks for proofs/L2.md (removing a loop strictly lowers the secondary's cost)."""

from __future__ import annotations

import sympy as sp

from proofs.checks._sym import is_pos, nonneg, pos


def test_L2_loop_without_the_running_minimum() -> None:
    # The minimum c_T is attained outside the loop: progress unchanged, length drops.
    l1, = nonneg("l1")
    l2, = pos("l2")
    delta = -(l1 + l2)  # J2(walk') - J2(walk) = -L(loop) + (c'_T - c_T), c'_T = c_T
    assert is_pos(-delta)


def test_L2_loop_containing_the_running_minimum() -> None:
    # Loop v = s_i -> ... -> u = s_k -> ... -> s_j = v, with c_T = d(u,g1) attained at u.
    # l1 = L(s_i..s_k) >= 0, l2 = L(s_k..s_j) > 0; d(v,g1) <= l1 + d(u,g1) (slack e);
    # c'_T <= d(v,g1) (slack f), because v stays on the shortened walk.
    du = sp.Symbol("du", real=True)
    l1, e, f = nonneg("l1 e f")
    l2, = pos("l2")
    dv = du + l1 - e
    c_t, c_t_new = du, dv - f
    delta = -(l1 + l2) + (c_t_new - c_t)
    assert is_pos(-delta)
