"""Symbolic checks for proofs/THM.md (weak PBNE: branch facts, indifference, value)."""

from __future__ import annotations

import sympy as sp

from proofs.checks._sym import is_nonneg, is_pos, is_zero, nonneg, pos

b2 = sp.Symbol("b2", positive=True)
b1 = 1 - b2


def test_THM_phase_II_payoff_does_not_depend_on_sigma() -> None:
    # reached phase-II prefix: x1 = b2/b1 (only xi^{1,II}), x2 = 1
    w = sp.Symbol("w", positive=True)
    sigma = sp.Symbol("sigma", real=True)
    payoff = w * (sigma * b1 * (b2 / b1) + (1 - sigma) * b2 * 1)
    assert is_zero(sp.diff(payoff, sigma))


def test_THM_sigma_is_one_along_a_shortest_path_from_the_running_minimum() -> None:
    d, = nonneg("d")
    w, = pos("w")
    c_prev = d + w  # running minimum = d(y_j, g1) = w + d(y_{j+1}, g1)
    c_new = sp.Min(c_prev, d)
    assert is_zero((c_prev - c_new) / w - 1)
    assert is_zero(c_new - d)  # running minimum is again the node's distance


def test_THM_remaining_secondary_cost_is_non_increasing_in_the_running_minimum() -> None:
    # progress available on the rest of xi2: max(0, c - m); more c, more progress
    c = sp.Symbol("c", real=True)
    a, dl = nonneg("a dl")
    for m, c_hi in ((c + dl + a, c + dl), (c + a, c + a + dl), (c - a, c + dl)):
        assert is_nonneg(sp.Max(0, c_hi - m) - sp.Max(0, c - m))


def test_THM_exchange_argument_is_strict() -> None:
    big_a, s_alt, gap = nonneg("A S_alt gap")
    p, = pos("P")  # cost of xi2 between t_alpha and k, > 0 by (*)
    s_orig = s_alt + gap  # S_k(d(s_k,g1)) <= S_k(c_k)
    assert is_pos((big_a + p + s_orig) - (big_a + 0 + s_alt))


def test_THM_attacker_condition_8b() -> None:
    c0, m_minus_c0, e1, e2 = nonneg("c0 U2star e1 e2")
    p1, p2 = pos("p1 p2")  # the prior
    u_star = p1 * c0 + p2 * m_minus_c0
    u_any = p1 * (c0 + e1) + p2 * (m_minus_c0 + e2)  # L1.2, XI2.1: each type's excess >= 0
    assert is_nonneg(u_any - u_star)
    assert is_zero(u_any.subs({e1: 0, e2: 0}) - u_star)


def test_THM_secondary_path_ending_at_g1_has_no_slack() -> None:
    c0, g12, extra = nonneg("c0 g12 extra")
    length = c0 + extra  # L(xi2) >= d(s0, g1)
    j2 = length - c0 + g12
    bound = (c0 + 0 + g12) - c0  # M - c0 with v = g1
    # optimality j2 <= bound forces extra = 0
    assert sp.solve(sp.Eq(j2, bound), extra) == [0]
    assert is_nonneg(j2 - bound)


def test_THM_value_is_positive_and_voi_below_one_at_a_goal_start() -> None:
    g12, = pos("g12")
    u_star = b2 * g12 + (b1 - b2) * 0  # s0 = g1: M = d(g1, g2)
    assert is_pos(u_star)
