"""The edge cases of proofs/README.md ("Edge cases") as predicates on instance documents (for
``hypothesis.find``).

Predicates that need the equilibrium use the solver (tests may import it); the brute-force
ones use the independent reference model of ``tests/properties/_reference.py``.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

from hypothesis import strategies as st

from dppverify.strategies import grid_worlds, instances, weighted_graphs
from solver import Equilibrium, instance_from_json
from solver.twogoal.equilibrium import paper_equilibrium
from tests.properties._reference import INF, Game, key

Doc = dict[str, Any]


@lru_cache(maxsize=4096)
def _solve_text(text: str) -> Equilibrium:
    return paper_equilibrium(instance_from_json(text))


def solved(doc: Doc) -> Equilibrium:
    """The solver's equilibrium of ``doc`` (cached by the document's JSON text)."""
    return _solve_text(json.dumps(doc, sort_keys=True))


def game(doc: Doc) -> Game:
    """The reference model of ``doc``."""
    return Game.from_doc(doc)


def _moving(doc: Doc) -> bool:
    g = game(doc)
    return not g.is_goal(g.start)


def start_is_g1(doc: Doc) -> bool:
    g = game(doc)
    return g.start == g.g1


def start_is_g2(doc: Doc) -> bool:
    g = game(doc)
    return g.start == g.g2


def start_next_to_goal(doc: Doc) -> bool:
    g = game(doc)
    return _moving(doc) and any(g.is_goal(v) for v, _ in g.succ[g.start])


def xi2_ends_at_g1(doc: Doc) -> bool:
    eq = solved(doc)
    return eq.phases.T > 0 and eq.secondary_path[-1] == eq.instance.primary


def _only_through(doc: Doc, target_is_g1: bool) -> bool:
    g = game(doc)
    if not _moving(doc):
        return False
    target, other = (g.g1, g.g2) if target_is_g1 else (g.g2, g.g1)
    seen, todo = {g.start}, [g.start]
    while todo:
        u = todo.pop()
        for v, _ in g.succ[u]:
            if v != other and v not in seen:
                seen.add(v)
                todo.append(v)
    return target not in seen


def g1_only_through_g2(doc: Doc) -> bool:
    return _only_through(doc, True)


def g2_only_through_g1(doc: Doc) -> bool:
    return _only_through(doc, False)


def t_ii_is_T_at_g2(doc: Doc) -> bool:
    eq = solved(doc)
    ph = eq.phases
    return ph.t_I < ph.t_II == ph.T and eq.secondary_path[-1] == eq.instance.secondary


def prior_half(doc: Doc) -> bool:
    eq = solved(doc)
    return (eq.instance.b1 == eq.instance.b2 and eq.phases.t_I < eq.phases.t_II
            and [p.label for p in eq.primary_paths] == ["xi1_II"])


def xi2_ties_with_different_phases(doc: Doc) -> bool:
    g = game(doc)
    if not _moving(doc):
        return False
    _, paths = g.best_secondary()
    return len({g.phases(p) for p in paths}) > 1


def _phase_ii_steps(doc: Doc) -> list[Any]:
    eq = solved(doc)
    return list(eq.schedule[eq.phases.t_I:eq.phases.t_II])


def phase_ii_has_one(doc: Doc) -> bool:
    return any(s == 1 for s in _phase_ii_steps(doc))


def phase_ii_has_zero(doc: Doc) -> bool:
    return any(s == 0 for s in _phase_ii_steps(doc))


def voi_zero(doc: Doc) -> bool:
    return _moving(doc) and solved(doc).VoI == 0


def all_three_phases(doc: Doc) -> bool:
    ph = solved(doc).phases
    return 0 < ph.t_I < ph.t_II < ph.T


def fractional_sigma_on_xi2(doc: Doc) -> bool:
    return any(0 < s < 1 for s in solved(doc).schedule)


def dead_end_reachable(doc: Doc) -> bool:
    """A node the start can reach from which no goal is reachable (proofs/README.md, edge cases:
    d(·,g1) = ∞; since d(g2,g1) is finite, a node that cannot reach g1 reaches no goal at all)."""
    g = game(doc)
    seen, todo = {g.start}, [g.start]
    while todo:
        u = todo.pop()
        if g.is_goal(u):
            continue
        for v, _ in g.succ[u]:
            if v not in seen:
                seen.add(v)
                todo.append(v)
    return any(g.d_to(v, g.g1) == INF for v in seen)


def asymmetric_goal_distances(doc: Doc) -> bool:
    g = game(doc)
    return g.d_to(g.g1, g.g2) != g.d_to(g.g2, g.g1)


def primary_is_second_goal(doc: Doc) -> bool:
    return key(doc["goals"][1]) == game(doc).g1


@dataclass(frozen=True)
class EdgeCase:
    """A named edge case, the strategy searched and the predicate that recognises it."""

    name: str
    strategy: st.SearchStrategy[Doc]
    predicate: Callable[[Doc], bool]


_small = instances(graphs=weighted_graphs(max_nodes=6))
_units = instances(graphs=weighted_graphs(max_nodes=7, weights="units"))
_loose = instances(graphs=weighted_graphs(max_nodes=6, directed=True, strongly_connected=False))
_weighted_grids = grid_worlds(min_size=3, max_size=5, max_density=0.3, weights="integers")

EDGE_CASES: tuple[EdgeCase, ...] = (
    EdgeCase("s0 = g1", _small, start_is_g1),
    EdgeCase("s0 = g2", _small, start_is_g2),
    EdgeCase("s0 adjacent to a goal", _small, start_next_to_goal),
    EdgeCase("xi2 ends at g1", _small, xi2_ends_at_g1),
    EdgeCase("g1 reachable only through g2", _small, g1_only_through_g2),
    EdgeCase("g2 reachable only through g1", _small, g2_only_through_g1),
    EdgeCase("t_II = T with xi2 ending at g2", _small, t_ii_is_T_at_g2),
    EdgeCase("b1 = b2 = 1/2, all weight on xi1_II", _small, prior_half),
    EdgeCase("ties in xi2 with different phases", _units, xi2_ties_with_different_phases),
    EdgeCase("phase II contains a sigma* = 1 step", _weighted_grids, phase_ii_has_one),
    EdgeCase("phase II contains a sigma* = 0 step", _weighted_grids, phase_ii_has_zero),
    EdgeCase("VoI* = 0", _small, voi_zero),
    EdgeCase("all three phases", _weighted_grids, all_three_phases),
    EdgeCase("fractional sigma* on xi2", _small, fractional_sigma_on_xi2),
    EdgeCase("a reachable dead end (d(v,g1) infinite)", _loose, dead_end_reachable),
    EdgeCase("d(g1,g2) != d(g2,g1)", _loose, asymmetric_goal_distances),
    EdgeCase("primary goal listed second", _small, primary_is_second_goal),
    EdgeCase("unit grid, g1 only through g2 (condition off)",
             grid_worlds(max_size=4, avoid_other_goal=False), g1_only_through_g2),
)
"""Each edge case with a strategy that reaches it within a few hundred examples."""

DEFAULT_STRATEGIES: dict[str, st.SearchStrategy[Doc]] = {
    "instances()": instances(),
    "grid_worlds()": grid_worlds(),
}
"""The default strategies (the slow test shows they reach the cases too)."""
