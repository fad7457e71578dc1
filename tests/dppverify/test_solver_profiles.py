"""Property: every profile `dpp solve` produces on random small instances is certified.

The tests may import both packages; ``dppverify`` itself never imports ``solver``.
"""

from __future__ import annotations

import json
from fractions import Fraction
from typing import Any

from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from dppverify import InvalidInstanceError, certify, instance_from_json
from dppverify.formats.json_reading import parse_json
from solver import instance_from_json as solver_instance_from_json
from tests.dppverify._helpers import grid_doc, make_doc

PRIORS = [("1/2", "1/2"), ("3/5", "2/5"), ("2/5", "3/5"), ("7/10", "3/10"), ("9/10", "1/10"),
          ("2/3", "1/3")]


@st.composite
def graph_instances(draw: st.DrawFn) -> dict[str, Any]:
    n = draw(st.integers(3, 6))
    directed = draw(st.booleans())
    pairs = [(u, v) for u in range(n) for v in range(n) if u != v and (directed or u < v)]
    chosen = draw(st.lists(st.sampled_from(pairs), min_size=n - 1, max_size=2 * n,
                           unique=True))
    weight = st.one_of(st.integers(1, 5), st.sampled_from(["1/2", "3/2", "5/3", "7/4"]))
    edges = [(u, v, draw(weight)) for u, v in chosen]
    start, g1, g2 = draw(st.permutations(range(n)))[:3]
    if draw(st.integers(0, 9)) == 0:
        start = g1  # start at a goal sometimes
    return make_doc(edges, start, [g1, g2], draw(st.sampled_from(PRIORS)), directed=directed,
                    nodes=list(range(n)))


@st.composite
def grid_instances(draw: st.DrawFn) -> dict[str, Any]:
    rows, cols = draw(st.integers(2, 3)), draw(st.integers(2, 4))
    cells = [(r, c) for r in range(rows) for c in range(cols)]
    start, a, b = draw(st.permutations(cells))[:3]
    blocked = draw(st.lists(st.sampled_from(cells), max_size=2, unique=True))
    blocked = [x for x in blocked if x not in (start, a, b)]
    return grid_doc(rows, cols, start, [a, b], draw(st.sampled_from(PRIORS)), blocked)


def _certify_solver_profile(doc: dict[str, Any]) -> None:
    from solver.twogoal.equilibrium import paper_equilibrium

    try:
        inst = instance_from_json(doc)
    except InvalidInstanceError:
        assume(False)
        return
    assume(inst.n_nodes > 0)
    prof = paper_equilibrium(solver_instance_from_json(doc)).to_json()
    cert = certify(doc, parse_json(json.dumps(prof)), trials=2, max_prefixes=200_000)
    assert cert.passed, [(c.id, c.message) for c in cert.failed()]
    u = cert.check("value.U").numbers["U"]
    assert u == Fraction(prof["value"]["U"])
    assert cert.check("game.value").numbers["V_H"] == u


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(graph_instances())
def test_solver_profiles_certify_on_random_graphs(doc: dict[str, Any]) -> None:
    _certify_solver_profile(doc)


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(grid_instances())
def test_solver_profiles_certify_on_random_grids(doc: dict[str, Any]) -> None:
    _certify_solver_profile(doc)
