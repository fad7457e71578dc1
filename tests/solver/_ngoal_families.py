"""Random N-goal instance families for the solver's tests and the refusal campaign.

Three families, each a seeded generator of instance documents (``docs/formats.md`` §1) with
N = 2..5 goals and exact weights:

- ``digraph``: a random (di)graph of 6–14 nodes, weights 1–3 or 1/2, goals in one strongly
  connected part (a cycle through them is added when needed);
- ``grid``: a 3×3 to 6×6 grid with random obstacles, unit weights, goals and start in the
  start's region;
- ``hub``: the hub gadgets of ``proofs/NGOAL.md`` (``u -> u1 -> m_j -> 2 or 3 goals``, return
  arcs of weight 10), where the 0/1 normals do not suffice; with ``dag=True`` the return arcs
  are left out (a finite game: every walk has at most four steps).

``GADGET`` is the N = 4 counterexample of NGOAL (coalition DP 25/14, value 12/7).
"""

from __future__ import annotations

import random
from fractions import Fraction
from typing import Any

import networkx as nx

from dppverify.game.examples import hub_document

Doc = dict[str, Any]

GADGET: Doc = {
    "graph": {"directed": True,
              "nodes": [{"id": x} for x in ("u", "u1", "A", "B", "C", "g1", "g2", "g3", "g4")],
              "edges": [{"source": a, "target": b, "weight": w} for a, b, w in (
                  ("u", "u1", 1), ("u1", "A", 1), ("u1", "B", 1), ("u1", "C", 1),
                  ("A", "g1", 1), ("A", "g2", 1), ("B", "g1", 1), ("B", "g3", 1),
                  ("C", "g2", 1), ("C", "g3", 1), ("C", "g4", 1), ("g1", "u", 10),
                  ("g2", "u", 10), ("g3", "u", 10), ("g4", "u", 10))]},
    "start": "u", "goals": ["g1", "g2", "g3", "g4"], "prior": ["2/7", "2/7", "2/7", "1/7"]}


def _prior(rng: random.Random, n: int) -> list[str]:
    ws = [rng.randint(1, 6) for _ in range(n)]
    return [str(Fraction(w, sum(ws))) for w in ws]


def hub(rng: random.Random, n_goals: int, *, dag: bool = False) -> Doc:
    """A random hub gadget (:func:`dppverify.game.examples.hub_document`); ``dag``: no return
    arcs, the goals joined by a cycle of weight-3 arcs instead (terminal costs stay finite)."""
    doc = hub_document(rng, n_goals, directed=True if dag else None, returns=not dag)
    if dag:
        goals = doc["goals"]
        doc["graph"]["edges"] += [{"source": g, "target": g2, "weight": 3}
                                  for g, g2 in zip(goals, goals[1:] + goals[:1], strict=True)]
    return doc


def digraph(rng: random.Random, n_goals: int) -> Doc:
    """A random (di)graph with the goals in one strongly connected part."""
    while True:
        n = rng.randint(max(6, n_goals + 1), 14)
        directed = rng.random() < 0.6
        g = nx.gnm_random_graph(n, rng.randint(n, 3 * n), seed=rng.randint(0, 10 ** 6),
                                directed=directed)
        weights = {e: rng.choice(["1", "1", "2", "3", "1/2"]) for e in g.edges}
        comps = (nx.strongly_connected_components(g) if directed
                 else nx.connected_components(g))
        part: set[int] = max(comps, key=lambda c: len(c))
        if len(part) < n_goals:
            continue
        goals = rng.sample(sorted(part), n_goals)
        reach = set().union(*(nx.ancestors(g, x) for x in goals)) - set(goals)
        if not reach:
            continue
        start = rng.choice(sorted(reach))
        return {"graph": {"directed": directed, "nodes": [{"id": i} for i in range(n)],
                          "edges": [{"source": a, "target": b, "weight": weights[(a, b)]}
                                    for a, b in g.edges]},
                "start": start, "goals": goals, "prior": _prior(rng, n_goals)}


def grid(rng: random.Random, n_goals: int) -> Doc:
    """A small grid with random obstacles (4-connected, unit weights)."""
    while True:
        h, w = rng.randint(3, 6), rng.randint(3, 6)
        g = nx.grid_2d_graph(h, w)
        for cell in list(g.nodes):
            if rng.random() < 0.2:
                g.remove_node(cell)
        if g.number_of_nodes() < n_goals + 1:
            continue
        comps: list[set[tuple[int, int]]] = list(nx.connected_components(g))
        sizes = [len(c) for c in comps]
        cells = sorted(comps[sizes.index(max(sizes))])
        if len(cells) < n_goals + 1:
            continue
        cells = rng.sample(cells, n_goals + 1)
        ids = {c: f"{c[0]},{c[1]}" for c in g.nodes}
        return {"graph": {"directed": False, "nodes": [{"id": ids[c]} for c in g.nodes],
                          "edges": [{"source": ids[a], "target": ids[b], "weight": 1}
                                    for a, b in g.edges]},
                "start": ids[cells[0]], "goals": [ids[c] for c in cells[1:]],
                "prior": _prior(rng, n_goals)}


FAMILIES = {"digraph": digraph, "grid": grid, "hub": hub}


def draw(family: str, seed: int, n_goals: int) -> Doc:
    """The instance of ``family`` with this seed and ``N``.

    Examples
    --------
    >>> draw("hub", 0, 4)["start"]
    'u'
    """
    return FAMILIES[family](random.Random(f"{family}-{seed}-{n_goals}"), n_goals)
