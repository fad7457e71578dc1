"""Instances: validation with one-line errors, the primary-goal rule, JSON round trips."""

from __future__ import annotations

import json
from fractions import Fraction as F
from pathlib import Path
from typing import Any

import networkx as nx
import numpy as np
import pytest

from solver import (
    Instance,
    InstanceFormatError,
    InvalidInstanceError,
    instance_from_json,
    instance_to_json,
    load_instance,
)


def _doc(**over: Any) -> dict[str, Any]:
    doc: dict[str, Any] = {
        "graph": {"directed": False, "nodes": [{"id": "s"}, {"id": "a"}, {"id": "b"}],
                  "edges": [{"source": "s", "target": "a", "weight": 1},
                            {"source": "s", "target": "b", "weight": "3/2"}]},
        "start": "s", "goals": ["a", "b"], "prior": ["3/5", "2/5"]}
    doc.update(over)
    return doc


@pytest.mark.parametrize("change,message", [
    ({"start": "zz"}, "start node 'zz' not found in graph"),
    ({"goals": ["a", "zz"]}, "goal node 'zz' not found in graph"),
    ({"goals": ["a", "a"]}, "the two goals must differ, both are 'a'"),
    ({"goals": ["a"]}, "'goals' must be a list of two node ids"),
    ({"prior": ["1", "0"]}, r"prior\[0\] must lie in \(0, 1\), got 1"),
    ({"prior": ["3/5", "3/5"]}, "prior must sum to 1, got 3/5 \\+ 3/5 = 6/5"),
    ({"prior": [0.6, "x"]}, r"prior\[1\]: 'x' is not a number"),
    ({"prior": [True, 0.5]}, r"prior\[0\]: expected a number, got True"),
])
def test_bad_instances_are_named_in_one_line(change: dict[str, Any], message: str) -> None:
    with pytest.raises(InvalidInstanceError, match=message) as info:
        instance_from_json(_doc(**change))
    assert "\n" not in str(info.value)


@pytest.mark.parametrize("weight,message", [
    (0, "weight of edge \\('s', 'a'\\) must be positive, got 0"),
    (-2, "must be positive, got -2"),
    ("abc", "weight of edge \\('s', 'a'\\): 'abc' is not a number"),
    ([1], "expected a number, got \\[1\\]"),
])
def test_bad_weights(weight: Any, message: str) -> None:
    doc = _doc()
    doc["graph"]["edges"][0]["weight"] = weight
    with pytest.raises(InvalidInstanceError, match=message):
        instance_from_json(doc)


def test_malformed_documents() -> None:
    with pytest.raises(InstanceFormatError, match="missing key: prior"):
        instance_from_json({k: v for k, v in _doc().items() if k != "prior"})
    with pytest.raises(InstanceFormatError, match="line 1 column"):
        instance_from_json('{"graph": ')
    with pytest.raises(InvalidInstanceError, match="unknown node 'q'"):
        instance_from_json(_doc(graph={"nodes": [{"id": "s"}, {"id": "a"}, {"id": "b"}],
                                       "edges": [{"source": "s", "target": "q"}]}))
    with pytest.raises(InvalidInstanceError, match="multigraphs are not supported"):
        instance_from_json(_doc(graph={"multigraph": True, "nodes": [], "edges": []}))
    with pytest.raises(InvalidInstanceError, match="duplicate edge"):
        instance_from_json(_doc(graph={"nodes": [{"id": "s"}, {"id": "a"}, {"id": "b"}],
                                       "edges": [{"source": "s", "target": "a"},
                                                 {"source": "a", "target": "s"}]}))


def test_file_errors_name_the_file(tmp_path: Path) -> None:
    bad = tmp_path / "bad.json"
    bad.write_text('{"graph": [1, 2,')
    with pytest.raises(InstanceFormatError, match=r"bad\.json: malformed JSON at line 1"):
        load_instance(bad)
    with pytest.raises(InstanceFormatError, match="cannot read file"):
        load_instance(tmp_path / "missing.json")
    wrong = tmp_path / "wrong.json"
    wrong.write_text(json.dumps(_doc(start="zz")))
    with pytest.raises(InvalidInstanceError, match=r"wrong\.json: start node 'zz'"):
        load_instance(wrong)


def test_numbers_are_read_exactly() -> None:
    doc = _doc(prior=[0.6, 0.4])
    doc["graph"]["edges"][0]["weight"] = 0.1
    inst = instance_from_json(json.dumps(doc))
    assert inst.prior == (F(3, 5), F(2, 5))
    numbers = inst.network.numbers
    assert numbers.exact and numbers.convert(inst.network.arc_weight(0, 1)) == F(1, 10)


def test_primary_goal_is_the_larger_prior_and_the_first_listed_at_a_tie() -> None:
    assert instance_from_json(_doc(prior=["2/5", "3/5"])).primary == "b"
    assert instance_from_json(_doc(prior=["1/2", "1/2"])).primary == "a"
    assert instance_from_json(_doc(goals=["b", "a"], prior=["1/2", "1/2"])).primary == "b"


@pytest.mark.parametrize("directed", [False, True])
def test_json_round_trip_is_exact(directed: bool) -> None:
    g = nx.DiGraph() if directed else nx.Graph()
    g.add_weighted_edges_from([((0, 1), "x", F(1, 3)), ("x", 7, F(22, 7)), (7, (0, 1), 2)])
    inst = Instance(g, (0, 1), ("x", 7), (F(1, 3), F(2, 3)))
    doc = instance_to_json(inst)
    again = instance_from_json(json.loads(json.dumps(doc)))
    assert instance_to_json(again) == doc
    assert again.start == (0, 1) and again.goals == ("x", 7)


def test_grid_round_trip_and_float_octile_round_trip() -> None:
    blocked = np.zeros((3, 4), dtype=bool)
    blocked[1, 1:3] = True
    for conn in (4, 8):
        inst = Instance.from_grid(blocked, (0, 0), ((2, 3), (2, 0)), ("1/2", "1/2"),
                                  connectivity=conn)
        doc = json.loads(json.dumps(instance_to_json(inst)))
        again = instance_from_json(doc)
        assert again.network.numbers.exact == (conn == 4)
        assert again.network.n_arcs == inst.network.n_arcs
        assert instance_to_json(again) == doc


def test_grid_cells() -> None:
    blocked = np.zeros((2, 2), dtype=bool)
    blocked[0, 1] = True
    with pytest.raises(InvalidInstanceError,
                       match=r"goal cell \(0, 1\) is an obstacle in the 2x2 grid"):
        Instance.from_grid(blocked, (0, 0), ((0, 1), (1, 1)), ("1/2", "1/2"))
    with pytest.raises(InvalidInstanceError,
                       match=r"start cell \(5, 5\) is outside the 2x2 grid \(rows 0-1, col"):
        Instance.from_grid(blocked, (5, 5), ((1, 0), (1, 1)), ("1/2", "1/2"))
    with pytest.raises(InvalidInstanceError, match="non-empty 2-D array"):
        Instance.from_grid(np.zeros(3, dtype=bool), (0, 0), ((1, 0), (1, 1)), ("1/2", "1/2"))
