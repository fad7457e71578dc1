"""Symbolic checks for proofs/XI2.md (secondary best response value M - d(s0,g1))."""

from __future__ import annotations

import sympy as sp

from proofs.checks._sym import is_nonneg, is_zero, nonneg, pos

c0 = sp.Symbol("c0", nonnegative=True)  # d(s0, g1)


def test_XI2_every_walk_costs_at_least_M_minus_d_s0_g1() -> None:
    # v: the walk's node closest to g1 (c_T = d(v,g1)); the walk splits at v into
    # L1 >= d(s0,v) (slack x) and L2 >= d(v,s_T) (slack y); d(v,s_T) + d(s_T,g2) >= d(v,g2).
    a, b, x, y, z, dv1, t2, dv2 = nonneg("a b x y z dv1 t2 dv2")
    t2 = dv2 + z - b  # d(v,s_T) + d(s_T,g2) = d(v,g2) + z
    j2 = (a + x) + (b + y) - (c0 - dv1) + t2
    assert is_nonneg(j2 - (a + dv1 + dv2 - c0))


def test_XI2_cut_concatenation_attains_the_bound_in_every_case() -> None:
    ds, dv1, dv2, f, z, g12, g21, h = nonneg("ds dv1 dv2 f z g12 g21 h")
    m = ds + dv1 + dv2  # M at v*: d(s0,v*) + d(v*,g1) + d(v*,g2)
    # A: first goal g2 reached at the end, v* on the cut walk: c_T = dv1 - f.
    assert is_nonneg((m - c0) - (ds + dv2 - c0 + (dv1 - f)))
    # B1: g1 on the head s0 -> v* (h = d(g1,v*), d(s0,v*) = c0 + h); J2 = d(g1,g2);
    #     d(g1,v*) + d(v*,g2) = d(g1,g2) + z.
    m_b1 = (c0 + h) + dv1 + (g12 + z - h)
    assert is_nonneg((m_b1 - c0) - g12)
    # B2: g1 on the tail v* -> g2: d(v*,g2) = d(v*,g1) + d(g1,g2); J2 = d(s0,v*) + dv1 - c0 + g12.
    m_b2 = ds + dv1 + (dv1 + g12)
    assert is_nonneg((m_b2 - c0) - (ds + dv1 - c0 + g12))
    # C: g2 on the head (h = d(g2,v*), d(s0,v*) = d(s0,g2) + h); c_T = d(g2,g1) - f;
    #    d(g2,v*) + d(v*,g1) = d(g2,g1) + z; J2 = d(s0,g2) - c0 + c_T.
    ds2 = sp.Symbol("ds2", nonnegative=True)
    m_c = (ds2 + h) + (g21 + z - h) + dv2
    assert is_nonneg((m_c - c0) - (ds2 - c0 + (g21 - f)))


def test_XI2_value_and_voi_closed_forms() -> None:
    b2 = sp.Symbol("b2", positive=True)
    b1 = 1 - b2
    m, d1, d2 = sp.symbols("M d1 d2", positive=True)
    u_star = b1 * d1 + b2 * (m - d1)  # primary pays d(s0,g1), secondary M - d(s0,g1)
    assert is_zero(u_star - (b2 * m + (b1 - b2) * d1))
    u_bar = b1 * d1 + b2 * d2
    assert is_zero((u_bar - u_star) / u_bar - b2 * (d1 + d2 - m) / (b1 * d1 + b2 * d2))
    assert is_zero(u_star.subs(b2, sp.Rational(1, 2)) - m / 2)  # symmetric at 1/2


def test_XI2_secondary_path_ending_at_g1_is_a_shortest_path() -> None:
    # J2(xi2) = L - c0 + d(g1,g2) <= J2(psi(s0,g1)) = d(g1,g2) and L >= c0 force L = c0.
    extra, = pos("extra")
    g12, = nonneg("g12")
    assert (((c0 + extra) - c0 + g12) - g12).is_positive
