"""Best responses: backward induction and LPs against brute force recomputed from the input."""

from __future__ import annotations

import itertools
import random
from fractions import Fraction
from typing import Any

import pytest

from dppverify.checks.lemmas import random_mixture
from dppverify.game.evaluation import evaluate, realization
from dppverify.game.instance import instance_from_json
from dppverify.game.profile import ProgressRule, TableRule
from dppverify.tree_route.best_response import (
    attacker_best_response,
    attacker_best_response_lp,
    defender_best_response,
    defender_best_response_lp,
    leaf_totals,
    payoff_on_tree,
)
from dppverify.tree_route.lp import lp_agrees
from dppverify.tree_route.tree import build_tree
from dppverify.tree_route.tree_defender import tree_defender
from tests.dppverify._helpers import (
    adjacency,
    all_walks,
    distances_to,
    load_cases,
    make_doc,
    progress_costs,
)

CASES = load_cases()


def _random_doc(seed: int) -> dict[str, Any]:
    rng = random.Random(seed)
    n = rng.randint(4, 6)
    directed = rng.random() < 0.4
    edges: dict[tuple[int, int], int] = {}
    for i in range(n):
        edges[(i, (i + 1) % n)] = rng.randint(1, 4)
        if directed:
            edges[((i + 1) % n, i)] = rng.randint(1, 4)
    for _ in range(n):
        u, v = rng.sample(range(n), 2)
        if directed or (v, u) not in edges:
            edges.setdefault((u, v), rng.randint(1, 4))
    prior = rng.choice([("1/2", "1/2"), ("3/5", "2/5"), ("1/4", "3/4")])
    return make_doc([(u, v, w) for (u, v), w in edges.items()], 0, [n - 1, n // 2], prior,
                    directed=directed, nodes=list(range(n)))


@pytest.mark.parametrize("index", range(0, len(CASES), 5))
def test_attacker_best_response_against_sigma_star_is_the_brute_force_minimum(index: int
                                                                             ) -> None:
    doc = CASES[index]["instance"]
    _check_sigma_star(doc, CASES[index]["expected"]["H"] + 2)


@pytest.mark.parametrize("seed", range(8))
def test_attacker_best_response_on_random_graphs(seed: int) -> None:
    _check_sigma_star(_random_doc(seed), 5)


def _check_sigma_star(doc: dict[str, Any], horizon: int) -> None:
    inst = instance_from_json(doc)
    r = inst.roles()
    g1, g2 = inst.nodes[r.g1], inst.nodes[r.g2]
    tree = build_tree(inst, horizon)
    td = tree_defender(tree, r, ProgressRule(r.g1))
    walks = list(all_walks(doc, horizon))
    for theta in (1, 2):
        brute = min(progress_costs(doc, w, g1, g2)[theta - 1] for w in walks)
        br = attacker_best_response(tree, r, td, theta)
        assert br.value == brute
        assert progress_costs(doc, inst.labels(br.walk), g1, g2)[theta - 1] == brute
        totals = leaf_totals(tree, r, td, theta)
        assert min(totals[p] for p in tree.leaves().tolist()) == brute
        assert lp_agrees(attacker_best_response_lp(tree, r, td, theta).value, brute)


def _table_cost(doc: dict[str, Any], table: dict[tuple[Any, ...], Fraction], walk: tuple[Any, ...],
                g1: Any, g2: Any) -> tuple[Fraction, Fraction]:
    """Costs of a walk against a table Defender (probability of allocating to g1)."""
    adj = adjacency(doc)
    u1 = u2 = Fraction(0)
    for t in range(1, len(walk)):
        w = dict(adj[walk[t - 1]])[walk[t]]
        s = table[walk[:t + 1]]
        u1 += w * s
        u2 += w * (1 - s)
    return u1 + distances_to(doc, g1)[walk[-1]], u2 + distances_to(doc, g2)[walk[-1]]


@pytest.mark.parametrize("seed", range(6))
def test_attacker_best_response_against_random_tables(seed: int) -> None:
    doc = _random_doc(100 + seed)
    rng = random.Random(seed)
    inst = instance_from_json(doc)
    r = inst.roles()
    g1, g2 = inst.nodes[r.g1], inst.nodes[r.g2]
    horizon = 4
    walks = list(all_walks(doc, horizon))
    prefixes = {w[:k] for w in walks for k in range(2, len(w) + 1)}
    table = {p: Fraction(rng.randint(0, 6), 6) for p in prefixes}
    rule = TableRule(goal=r.g1, default=None,
                     entries={tuple(inst.index[v] for v in p): q for p, q in table.items()})
    tree = build_tree(inst, horizon)
    td = tree_defender(tree, r, rule)
    assert not td.undefined
    for theta in (1, 2):
        brute = min(_table_cost(doc, table, w, g1, g2)[theta - 1] for w in walks)
        assert attacker_best_response(tree, r, td, theta).value == brute
        assert lp_agrees(attacker_best_response_lp(tree, r, td, theta).value, brute)


@pytest.mark.parametrize("seed", range(8))
def test_defender_best_response_is_the_best_pure_strategy(seed: int) -> None:
    """Greedy = max over ALL pure Defender strategies on the reached infosets (enumerated)."""
    doc = _random_doc(200 + seed)
    inst = instance_from_json(doc)
    r = inst.roles()
    tree = build_tree(inst, 4)
    rng = random.Random(seed)
    prim, sec = random_mixture(tree, rng, k_max=3), random_mixture(tree, rng, k_max=3)
    x1, x2 = realization(tree, prim), realization(tree, sec)
    infosets = sorted(p for p in set(x1) | set(x2) if p)
    assert len(infosets) <= 14
    best = None
    for bits in itertools.product((0, 1), repeat=len(infosets)):
        table = dict(zip((tree.walk(p) for p in infosets), map(Fraction, bits), strict=True))
        rule = TableRule(goal=r.g1, entries=table, default=Fraction(0))
        u = evaluate(inst, r, rule, prim, sec).U
        best = u if best is None else max(best, u)
        assert payoff_on_tree(tree, r, tree_defender(tree, r, rule), {1: x1, 2: x2}) == u
    greedy = defender_best_response(tree, r, {1: x1, 2: x2})
    assert greedy.value == best
    lp, sigma = defender_best_response_lp(tree, r, {1: x1, 2: x2})
    assert lp_agrees(lp.value, best)
    assert set(sigma) == set(infosets)
