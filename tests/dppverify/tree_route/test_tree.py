"""The truncated walk tree against brute-force enumeration of walks."""

from __future__ import annotations

import random
from typing import Any

import pytest

from dppverify.errors import HorizonError, TreeTooLargeError
from dppverify.game.instance import instance_from_json
from dppverify.tree_route.tree import build_tree, count_prefixes, simple_mask
from tests.dppverify._helpers import all_walks, grid_doc, load_cases, make_doc, triangle_doc


def _check_tree_against_brute_force(doc: dict[str, Any], horizon: int) -> None:
    inst = instance_from_json(doc)
    tree = build_tree(inst, horizon)
    leaves = {inst.labels(tree.walk(int(p))) for p in tree.leaves()}
    expected = set(all_walks(doc, horizon))
    assert leaves == expected
    prefixes = {w[:k] for w in expected for k in range(1, len(w) + 1)}
    walks = [inst.labels(tree.walk(p)) for p in range(tree.n_prefixes)]
    assert len(walks) == len(set(walks)) == tree.n_prefixes == count_prefixes(inst, horizon)
    assert set(walks) == prefixes
    for p in range(1, tree.n_prefixes):
        q = int(tree.parent[p])
        assert q < p and p in tree.children(q)
        assert tree.depth[p] == tree.depth[q] + 1 <= horizon
        assert tree.weight[p] == inst.weight(int(tree.node[q]), int(tree.node[p]))
        assert tree.find(tree.walk(p)) == p
    simple = simple_mask(tree)
    for p in range(tree.n_prefixes):
        w = tree.walk(p)
        assert bool(simple[p]) == (len(set(w)) == len(w))


@pytest.mark.parametrize("horizon", [1, 2, 3, 5])
def test_triangle_tree(horizon: int) -> None:
    _check_tree_against_brute_force(triangle_doc(), horizon)


@pytest.mark.parametrize("seed", range(10))
def test_random_graph_trees(seed: int) -> None:
    rng = random.Random(seed)
    n = rng.randint(4, 7)
    directed = rng.random() < 0.5
    edges = set()
    for i in range(n):
        edges.add((i, (i + 1) % n))
    for _ in range(n):
        u, v = rng.sample(range(n), 2)
        edges.add((u, v))
    doc = make_doc([(u, v, rng.randint(1, 3)) for u, v in sorted(edges)
                    if directed or (v, u) not in edges or u < v],
                   0, [n - 1, n // 2], ["3/5", "2/5"], directed=directed, nodes=list(range(n)))
    _check_tree_against_brute_force(doc, rng.randint(1, 6))


def test_grid_tree_and_conformance_trees() -> None:
    _check_tree_against_brute_force(grid_doc(2, 3, (0, 0), [(1, 2), (0, 2)], ["1/2", "1/2"]), 6)
    for case in load_cases()[::9]:
        _check_tree_against_brute_force(case["instance"], case["expected"]["H"] + 1)


def test_start_at_goal_is_a_single_leaf() -> None:
    doc = make_doc([("g1", "g2", 1)], "g1", ["g1", "g2"], ["1/2", "1/2"])
    tree = build_tree(instance_from_json(doc), 0)
    assert tree.n_prefixes == 1 and tree.n_leaves == 1
    assert build_tree(instance_from_json(doc), 4).n_prefixes == 1


def test_pruning_removes_dead_ends() -> None:
    doc = make_doc([("s", "dead", 1), ("s", "g1", 1), ("s", "g2", 1), ("g1", "g2", 1),
                    ("g2", "g1", 1)], "s",
                   ["g1", "g2"], ["1/2", "1/2"], directed=True)
    tree = build_tree(instance_from_json(doc), 3)
    assert tree.n_prefixes == 3


def test_horizon_errors() -> None:
    inst = instance_from_json(triangle_doc())
    with pytest.raises(HorizonError, match="no walk"):
        build_tree(inst, 0)
    with pytest.raises(HorizonError, match="non-negative"):
        build_tree(inst, -1)
    grid = instance_from_json(grid_doc(3, 3, (1, 1), [(0, 0), (2, 2)], ["3/5", "2/5"]))
    with pytest.raises(TreeTooLargeError, match="more than the limit of 10"):
        build_tree(grid, 8, max_prefixes=10)


def test_three_by_four_grid_at_horizon_12_has_about_137k_prefixes() -> None:
    inst = instance_from_json(grid_doc(3, 4, (0, 1), [(2, 0), (2, 3)], ["3/5", "2/5"]))
    tree = build_tree(inst, 12)
    assert tree.n_prefixes == count_prefixes(inst, 12) == 136_711
    assert all(inst.is_goal(int(tree.node[p])) for p in tree.leaves())
