"""Symbolic checks for proofs/L1.md (lower bound on U^1 and its exact equality case)."""

from __future__ import annotations

import sympy as sp

from proofs.checks._sym import is_pos, is_zero, nonneg, pos


def _j1_minus_c0(c0: sp.Expr, c_before: sp.Expr, d_end: sp.Expr) -> sp.Expr:
    c_t = sp.Min(c_before, d_end)
    return (c0 - c_t) + d_end - c0  # J1 - d(s0, g1), by TEL


def test_L1_equality_when_the_last_node_is_within_the_running_minimum() -> None:
    c0, c_before = sp.symbols("c0 c_before", real=True)
    e, = nonneg("e")
    # d(s_T, g1) <= c_{T-1}: covers s_T = g1 (d = 0) and s_T = g2 with d(g2,g1) <= c_{T-1}
    assert is_zero(_j1_minus_c0(c0, c_before, c_before - e))
    cb, = nonneg("cb")  # s_T = g1: d = 0 <= c_{T-1}
    assert is_zero(_j1_minus_c0(c0, cb, 0))


def test_L1_strict_when_the_fake_goal_is_farther_than_the_running_minimum() -> None:
    c0, c_before = sp.symbols("c0 c_before", real=True)
    a, = pos("a")
    assert is_pos(_j1_minus_c0(c0, c_before, c_before + a))


def test_L1_walk_of_length_zero() -> None:
    # T = 0: s0 is a goal, J1 = d(s0, g1) = c0 exactly.
    c0, = nonneg("c0")
    assert is_zero((c0 - c0) + c0 - c0)


def test_L1_triangle_walk_to_the_fake_goal_attains_the_bound() -> None:
    # examples/triangle.json: c0 = d(s,g1) = 3, d(g2,g1) = 2 <= c0: the walk s -> g2 costs 3.
    assert _j1_minus_c0(sp.Integer(3), sp.Integer(3), sp.Integer(2)) == 0
    # path g1 - s - g2 with unit weights (ERRATA E4): d(g2,g1) = 2 > c0 = 1: costs 2 > 1.
    assert _j1_minus_c0(sp.Integer(1), sp.Integer(1), sp.Integer(2)) == 1
