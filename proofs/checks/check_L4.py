"""Symbolic checks for proofs/L4.md (belief along xi2 never increases)."""

from __future__ import annotations

import sympy as sp

from proofs.checks._sym import is_nonneg, is_pos, is_zero, nonneg, pos


def _update(beta: sp.Expr, q1: sp.Expr, q2: sp.Expr) -> sp.Expr:
    """Bayes, eq. (2): continuation probabilities q1 (primary), q2 (secondary)."""
    return beta * q1 / (beta * q1 + (1 - beta) * q2)


def test_L4_update_with_a_secondary_that_surely_continues_never_increases() -> None:
    p, s, v = pos("p s v")
    u, = nonneg("u")
    beta = p / (p + s)  # any belief in (0, 1)
    q1 = u / (u + v)  # any probability in [0, 1)
    drop = beta - _update(beta, q1, 1)
    assert is_nonneg(drop)
    assert is_zero(drop - beta * (1 - beta) * (1 - q1) / (beta * q1 + 1 - beta))
    assert is_zero(beta - _update(beta, 1, 1))  # q1 = 1 keeps it


def test_L4_needs_the_secondary_to_be_deterministic() -> None:
    # a secondary that continues with probability 1/2 makes the belief rise
    p, s = pos("p s")
    beta = p / (p + s)
    assert is_pos(_update(beta, 1, sp.Rational(1, 2)) - beta)
