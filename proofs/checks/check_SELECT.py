"""Checks for proofs/SELECT.md (goal selection: the Attacker chooses its goal).

Exact throughout except SELECT.9's walk LP (HiGHS, a float LP compared within 1e-9 with the exact
DP). SELECT.A on random down-closed polyhedra, with the support function by two routes (the
solver's cover simplex and an independent vertex enumeration by Gauss–Jordan); SELECT.4's three
properties; SELECT.5 and SELECT.8 on random instances by following every walk of the
constructed profile with the written rule and with the mixture; SELECT.7(a), SELECT.8's algebra
and SELECT.10 in sympy.
"""

from __future__ import annotations

import itertools
import random
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from scipy.optimize import linprog

from dppverify.errors import HorizonError
from dppverify.game.instance import instance_from_json
from dppverify.game.mixture_rule import ProgressMixture
from dppverify.structured.selection_value import goal_values, selection_value
from dppverify.tree_route.tree import build_tree
from proofs.checks._linear import solve_square
from solver.coalitions.construction import certified_sets
from solver.coalitions.guarantee_rule import priority_order, rule_step
from solver.coalitions.guarantee_sets import symmetric_closure
from solver.coalitions.normal_cover import normal_cover_lp
from solver.coalitions.vertex_tables import zero_one_normals
from solver.formats.movingai import map_file, read_map_bytes
from solver.selection.equilibrium import _raise_off_support, selection_equilibrium
from tests.solver._ngoal_families import draw

Normal = tuple[int, ...]


def _dot(a: tuple, x: tuple | list) -> Fraction:
    return sum((Fraction(u) * Fraction(v) for u, v in zip(a, x, strict=True)), Fraction(0))


def _polyhedron(rng: random.Random, n: int) -> tuple[tuple[Normal, ...], list[Fraction],
                                                       list[Fraction]]:
    """Random normals (0/1 plus a symmetric extra for N >= 3), closed-looking costs, values."""
    normals = zero_one_normals(n)
    if n >= 3 and rng.random() < 0.5:
        normals = symmetric_closure([*normals, (2, 2, 1) + (0,) * (n - 3)])
    costs = [Fraction(rng.randint(2, 12) * sum(a) + rng.randint(0, 4), rng.randint(1, 3))
             for a in normals]
    r = [Fraction(rng.randint(-3, 3), rng.randint(1, 2)) for _ in range(n)]
    return normals, costs, r


def _diagonal(normals: tuple[Normal, ...], costs: list[Fraction], r: list[Fraction]
              ) -> tuple[Fraction, list[Normal]]:
    vals = [(m - _dot(a, r)) / sum(a) for a, m in zip(normals, costs, strict=True)]
    t = min(vals)
    return t, [a for a, v in zip(normals, vals, strict=True) if v == t]


def _vertices(normals: tuple[Normal, ...], costs: list[Fraction]) -> list[list[Fraction]]:
    """The vertices of ``F``: every choice of N rows solved (Gauss–Jordan in Fractions,
    ``proofs/checks/_linear.py``), kept when feasible."""
    n = len(normals[0])
    out = []
    for rows in itertools.combinations(range(len(normals)), n):
        x = solve_square([list(normals[k]) for k in rows], [costs[k] for k in rows])
        if x is not None and all(_dot(a, x) <= m for a, m in zip(normals, costs, strict=True)):
            out.append(x)
    return out


def _support_by_vertices(vertices: list[list[Fraction]], q: list[Fraction]) -> Fraction:
    """``h_F(q)`` as the best vertex of ``F`` (``q > 0``: a bounded LP, a vertex optimum)."""
    return max(_dot(tuple(q), x) for x in vertices)


def _in_hull(q: list[Fraction], binding: list[Normal]) -> bool:
    """``q ∈ conv{a/|a| : a ∈ binding}``: the cover LP with the binding columns free has value 0."""
    n = len(q)
    units = [tuple(int(i == j) for j in range(n)) for i in range(n)]
    cols = list(binding) + [u for u in units if u not in binding]
    costs = [Fraction(0)] * len(binding) + [Fraction(1)] * (len(cols) - len(binding))
    return normal_cover_lp(cols, costs, q).value == 0


def _simplex_grid(n: int, k: int) -> list[list[Fraction]]:
    return [[Fraction(c, k) for c in comp] for comp in itertools.product(range(k + 1), repeat=n)
            if sum(comp) == k]


@pytest.mark.parametrize("seed", range(12))
def test_SELECTA_the_diagonal_minimum_and_its_minimisers(seed: int) -> None:
    rng = random.Random(seed)
    n = 2 + seed % 3
    normals, costs, r = _polyhedron(rng, n)
    t, binding = _diagonal(normals, costs, r)
    h = [t + x for x in r]
    assert all(_dot(a, h) <= m for a, m in zip(normals, costs, strict=True))  # (i)
    q_star = [sum((Fraction(a[i], sum(a)) for a in binding), Fraction(0)) / len(binding)
              for i in range(n)]
    vertices = _vertices(normals, costs)
    for q in [*_simplex_grid(n, 6 if n < 4 else 4), q_star]:
        lp = normal_cover_lp(normals, costs, q)
        if all(x > 0 for x in q):
            assert lp.value == _support_by_vertices(vertices, q)  # two routes to h_F
        gap = lp.value - _dot(tuple(q), r) - t
        assert gap >= 0  # (ii)
        assert (gap == 0) == _in_hull(q, binding)  # (ii): equality exactly on Q*
        if gap == 0:  # (iii): h* optimal, every optimal cover on binding normals
            assert _dot(tuple(q), h) == lp.value
            assert all(normals[j] in binding for j in lp.cover)
    union = {i for a in binding for i, x in enumerate(a) if x}
    assert {i for i, x in enumerate(q_star) if x} == union


@pytest.mark.parametrize("seed", range(12))
def test_SELECT4_raising_keeps_h_in_F_and_makes_each_raised_goal_tight(seed: int) -> None:
    rng = random.Random(100 + seed)
    n = 2 + seed % 4
    normals, costs, r = _polyhedron(rng, n)
    r[0] += 20  # a very valuable goal: the choice concentrates on few goals
    t, binding = _diagonal(normals, costs, r)
    q = tuple(sum((Fraction(a[i], sum(a)) for a in binding), Fraction(0)) / len(binding)
              for i in range(n))
    h0 = [t + x for x in r]
    h = list(h0)
    tight = _raise_off_support(h, q, normals, costs)
    assert set(tight) == {i for i in range(n) if not q[i]}
    assert all(x >= y for x, y in zip(h, h0, strict=True))
    assert all(_dot(a, h) <= m for a, m in zip(normals, costs, strict=True))
    assert all(_dot(a, h) == m for a, m in zip(normals, costs, strict=True) if a in binding)
    for i in tight:
        assert any(a[i] > 0 and _dot(a, h) == m for a, m in zip(normals, costs, strict=True))


CASES = ([draw(f, s, n) for f in ("hub", "digraph", "grid") for s in range(2) for n in (2, 3, 4)]
         + [draw("grid", 1, 5)])


def _selection_doc(doc: dict, seed: int) -> dict:
    out = {k: v for k, v in doc.items() if k != "prior"}
    out["goal_selection"] = True
    if seed % 2:
        out["goal_values"] = [str(Fraction(i, 2)) for i in range(len(doc["goals"]))]
    return out


@pytest.mark.parametrize("k", range(len(CASES)))
def test_SELECT5_every_walk_costs_h_under_the_written_rule(k: int) -> None:
    doc = _selection_doc(CASES[k], k)
    eq = selection_equilibrium(doc)
    game = eq.selection.game
    cs = certified_sets(game)
    fix, graph = cs.written, cs.graph
    node = {int(v): i for i, v in enumerate(cs.labels)}
    normals = fix.system.normals
    order = priority_order(eq.choice)
    net = game.network
    for theta, mix in enumerate(eq.mixtures):
        assert sum(p for _, p in mix) == 1
        for walk, _ in mix:
            r = eq.h
            for v, u in itertools.pairwise(walk):
                w = Fraction(int(net.arc_weight(v, u) or 0), game.denominator)
                m_u = [fix.value(j, node[u]) for j in range(len(normals))]
                sigma, ok = rule_step(r, normals, m_u, w, order)
                assert ok
                r = tuple(x - w * s for x, s in zip(r, sigma, strict=True))
            assert eq.h[theta] - r[theta] + game.distance(theta, walk[-1]) == eq.h[theta]
    net_costs = [c - x for c, x in zip(eq.costs, eq.selection.values, strict=True)]
    assert all(c == eq.value for c, q in zip(net_costs, eq.choice, strict=True) if q)
    assert all(c >= eq.value for c in net_costs)
    assert graph.n_goals == game.n_goals
    # the checker's own V_sel (its own DP, vertex tables and arc test) agrees
    assert selection_value(instance_from_json(doc)).value == eq.value


@pytest.mark.parametrize("k", [k for k in range(len(CASES)) if len(CASES[k]["goals"]) == 2])
def test_SELECT8_the_mixture_charges_each_walk_h(k: int) -> None:
    doc = _selection_doc(CASES[k], k)
    eq = selection_equilibrium(doc, rule="mixture")
    assert eq.mixture is not None
    sel = instance_from_json(doc)  # the checker's reading and the checker's mixture
    mix = ProgressMixture(0, eq.mixture.alpha)
    game = sel
    for theta, walks in enumerate(eq.mixtures):
        for walk, _ in walks:
            cost = Fraction(game.dist_to[theta][walk[-1]])
            for (v, u), dist in zip(itertools.pairwise(walk), mix.along(game, walk),
                                    strict=True):
                cost += Fraction(game.weight(v, u)) * dist[theta]
            assert cost == eq.h[theta] == eq.mixture.guaranteed[theta]
    d1, d2, m = eq.mixture.d1, eq.mixture.d2, eq.mixture.M
    r1, r2 = goal_values(sel)
    assert eq.value == min(d1 - r1, d2 - r2, (m - r1 - r2) / 2)


def test_SELECT8_paper10() -> None:
    path = Path(__file__).resolve().parents[2] / "examples" / "paper10.map"
    doc = {"format": "dpp-map-instance/1", "map": str(path),
           "map_sha256": read_map_bytes(map_file(str(path)))[1], "start": [9, 0],
           "goals": [[0, 9], [0, 0]], "goal_selection": True}
    eq = selection_equilibrium(doc, rule="mixture")
    assert eq.mixture is not None
    assert (eq.mixture.d1, eq.mixture.d2, eq.mixture.M) == (18, 17, 25)
    assert (eq.value, eq.choice, eq.mixture.alpha) == (Fraction(25, 2), (Fraction(1, 2),) * 2,
                                                       Fraction(9, 20))


def test_SELECT7a_the_mixture_is_linear_walk_by_walk() -> None:
    alpha, w, d = sp.symbols("alpha w d", positive=True)
    sa, sb = sp.symbols("s_a s_b")  # the two rules' weight on the type's goal at one step
    mix = alpha * sa + (1 - alpha) * sb
    cost_mix = w * mix + d
    assert sp.expand(cost_mix - (alpha * (w * sa + d) + (1 - alpha) * (w * sb + d))) == 0


def test_SELECT8_the_weight_puts_both_types_on_the_diagonal() -> None:
    d1, d2, m, r1, r2 = sp.symbols("d1 d2 M r1 r2", real=True)
    gap = d1 + d2 - m
    a0 = (2 * d2 - m + r1 - r2) / (2 * gap)
    c1 = m - d2 + a0 * gap
    c2 = d2 - a0 * gap
    s = (m - r1 - r2) / 2
    assert sp.simplify(c1 - r1 - s) == 0 and sp.simplify(c2 - r2 - s) == 0
    # alpha0 > 1  <=>  M > 2 d1 - r1 + r2  (D > 0): alpha0 - 1 = (M - 2 d1 + r1 - r2) / (2 D)
    assert sp.simplify((a0 - 1) - (m - 2 * d1 + r1 - r2) / (2 * gap)) == 0
    # ... and then (M - r1 - r2)/2 - (d1 - r1) = (M - 2 d1 + r1 - r2)/2 > 0
    assert sp.simplify(s - (d1 - r1) - (m - 2 * d1 + r1 - r2) / 2) == 0
    # the mixture's costs: alpha (d1, M - d1) + (1 - alpha)(M - d2, d2)
    alpha = sp.symbols("alpha")
    assert sp.expand(alpha * d1 + (1 - alpha) * (m - d2) - (m - d2 + alpha * gap)) == 0
    assert sp.expand(alpha * (m - d1) + (1 - alpha) * d2 - (d2 - alpha * gap)) == 0


def test_SELECT10_two_goals_have_one_kink_at_one_half() -> None:
    q, d1, d2, m = sp.symbols("q d1 d2 M", real=True)
    above = (1 - q) * m + (2 * q - 1) * d1   # g1 primary (q >= 1/2): U* = b2 M + (b1 - b2) d1
    below = q * m + (1 - 2 * q) * d2         # g2 primary (q <= 1/2)
    assert sp.factor(above - below) == sp.factor((2 * q - 1) * (d1 + d2 - m))
    assert sp.simplify(above.subs(q, sp.Rational(1, 2)) - m / 2) == 0
    assert sp.simplify(below.subs(q, sp.Rational(1, 2)) - m / 2) == 0


def _walk_lp(doc: dict, horizon: int) -> float:
    """SELECT.9's LP on the walk tree: variables q, realization masses y_θ(p) (root q_θ), z_p."""
    sel = instance_from_json(doc)
    tree = build_tree(sel, horizon)
    n, p_count = sel.n_goals, tree.n_prefixes
    nv = n + n * p_count + p_count  # q, y, z
    yi = lambda t, p: n + t * p_count + p  # noqa: E731
    zi = lambda p: n + n * p_count + p  # noqa: E731
    cost = np.zeros(nv)
    cost[:n] = [-float(x) for x in goal_values(sel)]
    leaves = tree.leaves()
    for p in range(1, p_count):
        cost[zi(p)] = float(tree.weight[p])
    for t in range(n):
        for p in leaves:
            cost[yi(t, int(p))] = float(sel.dist_to[t][int(tree.node[p])])
    eq_rows, eq_rhs, ub_rows = [], [], []
    row = np.zeros(nv)
    row[:n] = 1
    eq_rows.append(row)
    eq_rhs.append(1.0)
    for t in range(n):
        row = np.zeros(nv)
        row[yi(t, 0)], row[t] = 1, -1
        eq_rows.append(row)
        eq_rhs.append(0.0)
        for p in range(p_count):
            kids = tree.children(p)
            if len(kids):
                row = np.zeros(nv)
                row[yi(t, p)] = 1
                for c in kids:
                    row[yi(t, c)] = -1
                eq_rows.append(row)
                eq_rhs.append(0.0)
        for p in range(1, p_count):
            row = np.zeros(nv)
            row[yi(t, p)], row[zi(p)] = 1, -1
            ub_rows.append(row)
    res = linprog(cost, A_ub=np.array(ub_rows), b_ub=np.zeros(len(ub_rows)),
                  A_eq=np.array(eq_rows), b_eq=np.array(eq_rhs), bounds=(0, None),
                  method="highs")
    assert res.status == 0
    return float(res.fun)


@pytest.mark.parametrize("k", [0, 1, 3, 6, 7])
@pytest.mark.parametrize("horizon", [2, 3])
def test_SELECT9_the_truncated_value_is_the_dp_diagonal(k: int, horizon: int) -> None:
    doc = _selection_doc(CASES[k], k)
    try:
        lp = _walk_lp(doc, horizon)
    except HorizonError as exc:  # no goal within the horizon: nothing to compare
        pytest.skip(str(exc))
    v = selection_value(instance_from_json(doc), horizon)
    assert v.value is not None or len(doc["goals"]) > 3
    if v.value is not None:
        assert abs(lp - float(v.value)) <= 1e-9
    else:
        assert float(v.lower) - 1e-9 <= lp <= float(v.upper) + 1e-9
