"""Shrinking a failure under a budget: the greedy pruning pass.

Hypothesis shrinks the *draws*; :func:`prune_failure` then deletes nodes and edges the
failure does not need. Both spend solver calls, and a slow solver makes every call count,
so both draw on one :class:`~dppverify.audit.config.ShrinkBudget` (solver calls and seconds).
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from fractions import Fraction
from typing import Any

from dppverify.audit.config import DEFAULT_CONFIG, AuditConfig, ShrinkBudget
from dppverify.audit.examine import Outcome, examine
from dppverify.audit.runner import SolverRunner
from dppverify.errors import CheckerError, TreeTooLargeError
from dppverify.game.instance import instance_from_json

Doc = dict[str, Any]


def simpler_graphs(graph: Doc) -> list[Doc]:
    """The graphs one simplification away, towards small undirected unit-weight graphs
    (docs/audit.md): undirected (if directed; of two opposite arcs the lighter is kept), every
    weight 1, then one edge's weight rounded up to an integer, or set to 1.

    Examples
    --------
    >>> g = {"directed": True, "nodes": [{"id": 0}, {"id": 1}],
    ...      "edges": [{"source": 0, "target": 1, "weight": "3/2"}]}
    >>> [(s["directed"], [e["weight"] for e in s["edges"]]) for s in simpler_graphs(g)]
    [(False, ['3/2']), (True, [1]), (True, [2]), (True, [1])]
    """
    out: list[Doc] = []
    edges = graph["edges"]
    if graph.get("directed"):
        lightest: dict[frozenset[str], dict[str, Any]] = {}
        for e in edges:
            key = frozenset((json.dumps(e["source"]), json.dumps(e["target"])))
            if key not in lightest or (Fraction(str(e.get("weight", 1)))
                                       < Fraction(str(lightest[key].get("weight", 1)))):
                lightest[key] = e
        out.append({**graph, "directed": False, "edges": list(lightest.values())})
    if any(e.get("weight", 1) != 1 for e in edges):
        out.append({**graph, "edges": [{**e, "weight": 1} for e in edges]})
    for k, e in enumerate(edges):
        w = Fraction(str(e.get("weight", 1)))
        for simpler in sorted({math.ceil(w), 1} - {w}, reverse=True):
            out.append({**graph, "edges": [*edges[:k], {**e, "weight": simpler}, *edges[k + 1:]]})
    return out


def _smaller_graphs(graph: Doc, keep: set[str]) -> list[Doc]:
    """The graphs one deletion or simplification away: without one node not in ``keep`` (and
    its edges), without one edge, then :func:`simpler_graphs`."""
    candidates = []
    for node in graph["nodes"]:
        key = json.dumps(node["id"])
        if key in keep:
            continue
        edges = [e for e in graph["edges"]
                 if key not in (json.dumps(e["source"]), json.dumps(e["target"]))]
        nodes = [n for n in graph["nodes"] if n is not node]
        candidates.append({**graph, "nodes": nodes, "edges": edges})
    for edge in graph["edges"]:
        candidates.append({**graph, "edges": [e for e in graph["edges"] if e is not edge]})
    return candidates + simpler_graphs(graph)


def prune_failure(solver: SolverRunner | Callable[[Doc], Any], outcome: Outcome,
                  config: AuditConfig = DEFAULT_CONFIG, *, budget: ShrinkBudget | None = None,
                  on_improve: Callable[[Outcome], None] | None = None) -> tuple[Outcome, int]:
    """Delete nodes and edges from a failing instance while it still fails the same way (the
    same :attr:`~dppverify.audit.examine.Outcome.identity`: check id, or exception type and
    place).

    Hypothesis shrinks the *draws*, which often leaves nodes the failure does not need (the
    node count is drawn first). This greedy pass removes, one at a time, every node other
    than the start and the goals (with its edges), then every edge, then tries the simpler
    graphs of :func:`simpler_graphs` (undirected, integer and unit weights), keeping a change
    when the instance stays valid and the solver's answer still fails the same check; it
    repeats until nothing changes or the budget is spent.

    Parameters
    ----------
    solver : SolverRunner or callable
        The solver under test.
    outcome : Outcome
        The failure to shrink.
    config : AuditConfig
        How each smaller instance is examined, and the default budget.
    budget : ShrinkBudget, optional
        The budget to draw on (started); default a fresh one of ``config``.
    on_improve : callable, optional
        Called with every smaller failure.

    Returns
    -------
    (Outcome, int)
        The smallest failure found and the solver calls spent.

    Examples
    --------
    >>> def stay_put(doc):           # a wrong solver: the Attacker never moves
    ...     s = doc["start"]
    ...     return {"format": "dpp-profile/1",
    ...             "attacker": {"primary": [{"path": [s], "probability": "1"}],
    ...                          "secondary": [{"path": [s], "probability": "1"}]}}
    >>> doc = {"graph": {"nodes": [{"id": i} for i in range(4)],
    ...        "edges": [{"source": 0, "target": i} for i in (1, 2, 3)]},
    ...        "start": 0, "goals": [1, 2], "prior": ["1/2", "1/2"]}
    >>> pruned, calls = prune_failure(stay_put, examine(stay_put, doc))
    >>> [n["id"] for n in pruned.instance["graph"]["nodes"]], pruned.check
    ([0, 1, 2], 'profile.wellformed')
    """
    budget = budget if budget is not None else config.budget().start()
    calls = 0
    best = outcome
    keep = {json.dumps(best.instance["start"]), *(json.dumps(g) for g in best.instance["goals"])}

    def attempt(doc: Doc) -> Outcome | None:
        nonlocal calls
        try:
            instance_from_json(doc)
        except CheckerError:  # e.g. a goal became unreachable
            return None
        if not budget.spend():
            return None
        calls += 1
        try:
            result = examine(solver, doc, config)
        except TreeTooLargeError:
            return None
        return result if result.identity == best.identity else None

    changed = True
    while changed and not budget.exhausted:
        changed = False
        for smaller_graph in _smaller_graphs(best.instance["graph"], keep):
            smaller = attempt({**best.instance, "graph": smaller_graph})
            if smaller is not None:
                best, changed = smaller, True
                if on_improve is not None:
                    on_improve(best)
                break
            if budget.exhausted:  # attempt() spent from it (mypy keeps the loop's narrowing)
                break  # type: ignore[unreachable]
    return best, calls
