"""Symbolic checks for proofs/L3.md (greedy rationality of the Defender)."""

from __future__ import annotations

import sympy as sp

from proofs.checks._sym import is_nonneg, is_pos, is_zero, nonneg, pos


def test_L3_per_infoset_payoff_is_maximised_greedily() -> None:
    # payoff at a prefix p: w (sigma A + (1 - sigma) B), A = b1 x1(p), B = b2 x2(p)
    w, = pos("w")
    big_b, gap, s = nonneg("B gap s")
    big_a = big_b + gap  # A >= B
    for sigma in (s / (1 + s), sp.Integer(0)):  # any sigma in [0, 1)
        payoff = w * (sigma * big_a + (1 - sigma) * big_b)
        best = w * big_a
        assert is_nonneg(best - payoff)
        assert is_zero((best - payoff) - w * (1 - sigma) * gap)  # strict iff gap > 0


def test_L3_greedy_rule_is_a_belief_threshold_at_one_half() -> None:
    big_a, big_b = pos("A B")
    belief = big_a / (big_a + big_b)  # Bayes: b1 x1 / (b1 x1 + b2 x2)
    assert is_zero((belief - sp.Rational(1, 2)) - (big_a - big_b) / (2 * (big_a + big_b)))


def test_L3_averaging_own_randomisation_changes_nothing() -> None:
    big_a, big_b = sp.symbols("A B", real=True)
    p1, p2 = pos("p1 p2")
    s1, s2, s3 = sp.symbols("s1 s2 s3", real=True)
    p3 = 1 - p1 - p2
    lhs = sum(p * (s * big_a + (1 - s) * big_b) for p, s in ((p1, s1), (p2, s2), (p3, s3)))
    bar = p1 * s1 + p2 * s2 + p3 * s3
    assert is_zero(lhs - (bar * big_a + (1 - bar) * big_b))


def test_L3_strict_preference_is_strict() -> None:
    w, gap = pos("w gap")
    s, = nonneg("s")
    sigma = s / (1 + s)  # < 1
    assert is_pos(w * (1 - sigma) * gap)
