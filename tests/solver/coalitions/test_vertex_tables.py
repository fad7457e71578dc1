"""The solver's vertex tables against an independent route (Gauss–Jordan in Fractions by hand,
``proofs/checks/_linear.py``, one system at a time), within int64 and past it.

The solver's tables were once a copy of the checker's (``dppverify/structured/cover.py``);
the checker's copy was later made exact beyond int64 and the solver's was not: on the first
system below it returned 16 "vertices" of which 15 did not solve the system. It then refused
such systems; now it computes them exactly (Bareiss determinants in Python integers past
Hadamard's int64 bound, and parts with their own denominators when the whole table's common
denominator leaves int64), and is compared here with the hand route, not with the checker.
"""

from __future__ import annotations

from fractions import Fraction

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from proofs.checks._linear import basic_solutions as basic_solutions_by_hand
from solver.coalitions.vertex_tables import vertex_table, zero_one_normals


def _solver_vertices(columns: list[tuple[int, ...]], rhs: tuple[int, ...]
                     ) -> set[tuple[Fraction, ...]]:
    table = vertex_table(columns, rhs)
    return {tuple(v.get(j, Fraction(0)) for j in range(len(columns))) for v in table.vertices()}


@st.composite
def systems(draw: st.DrawFn) -> tuple[list[tuple[int, ...]], tuple[int, ...]]:
    """Unit vectors plus a few extra non-negative normals (entries 0..16), right-hand side of
    full support: the shape of the solver's cover and packing systems."""
    n = draw(st.integers(2, 4))
    units = [tuple(int(i == j) for j in range(n)) for i in range(n)]
    extra = draw(st.lists(st.tuples(*[st.integers(0, 16)] * n).filter(any), max_size=4))
    rhs = draw(st.tuples(*[st.integers(1, 5)] * n))
    return units + extra, rhs


@settings(max_examples=40, deadline=None)
@given(systems())
def test_vertex_tables_equal_the_basic_solutions_by_hand(system: tuple[list[tuple[int, ...]],
                                                                   tuple[int, ...]]) -> None:
    columns, rhs = system
    assert _solver_vertices(columns, rhs) == basic_solutions_by_hand(columns, rhs)


def test_the_zero_one_covers_of_four_goals_equal_the_hand_route() -> None:
    zo = list(zero_one_normals(4))
    assert _solver_vertices(zo, (2, 2, 2, 1)) == basic_solutions_by_hand(zo, (2, 2, 2, 1))


@pytest.mark.parametrize(("extra", "parts"), [
    # determinants up to ~1e20: past Hadamard's int64 bound, Python integers
    ([tuple(p if j == i else 1 for j in range(5)) for i, p in
      enumerate((100003, 100019, 100043, 100049))], 1),
    # entries within the profile format's 0..16, but a common denominator ~4e51: parts
    ([tuple(16 if j == i else 1 for j in range(5)) for i in range(5)]
     + [(3, 5, 7, 11, 13), (16, 15, 14, 13, 12)], 2),
])
def test_tables_beyond_int64_are_exact(extra: list[tuple[int, ...]], parts: int) -> None:
    units = [tuple(int(i == j) for j in range(5)) for i in range(5)]
    table = vertex_table(units + extra, (1,) * 5)
    assert len(table.parts) >= parts
    for scaled, lcm in table.parts:  # every part exact with its own denominator
        assert lcm > 0 and all(int(x) >= 0 for x in scaled.ravel())
    assert _solver_vertices(units + extra, (1,) * 5) == basic_solutions_by_hand(units + extra,
                                                                               (1,) * 5)
