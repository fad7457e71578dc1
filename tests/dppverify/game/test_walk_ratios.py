"""The progress rule's σ along a walk: the integer fast path (decided once per walk) gives the
same numbers, with the same types, as the per-step exact ratio (issue 22)."""

from __future__ import annotations

from typing import Any

from hypothesis import assume, given, settings
from hypothesis import strategies as st

from dppverify.game.defender import sigma_along
from dppverify.game.instance import _read_game
from dppverify.game.profile import ProgressRule
from dppverify.game.progress_rule import progress_along
from dppverify.game.step_weights import step_weight
from dppverify.strategies import grid_worlds, instances, weighted_graphs

docs = st.one_of(
    instances(graphs=weighted_graphs(max_nodes=7, max_weight=4)),
    instances(graphs=weighted_graphs(max_nodes=7, weights="fractions", max_weight=4)),
    grid_worlds(max_size=4, max_cells=12),
)


@settings(deadline=None, max_examples=100)
@given(docs, st.data())
def test_progress_sigma_equals_the_per_step_ratio(doc: dict[str, Any], data: Any) -> None:
    inst = _read_game(doc)
    walk = [inst.start]
    for _ in range(data.draw(st.integers(min_value=1, max_value=8))):
        arcs = inst.succ[walk[-1]]
        if not arcs or inst.is_goal(walk[-1]):
            break
        walk.append(data.draw(st.sampled_from([v for v, _ in arcs])))
    assume(len(walk) >= 2)
    r = inst.roles()
    got = sigma_along(inst, r, ProgressRule(r.g1), walk)
    prog = progress_along(inst, r.g1, walk)
    want = [inst.numbers.ratio(p, step_weight(inst, walk, t))
            for t, p in enumerate(prog, start=1)]
    assert got == want and [type(x) for x in got] == [type(x) for x in want]
