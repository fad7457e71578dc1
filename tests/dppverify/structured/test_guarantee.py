"""The guarantee sets (dppverify.structured.guarantee): exact in both label-setting branches."""

from __future__ import annotations

import copy
from fractions import Fraction

import pytest

from dppverify.game.examples import hub4_document, star3_document
from dppverify.game.instance import instance_from_json
from dppverify.structured.arc_condition import arc_condition
from dppverify.structured.guarantee import guarantee_sets


@pytest.mark.parametrize("doc", [star3_document(), hub4_document()])
def test_huge_weights_take_the_exact_branch_and_scale_the_sets(doc: dict) -> None:
    # Weights of 2**52 put the label-setting beyond float64's exact integers (its exact
    # Dijkstra branch); every m_S scales by the same factor, and the arc condition is kept.
    factor = 2 ** 52
    big = copy.deepcopy(doc)
    for edge in big["graph"]["edges"]:
        edge["weight"] = edge["weight"] * factor
    small_inst, big_inst = instance_from_json(doc), instance_from_json(big)
    small, large = guarantee_sets(small_inst), guarantee_sets(big_inst)
    for mask in small.m:
        for v in range(small_inst.n_nodes):
            a, b = small.value(mask, v), large.value(mask, v)
            assert (a is None and b is None) or b == a * factor, (mask, v, a, b)
    assert arc_condition(large).holds == arc_condition(small).holds
    assert large.value(1, big_inst.start) == Fraction(small.value(1, small_inst.start) or 0) \
        * factor
