"""The structured route's faster arithmetic gives the numbers of the code it replaced.

On random graphs (integer and fractional weights, exact and float mode) and random mixed
profiles, the regrouped Defender payoffs, the beliefs cached per mass pair, the Bayes steps
cached per pair of masses, the per-walk step weights and the one-pass walk reading are compared
with reference copies of the per-step code they replaced (kept here verbatim).
"""

from __future__ import annotations

import random
from fractions import Fraction
from typing import Any

import numpy as np
import pytest

from dppverify.checks.structured import (
    _belief_consistency,
    _beliefs,
    _defender_payoffs,
    _sequential,
    _sigma_on_trie,
)
from dppverify.checks.structured_twogoal import HALF, telescoping_check
from dppverify.formats.json_reading import _resolve_walk_fast, resolve_walk
from dppverify.game.arc_rows import ArcRows
from dppverify.game.defender import sigma_along
from dppverify.game.distances import (
    ArcArrays,
    hops_by_arrays,
    scaled_distance_fields,
    uniform_hops,
)
from dppverify.game.evaluation import walk_cost
from dppverify.game.instance import Instance, instance_from_json
from dppverify.game.profile import ProgressRule, StrategyWalk, TableRule
from dppverify.game.step_weights import step_weight, step_weights
from dppverify.structured.trie import WalkTrie, mass_trie


# ------------------------------------------------------------------ the replaced code, verbatim
def old_defender_payoffs(instance: Instance, roles: Any, trie: WalkTrie,
                         sigma: dict[tuple[int, ...], Any]) -> tuple[Any, Any]:
    best: Any = 0
    at_sigma: Any = 0
    mode = instance.numbers
    for p, (x1, x2) in trie.mass.items():
        y1, y2 = roles.b1 * x1, roles.b2 * x2
        if len(p) > 1:
            w = step_weight(instance, p, len(p) - 1)
            s = sigma[p]
            if mode.exact:
                best += w * max(y1, y2)
                at_sigma += w * (s * y1 + (1 - s) * y2)
            else:
                best += float(w) * float(max(y1, y2))
                at_sigma += float(w) * (float(s) * float(y1) + (1 - float(s)) * float(y2))
        if instance.is_goal(p[-1]):
            term = y1 * roles.d1[p[-1]] + y2 * roles.d2[p[-1]]
            best += mode.convert(term)
            at_sigma += mode.convert(term)
    return mode.convert(best), mode.convert(at_sigma)


def old_beliefs(roles: Any, trie: WalkTrie) -> dict[tuple[int, ...], Fraction]:
    out = {}
    for p, (x1, x2) in trie.mass.items():
        y1, y2 = roles.b1 * x1, roles.b2 * x2
        if y1 + y2 > 0:
            out[p] = y1 / (y1 + y2)
    return out


def old_bayes_problems(roles: Any, trie: WalkTrie, beliefs: dict[tuple[int, ...], Fraction]
                       ) -> list[tuple[tuple[int, ...], Fraction]]:
    out = []
    for p, b in beliefs.items():
        if len(p) < 2:
            continue
        q = p[:-1]
        (a1, a2), (c1, c2) = trie.mass[q], trie.mass[p]
        prev = beliefs[q]
        l1 = c1 / a1 if a1 else Fraction(0)
        l2 = c2 / a2 if a2 else Fraction(0)
        bayes = prev * l1 / (prev * l1 + (1 - prev) * l2)
        if bayes != b:
            out.append((p, bayes))
    return out


def old_sequential_bad(trie: WalkTrie, sigma: dict[tuple[int, ...], Any],
                       beliefs: dict[tuple[int, ...], Fraction], mode: Any) -> int:
    bad = 0
    for p, b in beliefs.items():
        if len(p) < 2:
            continue
        s = sigma[p]
        if (b > HALF and not mode.equal(s, 1)) or (b < HALF and not mode.equal(s, 0)):
            bad += 1
    return bad


def old_telescoping_bad(instance: Instance, roles: Any, trie: WalkTrie, mode: Any) -> int:
    c_of = roles.d1
    bad = 0
    done: set[tuple[int, ...]] = set()
    for p in sorted(set(trie.mass), key=len, reverse=True):
        if len(p) < 2 or p in done:
            continue
        sig = sigma_along(instance, roles, ProgressRule(roles.g1), p)
        total: Any = 0
        c = c_of[p[0]]
        for t, s in enumerate(sig, start=1):
            total += step_weight(instance, p, t) * s
            c = min(c, c_of[p[t]])
            done.add(p[:t + 1])
            if not (mode.at_most(0, s) and mode.at_most(s, 1)):
                bad += 1
            if not mode.equal(total, c_of[p[0]] - c):
                bad += 1
    return bad


def old_walk_cost(instance: Instance, roles: Any, rule: Any, walk: tuple[int, ...],
                  theta: int) -> Any:
    sigma = sigma_along(instance, roles, rule, walk)
    total: Any = 0
    for t, s in enumerate(sigma, start=1):
        w = step_weight(instance, walk, t)
        total += w * (s if theta == 1 else 1 - s)
    total += roles.dist(theta)[walk[-1]]
    return instance.numbers.convert(total)


# ------------------------------------------------------------------ random games and profiles
def random_game(rng: random.Random, *, numbers: str = "exact", grid: bool = False
                ) -> Instance:
    """A random connected undirected graph (or a unit grid) with two goals."""
    if grid:
        rows, cols = rng.randint(3, 7), rng.randint(3, 7)
        nodes = [f"{r}_{c}" for r in range(rows) for c in range(cols)]
        edges = [{"source": f"{r}_{c}", "target": f"{r}_{c + 1}", "weight": 1}
                 for r in range(rows) for c in range(cols - 1)]
        edges += [{"source": f"{r}_{c}", "target": f"{r + 1}_{c}", "weight": 1}
                  for r in range(rows - 1) for c in range(cols)]
    else:
        n = rng.randint(5, 14)
        nodes = [f"v{i}" for i in range(n)]
        pairs = {(i - 1, i) for i in range(1, n)}  # a path keeps it connected
        while len(pairs) < n + rng.randint(1, 2 * n):
            a, b = sorted(rng.sample(range(n), 2))
            pairs.add((a, b))
        weights = [1, 2, 3, "1/2", "3/2", "5/3"]
        edges = [{"source": nodes[a], "target": nodes[b], "weight": rng.choice(weights)}
                 for a, b in sorted(pairs)]
    start, g1, g2 = rng.sample(nodes, 3)
    p = Fraction(rng.randint(1, 9), 10)
    doc = {"graph": {"directed": False, "nodes": [{"id": v} for v in nodes], "edges": edges},
           "start": start, "goals": [g1, g2], "prior": [str(p), str(1 - p)], "numbers": numbers}
    return instance_from_json(doc)


def random_walk(rng: random.Random, inst: Instance) -> tuple[int, ...] | None:
    """A random walk from the start until the first goal (None if it takes too long)."""
    walk = [inst.start]
    for _ in range(40):
        if inst.is_goal(walk[-1]):
            return tuple(walk)
        walk.append(rng.choice([v for v, _ in inst.succ[walk[-1]]]))
    return tuple(walk) if inst.is_goal(walk[-1]) else None


def mixed(rng: random.Random, inst: Instance) -> list[StrategyWalk]:
    walks = []
    while len(walks) < rng.randint(1, 4):
        w = random_walk(rng, inst)
        if w is not None:
            walks.append(w)
    raw = [rng.randint(0, 5) for _ in walks]
    if sum(raw) == 0:
        raw[0] = 1
    return [StrategyWalk(w, Fraction(r, sum(raw))) for w, r in zip(walks, raw, strict=True)]


def rule_for(rng: random.Random, inst: Instance, trie: WalkTrie) -> Any:
    roles = inst.roles()
    kind = rng.randrange(3)
    if kind == 0:
        return ProgressRule(roles.g1)
    if kind == 1:
        return ProgressRule(roles.g2)
    entries = {p: Fraction(rng.randint(0, 4), 4) for p in trie.mass
               if len(p) > 1 and rng.random() < 0.5}
    return TableRule(goal=roles.g1, entries=entries, default=ProgressRule(roles.g1))


CASES = [(seed, numbers, grid) for seed in range(40) for numbers, grid in
         (("exact", False), ("exact", True), ("float", False))]


@pytest.mark.parametrize(("seed", "numbers", "grid"), CASES)
def test_structured_arithmetic_equals_the_per_step_code(seed: int, numbers: str,
                                                        grid: bool) -> None:
    rng = random.Random(seed)
    inst = random_game(rng, numbers=numbers, grid=grid)
    if inst.start in inst.goals:
        return
    roles = inst.roles()
    primary, secondary = mixed(rng, inst), mixed(rng, inst)
    trie = mass_trie([primary, secondary])
    rule = rule_for(rng, inst, trie)
    sigma = _sigma_on_trie(inst, roles, rule, trie)  # by prefix id; the old code by tuple
    sig_t = {trie.walk(i): sigma[i] for i in range(trie.size) if trie.parent[i] >= 0}
    new, old = _defender_payoffs(inst, roles, trie, sigma), old_defender_payoffs(
        inst, roles, trie, sig_t)
    assert new == old and [type(x) for x in new] == [type(x) for x in old]
    beliefs = _beliefs(roles, trie)
    assert {trie.walk(i): b for i, b in beliefs.items()} == old_beliefs(roles, trie)
    # a corrupted belief somewhere: the cached Bayes step still finds exactly the old problems
    bent = dict(beliefs)
    some = sorted(i for i in bent if trie.parent[i] >= 0)
    for i in rng.sample(some, min(2, len(some))):
        bent[i] = bent[i] / 2 if bent[i] else Fraction(1, 3)
    for bel in (beliefs, bent):
        bel_t = {trie.walk(i): b for i, b in bel.items()}
        rec = _belief_consistency(inst, _NoClaims(), roles, trie, bel)
        want = old_bayes_problems(roles, trie, bel_t)
        assert (rec.status == "pass") == (not want)
        assert rec.message.count("Bayes' rule gives") == min(3, len(want))
        seq = _sequential(inst, trie, sigma, bel, inst.numbers)
        assert seq.numbers["violations"] == old_sequential_bad(trie, sig_t, bel_t, inst.numbers)
    tel = telescoping_check(inst, roles, trie, inst.numbers)
    assert tel.numbers["violations"] == old_telescoping_bad(inst, roles, trie, inst.numbers)
    for mw in (*primary, *secondary):
        assert step_weights(inst, mw.walk) == [step_weight(inst, mw.walk, t)
                                               for t in range(1, len(mw.walk))]
        for theta in (1, 2):
            assert walk_cost(inst, roles, rule, mw.walk, theta) == old_walk_cost(
                inst, roles, rule, mw.walk, theta)


class _NoClaims:
    claimed_prior = None


@pytest.mark.parametrize("seed", range(30))
def test_find_many_equals_find(seed: int) -> None:
    rng = np.random.default_rng(seed)
    n = int(rng.integers(1, 12))
    m = int(rng.integers(0, 40))
    tails = np.sort(rng.integers(0, n, m))
    heads = rng.integers(0, n, m)  # repeated arcs allowed: find returns the first
    values: tuple[Any, ...] = (Fraction(1, 2), 3, Fraction(7, 3))[:int(rng.integers(1, 4))]
    codes = rng.integers(0, len(values), m)
    rows = ArcRows(n, tails, heads, codes, values)
    us = rng.integers(0, n, 50).tolist()
    vs = rng.integers(0, n, 50).tolist()
    assert rows.find_many(us, vs) == [rows.find(u, v) for u, v in zip(us, vs, strict=True)]


@pytest.mark.parametrize("seed", range(40))
def test_one_pass_walk_reading_agrees(seed: int) -> None:
    """The one-pass reading returns the walk of the step-by-step loop, or defers to it."""
    rng = random.Random(seed)
    inst = random_game(rng, grid=seed % 2 == 0)
    ids = list(inst.nodes)
    for _ in range(20):
        walk = random_walk(rng, inst)
        raw: list[Any] = [inst.nodes[v] for v in walk] if walk else [rng.choice(ids)]
        if rng.random() < 0.5:  # break it: a node swapped, dropped, unknown or repeated
            k = rng.randrange(len(raw))
            raw[k] = rng.choice([*ids, "nowhere", 3.5, None])
        for complete in (True, False):
            fast = _resolve_walk_fast(inst, raw, complete=complete)
            slow = resolve_walk(inst, raw, complete=complete)
            assert fast is None or fast == slow


@pytest.mark.parametrize("seed", range(40))
def test_uniform_hops_equal_the_breadth_first_hops(seed: int) -> None:
    """One weight for every arc: hops from the distance rows = the BFS hop counts."""
    rng = random.Random(seed)
    n = rng.randint(1, 15)
    w = rng.choice([1, 2, Fraction(1, 3), Fraction(5, 2)])
    adj: list[list[tuple[int, Any]]] = [[] for _ in range(n)]
    for u in range(n):
        for v in rng.sample(range(n), rng.randint(0, min(3, n))):
            if v != u:
                adj[u].append((v, w))
    arcs = ArcArrays.from_adjacency([sorted(row) for row in adj])
    targets = rng.sample(range(n), rng.randint(1, min(3, n)))
    fields = scaled_distance_fields(arcs, n, targets)
    assert fields is not None
    scale, rows = fields
    assert uniform_hops(rows, int(w * scale)) == hops_by_arrays(arcs, n, targets)


@pytest.mark.parametrize("seed", range(60))
def test_pruned_seeds_give_the_same_fixpoint_fields(seed: int) -> None:
    """The value DP's third Dijkstra with dominated seeds dropped: the same fields, steps."""
    from dppverify.twogoal.value_fixpoint import _fixpoint

    rng = random.Random(seed)
    inst = random_game(rng, grid=seed % 3 == 0)
    for roles in (inst.roles(), inst.roles(1)):
        new, old = _fixpoint(inst, roles, None), _fixpoint(inst, roles, None, prune=False)
        assert (new is None) == (old is None)
        if new is not None and old is not None:
            for f in ("d1", "d2", "m", "h1", "h2", "hm"):
                assert np.array_equal(getattr(new, f), getattr(old, f)), f
            assert new.last == old.last


@pytest.mark.parametrize("seed", range(20))
def test_sigma_memo_returns_fresh_equal_lists(seed: int) -> None:
    """σ along a walk is remembered per instance: equal to a fresh computation, and a
    caller changing the list it got does not change what the next caller gets."""
    from dppverify.game.progress_rule import _progress_sigma

    rng = random.Random(seed)
    inst = random_game(rng, grid=seed % 2 == 0)
    roles = inst.roles()
    walk = random_walk(rng, inst)
    if walk is None or len(walk) < 2:
        return
    for goal in (roles.g1, roles.g2):
        first = sigma_along(inst, roles, ProgressRule(goal), walk)
        first[0] = "changed"
        again = sigma_along(inst, roles, ProgressRule(goal), list(walk))
        fresh = _progress_sigma(inst, ProgressRule(goal), walk)
        want = fresh if goal == roles.g1 else [inst.numbers.difference(1, s) for s in fresh]
        assert again == want
