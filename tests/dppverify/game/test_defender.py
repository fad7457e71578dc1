"""The progress rule σ* (eq. (7)) and table Defenders, against naive re-implementations."""

from __future__ import annotations

import random
import re
from fractions import Fraction

import pytest

from dppverify.game.defender import sigma_along
from dppverify.game.evaluation import walk_cost
from dppverify.game.instance import instance_from_json
from dppverify.game.profile import ProgressRule, TableRule
from dppverify.game.progress_rule import progress_along
from dppverify.tree_route.tree import build_tree
from dppverify.tree_route.tree_defender import tree_defender
from tests.dppverify._helpers import (
    all_walks,
    grid_doc,
    load_cases,
    make_doc,
    progress_costs,
    three_phase_doc,
)


def test_paper_figure_progress_example() -> None:
    """Fig. 3(a): c_0 = 3.5; moving to a node at distance 2 is progress 1.5, to 3 is 0.5."""
    doc = make_doc([("s", "a", 2), ("a", "g1", 2), ("s", "b", 1), ("b", "g1", 3),
                    ("s", "g2", 5), ("g2", "g1", 9)], "s", ["g1", "g2"], ["3/5", "2/5"])
    doc["graph"]["edges"].append({"source": "s", "target": "g1", "weight": "7/2"})
    inst = instance_from_json(doc)
    ix = inst.index
    assert progress_along(inst, ix["g1"], [ix["s"], ix["a"]]) == [Fraction(3, 2)]
    assert progress_along(inst, ix["g1"], [ix["s"], ix["b"]]) == [Fraction(1, 2)]
    r = inst.roles()
    assert sigma_along(inst, r, ProgressRule(r.g1), [ix["s"], ix["a"]]) == [Fraction(3, 4)]
    # both continue to g1 and pay exactly d(s0, g1) = 7/2 (Fig. 3(b))
    for mid in ("a", "b"):
        walk = (ix["s"], ix[mid], ix["g1"])
        assert walk_cost(inst, r, ProgressRule(r.g1), walk, 1) == Fraction(7, 2)


def test_new_progress_is_zero_when_the_minimum_was_reached_earlier() -> None:
    doc = make_doc([("s", "a", 1), ("a", "b", 1), ("b", "c", 1), ("c", "g1", 1),
                    ("a", "g1", 2), ("s", "g2", 1), ("g2", "g1", 3)], "s", ["g1", "g2"],
                   ["1/2", "1/2"])
    inst = instance_from_json(doc)
    ix = inst.index
    # d(.,g1): s 3, a 2, b 2, c 1: a -> b is no new progress although b is as close as a
    walk = [ix[v] for v in ("s", "a", "b", "c", "g1")]
    assert progress_along(inst, ix["g1"], walk) == [1, 0, 1, 1]


@pytest.mark.parametrize("case", load_cases()[::6], ids=lambda c: c["name"])
def test_sigma_star_on_every_walk_matches_a_naive_implementation(case: dict) -> None:
    doc = case["instance"]
    inst = instance_from_json(doc)
    r = inst.roles()
    g1, g2 = inst.nodes[r.g1], inst.nodes[r.g2]
    tree = build_tree(inst, case["expected"]["H"] + 1)
    td = tree_defender(tree, r, ProgressRule(r.g1))
    for p in tree.leaves().tolist():
        walk = tree.walk(p)
        labels = inst.labels(walk)
        u1, u2 = progress_costs(doc, labels, g1, g2)
        path = tree.prefixes(p)
        assert sum(td.alloc1[q] for q in path[1:]) + r.d1[walk[-1]] == u1
        assert sum(td.alloc2[q] for q in path[1:]) + r.d2[walk[-1]] == u2
        assert walk_cost(inst, r, ProgressRule(r.g1), walk, 1) == u1
        assert walk_cost(inst, r, ProgressRule(r.g1), walk, 2) == u2
        assert all(0 <= td.sigma1[q] <= 1 for q in path[1:])


def test_progress_towards_g2_is_the_mirror_rule() -> None:
    inst = instance_from_json(three_phase_doc())
    r = inst.roles()
    tree = build_tree(inst, 4)
    to_g2 = tree_defender(tree, r, ProgressRule(r.g2))
    swapped = inst.roles(1 - inst.primary_goal_index)
    mirror = tree_defender(tree, swapped, ProgressRule(swapped.g1))
    assert to_g2.alloc1 == mirror.alloc2 and to_g2.alloc2 == mirror.alloc1


def test_table_rule_entries_default_and_goal() -> None:
    inst = instance_from_json(grid_doc(2, 3, (0, 0), [(1, 2), (0, 2)], ["3/5", "2/5"]))
    r = inst.roles()
    tree = build_tree(inst, 4)
    rng = random.Random(3)
    entries = {tree.walk(p): Fraction(rng.randint(0, 4), 4)
               for p in range(1, tree.n_prefixes) if rng.random() < 0.5}
    for default in (Fraction(1, 3), ProgressRule(r.g2), None):
        rule = TableRule(goal=r.g2, entries=entries, default=default)
        td = tree_defender(tree, r, rule)
        for p in range(1, tree.n_prefixes):
            walk = tree.walk(p)
            if walk in entries:
                assert td.sigma1[p] == 1 - entries[walk]
            elif default is None:
                assert p in td.undefined
            elif isinstance(default, ProgressRule):
                prog = progress_along(inst, r.g2, walk)[-1]
                assert td.alloc2[p] == prog
            else:
                assert td.sigma1[p] == 1 - default
            if default is not None:
                assert sigma_along(inst, r, rule, walk)[-1] == td.sigma1[p]
        if default is None:
            with pytest.raises(LookupError, match="no entry"):
                for p in range(1, tree.n_prefixes):
                    sigma_along(inst, r, rule, tree.walk(p))


def test_walks_through_nodes_that_cannot_reach_g1_make_no_progress() -> None:
    doc = make_doc([("s", "trap", 1), ("trap", "g2", 1), ("s", "g1", 2), ("g1", "g2", 1),
                    ("g2", "g1", 1)], "s", ["g1", "g2"], ["2/3", "1/3"], directed=True)
    doc["graph"]["edges"].append({"source": "trap", "target": "trap2", "weight": 1})
    doc["graph"]["nodes"].append({"id": "trap2"})
    doc["graph"]["edges"].append({"source": "trap2", "target": "g2", "weight": 1})
    inst = instance_from_json(doc)
    walks = list(all_walks(doc, 4))
    assert ("s", "trap", "trap2", "g2") in walks
    ix = inst.index
    assert progress_along(inst, ix["g1"], [ix[v] for v in ("s", "trap", "trap2", "g2")]) == \
        [0, 0, 1]


def test_public_helpers_reject_bad_arguments_with_named_errors() -> None:
    from dppverify.errors import InvalidInstanceError, ProfileError
    from dppverify.game.evaluation import walk_cost
    from dppverify.game.examples import triangle
    from dppverify.game.profile import ProgressRule

    inst = triangle()
    r = inst.roles()
    s, g1 = inst.index["s"], inst.index["g1"]
    with pytest.raises(InvalidInstanceError, match="'s' is not a goal"):
        progress_along(inst, s, [s, g1])
    message = "step 2 of the walk, 'g1' -> 'g1', is not an edge"
    with pytest.raises(ProfileError, match=re.escape(message)):
        walk_cost(inst, r, ProgressRule(r.g1), (s, g1, g1), 1)
