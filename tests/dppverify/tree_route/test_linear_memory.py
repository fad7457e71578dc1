"""Deciding early in linear memory (issues 22 and 23): the structured route's walk trie
takes memory linear in the total walk length, and counting the walk tree of a long path
touches only the nodes a prefix can be at. Memory is measured with tracemalloc (allocations,
deterministic), never with timings."""

from __future__ import annotations

import tracemalloc
from fractions import Fraction

from dppverify.game.instance import instance_from_json
from dppverify.game.profile import StrategyWalk
from dppverify.structured.trie import mass_trie
from dppverify.tree_route.tree import count_prefixes


def test_the_trie_of_a_60000_step_walk_is_linear() -> None:
    steps = 60_000
    walk = tuple(range(steps + 1))
    other = (0, 1, 2, 3, 99_999)
    tracemalloc.start()
    try:
        trie = mass_trie([[StrategyWalk(walk, Fraction(1, 2)), StrategyWalk(other, Fraction(1, 2))],
                          [StrategyWalk(walk[:10], Fraction(1))]])
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    # one tuple per prefix would be ~ steps**2 / 2 * 8 bytes = 14 GB; linear is a few MB
    assert peak < 100 * steps * 8, peak
    assert trie.size == steps + 2  # the other walk shares 4 nodes, then one of its own
    assert trie.mass[walk[:4]] == (Fraction(1), Fraction(1))
    assert trie.mass[walk[:5]] == (Fraction(1, 2), Fraction(1))
    assert trie.mass[other] == (Fraction(1, 2), Fraction(0))
    assert trie.find(walk[:11]) is not None and trie.walk(trie.find(walk[:11]) or 0) == walk[:11]
    assert [len(ids) for ids in trie.ids] == [steps + 1, 5, 10]


def _path(n: int) -> dict[str, object]:
    return {"graph": {"nodes": [{"id": i} for i in range(n)],
                      "edges": [{"source": i, "target": i + 1} for i in range(n - 1)]},
            "start": n // 2, "goals": [0, n - 1], "prior": ["1/2", "1/2"]}


def test_counting_a_long_path_tree() -> None:
    inst = instance_from_json(_path(4001))
    assert count_prefixes(inst, 2000) == 1 + 2 * 2000  # the two straight walks
    assert count_prefixes(inst, 1999) == 0
    assert count_prefixes(inst, 2000, limit=100) == 101  # saturated just above the limit
    small = instance_from_json(_path(21))
    for h in range(8, 17):  # an independent oracle: enumerate the walks
        assert count_prefixes(small, h) == _brute(small, h), h
        assert count_prefixes(small, h, limit=50) == min(_brute(small, h), 51), h


def _brute(inst: object, horizon: int) -> int:
    """Prefixes of the pruned walk tree by enumeration: walks from the start that stop at the
    first goal and can still reach a goal within the steps left."""
    from dppverify.game.instance import Instance

    assert isinstance(inst, Instance)
    count = 0
    stack = [(inst.start, 0)]
    while stack:
        v, t = stack.pop()
        count += 1
        if inst.is_goal(v):
            continue
        for u, _ in inst.succ[v]:
            if t + 1 <= horizon and 0 <= inst.hops[u] <= horizon - t - 1:
                stack.append((u, t + 1))
    return count if 0 <= inst.hops[inst.start] <= horizon else 0
