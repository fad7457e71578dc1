"""V_H of the N-goal game: the tree route (LP + exact bracket), the coalition DP, the structured
value (proofs/NGOAL.md). Wherever both routes run their exact values agree, or their brackets
overlap and the structured route does not claim exactness; for two goals the DP equals the
two-goal checker's value.
"""

from __future__ import annotations

import copy
import itertools
import json
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from dppverify.agreement import compare_routes
from dppverify.errors import HorizonError
from dppverify.exact import Number
from dppverify.game.examples import star3, star3_document
from dppverify.game.instance import Instance, instance_from_json
from dppverify.strategies import instances, many_goal_instances, weighted_graphs
from dppverify.structured.coalition import CoalitionRunner, coalition_value
from dppverify.structured.proved_value import nvalue
from dppverify.tree_route.tree import count_prefixes
from dppverify.tree_route.value_lp import game_value

MAX_PREFIXES = 2500
DATA = Path(__file__).resolve().parents[1] / "data" / "ngoal_cases.json"


def coalition_values(instance: Instance, horizons: range) -> dict[int, Number]:
    """``V_H`` of the coalition DP for every ``H`` of ``horizons``, from one pass of its
    layers (unreachable horizons omitted)."""
    run = CoalitionRunner(instance)
    layer = run.layer0()
    out: dict[int, Number] = {}
    for k in range(0, horizons.stop):
        if k:
            layer = run.step(layer, k)
        if k in horizons:
            try:
                out[k] = run.value(layer, k, k).value
            except HorizonError:
                continue
    return out



def _horizons(inst: Instance, extra: int) -> list[int]:
    first = inst.hops[inst.start]
    return [h for h in range(first, first + extra + 1)
            if count_prefixes(inst, h) <= MAX_PREFIXES]


def test_star3_by_hand() -> None:
    # H = 1: the only walk is s a (weight 2): the Defender guards a against mass 1/2 (cost 1),
    # types b and c pay d(a, b) = d(a, c) = 2 at the end: 1 + 2/3 + 1/3 = 2.
    # H >= 2: all types walk s m together (1 · 1/2) and split at m (1/2 + 1/3 + 1/6): 3/2.
    inst = star3()
    assert coalition_values(inst, range(6)) == {1: 2, 2: Fraction(3, 2), 3: Fraction(3, 2),
                                                4: Fraction(3, 2), 5: Fraction(3, 2)}
    for h in (1, 2, 3):
        assert game_value(inst, h).bracket.exact == coalition_value(inst, h).value
    assert coalition_value(inst, None).value == Fraction(3, 2)


@given(many_goal_instances(min_goals=3, max_goals=5,
                       graphs=weighted_graphs(min_nodes=5, max_nodes=6, max_weight=4)))
def test_structured_and_tree_routes_agree(doc: dict[str, Any]) -> None:
    inst = instance_from_json(doc)
    for h in _horizons(inst, 2):
        a = compare_routes(inst, h, max_prefixes=MAX_PREFIXES)
        assert a.agree, (json.dumps(doc), h, a)
        assert a.dp >= a.tree.bracket.lower  # NG.2
        s = a.structured
        if s.value is None:  # a bracket: never claimed exact, and it holds the tree's bracket
            assert s.lower < s.upper and s.reason
        if inst.n_goals <= 3:
            assert s.value == a.dp  # NG.4


@given(instances(graphs=weighted_graphs(max_nodes=6, weights="fractions", max_weight=5)))
def test_for_two_goals_the_dp_is_the_two_goal_value(doc: dict[str, Any]) -> None:
    inst = instance_from_json(doc)  # two goals: read under the two-goal rules
    for h in _horizons(inst, 3):
        tree = game_value(inst, h, max_prefixes=MAX_PREFIXES)
        assert tree.bracket.closed
        assert coalition_value(inst, h).value == tree.bracket.exact


def test_recorded_cases_agree() -> None:
    """Cases kept in tests/data/ngoal_cases.json (hand-made and from the evidence script)."""
    for case in json.loads(DATA.read_text(encoding="utf-8")):
        inst = instance_from_json(case["instance"])
        h = case["horizon"]
        assert nvalue(inst, h).value == Fraction(case["value"]), case["name"]
        if "coalition_dp" in case:
            assert coalition_value(inst, h).value == Fraction(case["coalition_dp"])
        if h is not None:
            assert compare_routes(inst, h).agree, case["name"]


@given(many_goal_instances(min_goals=2, max_goals=4), st.integers(2, 5),
       st.permutations(range(4)))
def test_value_is_homogeneous_and_symmetric(doc: dict[str, Any], factor: int,
                                           perm: list[int]) -> None:
    inst = instance_from_json(doc)
    h = inst.hops[inst.start] + 2
    base = coalition_value(inst, h).value
    scaled = copy.deepcopy(doc)
    for e in scaled["graph"]["edges"]:
        e["weight"] = str(Fraction(e.get("weight", 1)) * factor)
    assert coalition_value(instance_from_json(scaled), h).value == factor * base
    order = [i for i in perm if i < len(doc["goals"])]
    permuted = {**doc, "goals": [doc["goals"][i] for i in order],
                "prior": [doc["prior"][i] for i in order]}
    assert coalition_value(instance_from_json(permuted), h).value == base


@given(many_goal_instances(min_goals=2, max_goals=5))
def test_values_do_not_increase_with_h_and_reach_the_infinite_horizon(
        doc: dict[str, Any]) -> None:
    inst = instance_from_json(doc)
    inf = coalition_value(inst, None)
    values = coalition_values(inst, range(inf.layers + 2))
    seq = [values[h] for h in sorted(values)]
    assert all(a >= b for a, b in itertools.pairwise(seq))
    assert seq[-1] == inf.value
    assert coalition_value(inst, inf.layers).coalition_costs == inf.coalition_costs


@pytest.mark.parametrize(("factor", "path"), [(1, "float64"), (10 ** 14, "int64"),
                                             (10 ** 18, "object")])
def test_every_arithmetic_path_is_exact(factor: int, path: str) -> None:
    doc = star3_document()
    for e in doc["graph"]["edges"]:
        e["weight"] = e["weight"] * factor
    inst = instance_from_json(doc)
    run = CoalitionRunner(inst)
    used = ("float64" if run.float_exact else "int64" if run.dtype == np.dtype(np.int64)
            else "object")
    assert used == path
    assert coalition_value(inst, 2).value == Fraction(3, 2) * factor


def test_horizon_errors() -> None:
    inst = star3()
    with pytest.raises(HorizonError, match="within H = 0"):
        coalition_value(inst, 0)
    with pytest.raises(HorizonError, match="non-negative"):
        coalition_value(inst, -1)
    with pytest.raises(HorizonError, match="did not converge within 1"):
        coalition_value(inst, None, max_layers=1)
    assert 0 not in coalition_values(inst, range(2))
