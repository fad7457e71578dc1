"""Exact checks of proofs/NGOAL.md: NG.2 (the coalition DP is an upper bound on V_H) on a small
deterministic campaign, NG.3 (two goals: the DP's root cover gives DP.1's formula), the two
algebraic steps of the proofs (subadditivity of the max; the slope of NG.3's objective), the
finite vertex enumeration behind NG.4 and NG.8(c), and the N = 4 refutation on the hub.
"""

from __future__ import annotations

import itertools
import random
from fractions import Fraction

import sympy as sp

from dppverify.agreement import compare_routes
from dppverify.game.examples import hub4
from dppverify.game.instance import instance_from_json
from dppverify.structured.coalition import coalition_value
from dppverify.structured.cover import zero_one_normals
from dppverify.structured.packing import packing_vertices
from dppverify.structured.proved_value import nvalue
from dppverify.tree_route.tree import count_prefixes
from dppverify.tree_route.value_lp import game_value
from proofs.checks._linear import basic_solutions
from proofs.checks.ngoal_evidence import FAMILIES, draw_case


def _cases(seed: int, goals: int, count: int) -> list[dict[str, object]]:
    rng = random.Random(seed)
    out: list[dict[str, object]] = []
    while len(out) < count:
        doc = draw_case(rng, FAMILIES[len(out) % len(FAMILIES)], goals)
        if doc is None:
            continue
        try:
            instance_from_json(doc)
        except ValueError:
            continue
        out.append(doc)
    return out


def test_NG2_the_dp_is_never_below_the_exact_lower_bound_and_NG4_holds_here() -> None:
    for goals in (3, 4):
        for doc in _cases(7, goals, 4):
            inst = instance_from_json(doc)
            h = inst.hops[inst.start] + 1
            if count_prefixes(inst, h) > 1500:
                h -= 1
            a = compare_routes(inst, h, max_prefixes=1500)
            assert a.dp >= a.tree.bracket.lower  # NG.2: V_H <= DP
            assert a.agree  # NG.4 on these cases


def test_NG3_two_goal_root_cover_is_dp1() -> None:
    for doc in _cases(3, 2, 8):
        inst = instance_from_json(doc)
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


def _packing_vertices_by_hand(n_goals: int) -> set[tuple[Fraction, ...]]:
    """Vertices of P = {λ >= 0 : Σ_S λ_S 1_S <= 1} (all non-empty S): every basis of [A | I].

    Independent of dppverify.structured.proved_value: Gauss–Jordan elimination in Fractions
    (proofs/checks/_linear.py) on every choice of N columns of the standard form
    Σ λ_S 1_S + s = 1, kept when non-singular and non-negative (a vertex of a standard-form
    polyhedron is a basic feasible solution).
    """
    sets = list(range(1, 1 << n_goals))
    cols = [tuple((t >> i) & 1 for i in range(n_goals)) for t in sets]
    cols += [tuple(int(i == j) for i in range(n_goals)) for j in range(n_goals)]
    return {c[:len(sets)] for c in basic_solutions(cols, (1,) * n_goals)}


def _y(lam: tuple[Fraction, ...], n_goals: int) -> tuple[Fraction, ...]:
    return tuple(sum((lam[j] for j, t in enumerate(range(1, 1 << n_goals)) if t >> i & 1),
                     Fraction(0)) for i in range(n_goals))


def test_NG4_NG8_the_packing_vertices_with_a_fractional_direction() -> None:
    # NG.8(c): only vertices λ of P whose y_λ is not 0/1 need checking. N = 2, 3: none, which
    # proves NG.4; N = 4: exactly the permutations of (1, 1, 1, 1/2).
    half = Fraction(1, 2)
    expected = {2: set(), 3: set(),
                4: set(itertools.permutations((Fraction(1),) * 3 + (half,)))}
    for n in (2, 3, 4):
        verts = _packing_vertices_by_hand(n)
        frac = {_y(lam, n) for lam in verts if any(x not in (0, 1) for x in _y(lam, n))}
        assert frac == expected[n], (n, frac)
        assert len(verts) == {2: 5, 3: 16, 4: 95}[n]
        # the code's vectorised enumeration finds the same vertices and directions
        code = packing_vertices(zero_one_normals(n))
        assert {y for _, y in code} == frac
        assert {lam for lam, _ in code} == {lam for lam in verts if _y(lam, n) in frac}
    # N = 5 by the code's enumeration only (377k bases): 45 directions, five up to permutation
    five = {y for _, y in packing_vertices(zero_one_normals(5))}
    assert len(five) == 45
    assert len({tuple(sorted(y)) for y in five}) == 5


def test_NG4_refuted_for_four_goals_on_the_hub() -> None:
    for directed in (True, False):
        inst = hub4(directed=directed)
        for h in (3, 4, None):
            assert coalition_value(inst, h).value == Fraction(25, 14)
            v = nvalue(inst, h)
            assert v.closed and v.value == Fraction(12, 7)
            assert (2, 2, 2, 1) in v.normals
            if h is not None:
                b = game_value(inst, h).bracket
                assert b.closed and b.exact == Fraction(12, 7)
