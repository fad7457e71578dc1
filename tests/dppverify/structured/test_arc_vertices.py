"""The guarantee rule's arc test by the vertices of ``F_v`` (proofs/NRULE.md NR.2(b)), against
independent routes.

- the maximal vertices of a normal-described set (double description) equal those of a brute
  force over every choice of ``N`` tight rows, solved by Gauss–Jordan in Fractions
  (``proofs/checks/_linear.py``);
- the small LP ``φ_u(r)`` of :func:`~dppverify.structured.sum_membership.sum_membership`
  equals the largest ``λ·b`` over every vertex of the packing polytope, enumerated by hand;
- the vertex route decides every arc as the direction route (NR.2(a): the support functions in
  every packing direction) does, on the rule's sets and on sets enlarged at random tails so
  that arcs fail;
- rules with 64 valid extra normals (the format's maximum) are decided on both routes.
"""

from __future__ import annotations

import itertools
import math
import random
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from dppverify.certify import certify
from dppverify.errors import InvalidInstanceError
from dppverify.game.instance import instance_from_json
from dppverify.structured.arc_condition import arc_condition, walkable_arcs
from dppverify.structured.cover import min_cover_vectors, zero_one_normals
from dppverify.structured.guarantee import guarantee_sets
from dppverify.structured.normal_fixpoint import NormalSets
from dppverify.structured.set_vertices import maximal_vertices
from dppverify.structured.sum_membership import sum_membership
from proofs.checks._linear import basic_solutions as basic_solutions_by_hand
from proofs.checks._linear import solve_square
from tests.dppverify.structured._instances import extras, instance_doc
from tests.solver._ngoal_families import hub

Normal = tuple[int, ...]


def _system(rng: random.Random, top: int = 4) -> tuple[list[Normal], list[int]]:
    """0/1 normals and a few extras, support numbers of a few points (so that many rows are
    tight together: degenerate vertices), sometimes loosened; ``2 <= N <= top``."""
    n = rng.randint(2, top)
    extra = {a for a in (tuple(rng.randint(0, 3) for _ in range(n))
                         for _ in range(rng.randint(0, 6))) if any(x > 1 for x in a)}
    normals = list(zero_one_normals(n)) + sorted(extra)
    pts = [[rng.randint(0, 6) for _ in range(n)] for _ in range(rng.randint(1, 4))]
    values = [max(sum(a * p for a, p in zip(nm, pt, strict=True)) for pt in pts)
              + rng.randint(0, 1) for nm in normals]
    return normals, values


def _brute_vertices(normals: list[Normal], values: list[int]) -> set[tuple[Fraction, ...]]:
    n = len(normals[0])
    found = set()
    for rows in itertools.combinations(range(len(normals)), n):
        r = solve_square([normals[j] for j in rows], [values[j] for j in rows])
        if r is not None and all(sum((a * x for a, x in zip(normals[j], r, strict=True)),
                                     Fraction(0)) <= values[j] for j in range(len(normals))):
            found.add(tuple(r))
    return {r for r in found
            if not any(q != r and all(x <= y for x, y in zip(r, q, strict=True)) for q in found)}


def _check_vertices(seed: int, top: int) -> None:
    normals, values = _system(random.Random(seed), top)
    got = {tuple(Fraction(x, t) for x in xs) for xs, t, _ in maximal_vertices(normals, values)}
    assert got == _brute_vertices(normals, values), (normals, values)
    for xs, t, tight in maximal_vertices(normals, values):  # the tight mask is exact
        assert tight == sum(1 << j for j, a in enumerate(normals)
                            if sum(ai * x for ai, x in zip(a, xs, strict=True)) == t * values[j])


@settings(max_examples=25, deadline=None, derandomize=True)
@given(st.integers(0, 10 ** 6))
def test_maximal_vertices_equal_the_brute_force(seed: int) -> None:
    _check_vertices(seed, 3)


@pytest.mark.slow
@settings(max_examples=500, deadline=None)
@given(st.integers(0, 10 ** 9))
def test_campaign_maximal_vertices_equal_the_brute_force(seed: int) -> None:
    _check_vertices(seed, 4)


def _check_membership(seed: int, top: int) -> None:
    rng = random.Random(seed)
    normals, _ = _system(rng, top)
    n = len(normals[0])
    b = [rng.randint(-6, 8) for _ in normals]
    w = rng.randint(0, 12)
    got = sum_membership(normals, b, w)
    slack = [tuple(int(i == j) for i in range(n)) for j in range(n)]
    lams = basic_solutions_by_hand(normals + slack, (1,) * n)
    best = max(sum((lam[j] * b[j] for j in range(len(normals))), Fraction(0)) for lam in lams)
    assert got.value == best and got.inside == (best <= w)


@settings(max_examples=25, deadline=None, derandomize=True)
@given(st.integers(0, 10 ** 6))
def test_the_membership_lp_is_the_packing_maximum(seed: int) -> None:
    _check_membership(seed, 3)


@pytest.mark.slow
@settings(max_examples=300, deadline=None)
@given(st.integers(0, 10 ** 9))
def test_campaign_the_membership_lp_is_the_packing_maximum(seed: int) -> None:
    _check_membership(seed, 4)


def _draw_sets(rng: random.Random, goals: tuple[int, ...]) -> tuple[NormalSets, int] | None:
    n = rng.choice(goals)
    try:
        inst = instance_from_json(instance_doc(rng, n, rng.choice(["digraph", "dag", "grid",
                                                                   "hub"])))
    except InvalidInstanceError:
        return None
    sets = guarantee_sets(inst, extras(rng, n) if rng.random() < 0.7 else [])
    tails, heads, weights = walkable_arcs(sets, inst.start)
    if not tails:
        return None
    if rng.random() < 0.7:  # enlarge F_v at a few tails up to the step bound: arcs fail
        rows = [np.asarray(r, dtype=object).copy() for r in sets.rows]
        for _ in range(rng.randint(1, 3)):
            v = tails[rng.randrange(len(tails))]
            for j in rng.sample(range(len(rows)), rng.randint(1, len(rows))):
                cap = min(int(Fraction(w) * sets.scale) * max(sets.normals[j]) + int(rows[j][u])
                          for x, u, w in zip(tails, heads, weights, strict=True) if x == v)
                if cap > rows[j][v]:
                    rows[j][v] = cap if rng.random() < 0.5 else rng.randint(int(rows[j][v]) + 1,
                                                                            cap)
        sets = NormalSets(inst, sets.normals, sets.scale, tuple(rows), sets.finite)
    return sets, inst.start


def _check_routes(seed: int, goals: tuple[int, ...] = (4,)) -> bool | None:
    drawn = _draw_sets(random.Random(seed), goals)
    if drawn is None:
        return None
    sets, start = drawn
    by_vertices = arc_condition(sets, start, route="vertices")
    by_directions = arc_condition(sets, start, route="directions")
    assert by_vertices.holds == by_directions.holds, seed
    assert by_vertices.failing == by_directions.failing, seed
    return by_vertices.holds


@settings(max_examples=20, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(st.integers(0, 10 ** 6))
def test_the_vertex_route_decides_every_arc_as_the_direction_route(seed: int) -> None:
    _check_routes(seed)


def test_both_outcomes_occur_among_the_drawn_sets() -> None:
    """The comparison above is not vacuous: some drawn sets pass, some fail."""
    assert {_check_routes(seed) for seed in range(16)} >= {True, False}


@pytest.mark.slow
@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.integers(0, 10 ** 9))
def test_campaign_the_vertex_route_decides_every_arc_as_the_direction_route(seed: int) -> None:
    _check_routes(seed, (4, 4, 5))


def _normals64(rng: random.Random, n: int) -> list[Normal]:
    out: set[Normal] = set()
    while len(out) < 64:
        a = tuple(rng.randint(0, 3) for _ in range(n))
        if any(x > 1 for x in a) and math.gcd(*a) == 1:
            out.add(a)
    return sorted(out)


def _rule_profile(doc: dict[str, object], normals: list[Normal]) -> dict[str, object]:
    inst = instance_from_json(doc)
    sets = guarantee_sets(inst, normals)
    col = sets.column(inst.start)
    assert col is not None
    h = min_cover_vectors(sets.normals, col, inst.prior).dual
    attacker = []
    for g in inst.goals:  # u -> u1 -> a middle -> the goal (the hub's shape)
        walk = next([inst.start, u1, m, g] for u1, _ in inst.succ[inst.start]
                    for m, _ in inst.succ[u1] if any(x == g for x, _ in inst.succ[m]))
        attacker.append([{"path": [inst.nodes[v] for v in walk], "probability": 1}])
    return {"format": "dpp-ngoal-profile/1", "attacker": attacker,
            "defender": {"rule": "guarantee", "h": [str(x) for x in h],
                         "normals": [list(a) for a in normals]}}


@pytest.mark.parametrize("n", [4, pytest.param(5, marks=pytest.mark.slow)])
def test_sixty_four_normals_are_decided_on_both_routes(n: int) -> None:
    """Once an internal TypeError (object arrays in the vertex tables) or minutes of packing
    directions; now decided, and the two routes agree on this finite game."""
    doc = hub(random.Random(1), n, dag=True)
    prof = _rule_profile(doc, _normals64(random.Random(n), n))
    cert = certify(doc, prof, horizon="inf", route="structured")
    assert cert.check("pbne.attacker_br").status in ("pass", "fail")
    tree = certify(doc, prof, horizon=4, route="tree")
    assert tree.check("pbne.attacker_br").status in ("pass", "fail")
    assert tree.verdict == cert.verdict
    assert (cert.check("pbne.attacker_br").status
            == tree.check("pbne.attacker_br").status)


def test_sixty_four_normals_on_five_goals_are_decided_by_the_structured_route() -> None:
    doc = hub(random.Random(1), 5, dag=True)
    cert = certify(doc, _rule_profile(doc, _normals64(random.Random(5), 5)), horizon="inf",
                   route="structured")
    assert cert.check("pbne.attacker_br").status in ("pass", "fail")
