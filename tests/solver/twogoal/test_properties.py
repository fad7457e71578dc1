"""Hypothesis properties of the constructive solver on random small graphs.

Everything is recomputed from the input graph with networkx and Fractions, independently of
the solver's own distances, schedule and evaluation:

- the closed-form ξ² (proofs/XI2.md) costs the secondary exactly the minimum over ALL simple paths
  that end at the first goal they reach (brute force);
- every primary path is a path of the graph from ``s0`` costing the primary exactly
  ``d(s0, g1)`` (Lemma 1's equality case);
- along ξ² the Bayes belief is ``b1`` / ``1/2`` / ``0`` in phases I / II / III (Lemma 5) and
  ``1`` on every primary step off ξ²: beliefs by Bayes' rule from both types' mixtures as the
  solver writes them (its profile document), phases from σ* recomputed along ξ² by eq. (7),
  and the solver's own reported beliefs (``Equilibrium.trajectories``) must agree.
"""

from __future__ import annotations

from collections.abc import Hashable, Iterator, Sequence
from fractions import Fraction
from itertools import pairwise

import networkx as nx
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from solver import Equilibrium, Instance
from solver.twogoal.equilibrium import paper_equilibrium

PRIORS = [Fraction(1, 2), Fraction(3, 5), Fraction(2, 3), Fraction(7, 10), Fraction(9, 10)]


@st.composite
def small_instances(draw: st.DrawFn, *, max_nodes: int = 7) -> Instance:
    """Random connected-ish graphs with integer weights 1..5, directed or not."""
    n = draw(st.integers(min_value=3, max_value=max_nodes))
    directed = draw(st.booleans())
    pairs = [(u, v) for u in range(n) for v in range(n) if u != v and (directed or u < v)]
    chosen = draw(st.lists(st.sampled_from(pairs), min_size=n - 1, max_size=3 * n, unique=True))
    g: nx.Graph = nx.DiGraph() if directed else nx.Graph()
    g.add_nodes_from(range(n))
    for u, v in chosen:
        g.add_edge(u, v, weight=draw(st.integers(min_value=1, max_value=5)))
    start, a, b = draw(st.permutations(list(range(n))))[:3]
    for x, y in ((start, a), (start, b), (a, b), (b, a)):
        assume(nx.has_path(g, x, y))
    b1 = draw(st.sampled_from(PRIORS))
    return Instance(g, start, (a, b), (b1, 1 - b1))


def _dist(g: nx.Graph, target: Hashable) -> dict[Hashable, Fraction]:
    rev = g.reverse(copy=False) if g.is_directed() else g
    return {v: Fraction(d) for v, d in nx.single_source_dijkstra_path_length(rev, target).items()}


def _sigma(g: nx.Graph, walk: Sequence[Hashable],
           to_g1: dict[Hashable, Fraction]) -> list[Fraction]:
    """σ*(g1) after each step, straight from eq. (7)."""
    c = to_g1[walk[0]]
    out = []
    for u, v in pairwise(walk):
        c_next = min(c, to_g1.get(v, c))
        out.append((c - c_next) / Fraction(g[u][v]["weight"]))
        c = c_next
    return out


def _cost(g: nx.Graph, walk: Sequence[Hashable], theta: int, to_g1: dict[Hashable, Fraction],
          to_g2: dict[Hashable, Fraction]) -> Fraction:
    """The cost of ``walk`` to type ``theta`` against σ* (U^θ, eq. (3))."""
    sig = _sigma(g, walk, to_g1)
    paid = sum((Fraction(g[u][v]["weight"]) * (s if theta == 1 else 1 - s)
                for (u, v), s in zip(pairwise(walk), sig, strict=True)), Fraction(0))
    return paid + (to_g1 if theta == 1 else to_g2)[walk[-1]]


def _goal_paths(g: nx.Graph, start: Hashable, goals: set[Hashable]) -> Iterator[list[Hashable]]:
    """Every simple path from ``start`` that ends at the first goal it reaches."""
    stack: list[list[Hashable]] = [[start]]
    while stack:
        path = stack.pop()
        if path[-1] in goals:
            yield path
            continue
        for nxt in g.successors(path[-1]) if g.is_directed() else g.neighbors(path[-1]):
            if nxt not in path:
                stack.append([*path, nxt])


def _solved(inst: Instance) -> tuple[Equilibrium, nx.Graph, Hashable, Hashable,
                                     dict[Hashable, Fraction], dict[Hashable, Fraction]]:
    """The equilibrium, the graph, g1, g2 and the brute-force distances to g1 and g2."""
    g, g1, g2 = inst.graph, inst.primary, inst.secondary
    return paper_equilibrium(inst), g, g1, g2, _dist(g, g1), _dist(g, g2)


COMMON = settings(max_examples=60, deadline=None, derandomize=True,
                  suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow])


@COMMON
@given(small_instances())
def test_xi2_cost_is_the_brute_force_minimum_over_simple_paths(inst: Instance) -> None:
    eq, g, g1, g2, to_g1, to_g2 = _solved(inst)
    best = min(_cost(g, p, 2, to_g1, to_g2) for p in _goal_paths(g, inst.start, {g1, g2}))
    assert _cost(g, eq.secondary_path, 2, to_g1, to_g2) == best
    assert eq.U2 == best


@COMMON
@given(small_instances())
def test_every_primary_path_costs_exactly_d_s0_g1(inst: Instance) -> None:
    eq, g, g1, g2, to_g1, to_g2 = _solved(inst)
    assert sum(p.probability for p in eq.primary_paths) == 1
    for path in eq.primary_paths:
        assert path.nodes[0] == inst.start and path.nodes[-1] in (g1, g2)
        assert all(g.has_edge(u, v) for u, v in pairwise(path.nodes))
        assert _cost(g, path.nodes, 1, to_g1, to_g2) == to_g1[inst.start]
    assert eq.U1 == to_g1[inst.start]


Mixture = list[tuple[tuple[Hashable, ...], Fraction]]


def _mixtures(eq: Equilibrium) -> tuple[Mixture, Mixture]:
    """Both types' mixed strategies as the solver writes them in its profile document."""
    profile = eq.to_json()

    def mixture(theta: str) -> Mixture:
        return [(tuple(e["path"]), Fraction(e["probability"]))
                for e in profile["attacker"][theta]]

    return mixture("primary"), mixture("secondary")


def _belief(primary: Mixture, secondary: Mixture, prefix: Sequence[Hashable],
            b1: Fraction) -> Fraction:
    """Bayes' rule (eq. (2)) from both types' mixtures, computed from scratch."""
    n = len(prefix)
    x1 = sum((p for nodes, p in primary if nodes[:n] == tuple(prefix)), Fraction(0))
    x2 = sum((p for nodes, p in secondary if nodes[:n] == tuple(prefix)), Fraction(0))
    return b1 * x1 / (b1 * x1 + (1 - b1) * x2)


def _phases(sigma: Sequence[Fraction]) -> tuple[int, int]:
    """``(t_I, t_II)`` from σ*(g1) along ξ² (Sec. V-B): phase I is the initial run of
    σ* = 1, ``t_II`` the last step with σ* > 0 (``t_I`` when there is none later)."""
    t_i = next((t for t, s in enumerate(sigma) if s != 1), len(sigma))
    return t_i, max([t_i, *(t for t, s in enumerate(sigma, start=1) if s > 0)])


@COMMON
@given(small_instances())
def test_beliefs_are_b1_half_zero_by_phase_and_one_off_xi2(inst: Instance) -> None:
    eq = paper_equilibrium(inst)
    g, b1 = inst.graph, Fraction(inst.b1)
    primary, secondary = _mixtures(eq)
    assert len(secondary) == 1 and secondary[0][1] == 1  # ξ² is a pure strategy
    xi2 = secondary[0][0]
    t_i, t_ii = _phases(_sigma(g, xi2, _dist(g, inst.primary)))  # eq. (7), not the solver's
    assert (eq.phases.t_I, eq.phases.t_II, eq.phases.T) == (t_i, t_ii, len(xi2) - 1)
    reported = {t.label: t.belief_g1 for t in eq.trajectories}
    for t in range(len(xi2)):
        expected = b1 if t <= t_i else Fraction(1, 2) if t <= t_ii else Fraction(0)
        assert _belief(primary, secondary, xi2[: t + 1], b1) == expected, t
        assert reported["xi2"][t] == expected, t
    for (nodes, p), path in zip(primary, eq.primary_paths, strict=True):
        assert p > 0
        for t in range(1, len(nodes)):
            if nodes[: t + 1] != xi2[: t + 1]:
                assert _belief(primary, secondary, nodes[: t + 1], b1) == 1
                assert reported[path.label][t] == 1


def test_the_generator_reaches_all_three_phases_and_ties() -> None:
    """The properties above are only as good as the instances: make sure the hard ones occur."""
    from hypothesis import Phase, find

    quick = settings(max_examples=2000, database=None, phases=[Phase.generate])

    def three_phases(inst: Instance) -> bool:
        ph = paper_equilibrium(inst).phases
        return 0 < ph.t_I < ph.t_II < ph.T

    find(small_instances(), three_phases, settings=quick)
    find(small_instances(),
         lambda i: i.b1 == Fraction(1, 2) and paper_equilibrium(i).phases.t_II == 0,
         settings=quick)
