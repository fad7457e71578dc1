"""Checks for proofs/DP.md (the three-field DP of V_H: the class C, DP.1 on examples)."""

from __future__ import annotations

import itertools
from fractions import Fraction

import sympy as sp

from dppverify import game_value, instance_from_json
from dppverify.twogoal.value_dp import structured_value
from proofs.checks._sym import is_nonneg, is_zero, nonneg, pos


def _h(a: sp.Expr, b: sp.Expr, c: sp.Expr, y1: sp.Expr, y2: sp.Expr) -> sp.Expr:
    return (a * sp.Max(y1 - y2, 0) + b * sp.Max(y2 - y1, 0) + c * sp.Min(y1, y2))


def test_DP_max_decomposes_into_the_three_terms() -> None:
    for y1, y2 in itertools.product((0, 1, 2, sp.Rational(7, 3)), repeat=2):
        top = sp.Max(y1, y2)
        assert top == sp.Max(y1 - y2, 0) + sp.Max(y2 - y1, 0) + sp.Min(y1, y2)
    z1, z2 = nonneg("z1 z2")
    for lo, hi in ((z1, z1 + z2), (z1 + z2, z1)):  # both orders, symbolically
        assert is_zero(sp.Max(lo, hi) - (sp.Max(lo - hi, 0) + sp.Max(hi - lo, 0) + sp.Min(lo, hi)))


def test_DP_class_is_convex_on_the_segment_iff_c_at_most_a_plus_b() -> None:
    a, b, s = nonneg("a b s")
    # phi(0) = b, phi(1/2) = c/2, phi(1) = a; convex iff c/2 <= (a + b)/2
    for c, convex in ((a + b - s, True), (a + b + s + 1, False)):
        gap = (a + b) / 2 - c / 2
        assert is_nonneg(gap) == convex


def test_DP_the_attaining_split_costs_h() -> None:
    a, b, t = pos("a b t")
    y2, e = pos("y2 e")
    y1 = y2 + e  # y1 >= y2
    c_step = a + b - t  # the step term is the minimum (c < a + b)
    split_step = a * (y1 - y2) + c_step * y2
    assert is_zero(split_step - _h(a, b, c_step, y1, y2))
    c_split = a + b  # the split term is the minimum
    split_split = a * (y1 - y2) + a * y2 + b * y2
    assert is_zero(split_split - _h(a, b, c_split, y1, y2))


def test_DP_subadditivity_on_rational_samples() -> None:
    grid = [Fraction(k, 2) for k in range(5)]
    for a, b in itertools.product((Fraction(1), Fraction(5, 2)), repeat=2):
        for c in (a + b, a + b - Fraction(1, 3), Fraction(1, 2)):
            def h(y1: Fraction, y2: Fraction, a: Fraction = a, b: Fraction = b,
                  c: Fraction = c) -> Fraction:
                return a * max(y1 - y2, 0) + b * max(y2 - y1, 0) + c * min(y1, y2)
            for y, z in itertools.product(itertools.product(grid, repeat=2), repeat=2):
                assert h(*y) + h(*z) >= h(y[0] + z[0], y[1] + z[1])


EXAMPLE = {"graph": {"nodes": [{"id": v} for v in ("g1", "s", "a", "g2")],
                     "edges": [{"source": "g1", "target": "s"}, {"source": "s", "target": "a"},
                               {"source": "a", "target": "g2"}]},
           "start": "s", "goals": ["g1", "g2"], "prior": ["7/10", "3/10"]}


def test_DP_value_of_the_HORIZON_example_by_hand_and_by_the_tree() -> None:
    inst = instance_from_json(EXAMPLE)
    # by hand: d(g1,g2) = d(g2,g1) = 3. H = 1: D1(s) = 1, D2(s) = 1 + 3, m(s) = min(1 + 3, 5) = 4
    # V_1 = 3/10 * 4 + 4/10 * 1 = 8/5 (HORIZON.4). H = 2: D2(s) = 2, m(s) = min(4, 1 + 2) = 3,
    # V_2 = 3/10 * 3 + 4/10 * 1 = 13/10 = U*.
    by_hand = {1: Fraction(8, 5), 2: Fraction(13, 10)}
    for h, v in by_hand.items():
        dp = structured_value(inst, h)
        assert dp.value == v
        assert game_value(inst, h).bracket.exact == v
    assert structured_value(inst, None).value == Fraction(13, 10)


def test_DP5_dijkstra_fixpoint_and_its_steps_by_hand() -> None:
    """DP.5 on the HORIZON example: the fixpoint, the steps h and K, and the stop at K + 1."""
    from dppverify.twogoal.value_dp import value_fields
    from dppverify.twogoal.value_fixpoint import fixpoint_fields

    inst = instance_from_json(EXAMPLE)
    r = inst.roles()
    fx = fixpoint_fields(inst, r)
    assert fx is not None
    s = inst.index["s"]
    # by hand: D1(s) = 1 in 1 step; D2(s) = 2 (s -> a -> g2) in 2 steps, not 4 via g1 in 1;
    # m(s) = min(1 + m(g1) = 4, D1 + D2 = 3 after eta(s) = 2 steps) = 3, h^m(s) = 2
    assert (fx.d1[s], fx.d2[s], fx.m[s]) == (1, 2, 3)
    assert (fx.h1[s], fx.h2[s], fx.hm[s]) == (1, 2, 2)
    assert fx.last == 2
    for h in range(0, 6):  # (d): the layers stop after step K + 1 = 3, equal from step K = 2
        layers = value_fields(inst, h, r, method="layers")
        assert layers.steps == min(h, fx.last + 1) and layers.fixpoint == (h >= fx.last + 1)
        assert (layers.m[s] == fx.m[s]) == (h >= fx.hm[s])
        assert (layers.d2[s] == fx.d2[s]) == (h >= fx.h2[s])
