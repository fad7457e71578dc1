"""Instance builders and brute-force references shared by the checker tests.

The references here are deliberately naive (enumerate every walk by depth-first search on a
plain dict adjacency) so that tests recompute results from the input rather than trusting
the checker's tree or backward induction.
"""

from __future__ import annotations

import itertools
import json
from collections.abc import Hashable, Iterator, Sequence
from fractions import Fraction
from pathlib import Path
from typing import Any

import click
from click.testing import CliRunner, Result
from hypothesis import strategies as st

from dppverify.strategies import grid_worlds, instances, weighted_graphs

DATA = Path(__file__).resolve().parents[1] / "data"

Edge = tuple[Any, Any, Any]


def make_doc(edges: Sequence[Edge], start: Any, goals: Sequence[Any], prior: Sequence[Any],
             *, directed: bool = False, nodes: Sequence[Any] | None = None) -> dict[str, Any]:
    """An instance document from ``(u, v, weight)`` triples."""
    ids: list[Any] = list(nodes) if nodes is not None else []
    for u, v, _ in edges:
        for x in (u, v):
            if x not in ids:
                ids.append(x)
    for x in (start, *goals):
        if x not in ids:
            ids.append(x)
    return {"graph": {"directed": directed, "multigraph": False, "graph": {},
                      "nodes": [{"id": x} for x in ids],
                      "edges": [{"source": u, "target": v, "weight": w} for u, v, w in edges]},
            "start": start, "goals": list(goals), "prior": [str(Fraction(p)) for p in prior]}


def triangle_doc(prior: tuple[str, str] = ("7/10", "3/10")) -> dict[str, Any]:
    """proofs/ERRATA.md E1 / formats.md: s–g2 (2), g2–g1 (2), s–g1 (3)."""
    return make_doc([("s", "g2", 2), ("g2", "g1", 2), ("s", "g1", 3)], "s", ["g1", "g2"], prior)


def grid_doc(rows: int, cols: int, start: tuple[int, int], goals: Sequence[tuple[int, int]],
             prior: Sequence[Any], blocked: Sequence[tuple[int, int]] = ()) -> dict[str, Any]:
    """A 4-connected unit grid; node ids are ``[row, col]`` lists."""
    free = [(r, c) for r in range(rows) for c in range(cols) if (r, c) not in set(blocked)]
    edges = []
    for r, c in free:
        for dr, dc in ((0, 1), (1, 0)):
            if (r + dr, c + dc) in free:
                edges.append(([r, c], [r + dr, c + dc], 1))
    return make_doc(edges, list(start), [list(g) for g in goals], prior,
                    nodes=[[r, c] for r, c in free])


def write_doc(tmp_path: Path, name: str, doc: Any) -> str:
    """Write ``doc`` (JSON-dumped unless it is already text) to ``tmp_path/name``; its path."""
    p = tmp_path / name
    p.write_text(doc if isinstance(doc, str) else json.dumps(doc))
    return str(p)


def run_cli(cmd: click.Command, args: list[str]) -> Result:
    """Invoke a checker command in-process; it must end by exit code, never by a traceback."""
    result = CliRunner().invoke(cmd, args)
    assert "Traceback" not in result.output
    assert result.exception is None or isinstance(result.exception, SystemExit), result.exception
    return result


def load_cases() -> list[dict[str, Any]]:
    """The conformance cases (tests/data/conformance_cases.json)."""
    cases: list[dict[str, Any]] = json.loads((DATA / "conformance_cases.json").read_text())
    return cases


def _key(x: Any) -> Hashable:
    return tuple(_key(y) for y in x) if isinstance(x, list) else x


def adjacency(doc: dict[str, Any]) -> dict[Hashable, list[tuple[Hashable, Fraction]]]:
    """Plain adjacency of an instance document (independent of dppverify's parser)."""
    g = doc["graph"]
    adj: dict[Hashable, list[tuple[Hashable, Fraction]]] = {_key(n["id"]): [] for n in g["nodes"]}
    for e in g.get("edges", g.get("links", [])):
        u, v, w = _key(e["source"]), _key(e["target"]), Fraction(str(e.get("weight", 1)))
        adj[u].append((v, w))
        if not g.get("directed", False) and u != v:
            adj[v].append((u, w))
    return adj


def all_walks(doc: dict[str, Any], horizon: int) -> Iterator[tuple[Hashable, ...]]:
    """Every walk from the start with at most ``horizon`` steps that ends at its first goal."""
    adj = adjacency(doc)
    goals = {_key(g) for g in doc["goals"]}
    start = _key(doc["start"])

    def dfs(walk: list[Hashable]) -> Iterator[tuple[Hashable, ...]]:
        if walk[-1] in goals:
            yield tuple(walk)
            return
        if len(walk) - 1 == horizon:
            return
        for v, _ in adj[walk[-1]]:
            walk.append(v)
            yield from dfs(walk)
            walk.pop()

    yield from dfs([start])


def distances_to(doc: dict[str, Any], target: Any) -> dict[Hashable, Fraction]:
    """Bellman-Ford distances to ``target`` (a second, slow, independent reference)."""
    adj = adjacency(doc)
    t = _key(target)
    dist: dict[Hashable, Fraction] = {t: Fraction(0)}
    for _ in range(len(adj)):
        changed = False
        for u, arcs in adj.items():
            for v, w in arcs:
                if v in dist and (u not in dist or dist[v] + w < dist[u]):
                    dist[u] = dist[v] + w
                    changed = True
        if not changed:
            break
    return dist


def profile_doc(primary: Sequence[tuple[Sequence[Any], Any]],
                secondary: Sequence[tuple[Sequence[Any], Any]], goals: tuple[Any, Any],
                defender: dict[str, Any] | None = None, **extra: Any) -> dict[str, Any]:
    """A ``dpp-profile/1`` document from ``(path, probability)`` pairs."""
    doc: dict[str, Any] = {
        "format": "dpp-profile/1",
        "goals": {"primary": goals[0], "secondary": goals[1]},
        "defender": defender or {"rule": "progress", "goal": goals[0]},
        "attacker": {
            "primary": [{"path": list(p), "probability": str(Fraction(q))} for p, q in primary],
            "secondary": [{"path": list(p), "probability": str(Fraction(q))}
                          for p, q in secondary],
        },
    }
    doc.update(extra)
    return doc


def three_phase_doc() -> dict[str, Any]:
    """The conformance case ``phases=I+II+III``: start 3, g1 = 2 (prior 2/3), g2 = 4.

    Hand computation (paper Sec. V): d(·, g1) = {2: 0, 5: 1/2, 0: 5/2, 1: 10/3, 3: 13/3,
    4: 7/2}; ξ² = 3 1 0 4 with σ* = 1, 5/18, 0 (t_I = 1, t_II = 2, T = 3);
    ξ^{1,I} = 3 1 2, ξ^{1,II} = 3 1 0 5 2, each with probability b2/b1 = 1/2;
    U¹ = 13/3, U² = 3·13/18 + 1 = 19/6, U = 71/18.
    """
    return make_doc([(0, 1, 3), (0, 2, 4), (0, 4, 1), (0, 5, 2), (1, 2, "10/3"), (1, 3, 1),
                     (2, 5, "1/2")], 3, [4, 2], ["1/3", "2/3"], nodes=[0, 1, 2, 3, 4, 5])


def three_phase_profile() -> dict[str, Any]:
    """The equilibrium of :func:`three_phase_doc`, written by hand from the construction."""
    return profile_doc([([3, 1, 2], "1/2"), ([3, 1, 0, 5, 2], "1/2")], [([3, 1, 0, 4], 1)],
                       (2, 4), phases={"t_I": 1, "t_II": 2, "T": 3},
                       prior={"primary": "2/3", "secondary": "1/3"},
                       value={"U1": "13/3", "U2": "19/6", "U": "71/18", "U_bar": "41/9",
                              "VoI": "11/82"})


def triangle_profile() -> dict[str, Any]:
    """formats.md's example profile (eq. (15): ξ^{1,II} = s g2 with b2/b1 = 3/7)."""
    return profile_doc([(["s", "g1"], "4/7"), (["s", "g2"], "3/7")], [(["s", "g2"], 1)],
                       ("g1", "g2"), phases={"t_I": 0, "t_II": 1, "T": 1},
                       prior={"primary": "7/10", "secondary": "3/10"},
                       value={"U1": "3", "U2": "1", "U": "12/5", "U_bar": "27/10",
                              "VoI": "1/9"})


def progress_costs(doc: dict[str, Any], walk: Sequence[Any], g1: Any, g2: Any
                   ) -> tuple[Fraction, Fraction]:
    """Both types' costs of ``walk`` against σ* (eq. (7)), by a naive re-implementation.

    Returns ``(U¹, U²)`` of the walk: ``Σ w σ*(g1) + d(end, g1)`` and
    ``Σ w (1 − σ*(g1)) + d(end, g2)``, distances by Bellman-Ford.
    """
    adj = adjacency(doc)
    d1, d2 = distances_to(doc, g1), distances_to(doc, g2)
    nodes = [_key(v) for v in walk]
    inf = Fraction(10**18)
    c = d1.get(nodes[0], inf)
    u1 = u2 = Fraction(0)
    for a, b in itertools.pairwise(nodes):
        w = dict(adj[a])[b]
        new = min(c, d1.get(b, inf))
        sigma = (c - new) / w
        u1 += w * sigma
        u2 += w * (1 - sigma)
        c = new
    return u1 + d1[nodes[-1]], u2 + d2[nodes[-1]]


def tree_horizon(instance: Any, profile: Any) -> int:
    """The profile's own length (at least the steps to the nearest goal): the horizon tests
    pass explicitly when they exercise the walk tree (issue 18: without a horizon ``certify``
    certifies the untruncated game, by the structured route)."""
    from dppverify.checks.suites import shortest_horizon
    from dppverify.game.inputs import as_instance, as_profile

    inst = as_instance(instance)
    return shortest_horizon(inst, as_profile(profile, inst))


def instance_documents(max_nodes: int, max_weight: int, float_nodes: int, grid_size: int,
                       grid_cells: int) -> st.SearchStrategy[dict[str, Any]]:
    """Two-goal instance documents of every kind the reader takes: fractional weights,
    directed graphs (not always strongly connected), float mode, grid worlds."""
    return st.one_of(
        instances(graphs=weighted_graphs(max_nodes=max_nodes, weights="fractions",
                                         max_weight=max_weight)),
        instances(graphs=weighted_graphs(max_nodes=max_nodes, directed=True,
                                         strongly_connected=False)),
        instances(graphs=weighted_graphs(max_nodes=float_nodes, weights="floats")).map(
            lambda d: {**d, "numbers": "float"}),
        grid_worlds(max_size=grid_size, max_cells=grid_cells),
    )

