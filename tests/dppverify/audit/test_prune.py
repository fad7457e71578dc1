"""The audit's pruning pass: the written failure needs every node and edge it keeps."""

from __future__ import annotations

import json
from typing import Any

from dppverify.audit import examine, prune_failure
from dppverify.errors import CheckerError
from dppverify.game.instance import instance_from_json
from tests.mutants.solvers import mutant_drop_phase_ii

# What hypothesis' shrinking alone left for mutant_drop_phase_ii (seed 0): five nodes (2, 4..7)
# hang off the goal 0 and play no part in the failure.
SHRUNK: dict[str, Any] = {
    "graph": {"directed": True, "multigraph": False, "graph": {},
              "nodes": [{"id": i} for i in range(8)],
              "edges": [{"source": 0, "target": 1, "weight": 1},
                        {"source": 1, "target": 0, "weight": 2},
                        {"source": 1, "target": 3, "weight": 2},
                        {"source": 3, "target": 0, "weight": 1},
                        *({"source": a, "target": b, "weight": 1}
                          for i in (2, 4, 5, 6, 7) for a, b in ((0, i), (i, 0)))]},
    "start": 1, "goals": [0, 3], "prior": ["1/2", "1/2"]}


def _still_fails(doc: dict[str, Any], check: str) -> bool:
    try:
        instance_from_json(doc)
    except CheckerError:
        return False
    return examine(mutant_drop_phase_ii, doc).check == check


def test_pruning_keeps_the_failure_and_is_one_minimal() -> None:
    before = examine(mutant_drop_phase_ii, SHRUNK)
    assert not before.passed
    pruned, calls = prune_failure(mutant_drop_phase_ii, before)
    assert pruned.check == before.check and calls > 0
    graph = pruned.instance["graph"]
    assert len(graph["nodes"]) < len(SHRUNK["graph"]["nodes"])
    keep = {json.dumps(pruned.instance["start"]), *map(json.dumps, pruned.instance["goals"])}
    for node in graph["nodes"]:  # no further node can go ...
        key = json.dumps(node["id"])
        if key in keep:
            continue
        smaller = {"nodes": [n for n in graph["nodes"] if n is not node],
                   "edges": [e for e in graph["edges"]
                             if key not in (json.dumps(e["source"]), json.dumps(e["target"]))]}
        assert not _still_fails({**pruned.instance, "graph": {**graph, **smaller}}, pruned.check)
    for edge in graph["edges"]:  # ... and no further edge
        smaller = {"edges": [e for e in graph["edges"] if e is not edge]}
        assert not _still_fails({**pruned.instance, "graph": {**graph, **smaller}}, pruned.check)


def test_the_pruned_failure_replays() -> None:
    before = examine(mutant_drop_phase_ii, SHRUNK)
    pruned, _ = prune_failure(mutant_drop_phase_ii, before)
    assert examine(mutant_drop_phase_ii, pruned.instance).check == before.check
