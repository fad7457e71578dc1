"""Exact checks of proofs/NGOAL.md: NG.2 (the coalition DP is an upper bound on V_H) on a small
deterministic campaign, NG.3 (two goals: the DP's root cover gives DP.1's formula), and the two
algebraic steps of the proofs (subadditivity of the max; the slope of NG.3's objective).
"""

from __future__ import annotations

import random
from fractions import Fraction

import sympy as sp

from dppverify.ngoal.agreement import compare_routes
from dppverify.ngoal.coalition import coalition_value
from dppverify.ngoal.instance import ninstance_from_json
from dppverify.ngoal.tree import count_nprefixes
from proofs.checks.ngoal_evidence import FAMILIES, draw_case


def _cases(seed: int, goals: int, count: int) -> list[dict[str, object]]:
    rng = random.Random(seed)
    out: list[dict[str, object]] = []
    while len(out) < count:
        doc = draw_case(rng, FAMILIES[len(out) % len(FAMILIES)], goals)
        if doc is None:
            continue
        try:
            ninstance_from_json(doc)
        except ValueError:
            continue
        out.append(doc)
    return out


def test_NG2_the_dp_is_never_below_the_exact_lower_bound_and_NG4_holds_here() -> None:
    for goals in (3, 4):
        for doc in _cases(7, goals, 4):
            inst = ninstance_from_json(doc)
            h = inst.hops[inst.start] + 1
            if count_nprefixes(inst, h) > 1500:
                h -= 1
            a = compare_routes(inst, h, max_prefixes=1500)
            assert a.dp >= a.tree.bracket.lower  # NG.2: V_H <= DP
            assert a.agree  # NG.4 on these cases


def test_NG3_two_goal_root_cover_is_dp1() -> None:
    for doc in _cases(3, 2, 8):
        inst = ninstance_from_json(doc)
        h = inst.hops[inst.start] + 2
        v = coalition_value(inst, h)
        d1, d2, m = (v.coalition_costs[k] for k in (1, 2, 3))
        big, small = (0, 1) if inst.prior[0] >= inst.prior[1] else (1, 0)
        dbig = (d1, d2)[big]
        b_big, b_small = inst.prior[big], inst.prior[small]
        assert m <= d1 + d2
        assert v.value == b_small * m + (b_big - b_small) * dbig
        assert sum(v.cover.values(), Fraction(0)) <= 1


def test_subadditivity_of_the_max_and_the_NG3_slope() -> None:
    # max(a1 + c1, a2 + c2) <= max(a1, a2) + max(c1, c2) (the step of NG.2, two types; N types
    # follow by induction): in each of the four cases of which argument attains each max, the
    # other is the max minus a non-negative slack, and the gap is a sum of slacks.
    s, t = sp.symbols("s t", nonnegative=True)
    x, y = sp.symbols("x y", real=True)
    for a_top in (0, 1):
        for c_top in (0, 1):
            a = [x - s if i != a_top else x for i in range(2)]
            c = [y - t if i != c_top else y for i in range(2)]
            right = x + y  # max(a) + max(c)
            for i in range(2):
                gap = sp.expand(right - (a[i] + c[i]))
                assert gap.is_nonnegative, gap
    b1, b2, d1, d2, m, c = sp.symbols("b1 b2 D1 D2 m c12", real=True)
    objective = (b1 - c) * d1 + (b2 - c) * d2 + c * m
    assert sp.expand(sp.diff(objective, c)) == sp.expand(m - d1 - d2)
    assert sp.expand(objective.subs(c, b2) - (b2 * m + (b1 - b2) * d1)) == 0
