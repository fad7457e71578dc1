"""`dpp solve` refuses no N = 4/5 instance for arithmetic reasons (the exact vertex tables and DP
past int64).

The solver once refused every system whose vertices' common denominator left int64 ("the
vertices' common denominator 254583463751416800 leaves int64 … no profile written"), among
them every five-goal finite hub gadget that needs extra normals, where ``dpp value`` proves
the value. Its tables are now exact past int64 (parts with their own denominators, Bareiss
determinants in Python integers), so a refusal may name a budget (rounds, layers, normals,
bases) but never the arithmetic. The hub gadgets (with and without return arcs) and the
solver's own families are drawn at N = 4 and 5; the short run is in the default suite, the
long one (with the two five-goal finite hubs that were refused, about two minutes each) is
``slow``.
"""

from __future__ import annotations

import random

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from solver.coalitions.construction import FixpointNotReached, coalition_equilibrium
from solver.game.instance_reading import instance_from_json
from tests.solver._ngoal_families import draw, hub

ARITHMETIC = ("int64", "exact range", "denominator", "hadamard", "overflow")
"""Words of a refusal for arithmetic reasons (none of the budget's)."""


def _solve(doc: dict[str, object]) -> None:
    try:
        coalition_equilibrium(instance_from_json(doc))
    except FixpointNotReached as exc:
        text = str(exc).lower()
        assert not any(w in text for w in ARITHMETIC), str(exc)


@settings(max_examples=8, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 10 ** 6), n=st.integers(4, 5))
def test_hub_gadgets_are_never_refused_for_arithmetic(seed: int, n: int) -> None:
    """With return arcs at N = 4, 5; the finite hubs at N = 4 (at N = 5 those that need extra
    normals take minutes: the slow campaign)."""
    _solve(hub(random.Random(seed), n, dag=False))
    if n == 4:
        _solve(hub(random.Random(seed), n, dag=True))


@settings(max_examples=6, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(family=st.sampled_from(["digraph", "grid", "hub"]), seed=st.integers(0, 10 ** 6),
       n=st.integers(4, 5))
def test_the_solver_families_are_never_refused_for_arithmetic(family: str, seed: int,
                                                              n: int) -> None:
    _solve(draw(family, seed, n))


@pytest.mark.slow
@pytest.mark.parametrize("seed", [0, 7])
def test_the_five_goal_finite_hubs_once_refused_are_solved(seed: int) -> None:
    """Seeds 0 and 7 of the finite hubs at N = 5 were refused (the common denominator above);
    now they are solved: the value 49/15 of seed 0 is the top of the bracket then reported."""
    eq = coalition_equilibrium(instance_from_json(hub(random.Random(seed), 5, dag=True)))
    assert eq.normals  # the 0/1 normals did not suffice
    if seed == 0:
        assert str(eq.U) == "49/15"


@pytest.mark.slow
@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 10 ** 9), n=st.integers(4, 5), dag=st.booleans())
def test_campaign_hub_gadgets_are_never_refused_for_arithmetic(seed: int, n: int,
                                                               dag: bool) -> None:
    _solve(hub(random.Random(seed), n, dag=dag))
