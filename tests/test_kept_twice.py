"""The small pieces of mathematics the solver and the checker each keep their own copy of
(docs/architecture.md, "What stays twice, and why"), compared with each other wherever both
run: the same answer from both packages on every input tried.

The larger pairs are cross-checked elsewhere: the map and instance readers in
``tests/maps/test_readers_agree.py`` and ``tests/maps/test_map_instance.py``; the vertex tables
each against a third route (Gauss–Jordan in Fractions by hand, ``proofs/checks/_linear.py``,
in ``tests/solver/coalitions/test_vertex_tables.py`` and
``tests/dppverify/structured/test_cover.py``) and with each other below; the number modes,
phases and N-goal rules by every certificate of a solved profile.
"""

from __future__ import annotations

import itertools
import random
from fractions import Fraction

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dppverify.game.instance import instance_from_json as checker_instance
from dppverify.structured import cover as checker_cover
from dppverify.structured import packing as checker_packing
from dppverify.structured.guarantee import rule_order
from dppverify.structured.set_vertices import maximal_vertices
from dppverify.structured.sum_membership import sum_membership
from solver.coalitions import vertex_tables as solver_tables
from solver.coalitions.arc_vertices import gauge, set_vertices
from solver.coalitions.guarantee_rule import priority_order
from solver.coalitions.normal_system import symmetric_table as solver_symmetric
from solver.game.instance_reading import instance_from_json as solver_instance


def _closure(n: int, *seeds: tuple[int, ...]) -> tuple[tuple[int, ...], ...]:
    """The 0/1 normals of ``n`` goals and every permutation of the seeds (sorted, no repeats)."""
    extra = sorted({p for s in seeds for p in itertools.permutations(s)})
    return checker_cover.zero_one_normals(n) + tuple(extra)


NORMAL_SETS = [
    checker_cover.zero_one_normals(3),
    checker_cover.zero_one_normals(4),
    checker_cover.zero_one_normals(5),
    _closure(3, (2, 1, 1)),
    _closure(4, (2, 1, 1, 1)),
    _closure(4, (2, 2, 1, 1), (3, 1, 1, 1)),
]


@pytest.mark.parametrize("n", [2, 3, 4, 5])
def test_the_zero_one_normals_in_mask_order(n: int) -> None:
    assert solver_tables.zero_one_normals(n) == checker_cover.zero_one_normals(n)


@settings(max_examples=200, deadline=None)
@given(st.lists(st.fractions(min_value=0, max_value=1, max_denominator=6), min_size=2,
                max_size=5))
def test_the_priority_order_of_the_guarantee_rule(prior: list[Fraction]) -> None:
    assert priority_order(prior) == rule_order(prior)


@pytest.mark.parametrize("normals", NORMAL_SETS, ids=lambda a: f"N{len(a[0])}-{len(a)}")
def test_the_directions_of_the_packing_polytope(normals: tuple[tuple[int, ...], ...]) -> None:
    """The solver keeps the directions that are not 0/1 vectors, the checker all of them."""
    ours = {d.y for d in solver_tables.packing_directions(normals)}
    theirs = {y for y in checker_packing.packing_directions(normals)
              if any(x not in (0, 1) for x in y)}
    assert ours == theirs


@pytest.mark.parametrize("normals", NORMAL_SETS[:5], ids=lambda a: f"N{len(a[0])}-{len(a)}")
def test_the_cover_tables_of_small_right_hand_sides(normals: tuple[tuple[int, ...], ...]
                                                   ) -> None:
    n = len(normals[0])
    for rhs in itertools.product(range(3 if n < 5 else 2), repeat=n):
        if not any(rhs):
            continue
        a = solver_symmetric(normals, rhs)
        b = checker_cover.symmetric_table(normals, rhs)
        ours = {tuple(v.get(j, Fraction(0)) for j in range(len(normals))) for v in a.vertices()}
        theirs = {tuple(v[b.columns.index(j)] if j in b.columns else Fraction(0)
                        for j in range(len(normals))) for v in b.vertices}
        assert ours == theirs, rhs


@pytest.mark.parametrize("prior", [("3/5", "2/5"), ("2/5", "3/5"), ("1/2", "1/2")])
def test_the_primary_goal_index_of_two_goal_instances(prior: tuple[str, str]) -> None:
    doc = {"graph": {"directed": False, "nodes": [{"id": v} for v in "sab"],
                     "edges": [{"source": "s", "target": "a", "weight": 1},
                               {"source": "s", "target": "b", "weight": 2}]},
           "start": "s", "goals": ["a", "b"], "prior": list(prior)}
    assert (solver_instance(doc).primary_goal_index
            == checker_instance(doc).primary_goal_index)


@pytest.mark.parametrize("seed", range(6))
def test_the_vertices_of_a_set_and_the_membership_lp(seed: int) -> None:
    """The arc test by the vertices of ``F_v`` (proofs/NRULE.md NR.2(b)): the maximal vertices
    and ``φ_u`` of each package agree on sets given by the support numbers of random points."""
    rng = random.Random(seed)
    for normals in NORMAL_SETS:
        pts = [[rng.randint(0, 6) for _ in normals[0]] for _ in range(rng.randint(1, 4))]
        values = [max(sum(a * p for a, p in zip(nm, pt, strict=True)) for pt in pts)
                  for nm in normals]
        ours = {tuple(Fraction(x, t) for x in xs) for xs, t in set_vertices(normals, values)}
        theirs = {tuple(Fraction(x, t) for x in xs)
                  for xs, t, _ in maximal_vertices(normals, values)}
        assert ours == theirs
        b = [rng.randint(-6, 8) for _ in normals]
        assert gauge(normals, b)[0] == sum_membership(normals, b, 0).value
