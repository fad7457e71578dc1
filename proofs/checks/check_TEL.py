"""Symbolic checks for proofs/TEL.md (telescoping identity, sigma* in [0, 1])."""

from __future__ import annotations

import sympy as sp

from proofs.checks._sym import is_nonneg, is_pos, is_zero, nonneg, pos


def test_TEL_sum_of_w_sigma_telescopes_for_every_length_up_to_8() -> None:
    for n in range(9):
        d = sp.symbols(f"d1:{n + 2}", real=True)  # d(s_t, g1), t = 1..n
        w = sp.symbols(f"w1:{n + 2}", positive=True)
        c = [sp.Symbol("c0", real=True)]
        total = sp.Integer(0)
        for t in range(1, n + 1):
            c.append(sp.Min(c[t - 1], d[t - 1]))
            sigma = (c[t - 1] - c[t]) / w[t - 1]  # eq. (7)
            total += w[t - 1] * sigma
        assert is_zero(total - (c[0] - c[n]))


def test_TEL_sigma_is_zero_without_new_progress() -> None:
    c_prev = sp.Symbol("c_prev", real=True)
    a, = nonneg("a")
    w, = pos("w")
    for d_new in (c_prev + a, sp.oo):  # d(s_t, g1) >= c_{t-1}, or g1 unreachable from s_t
        sigma = (c_prev - sp.Min(c_prev, d_new)) / w
        assert is_zero(sigma)


def test_TEL_sigma_in_unit_interval_with_new_progress() -> None:
    # c_{t-1} <= d(s_{t-1}, g1)  (slack a),  d(s_{t-1}, g1) <= w + d(s_t, g1)  (slack b),
    # new progress p = c_{t-1} - d(s_t, g1) > 0.
    c_prev = sp.Symbol("c_prev", real=True)
    a, b = nonneg("a b")
    p, = pos("p")
    d_new = c_prev - p
    d_prev = c_prev + a
    w = d_prev - d_new + b
    sigma = (c_prev - sp.Min(c_prev, d_new)) / w
    assert is_pos(sigma)
    assert is_nonneg(1 - sigma)
    # sigma = 1 exactly when both slacks vanish: s_{t-1} is closest so far (a = 0) and the
    # edge lies on a shortest path to g1 (b = 0)  -- the paper's conditions (i), (ii).
    assert is_zero(sp.simplify((1 - sigma) * w) - (a + b))


def test_TEL_type_costs_of_a_walk() -> None:
    # J1 = sum w sigma + d(s_T,g1);  J2 = sum w (1 - sigma) + d(s_T,g2) = L - (c0 - cT) + ...
    c0, cT, big_l, t1, t2 = sp.symbols("c0 cT L t1 t2", real=True)
    j1 = (c0 - cT) + t1
    j2 = (big_l - (c0 - cT)) + t2
    assert is_zero(j1 + j2 - (big_l + t1 + t2))  # constant-sum allocation (Sec. VI)
