"""Instance parsing and validation: exact numbers, node ids, one-line errors."""

from __future__ import annotations

import copy
import json
import random
from fractions import Fraction
from pathlib import Path
from typing import Any

import pytest

from dppverify.errors import CheckerError, InvalidInstanceError
from dppverify.exact import INF
from dppverify.game.instance import instance_from_json, load_instance
from tests.dppverify._helpers import distances_to, grid_doc, load_cases, make_doc, triangle_doc


def test_triangle_parses_exactly() -> None:
    inst = instance_from_json(triangle_doc())
    r = inst.roles()
    assert inst.nodes[r.g1] == "g1" and inst.nodes[r.g2] == "g2"
    assert (r.b1, r.b2) == (Fraction(7, 10), Fraction(3, 10))
    assert r.d1[inst.start] == 3 and r.d2[inst.start] == 2
    assert r.d1[r.g2] == 2 and r.d2[r.g1] == 2


def test_decimal_literals_are_exact_decimals_and_strings_are_rationals() -> None:
    text = json.dumps(make_doc([("s", "a", "3/2"), ("a", "g1", 1), ("s", "g2", 2)], "s",
                               ["g1", "g2"], ["1/2", "1/2"])).replace('"1/2"', "0.5")
    text = text.replace('"weight": 2', '"weight": 0.1')
    inst = instance_from_json(text)
    assert inst.prior == (Fraction(1, 2), Fraction(1, 2))
    assert inst.weight(inst.index["s"], inst.index["a"]) == Fraction(3, 2)
    assert inst.weight(inst.index["s"], inst.index["g2"]) == Fraction(1, 10)
    assert inst.exact


def test_float_mode_reads_binary_floats_and_keeps_priors_exact() -> None:
    doc = make_doc([("s", "g1", 1), ("s", "g2", 2)], "s", ["g1", "g2"], ["3/5", "2/5"])
    doc["graph"]["edges"][0]["weight"] = Fraction("1.4142135623730951")
    doc["numbers"] = "float"
    inst = instance_from_json(doc)
    w = inst.weight(inst.index["s"], inst.index["g1"])
    assert isinstance(w, float) and w == 2 ** 0.5
    assert not inst.exact and inst.prior == (Fraction(3, 5), Fraction(2, 5))


def test_grid_node_ids_become_tuples() -> None:
    inst = instance_from_json(grid_doc(2, 2, (0, 0), [(1, 1), (0, 1)], ["3/5", "2/5"]))
    assert inst.nodes[inst.start] == (0, 0)
    assert set(inst.nodes) == {(0, 0), (0, 1), (1, 0), (1, 1)}


def test_primary_goal_is_larger_prior_and_goals0_at_a_tie() -> None:
    doc = triangle_doc()
    doc["goals"], doc["prior"] = ["g2", "g1"], ["3/10", "7/10"]
    inst = instance_from_json(doc)
    assert inst.nodes[inst.roles().g1] == "g1" and not inst.tied
    tied = instance_from_json(triangle_doc(("1/2", "1/2")))
    assert tied.tied and tied.nodes[tied.roles().g1] == "g1"
    assert tied.nodes[tied.roles(1).g1] == "g2"


def _bad(mutate: Any) -> dict[str, Any]:
    doc = copy.deepcopy(triangle_doc())
    mutate(doc)
    return doc


BAD: list[tuple[str, Any, str]] = [
    ("unknown edge node", lambda d: d["graph"]["edges"].append(
        {"source": "s", "target": "zz"}), "unknown node \"zz\""),
    ("unknown start", lambda d: d.update(start="nope"), "start: unknown node"),
    ("unknown goal", lambda d: d.update(goals=["g1", "q"]), "goals[1]: unknown node"),
    ("equal goals", lambda d: d.update(goals=["g1", "g1"]), "must differ"),
    ("zero weight", lambda d: d["graph"]["edges"][0].update(weight=0), "must be positive"),
    ("negative weight", lambda d: d["graph"]["edges"][1].update(weight="-1/2"),
     "must be positive"),
    ("text weight", lambda d: d["graph"]["edges"][1].update(weight="heavy"), "not a number"),
    ("bool weight", lambda d: d["graph"]["edges"][1].update(weight=True), "expected a number"),
    ("prior one", lambda d: d.update(prior=["1", "0"]), "strictly between 0 and 1"),
    ("prior negative", lambda d: d.update(prior=["-1/2", "3/2"]), "strictly between"),
    ("prior sum", lambda d: d.update(prior=["1/2", "1/3"]), "must sum to exactly 1"),
    ("prior length", lambda d: d.update(prior=["1"]), "prior: must be a list of two"),
    ("missing key", lambda d: d.pop("start"), "missing key: start"),
    ("multigraph", lambda d: d["graph"].update(multigraph=True), "multigraph"),
    ("duplicate edge", lambda d: d["graph"]["edges"].append(
        {"source": "g2", "target": "s", "weight": 5}), "duplicate edge"),
    ("duplicate node", lambda d: d["graph"]["nodes"].append({"id": "s"}), "duplicate node"),
    ("nodes not list", lambda d: d["graph"].update(nodes={"s": 1}), "graph.nodes"),
    ("object node id", lambda d: d["graph"]["nodes"].append({"id": {"a": 1}}), "object"),
    ("numbers mode", lambda d: d.update(numbers="decimal"), "numbers:"),
    ("goal unreachable from start", lambda d: d["graph"].update(
        directed=True, edges=[{"source": "g2", "target": "g1"}, {"source": "g1", "target": "g2"},
                              {"source": "g1", "target": "s"}]), "unreachable from start"),
    ("d(g2, g1) infinite", lambda d: d["graph"].update(
        directed=True, edges=[{"source": "s", "target": "g1"}, {"source": "s", "target": "g2"},
                              {"source": "g1", "target": "g2"}]),
     "d(\"g2\", \"g1\") is infinite"),
]


@pytest.mark.parametrize(("name", "mutate", "needle"), BAD, ids=[b[0] for b in BAD])
def test_bad_instances_raise_one_line_errors(name: str, mutate: Any, needle: str) -> None:
    with pytest.raises(InvalidInstanceError) as info:
        instance_from_json(_bad(mutate))
    message = str(info.value)
    assert needle in message, message
    assert "\n" not in message


@pytest.mark.parametrize("text", ["{not json", "[1, 2]", "", "{\"graph\": NaN}", "null"])
def test_malformed_documents(text: str) -> None:
    with pytest.raises(InvalidInstanceError) as info:
        instance_from_json(text)
    assert "\n" not in str(info.value)


def test_load_instance_names_the_file(tmp_path: Path) -> None:
    p = tmp_path / "bad.json"
    p.write_text("{\"graph\": ")
    with pytest.raises(CheckerError, match=r"bad\.json: malformed JSON at line 1"):
        load_instance(p)
    p.write_bytes(b"\xff\xfe")
    with pytest.raises(InvalidInstanceError, match="cannot read"):
        load_instance(p)


@pytest.mark.parametrize("seed", range(12))
def test_distances_match_bellman_ford(seed: int) -> None:
    rng = random.Random(seed)
    n = rng.randint(3, 9)
    directed = rng.random() < 0.5
    edges = {}
    for _ in range(rng.randint(n, 3 * n)):
        u, v = rng.sample(range(n), 2)
        key = (u, v) if directed else (min(u, v), max(u, v))
        edges[key] = Fraction(rng.randint(1, 9), rng.randint(1, 3))
    # make it strongly connected with a cycle so that the instance is valid
    for i in range(n):
        key = (i, (i + 1) % n) if directed else (min(i, (i + 1) % n), max(i, (i + 1) % n))
        edges.setdefault(key, Fraction(5))
    doc = make_doc([(u, v, str(w)) for (u, v), w in edges.items()], 0, [n - 1, n - 2],
                   ["2/3", "1/3"], directed=directed, nodes=list(range(n)))
    inst = instance_from_json(doc)
    for slot, g in enumerate(inst.goals):
        ref = distances_to(doc, inst.nodes[g])
        got = {inst.nodes[v]: d for v, d in enumerate(inst.dist_to[slot])}
        assert {k: v for k, v in got.items() if v != INF} == ref


def test_conformance_instances_all_parse() -> None:
    for case in load_cases():
        inst = instance_from_json(case["instance"])
        d1 = Fraction(case["expected"]["d1"])
        r = inst.roles()
        assert d1 in {r.d1[inst.start], r.d2[inst.start]}
        if not inst.tied:
            assert r.d1[inst.start] == d1
