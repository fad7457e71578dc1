"""Checks for proofs/NRULE.md (the guarantee rule with facet normals; the checker's decision).

Exact throughout (Fractions). Each test names the step of NRULE it checks, on small random
instances drawn here (seeded) and on the four-goal hub of NGOAL.
"""

from __future__ import annotations

import itertools
import math
import random
from fractions import Fraction

from dppverify.game.examples import hub4, hub_document
from dppverify.game.instance import Instance, instance_from_json
from dppverify.game.rules import GuaranteeRule
from dppverify.structured.arc_condition import arc_condition, walkable_arcs
from dppverify.structured.cover import basic_solutions, min_cover_vectors, zero_one_normals
from dppverify.structured.guarantee import guarantee_sigma, rule_order
from dppverify.structured.lexmin import simplex_min
from dppverify.structured.normal_fixpoint import normal_sets
from dppverify.structured.rule_response import RuleSearch
from proofs.checks._linear import solve_square

HUB_EXTRAS = [(2, 2, 2, 1), (2, 2, 1, 2), (2, 1, 2, 2), (1, 2, 2, 2)]


def _hub(rng: random.Random, n_goals: int) -> Instance:
    """A random directed hub without shortcuts (u -> u1 -> middles -> two or three goals;
    every walk has at most three steps): :func:`dppverify.game.examples.hub_document`."""
    return instance_from_json(hub_document(rng, n_goals, directed=True, shortcuts=False))


def _grid(rng: random.Random, n_goals: int) -> Instance:
    """A small undirected grid with random weights (walks can cycle)."""
    rows, cols = 3, rng.randint(3, 4)
    cells = [(i, j) for i in range(rows) for j in range(cols)]
    start, *goals = rng.sample(cells, n_goals + 1)
    edges = [{"source": f"{i},{j}", "target": f"{i + di},{j + dj}", "weight": rng.randint(1, 3)}
             for i, j in cells for di, dj in ((0, 1), (1, 0)) if (i + di, j + dj) in cells]
    ws = [rng.randint(1, 6) for _ in range(n_goals)]
    doc = {"graph": {"directed": False, "nodes": [{"id": f"{i},{j}"} for i, j in cells],
                     "edges": edges},
           "start": f"{start[0]},{start[1]}", "goals": [f"{i},{j}" for i, j in goals],
           "prior": [str(Fraction(w, sum(ws))) for w in ws]}
    return instance_from_json(doc)


def _layered(inst: Instance, normals: tuple[tuple[int, ...], ...]
             ) -> dict[tuple[int, ...], dict[int, Fraction]]:
    """The rule's DP by layers (dominated covers) until a layer repeats (NR.1(b))."""
    goals = set(inst.goals)
    order = sorted(normals, key=lambda a: (sum(a), a))
    tables = {}
    for a in order:
        cols = [b for b in normals if b != a and all(x <= y for x, y in zip(b, a, strict=True))]
        tables[a] = (cols, basic_solutions(cols, a).vertices if sum(a) > 1 else [])
    term = {a: {g: sum((Fraction(a[t]) * Fraction(inst.dist_to[t][g]) for t in range(len(a))),
                       Fraction(0)) for g in goals} for a in normals}
    layer = {a: dict(term[a]) for a in normals}
    for k in range(1, 500):
        new: dict[tuple[int, ...], dict[int, Fraction]] = {}
        for a in order:
            row = dict(term[a])
            cols, verts = tables[a]
            idx = basic_solutions(cols, a).columns if verts else ()
            for v in range(inst.n_nodes):
                if v in goals:
                    continue
                vals = [Fraction(w) * max(a) + layer[a][u] for u, w in inst.succ[v]
                        if u in layer[a]]
                for vert in verts:
                    parts = [(cols[idx[j]], c) for j, c in enumerate(vert) if c]
                    if all(v in new[b] for b, _ in parts):
                        vals.append(sum((c * new[b][v] for b, c in parts), Fraction(0)))
                if vals:
                    row[v] = min(vals)
            new[a] = row
        if k > max(inst.hops) and new == layer:
            return new
        layer = new
    raise AssertionError("no repeated layer")


def test_NR1_a_full_closure_is_circular_so_the_rule_uses_dominated_covers() -> None:
    # (1, 1, 0, 0) = 1/2 (2, 1, 0, 0) + 1/2 (0, 1, 0, 0): a vertex of the full cover polytope
    # of a 0/1 vector using a normal that is not below it
    normals = (*zero_one_normals(4), (2, 1, 0, 0))
    full = basic_solutions(normals, (1, 1, 0, 0))
    uses = [{normals[full.columns[j]]: c for j, c in enumerate(v) if c} for v in full.vertices]
    assert {(2, 1, 0, 0): Fraction(1, 2), (0, 1, 0, 0): Fraction(1, 2)} in uses
    # a vertex of a cover polytope either is the normal itself or avoids it (NR.1's proof)
    rng = random.Random(0)
    for _ in range(30):
        base = list(zero_one_normals(3)) + [tuple(rng.randint(0, 3) for _ in range(3))
                                            for _ in range(3)]
        cand = tuple(dict.fromkeys(a for a in base if any(a) and math.gcd(*a) == 1))
        a = rng.choice(cand)
        t = basic_solutions(cand, a)
        for v in t.vertices:
            coef = {cand[t.columns[j]]: c for j, c in enumerate(v) if c}
            assert coef == {a: 1} or a not in coef


def test_NR1_label_setting_is_the_repeated_layer_and_the_denominators_are_bounded() -> None:
    rng = random.Random(1)
    for trial in range(8):
        n_goals = 3 + trial % 2
        inst = _hub(rng, n_goals) if trial % 2 else _grid(rng, n_goals)
        extra = ([(2, 1, 1), (1, 2, 1)] if n_goals == 3 else rng.sample(HUB_EXTRAS, 2))
        sets = normal_sets(inst, extra)
        want = _layered(inst, sets.normals)
        for j, a in enumerate(sets.normals):
            for v in range(inst.n_nodes):
                assert sets.value_at(j, v) == want[a].get(v), (trial, a, v)
        # NR.1(b): the denominators divide W·L^rank
        lcm = 1
        for a in sets.normals:
            cols = [b for b in sets.normals if b != a
                    and all(x <= y for x, y in zip(b, a, strict=True))]
            if sum(a) > 1:
                lcm = math.lcm(lcm, basic_solutions(cols, a).lcm)
        bound = lcm ** max(sum(a) for a in sets.normals)
        for a, row in want.items():
            assert all(bound % x.denominator == 0 for x in row.values()), (trial, a)


def test_NR1_d_the_zero_one_rows_ignore_the_extra_normals() -> None:
    plain, refined = normal_sets(hub4()), normal_sets(hub4(), HUB_EXTRAS)
    for j in range(15):
        for v in range(hub4().n_nodes):
            assert plain.value_at(j, v) == refined.value_at(j, v)


def test_NR2_every_walk_costs_at_least_h_when_the_arc_condition_holds() -> None:
    inst = hub4()
    sets = normal_sets(inst, HUB_EXTRAS)
    col = sets.column(inst.start)
    assert col is not None
    h = min_cover_vectors(sets.normals, col, inst.prior).dual
    rs = RuleSearch(inst, GuaranteeRule(tuple(h), tuple(HUB_EXTRAS)), sets)
    assert rs.in_start and rs.arc.holds
    order = rule_order(inst.prior)
    rng = random.Random(2)
    for _ in range(200):
        r = list(h)
        v = inst.start
        cost = [Fraction(0)] * 4
        while not inst.is_goal(v):
            u, w = rng.choice([x for x in inst.succ[v] if x[0] in rs.nodes])
            sigma, ok = guarantee_sigma(r, sets, u, w, order)
            assert ok  # F is never empty
            r = [x - Fraction(w) * s for x, s in zip(r, sigma, strict=True)]
            cost = [c + Fraction(w) * s for c, s in zip(cost, sigma, strict=True)]
            assert rs.in_sets(tuple(r), u)  # the state stays in F_u
            v = u
        for t in range(4):
            total = cost[t] + Fraction(inst.dist_to[t][v])
            assert total >= h[t]  # NR.2
            assert total == h[t] - r[t] + Fraction(inst.dist_to[t][v])  # NR.3


def _vertices(normals: tuple[tuple[int, ...], ...], m: list[Fraction]) -> list[list[Fraction]]:
    """The maximal vertices of F = {r : a·r <= m_a, a ∈ A} (N tight, independent rows,
    feasible; not below another vertex)."""
    n = len(normals[0])
    found: set[tuple[Fraction, ...]] = set()
    for rows in itertools.combinations(range(len(normals)), n):
        r = solve_square([normals[j] for j in rows], [m[j] for j in rows])
        if r is not None and all(sum((a * x for a, x in zip(normals[j], r, strict=True)),
                                     Fraction(0)) <= m[j] for j in range(len(normals))):
            found.add(tuple(r))
    out = [list(r) for r in found]
    # F_u + wΔ^N is down-closed too: the vertices below another one need no test
    return [r for r in out if not any(q != r and all(x <= y for x, y in zip(r, q, strict=True))
                                      for q in out)]


def _in_sum(normals: tuple[tuple[int, ...], ...], r: list[Fraction], m: list[Fraction],
            w: Fraction) -> bool:
    """r ∈ F_u + wΔ^N: some σ ∈ Δ^N with a·(r - wσ) <= m_a(u) for every a (exact simplex
    over σ and one slack per normal)."""
    n, k = len(r), len(normals)
    rows = [[w * a[t] for t in range(n)] + [Fraction(-int(i == j)) for i in range(k)]
            for j, a in enumerate(normals)]
    rhs = [sum((a[t] * r[t] for t in range(n)), Fraction(0)) - m[j]
           for j, a in enumerate(normals)]
    rows.append([Fraction(1)] * n + [Fraction(0)] * k)
    rhs.append(Fraction(1))
    return simplex_min([Fraction(0)] * (n + k), rows, rhs) is not None


def test_NR2_the_arc_test_is_containment_at_the_vertices_of_F() -> None:
    """NR.2's criterion, as the checker evaluates it (support functions in the packing
    directions), against the definition: F_x is down-closed with recession cone -R^N_+, so
    F_x ⊆ F_u + wΔ^N (also down-closed) iff every vertex of F_x lies in F_u + wΔ^N."""
    rng = random.Random(9)
    cases = [(hub4(), ()), (hub4(), (HUB_EXTRAS[0],)), (hub4(), tuple(HUB_EXTRAS))]
    cases.append((_hub(rng, 4), tuple(rng.sample(HUB_EXTRAS, rng.randint(0, 2)))))
    verdicts = set()
    for inst, extra in cases:
        sets = normal_sets(inst, extra)
        got = arc_condition(sets, inst.start)
        tails, heads, weights = walkable_arcs(sets, inst.start)
        failing = set()
        for x, u, w in zip(tails, heads, weights, strict=True):
            mx, mu = sets.column(x), sets.column(u)
            assert mx is not None and mu is not None
            if not all(_in_sum(sets.normals, r, mu, Fraction(w))
                       for r in _vertices(sets.normals, mx)):
                failing.add((x, u))
        assert got.holds == (not failing), (extra, got, failing)
        assert set(got.failing) == failing
        verdicts.add(got.holds)
    assert verdicts == {True, False}  # both outcomes occur


def test_NR4_ab_the_abstract_state_gives_the_same_sigma_as_the_true_state() -> None:
    rng = random.Random(3)
    checked = dropped = 0
    for trial in range(30):
        inst = _grid(rng, 3 + trial % 2)
        sets = normal_sets(inst)
        col = sets.column(inst.start)
        assert col is not None
        h = [x - Fraction(rng.randint(0, 8)) for x in
             min_cover_vectors(sets.normals, col, inst.prior).dual]
        rs = RuleSearch(inst, GuaranteeRule(tuple(h)), sets)
        theta = rng.randrange(inst.n_goals)
        r_true = [Fraction(x) for x in h]
        r_abs = rs.abstract(tuple(r_true), theta)
        v = inst.start
        for _ in range(12):
            if inst.is_goal(v):
                break
            u, w = rng.choice(rs.succ[v])
            new_abs, s_abs = rs.step(r_abs, u, w)
            new_true, s_true = rs.step(tuple(r_true), u, w)
            assert s_abs == s_true, (trial, r_true, r_abs)  # NR.4(b)
            r_true = [x for x in new_true if x is not None]
            r_abs = rs.abstract(new_abs, theta)
            assert all(a is None or a == b for a, b in zip(r_abs, r_true, strict=True))
            v = u
            checked += 1
            dropped += any(a is None for a in r_abs)
    assert checked > 50 and dropped > 10


def test_NR4_d_the_search_equals_an_exhaustive_enumeration_on_finite_games() -> None:
    rng = random.Random(4)
    for trial in range(10):
        n_goals = 3 + trial % 3
        inst = _hub(rng, n_goals)
        extra = rng.sample(HUB_EXTRAS, 2) if n_goals == 4 else []
        sets = normal_sets(inst, extra)
        col = sets.column(inst.start)
        assert col is not None
        h = [x + Fraction(rng.randint(-2, 2), 2) for x in
             min_cover_vectors(sets.normals, col, inst.prior).dual]
        rule = GuaranteeRule(tuple(h), tuple(extra))
        rs = RuleSearch(inst, rule, sets)
        order = rule_order(inst.prior)
        # every walk of the finite game (hub gadgets: at most 4 steps)
        walks: list[list[int]] = [[inst.start]]
        done = []
        while walks:
            w = walks.pop()
            if inst.is_goal(w[-1]):
                done.append(w)
                continue
            walks.extend([*w, u] for u, _ in rs.succ.get(w[-1], ()))
        for theta in range(n_goals):
            costs = []
            for w in done:
                r = list(h)
                for a, b in itertools.pairwise(w):
                    wt = Fraction(inst.weight(a, b))  # type: ignore[arg-type]
                    s, _ = guarantee_sigma(r, sets, b, wt, order)
                    r = [x - wt * y for x, y in zip(r, s, strict=True)]
                costs.append(h[theta] - r[theta] + Fraction(inst.dist_to[theta][w[-1]]))
            exact = min(costs)
            for bound in (exact, exact + 1, h[theta]):
                res = rs.best(theta, bound)
                assert res.decided
                if exact < bound:
                    assert res.value == exact, (trial, theta, bound)
                else:
                    assert res.value is None
