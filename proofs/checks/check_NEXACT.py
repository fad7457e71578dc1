"""Checks for proofs/NEXACT.md (N goals on every instance: the exact guarantee rule).

Exact throughout (Fractions, sympy ranks). NX.1 on random cover LPs; NX.2 and NX.4 on random
instances (hub gadgets, digraphs, grids) by following every piece of the Attacker with the
rule; NX.6 on the N = 4 gadget of proofs/NGOAL.md through the proved route alone, with the
added normals confirmed as facets of the exact layer set by an independent vertex enumeration.
"""

from __future__ import annotations

import itertools
import random
from fractions import Fraction

import numpy as np
import pytest
import sympy as sp

import solver.coalitions.guarantee_sets as gsets
from solver.coalitions.construction import arc_graph
from solver.coalitions.guarantee_rule import priority_order, rule_step
from solver.coalitions.guarantee_sets import GuaranteeSets, guarantee_sets
from solver.coalitions.normal_attacker import _moves
from solver.coalitions.normal_cover import normal_cover_lp
from solver.coalitions.normal_dp import LayerFailure, layered_dp
from solver.coalitions.normal_system import NormalSystem, symmetric_closure
from solver.coalitions.vertex_tables import packing_vertices, primitive, zero_one_normals
from solver.game.instance_reading import instance_from_json
from solver.numbers import solve_exact
from tests.solver._ngoal_families import GADGET, draw

CASES = ([GADGET] + [draw("hub", s, n) for s in range(6) for n in (4, 5)]
         + [draw(f, s, n) for f in ("digraph", "grid") for s in range(3) for n in (3, 4)])


def test_NX1_the_root_lp_is_dual_feasible_tight_and_complementary() -> None:
    rng = random.Random(1)
    normals = symmetric_closure([(2, 2, 2, 1)])
    for _ in range(40):
        costs = [Fraction(rng.randint(1, 9) * sum(a), rng.randint(1, 3)) for a in normals]
        b = [Fraction(rng.randint(1, 5)) for _ in range(4)]
        lp = normal_cover_lp(normals, costs, b, order=(0, 1, 2, 3))
        h = lp.dual
        for a, c in zip(normals, costs, strict=True):
            assert sum((x * y for x, y in zip(a, h, strict=True)), Fraction(0)) <= c
        assert sum((x * y for x, y in zip(b, h, strict=True)), Fraction(0)) == lp.value
        for j, c in lp.cover.items():
            assert c > 0
            assert sum((x * y for x, y in zip(normals[j], h, strict=True)),
                       Fraction(0)) == costs[j]
        assert [sum((c * normals[j][i] for j, c in lp.cover.items()), Fraction(0))
                for i in range(4)] == b


def _sets(doc: dict) -> tuple:
    game = instance_from_json(doc)
    graph, _ = arc_graph(game)
    found = guarantee_sets(graph)
    assert isinstance(found, GuaranteeSets)
    return game, graph, found.fixpoint


@pytest.mark.parametrize("doc", CASES)
def test_NX2_every_normal_has_a_ranked_cover_and_ranks_fall(doc: dict) -> None:
    _, graph, fix = _sets(doc)
    scale_w = fix.scale // graph.denominator
    for v in range(graph.n_nodes):
        if graph.is_goal[v] or not fix.finite[v]:
            continue
        lo = int(graph.indptr[v])
        for j in range(len(fix.system.normals)):
            moves = _moves(graph, fix, j, v)
            total = Fraction(0)
            for n, c, u in moves:
                assert fix.rank[n, u] < fix.rank[j, v]
                w = next(int(graph.weights[k]) for k in range(lo, int(graph.indptr[v + 1]))
                         if int(graph.heads[k]) == u)
                total += c * (w * scale_w * int(fix.system.tops[n]) + int(fix.m[n, u]))
            assert total == int(fix.m[j, v])
            assert [sum((c * fix.system.normals[n][i] for n, c, _ in moves), Fraction(0))
                    for i in range(graph.n_goals)] == list(fix.system.normals[j])


@pytest.mark.parametrize("doc", CASES)
def test_NX4_every_piece_is_tight_and_sigma_is_greedy(doc: dict) -> None:
    game, graph, fix = _sets(doc)
    normals = fix.system.normals
    order = priority_order(game.prior)
    costs = [fix.value(j, graph.start) for j in range(len(normals))]
    root = normal_cover_lp(normals, costs, list(game.prior), order)
    h = tuple(root.dual)

    def dot(a: tuple, r: tuple) -> Fraction:
        return sum((x * y for x, y in zip(a, r, strict=True)), Fraction(0))

    stack: list[tuple[tuple[int, ...], dict[int, Fraction], tuple[Fraction, ...]]] = [
        ((graph.start,), dict(root.cover), h)]
    while stack:
        walk, pieces, r = stack.pop()
        v = walk[-1]
        for j in pieces:  # NX.4: every piece tight
            assert dot(normals[j], r) == fix.value(j, v)
        if graph.is_goal[v]:
            d = graph.terminal[graph.goals.index(v)]
            for j in pieces:
                for t, x in enumerate(normals[j]):
                    if x:
                        assert r[t] == Fraction(int(d[t]), graph.denominator)
            continue
        nxt: dict[int, dict[int, Fraction]] = {}
        for j, mass in pieces.items():
            for n, c, u in _moves(graph, fix, j, v):
                nxt.setdefault(u, {}).setdefault(n, Fraction(0))
                nxt[u][n] += mass * c
        lo, hi = int(graph.indptr[v]), int(graph.indptr[v + 1])
        for u, kids in nxt.items():
            w = next(Fraction(int(graph.weights[k]), graph.denominator) for k in range(lo, hi)
                     if int(graph.heads[k]) == u)
            m_u = [fix.value(j, u) for j in range(len(normals))]
            sigma, ok = rule_step(r, normals, m_u, w, order)
            assert ok
            y = [sum((mass * normals[n][t] for n, mass in kids.items()), Fraction(0))
                 for t in range(graph.n_goals)]
            top = max(y)
            assert all(y[t] == top for t in range(graph.n_goals) if sigma[t] > 0)
            stack.append(((*walk, u), kids, tuple(x - w * s for x, s in zip(r, sigma,
                                                                           strict=True))))


def _face_dimension(rows: list[tuple[tuple[int, ...], Fraction]], p: tuple[int, ...],
                    beta: Fraction) -> int:
    """The dimension of ``{r : rows} ∩ {p·r = β}`` from its vertices (no ray: ``p > 0``)."""
    n = len(p)
    others = [(a, b) for a, b in rows if a != p]
    verts = set()
    for tight in itertools.combinations(range(len(others)), n - 1):
        mat = [[Fraction(x) for x in p]] + [[Fraction(x) for x in others[k][0]] for k in tight]
        sol = solve_exact(mat, [beta] + [others[k][1] for k in tight])
        if sol is None:
            continue
        if all(sum((Fraction(x) * y for x, y in zip(a, sol, strict=True)), Fraction(0)) <= b
               for a, b in rows):
            verts.add(tuple(sol))
    pts = sorted(verts)
    if not pts:
        return -1
    diffs = sp.Matrix([[sp.Rational(x - y) for x, y in zip(q, pts[0], strict=True)]
                       for q in pts[1:]] or [[0] * n])
    return int(diffs.rank())


def test_NX6_the_proved_route_adds_facets_of_the_exact_layer_set(
        monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(gsets, "HEURISTIC_ROUNDS", 0)
    game = instance_from_json(GADGET)
    graph, _ = arc_graph(game)
    found = guarantee_sets(graph)
    assert isinstance(found, GuaranteeSets) and found.rounds == 1
    assert set(found.extra_normals) == set(itertools.permutations((2, 2, 2, 1)))
    # the failing layer of the 0/1 DP: the exact set there, written out independently
    system = NormalSystem(zero_one_normals(4))
    fail = layered_dp(graph, system, check_layers=True, max_layers=100)
    assert isinstance(fail, LayerFailure)
    v = int(fail.tails[0])
    rows: dict[tuple[int, ...], Fraction] = {}
    lo, hi = int(graph.indptr[v]), int(graph.indptr[v + 1])
    for k in range(lo, hi):
        u = int(graph.heads[k])
        if not fail.old_finite[u]:
            continue
        w = Fraction(int(graph.weights[k]), graph.denominator)
        mu = [Fraction(int(x), fail.scale) for x in fail.old[:, u]]
        for lam in packing_vertices(system.normals):
            if not any(lam):
                continue
            y = [sum((lam[j] * system.normals[j][i] for j in range(15)), Fraction(0))
                 for i in range(4)]
            p = primitive(y)
            i0 = next(i for i in range(4) if p[i])
            b = Fraction(p[i0]) / y[i0] * (w + sum((lam[j] * mu[j] for j in range(15)),
                                                   Fraction(0)))
            rows[p] = min(rows.get(p, b), b)
    listed = list(rows.items())
    hit = [p for p in found.extra_normals if p in rows and _face_dimension(listed, p,
                                                                           rows[p]) == 3]
    assert hit, "no added normal is a facet of the exact layer set"
    # and the 0/1 sets at that layer violate it
    col = int(np.flatnonzero(fail.rows == v)[0])
    at_v = [Fraction(int(x), fail.scale) for x in fail.new[:, col]]
    p = hit[0]
    assert normal_cover_lp(system.normals, at_v, [Fraction(x) for x in p]).value > rows[p]
