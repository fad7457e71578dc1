"""Exact fractional covers: the vertex tables and the exact simplex (dppverify.structured.cover)."""

from __future__ import annotations

import itertools
from fractions import Fraction

import numpy as np
import pytest
import scipy.optimize
from hypothesis import given
from hypothesis import strategies as st

from dppverify.structured.cover import (
    balanced_vertices,
    basic_solutions,
    members,
    min_cover,
    popcount,
)
from proofs.checks._linear import basic_solutions as basic_solutions_by_hand


@pytest.mark.parametrize(("size", "count"), [(2, 1), (3, 5), (4, 41), (5, 1291)])
def test_vertex_count_is_the_number_of_minimal_balanced_collections(size: int, count: int) -> None:
    # Known counts of minimal balanced collections without the grand coalition (Shapley;
    # OEIS A003441 minus one): 1, 5, 41, 1291 on 2, 3, 4, 5 players.
    assert len(balanced_vertices(size).vertices) == count


@pytest.mark.parametrize("size", [2, 3, 4])
def test_every_vertex_is_an_exact_fractional_partition(size: int) -> None:
    bv = balanced_vertices(size)
    full = (1 << size) - 1
    seen = set()
    for v in bv.vertices:
        assert all(c >= 0 for c in v)
        cover = [sum((c for t, c in zip(bv.columns, v, strict=True) if t >> i & 1), Fraction(0))
                 for i in range(size)]
        assert cover == [1] * size
        assert full not in [t for t, c in zip(bv.columns, v, strict=True) if c]
        assert v not in seen
        seen.add(v)
    assert np.array_equal(bv.scaled, np.array([[int(v[j] * bv.lcm) for v in bv.vertices]
                                               for j in range(len(bv.columns))]))


def test_sizes_outside_the_tables_are_refused() -> None:
    with pytest.raises(ValueError, match="2 to 5"):
        balanced_vertices(6)


def _costs(size: int) -> st.SearchStrategy[dict[int, Fraction]]:
    masks = list(range(1, 1 << size))
    return st.lists(st.fractions(min_value=0, max_value=20, max_denominator=6),
                    min_size=len(masks), max_size=len(masks)).map(
        lambda xs: dict(zip(masks, xs, strict=True)))


@given(st.sampled_from([3, 4]).flatmap(lambda s: st.tuples(st.just(s), _costs(s))))
def test_vertex_minimum_equals_the_exact_simplex(case: tuple[int, dict[int, Fraction]]) -> None:
    size, costs = case
    full = (1 << size) - 1
    proper = {t: c for t, c in costs.items() if t != full}
    bv = balanced_vertices(size)
    by_vertices = min(sum((c * proper[t] for t, c in zip(bv.columns, v, strict=True)),
                          Fraction(0)) for v in bv.vertices)
    lp = min_cover(proper, [1] * size)
    assert lp.value == by_vertices


@given(st.integers(2, 4).flatmap(lambda s: st.tuples(
    _costs(s), st.lists(st.integers(1, 9), min_size=s, max_size=s))))
def test_min_cover_is_certified_by_its_dual_and_matches_highs(
        case: tuple[dict[int, Fraction], list[int]]) -> None:
    costs, rhs = case
    lp = min_cover(costs, rhs)
    # primal feasible, dual feasible, equal objectives: optimal, exactly
    for i in range(len(rhs)):
        assert sum((c for t, c in lp.cover.items() if t >> i & 1), Fraction(0)) == rhs[i]
    assert all(c > 0 for c in lp.cover.values())
    assert sum((c * costs[t] for t, c in lp.cover.items()), Fraction(0)) == lp.value
    for t, m in costs.items():
        assert sum(lp.dual[i] for i in members(t)) <= m
    assert sum((r * p for r, p in zip(rhs, lp.dual, strict=True)), Fraction(0)) == lp.value
    masks = sorted(costs)
    a = np.array([[t >> i & 1 for t in masks] for i in range(len(rhs))], dtype=float)
    ref = scipy.optimize.linprog([float(costs[t]) for t in masks], A_eq=a, b_eq=rhs,
                                 bounds=(0, None), method="highs")
    assert ref.status == 0
    assert abs(ref.fun - float(lp.value)) <= 1e-7 * max(1.0, abs(ref.fun))


def test_min_cover_rejects_bad_input() -> None:
    with pytest.raises(ValueError, match="singleton"):
        min_cover({1: 1, 3: 1}, [1, 1])
    with pytest.raises(ValueError, match="non-negative"):
        min_cover({1: 1, 2: 1}, [1, -1])


def test_min_cover_takes_a_goal_without_mass() -> None:
    """A zero weight (a goal the goal-selection Attacker never chooses) is covered by nothing:
    the cover of (1, 0) is the singleton of goal 1 alone, even when a pair is cheaper."""
    lp = min_cover({1: 3, 2: 2, 3: 1}, [1, 0])
    assert lp.value == 3 and dict(lp.cover) == {1: 1}


def test_masks() -> None:
    assert [popcount(m) for m in range(8)] == [0, 1, 1, 2, 1, 2, 2, 3]
    assert [members(m) for m in (0, 5, 6)] == [(), (0, 2), (1, 2)]
    assert all(len(members(m)) == popcount(m) for m in itertools.chain(range(64)))


def test_vertex_tables_stay_exact_beyond_int64() -> None:
    """Five goals, four normals with large prime entries: the determinants' lcm is about
    10^20 (beyond int64). The table was once built in int64 (its lcm overflowed silently,
    giving vertices that do not solve the system, or a caught crash in np.gcd); it is exact
    now and equals a brute-force enumeration in Fractions."""
    units = [tuple(int(i == j) for j in range(5)) for i in range(5)]
    primes = (100003, 100019, 100043, 100049)
    extra = [tuple(p if j == i else 1 for j in range(5)) for i, p in enumerate(primes)]
    columns = units + extra
    rhs = (1, 1, 1, 1, 1)
    table = basic_solutions(columns, rhs)
    assert table.lcm >= 2 ** 63
    got = {tuple(v[table.columns.index(j)] if j in table.columns else Fraction(0)
                 for j in range(len(columns))) for v in table.vertices}
    for c in got:
        assert all(x >= 0 for x in c)
        assert all(sum(c[j] * columns[j][i] for j in range(len(columns))) == rhs[i]
                   for i in range(5))
    assert got == basic_solutions_by_hand(columns, rhs)
