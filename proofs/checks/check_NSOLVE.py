"""Checks for proofs/NSOLVE.md (N goals: the guarantee-vector Defender and the arc condition).

Exact throughout (Fractions, sympy ranks). NSOLVE.2's enumeration of the non-pattern extreme
rays is re-checked ray by ray, and the arc condition itself by brute force (every vertex of
``G_v`` lies in ``G_u + wΔ^N``) on random closed coalition-cost vectors.
"""

from __future__ import annotations

import itertools
import random
from collections.abc import Iterator, Sequence
from fractions import Fraction

import numpy as np
import sympy as sp

from dppverify.game.instance import Instance, instance_from_json
from dppverify.structured.arc_condition import bad_rays
from dppverify.structured.coalition import CoalitionRunner
from dppverify.structured.cover import balanced_vertices, members, min_cover
from dppverify.structured.guarantee import guarantee_sets, guarantee_sigma, rule_order


def _y(ray: tuple[tuple[int, Fraction], ...], n: int) -> list[Fraction]:
    return [sum((c for s, c in ray if s >> i & 1), Fraction(0)) for i in range(n)]


def test_NSOLVE2_no_non_pattern_ray_for_two_and_three_goals() -> None:
    assert bad_rays(2) == () and bad_rays(3) == ()


def test_NSOLVE2_the_four_goal_rays_are_extreme_and_not_patterns() -> None:
    n = 4
    rays = bad_rays(n)
    assert len(rays) == 36
    assert sum(1 for _, star in rays if star == 0) == 9
    assert (((3, Fraction(1, 2)), (5, Fraction(1, 2)), (14, Fraction(1, 2))), 0) in rays
    masks = list(range(1, 1 << n))
    for ray, star in rays:
        c = {s: x for s, x in ray}
        y = _y(ray, n)
        assert y[star] == 1 == max(y) and all(x > 0 for x in c.values())
        assert not all(v in (0, 1) for v in y)  # not a fractional partition of a set ∋ θ*
        tight = [[sp.Integer(int(s == t)) for t in masks] for s in masks if s not in c]
        tight += [[sp.Integer((t >> star & 1) - (t >> i & 1)) for t in masks]
                  for i in range(n) if i != star and y[i] == y[star]]
        assert sp.Matrix(tight).rank() == len(masks) - 1  # an extreme ray of C_θ*


def _close(raw: dict[int, Fraction], n: int) -> dict[int, Fraction]:
    """The split closure: ``m_S = min(raw_S, min over minimal balanced collections)``."""
    m: dict[int, Fraction] = {}
    for s in sorted(raw, key=lambda t: (bin(t).count("1"), t)):
        best = raw[s]
        el = members(s)
        if len(el) >= 2:
            table = balanced_vertices(len(el))
            for vert in table.vertices:
                tot = Fraction(0)
                for j, coef in enumerate(vert):
                    if coef:
                        glob = sum(1 << el[i] for i in members(table.columns[j]))
                        tot += coef * m[glob]
                best = min(best, tot)
        m[s] = best
    return m


def _solve(rows: list[list[Fraction]], rhs: list[Fraction]) -> list[Fraction] | None:
    """Exact Gauss-Jordan on a square system (None when singular)."""
    n = len(rows)
    a = [[*r, x] for r, x in zip(rows, rhs, strict=True)]
    for c in range(n):
        p = next((i for i in range(c, n) if a[i][c]), None)
        if p is None:
            return None
        a[c], a[p] = a[p], a[c]
        a[c] = [x / a[c][c] for x in a[c]]
        for i in range(n):
            if i != c and a[i][c]:
                f = a[i][c]
                a[i] = [x - f * y for x, y in zip(a[i], a[c], strict=True)]
    return [a[i][n] for i in range(n)]


def _vertices(m: dict[int, Fraction], n: int) -> list[list[Fraction]]:
    """Every vertex of ``{r : r(S) <= m_S ∀S}`` (n tight, linearly independent constraints)."""
    out = []
    masks = sorted(m)
    for basis in itertools.combinations(masks, n):
        r = _solve([[Fraction(s >> i & 1) for i in range(n)] for s in basis],
                   [m[s] for s in basis])
        if r is not None and all(sum((r[i] for i in members(s)), Fraction(0)) <= m[s]
                                 for s in masks):
            out.append(r)
    return out


def _feasible(r: list[Fraction], mu: dict[int, Fraction], w: Fraction, n: int) -> bool:
    """Is there σ ∈ Δ^N with σ(S) >= (r(S) - mu_S)/w for every S? (vertex enumeration)"""
    need = {s: (sum((r[i] for i in members(s)), Fraction(0)) - mu[s]) / w for s in mu}
    cons = [(1 << i, Fraction(0)) for i in range(n)] + sorted(need.items())
    for choice in itertools.combinations(cons, n - 1):
        rows = [[Fraction(s >> i & 1) for i in range(n)] for s, _ in choice]
        sol = _solve([*rows, [Fraction(1)] * n], [b for _, b in choice] + [Fraction(1)])
        if sol is not None and all(sum((sol[i] for i in members(s)), Fraction(0)) >= b
                                   for s, b in cons):
            return True
    return False


def _ray_test(mv: dict[int, Fraction], mu: dict[int, Fraction], w: Fraction, n: int) -> bool:
    """NSOLVE.2's test: ``cov_v(y_ρ) <= cov_u(y_ρ) + w`` for every non-pattern ray."""
    for ray, _ in bad_rays(n):
        y = _y(ray, n)
        if min_cover(mv, y).value > min_cover(mu, y).value + w:
            return False
    return True


def test_NSOLVE2_the_arc_condition_by_brute_force() -> None:
    rng = random.Random(0)
    checked = {3: 0, 4: 0}
    for trial in range(44):
        n = 3 if trial < 30 else 4
        masks = range(1, 1 << n)
        mu = _close({s: Fraction(rng.randint(0, 12), rng.choice([1, 2])) for s in masks}, n)
        w = Fraction(rng.randint(1, 4), rng.choice([1, 2]))
        mv = _close({s: min(mu[s] + w, Fraction(rng.randint(0, 16), rng.choice([1, 2])))
                     for s in masks}, n)
        holds = all(_feasible(r, mu, w, n) for r in _vertices(mv, n))  # brute force
        assert holds == (n == 3 or _ray_test(mv, mu, w, n)), (n, mu, mv, w)  # iff (NSOLVE.2)
        checked[n] += holds
    assert checked[3] == 30 and checked[4] >= 4


BERLIN_V = (153, 256, 385, 97, 218, 298, 425, 314, 442, 540, 683, 402, 523, 594, 725)
"""``m_S`` (masks 1 … 15) at the cell (46, 150) of Berlin_1_256, four goals (proofs/NSOLVE.md);
at its neighbour (47, 150) every entry is one less."""


def test_NSOLVE2_where_the_arc_condition_fails_the_direction_test_says_so() -> None:
    mv = {s: Fraction(x) for s, x in enumerate(BERLIN_V, start=1)}
    mu = {s: x - 1 for s, x in mv.items()}  # m_S(v) = m_S(u) + 1: every coalition steps
    outside = [r for r in _vertices(mv, 4) if not _feasible(r, mu, Fraction(1), 4)]
    assert len(outside) == 2  # G_v is not inside G_u + Δ: the arc condition fails
    assert not _ray_test(mv, mu, Fraction(1), 4)


def _instance(rng: random.Random, n_goals: int) -> Instance | None:
    n = rng.randint(n_goals + 1, n_goals + 4)
    edges = {(u, v) for u in range(n) for v in range(n) if u != v and rng.random() < 0.35}
    doc = {"graph": {"directed": True, "nodes": [{"id": v} for v in range(n)],
                     "edges": [{"source": u, "target": v,
                                "weight": str(Fraction(rng.randint(1, 4), rng.choice([1, 2])))}
                               for u, v in sorted(edges)]},
           "start": n - 1, "goals": list(range(n_goals)),
           "prior": [str(Fraction(1, n_goals))] * n_goals}
    try:
        return instance_from_json(doc)
    except ValueError:
        return None


def _instances(rng: random.Random, count: int, goals: Sequence[int]) -> Iterator[Instance]:
    """``count`` random instances (drawn until valid), each with a goal count from ``goals``
    (drawn when there is a choice)."""
    done = 0
    while done < count:
        inst = _instance(rng, goals[0] if len(goals) == 1 else rng.choice(goals))
        if inst is not None:
            done += 1
            yield inst


def test_NSOLVE3_label_setting_equals_the_layered_fixpoint() -> None:
    rng = random.Random(1)
    for inst in _instances(rng, 25, [2, 3, 4]):
        run = CoalitionRunner(inst)
        layer = run.layer0()
        k = 0
        while True:
            k += 1
            nxt = run.step(layer, k)
            if k > max(inst.hops) and all(np.array_equal(nxt[m], layer[m]) for m in layer):
                break
            layer = nxt
        sets = guarantee_sets(inst)
        for mask, vals in nxt.items():
            for v in range(inst.n_nodes):
                want = None if int(vals[v]) >= run.big else Fraction(int(vals[v]), run.scale)
                assert sets.value(mask, v) == want


def test_NSOLVE1_every_walk_costs_at_least_h() -> None:
    rng = random.Random(2)
    for inst in _instances(rng, 20, [3]):
        sets = guarantee_sets(inst)
        costs = {s: Fraction(int(v[inst.start]), sets.scale) for s, v in sets.m.items()}
        h = min_cover(costs, inst.prior).dual  # an optimal dual: h ∈ G_s0
        order = rule_order(inst.prior)
        for _ in range(30):
            r, paid, v = list(h), [Fraction(0)] * 3, inst.start
            for _ in range(12):
                if inst.is_goal(v):
                    break
                arcs = [(u, w) for u, w in inst.succ[v] if sets.value(1, u) is not None]
                u, w = rng.choice(arcs)
                sigma, ok = guarantee_sigma(r, sets, u, w, order)
                assert ok  # F is never empty (N = 3: the arc condition always holds)
                r = [x - Fraction(w) * s for x, s in zip(r, sigma, strict=True)]
                paid = [p + Fraction(w) * s for p, s in zip(paid, sigma, strict=True)]
                v = u
            if inst.is_goal(v):
                for t in range(3):
                    assert paid[t] + Fraction(inst.dist_to[t][v]) >= h[t]


def test_NSOLVE5_two_goals_the_rule_is_the_progress_rule() -> None:
    rng = random.Random(3)
    for inst in _instances(rng, 20, [2]):
        sets = guarantee_sets(inst)
        d1 = [Fraction(x) if x != float("inf") else None for x in inst.dist_to[0]]
        m12 = sets.value(3, inst.start)
        assert m12 is not None and d1[inst.start] is not None
        h = [d1[inst.start], m12 - d1[inst.start]]  # (d(s0, g1), M - d(s0, g1))
        for _ in range(20):
            r, v, c = list(h), inst.start, d1[inst.start]
            for _ in range(10):
                if inst.is_goal(v):
                    break
                arcs = [(u, w) for u, w in inst.succ[v] if sets.value(1, u) is not None]
                u, w = rng.choice(arcs)
                sigma, ok = guarantee_sigma(r, sets, u, w, (0, 1))
                du = d1[u]
                assert ok and du is not None
                c_next = min(c, du)
                assert sigma[0] == (c - c_next) / Fraction(w)  # σ*(g1) = new progress / w
                r = [x - Fraction(w) * s for x, s in zip(r, sigma, strict=True)]
                v, c = u, c_next
