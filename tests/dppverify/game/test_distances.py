"""The value DP's Dijkstra fixpoint equals the layered Bellman–Ford iteration, bit for bit.

``value_fields(..., method="auto")`` takes the three-Dijkstra fixpoint wherever ``H`` reaches it
(proofs/DP.md, DP.5) and the layers elsewhere; ``method="layers"`` is the hop-by-hop iteration.
Both must give the same arrays, steps, fixpoint flag, sentinel and arithmetic at every horizon,
on random instances (exact, float, directed, grids, both role labellings) and a larger maze.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from dppverify.game.instance import Instance, _read_game
from dppverify.twogoal.value_dp import structured_value, value_fields
from dppverify.twogoal.value_fixpoint import fixpoint_fields
from tests.dppverify._helpers import instance_documents

docs = instance_documents(max_nodes=9, max_weight=7, float_nodes=6, grid_size=5, grid_cells=20)


def _same_fields(inst: Instance, h: int | None, slot: int) -> None:
    roles = inst.roles(slot)
    a = value_fields(inst, h, roles, method="auto")
    b = value_fields(inst, h, roles, method="layers")
    for col in ("d1", "d2", "m"):
        x, y = getattr(a, col), getattr(b, col)
        assert x.dtype == y.dtype and np.array_equal(x, y), (col, h)
    assert (a.steps, a.fixpoint, a.sentinel, a.scale, a.arithmetic) == \
        (b.steps, b.fixpoint, b.sentinel, b.scale, b.arithmetic), h


@settings(deadline=None, max_examples=120)
@given(docs, st.booleans())
def test_dijkstra_fixpoint_equals_the_layers(doc: dict[str, Any], swap: bool) -> None:
    inst = _read_game(doc)
    slot = 1 - inst.primary_goal_index if swap and inst.tied else inst.primary_goal_index
    fx = fixpoint_fields(inst, inst.roles(slot))
    last = fx.last if fx is not None else 2 * inst.n_nodes
    for h in [*range(0, last + 3), None]:
        _same_fields(inst, h, slot)
    if fx is not None:  # the Dijkstra route is taken where H reaches the fixpoint
        assert value_fields(inst, None).steps == fx.last + 1


def test_a_maze_fixpoint_is_found_by_dijkstra_and_equals_the_layers() -> None:
    walls = {1: "@" * 14 + ".", 3: "." + "@" * 14}  # a serpentine: openings right, left, ...
    rows = ["." * 15 if r % 2 == 0 else walls[r % 4] for r in range(15)]
    cells = [(r, c) for r, row in enumerate(rows) for c, ch in enumerate(row) if ch == "."]
    idx = set(cells)
    edges = [{"source": list(a), "target": [a[0] + dr, a[1] + dc], "weight": "3/2"}
             for a in cells for dr, dc in ((0, 1), (1, 0)) if (a[0] + dr, a[1] + dc) in idx]
    doc = {"graph": {"nodes": [{"id": list(c)} for c in cells], "edges": edges},
           "start": [14, 0], "goals": [[0, 14], [0, 0]], "prior": ["2/3", "1/3"]}
    inst = _read_game(doc)
    fx = fixpoint_fields(inst)
    assert fx is not None and fx.last > 50  # a long serpentine: many layers
    for h in (fx.last - 1, fx.last, fx.last + 1, fx.last + 7, None):
        _same_fields(inst, h, inst.primary_goal_index)
    assert structured_value(inst, None).value == structured_value(inst, fx.last + 1).value


@settings(deadline=None, max_examples=80)
@given(docs)
def test_structured_value_is_the_layers_value_at_every_horizon(doc: dict[str, Any]) -> None:
    """``structured_value`` may take the fixpoint once the start's fields are final."""
    inst = _read_game(doc)
    fx = fixpoint_fields(inst)
    last = fx.last if fx is not None else 2 * inst.n_nodes
    s0 = inst.start
    for h in [*range(inst.hops[s0], last + 3), None]:
        got = structured_value(inst, h)
        f = value_fields(inst, h, method="layers")
        want = (f.number(f.d1[s0]), f.number(f.d2[s0]), f.number(f.m[s0]), f.steps, f.fixpoint,
                f.arithmetic)
        assert (got.d1, got.d2, got.m, got.steps, got.fixpoint, got.arithmetic) == want, h
        assert type(got.d1) is type(want[0]) and type(got.m) is type(want[2])
