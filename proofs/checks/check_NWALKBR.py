"""Checks for proofs/NWALKBR.md (N goals: best responses over all walks against a table
Defender with a default; the Defender's regret on the profile's prefixes; off-path beliefs).
"""

from __future__ import annotations

import itertools
import random
from fractions import Fraction

import sympy as sp

from dppverify.game.instance import Instance, instance_from_json
from dppverify.structured.table_br import table_defender, walk_best_response
from dppverify.tree_route.best_response import attacker_best_response
from dppverify.tree_route.players import defender_from_table
from dppverify.tree_route.tree import build_tree, count_prefixes
from proofs.checks._sym import is_nonneg, is_zero, nonneg

DISTRIBUTIONS = [(Fraction(1), Fraction(0), Fraction(0)), (Fraction(0), Fraction(1), Fraction(0)),
                 (Fraction(0), Fraction(0), Fraction(1)), (Fraction(1, 3),) * 3,
                 (Fraction(1, 2), Fraction(0), Fraction(1, 2)),
                 (Fraction(0), Fraction(2, 3), Fraction(1, 3))]


def _instance(rng: random.Random) -> Instance | None:
    n = rng.randint(4, 6)
    edges = {(u, v) for u in range(n) for v in range(u + 1, n) if rng.random() < 0.5}
    doc = {"graph": {"directed": False, "nodes": [{"id": v} for v in range(n)],
                     "edges": [{"source": u, "target": v,
                                "weight": str(Fraction(rng.randint(1, 6), rng.choice([1, 2])))}
                               for u, v in sorted(edges)]},
           "start": n - 1, "goals": [0, 1, 2], "prior": ["1/2", "1/3", "1/6"]}
    try:
        return instance_from_json(doc)
    except ValueError:
        return None


def _random_walk(inst: Instance, rng: random.Random, steps: int) -> tuple[int, ...]:
    w = [inst.start]
    while len(w) <= steps and not inst.is_goal(w[-1]):
        live = [u for u, _ in inst.succ[w[-1]] if inst.is_goal(u) or inst.hops[u] >= 0]
        w.append(rng.choice(live))
    return tuple(w)


def test_NWALKBR_equals_exhaustive_backward_induction_over_all_walks() -> None:
    rng = random.Random(0)
    checked = 0
    while checked < 60:
        inst = _instance(rng)
        if inst is None or inst.is_goal(inst.start):
            continue
        entries = {}
        for _ in range(rng.randint(0, 4)):
            w = _random_walk(inst, rng, rng.randint(1, 3))
            if len(w) > 1:
                entries[w] = rng.choice(DISTRIBUTIONS)
        default = rng.choice(DISTRIBUTIONS)
        tdef = table_defender(inst, entries, default)
        bound = max(tdef.trie.depth) + 1 + inst.n_nodes - inst.n_goals
        if count_prefixes(inst, bound + 2) > 20000:
            continue
        tree = build_tree(inst, bound + 2)  # NW.1's bound and two more steps
        table = {p: d for w, d in entries.items() if (p := tree.find(w)) is not None}
        tree_def = defender_from_table(tree, table, default)
        for theta in range(inst.n_goals):
            br = walk_best_response(tdef, theta)
            exhaustive = attacker_best_response(tree, inst, tree_def, theta)
            assert br.value == exhaustive.value, (theta, entries, default)
            assert len(br.walk) - 1 <= bound
            # the witness is a walk of the game and costs what NW.1 says
            p = tree.find(br.walk)
            assert p is not None and tree.is_leaf_mask()[p]
        checked += 1


def test_NWALKBR_defender_regret_is_a_sum_of_nonnegative_greedy_gaps() -> None:
    # one reached prefix, three types: y = b_θ x_θ(p), σ on the simplex (NW.3)
    y1, gap2, gap3, s2, s3, w = nonneg("y1 gap2 gap3 s2 s3 w")
    y = (y1, y1 - gap2, y1 - gap3)  # y1 is a maximal coordinate
    s1 = 1 - s2 - s3
    regret = w * (y[0] - (s1 * y[0] + s2 * y[1] + s3 * y[2]))
    assert is_zero(regret - w * (s2 * gap2 + s3 * gap3))
    assert is_nonneg(w * (s2 * gap2 + s3 * gap3))  # zero iff no mass on a smaller coordinate


def test_NWALKBR_any_distribution_is_greedy_for_the_uniform_belief_on_its_support() -> None:
    # NW.4 for N = 3: every support S, every σ on S, every vertex τ of the simplex
    for k in (1, 2, 3):
        for support in itertools.combinations(range(3), k):
            mu = [sp.Rational(1, k) if t in support else 0 for t in range(3)]
            a, b = nonneg("a b")
            free = [a, b][:k - 1]
            sigma = [sp.Integer(0)] * 3
            for t, x in zip(support, [*free, 1 - sum(free)], strict=True):
                sigma[t] = x
            value = sum(m * s for m, s in zip(mu, sigma, strict=True))
            assert is_zero(value - sp.Rational(1, k))
            for t in range(3):
                assert is_nonneg(value - mu[t])
