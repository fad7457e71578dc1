"""The pair evaluation recomputed by hand; theorems it must respect; the bundled map."""

from __future__ import annotations

import filecmp
import itertools
from fractions import Fraction
from pathlib import Path

import networkx as nx
import numpy as np
import pytest
from scipy import ndimage

from solver import Instance
from solver.experiments.compare import paper10_instance, paper10_path
from solver.literature.strategy_pairs import PAIRS, PairEvaluator
from solver.twogoal.equilibrium import paper_equilibrium
from tests.solver.literature._graphs import random_instance

ROOT = Path(__file__).resolve().parents[3]


def _cost_by_hand(inst: Instance, path: list[object], theta: int,
                  sigma_g1: list[Fraction]) -> Fraction:
    """Σ w(e_t) σ_t(g^θ) + d(s_T, g^θ) with networkx distances."""
    goal = inst.primary if theta == 1 else inst.secondary
    total = Fraction(0)
    for (u, v), s in zip(itertools.pairwise(path), sigma_g1, strict=True):
        w = Fraction(inst.graph.edges[u, v].get("weight", 1))
        total += w * (s if theta == 1 else 1 - s)
    return total + Fraction(nx.shortest_path_length(inst.graph, path[-1], goal, weight="weight"))


def _sigma_star_by_hand(inst: Instance, path: list[object]) -> list[Fraction]:
    d1 = nx.shortest_path_length(inst.graph, target=inst.primary, weight="weight")
    c = [Fraction(min(d1[v] for v in path[: t + 1])) for t in range(len(path))]
    return [(c[t - 1] - c[t]) / Fraction(inst.graph.edges[path[t - 1], path[t]].get("weight", 1))
            for t in range(1, len(path))]


@pytest.mark.parametrize("seed", range(8))
def test_pairs_match_a_hand_evaluation(seed: int) -> None:
    inst = random_instance(seed)
    game = PairEvaluator.of(inst)
    net = inst.network
    d1 = nx.shortest_path_length(inst.graph, inst.start, inst.primary, weight="weight")
    d2 = nx.shortest_path_length(inst.graph, inst.start, inst.secondary, weight="weight")
    u_bar = inst.b1 * d1 + inst.b2 * d2
    for defender, attacker in PAIRS:
        att = game.attacker(attacker)
        u = []
        for theta, mix in ((1, att.primary), (2, att.secondary)):
            total = Fraction(0)
            for mp in mix:
                path = [net.labels[v] for v in mp.walk]
                if defender == "sigma*":
                    sig = _sigma_star_by_hand(inst, path)
                else:
                    sig = [Fraction(int(game.observer.favours_g1(v))) for v in mp.walk[1:]]
                total += mp.probability * _cost_by_hand(inst, path, theta, sig)
            u.append(total)
        r = game.pair(defender, attacker)
        assert (r.U1, r.U2) == (u[0], u[1])
        assert r.U == inst.b1 * u[0] + inst.b2 * u[1]
        assert r.VoI == (u_bar - r.U) / u_bar
        assert all(isinstance(x, Fraction) for x in (r.U1, r.U2, r.U, r.VoI))


@pytest.mark.parametrize("seed", range(8))
def test_equilibrium_pair_and_best_response(seed: int) -> None:
    """(σ*, γ*) reproduces paper_equilibrium(); no baseline Attacker does better against σ*, and the
    primary type pays d(s0, g1) on every path that ends at g1 (Lemma 1)."""
    inst = random_instance(seed)
    game = PairEvaluator.of(inst)
    eq = paper_equilibrium(inst)
    r = game.pair("sigma*", "gamma*")
    assert (r.U1, r.U2, r.U, r.VoI) == (eq.U1, eq.U2, eq.U, eq.VoI)
    d1 = nx.shortest_path_length(inst.graph, inst.start, inst.primary, weight="weight")
    for attacker in ("ambiguity", "exaggeration"):
        other = game.pair("sigma*", attacker)
        assert other.U >= r.U and other.VoI <= r.VoI
        assert other.U1 == d1


def test_obstacle_free_grid_sigma_prime_equals_sigma_star() -> None:
    inst = Instance.from_grid(np.zeros((8, 8), bool), (7, 0), ((0, 7), (0, 0)), ("3/5", "2/5"))
    game = PairEvaluator.of(inst)
    att = game.attacker("gamma*")
    for mp in (*att.primary, *att.secondary):
        assert game.defender("sigma*")(mp.walk) == game.defender("sigma'")(mp.walk)
    assert game.pair("sigma'", "gamma*").VoI == game.pair("sigma*", "gamma*").VoI


def test_paper10_map_bundled_and_valid() -> None:
    assert filecmp.cmp(paper10_path(), ROOT / "examples" / "paper10.map", shallow=False)  # the link
    inst = paper10_instance()
    blocked = inst.network.labels.blocked  # type: ignore[attr-defined]
    for goal, other in (((0, 9), (0, 0)), ((0, 0), (0, 9))):
        free = ~blocked
        free[other] = False
        lab, _ = ndimage.label(free)
        assert lab[9, 0] == lab[goal] != 0
    ph = paper_equilibrium(inst).phases
    assert 0 < ph.t_I < ph.t_II < ph.T  # all three phases, like the paper's Fig. 7
    assert [(r.defender, r.attacker)
            for r in PairEvaluator.of(inst).compare(PAIRS)] == list(PAIRS)
