"""Small random instances and an independent eq. (17), Dragan's belief, for the experiment tests."""

from __future__ import annotations

import itertools
import random
from fractions import Fraction

import mpmath
import networkx as nx

from solver import Instance


def random_instance(seed: int, n: int = 7, p: float = 0.45) -> Instance:
    """A connected random graph with integer weights 1..3, start 0, goals n-1 and n-2, where
    each goal is reachable from the start without passing the other."""
    rng = random.Random(seed)
    while True:
        g = nx.gnp_random_graph(n, p, seed=rng.randrange(10**9))
        if not nx.is_connected(g):
            continue
        ok = all(nx.has_path(g.subgraph(set(g) - {other}), 0, goal)
                 for goal, other in ((n - 1, n - 2), (n - 2, n - 1)))
        if not ok:
            continue
        for u, v in g.edges:
            g.edges[u, v]["weight"] = rng.randint(1, 3)
        prior = rng.choice([("3/5", "2/5"), ("1/2", "1/2"), ("7/10", "3/10"), ("2/3", "1/3")])
        return Instance(g, 0, (n - 1, n - 2), prior)


def literal_belief(graph: nx.Graph, walk: list[object], goals: tuple[object, object],
                   prior: tuple[Fraction, Fraction], dps: int = 80) -> mpmath.mpf:
    """P(goals[0] | walk) by eq. (17) written out, C included: exp(-C - V_i(s_t)) /
    exp(-V_i(s_0)) * b_i / Z with V_i = networkx Dijkstra distance."""
    ctx = mpmath.MPContext()
    ctx.dps = dps
    cost = sum(graph.edges[u, v].get("weight", 1) for u, v in itertools.pairwise(walk))
    terms = []
    for goal, b in zip(goals, prior, strict=True):
        v_now = nx.shortest_path_length(graph, walk[-1], goal, weight="weight")
        v_start = nx.shortest_path_length(graph, walk[0], goal, weight="weight")
        terms.append(ctx.exp(-ctx.mpf(cost) - v_now) / ctx.exp(-ctx.mpf(v_start))
                     * ctx.mpf(b.numerator) / b.denominator)
    return terms[0] / (terms[0] + terms[1])
