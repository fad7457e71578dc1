"""Symbolic checks for proofs/L5.md (beliefs b1 / 1/2 / 0 induced by eq. (15))."""

from __future__ import annotations

import sympy as sp

from proofs.checks._sym import is_nonneg, is_zero, nonneg

e = sp.Symbol("e", nonnegative=True)  # b1 = 1/2 + e, e in [0, 1/2)
B1 = sp.Rational(1, 2) + e
B2 = 1 - B1
P_II = B2 / B1  # eq. (15): gamma*(xi^{1,II} | g1)
P_I = 1 - P_II


def _belief(mass1: sp.Expr, mass2: sp.Expr) -> sp.Expr:
    return B1 * mass1 / (B1 * mass1 + B2 * mass2)


def test_L5_eq15_probabilities_are_in_the_unit_interval() -> None:
    h, = nonneg("h")
    b2 = sp.Rational(1, 2) - h / (1 + h) / 2  # every b2 in (0, 1/2]
    p_ii = b2 / (1 - b2)
    assert is_nonneg(p_ii) and is_nonneg(1 - p_ii)
    assert is_zero(P_I + P_II - 1)


def test_L5_phase_beliefs_for_every_prior() -> None:
    assert is_zero(_belief(1, 1) - B1)  # phase I: both primary paths still on xi2
    assert is_zero(_belief(P_II, 1) - sp.Rational(1, 2))  # phase II: only xi^{1,II}
    assert is_zero(_belief(0, 1))  # phase III: both primary paths have left
    # off xi2 only the primary has mass (when positive): belief 1
    assert is_zero(_belief(P_I, 0) - 1) and is_zero(_belief(P_II, 0) - 1)


def test_L5_step_by_step_bayes_agrees() -> None:
    def update(beta: sp.Expr, q1: sp.Expr, q2: sp.Expr) -> sp.Expr:
        return beta * q1 / (beta * q1 + (1 - beta) * q2)

    beta = B1
    beta = update(beta, P_II, 1)  # step t_I + 1: the primary stays on xi2 w.p. b2/b1
    assert is_zero(beta - sp.Rational(1, 2))
    beta = update(beta, 1, 1)  # inside phase II both continue surely
    assert is_zero(beta - sp.Rational(1, 2))
    assert is_zero(update(beta, 0, 1))  # step t_II + 1: the primary has left


def test_L5_swapped_reading_gives_phase_II_belief_b1_minus_b2_over_b1() -> None:
    swapped = _belief(P_I, 1)
    assert is_zero(swapped - (B1 - B2) / B1)
    assert sp.solve(sp.Eq(swapped, sp.Rational(1, 2)), e) == [sp.Rational(1, 6)]  # b1 = 2/3
