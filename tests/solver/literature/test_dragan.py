"""Dragan's observer (eq. (17)) and the exact σ' decision against independent computations."""

from __future__ import annotations

import random
from fractions import Fraction

import mpmath
import networkx as nx
import pytest

from solver.literature.dragan_belief import ln_at_least
from solver.literature.greedy_defender import DraganDefender
from solver.literature.strategy_pairs import PairEvaluator
from tests.solver.literature._graphs import literal_belief, random_instance


@pytest.mark.parametrize("seed", range(6))
def test_belief_matches_literal_eq17_along_random_walks(seed: int) -> None:
    inst = random_instance(seed)
    game = PairEvaluator.of(inst)
    net = inst.network
    rng = random.Random(seed)
    walk = [inst.start]
    for _ in range(6):  # a random walk, revisits allowed: C grows but must cancel
        walk.append(rng.choice(list(inst.graph.neighbors(walk[-1]))))
    ours = game.observer.beliefs([net.index_of(v) for v in walk])
    for t in range(len(walk)):
        ref = literal_belief(inst.graph, walk[: t + 1], (inst.primary, inst.secondary),
                             (inst.b1, inst.b2))
        assert abs(ours[t] - ref) < mpmath.mpf(10) ** -45


@pytest.mark.parametrize("seed", range(6))
def test_sigma_prime_is_greedy_on_the_literal_belief(seed: int) -> None:
    inst = random_instance(seed)
    game = PairEvaluator.of(inst)
    net = inst.network
    alt = DraganDefender(game.observer)
    for v in inst.graph.nodes:
        walk = nx.shortest_path(inst.graph, inst.start, v)
        ref = literal_belief(inst.graph, walk, (inst.primary, inst.secondary),
                             (inst.b1, inst.b2), dps=120)
        with mpmath.workdps(120):
            if inst.b1 == inst.b2 and abs(ref - mpmath.mpf(1) / 2) < mpmath.mpf(10) ** -100:
                expected = True  # belief exactly 1/2: σ' picks g1
            else:
                expected = ref >= mpmath.mpf(1) / 2
        assert alt.allocates_g1(net.index_of(v)) == expected


def _convergents(x: mpmath.mpf, n: int) -> list[Fraction]:
    out, a, h0, h1, k0, k1 = [], x, 0, 1, 1, 0
    for _ in range(n):
        q = int(mpmath.floor(a))
        h0, h1 = h1, q * h1 + h0
        k0, k1 = k1, q * k1 + k0
        out.append(Fraction(h1, k1))
        a = 1 / (a - q)
    return out


@pytest.mark.parametrize("ratio", [Fraction(3, 2), Fraction(7, 3), Fraction(2, 3),
                                   Fraction(1001, 1000)])
def test_ln_comparison_on_near_misses(ratio: Fraction) -> None:
    """Continued-fraction convergents of ln(ratio) approach it from both sides, up to
    ~1e-30 away: the exact decision must agree with a 200-digit evaluation."""
    with mpmath.workdps(200):
        ln = mpmath.log(mpmath.mpf(ratio.numerator) / ratio.denominator)
        for delta in _convergents(ln, 30):
            assert ln_at_least(ratio, delta) == (ln >= mpmath.mpf(delta.numerator)
                                                 / delta.denominator)


def test_ln_comparison_tie_and_errors() -> None:
    assert ln_at_least(Fraction(1), Fraction(0)) is True
    assert ln_at_least(Fraction(1), Fraction(1, 10**30)) is False
    with pytest.raises(ValueError):
        ln_at_least(Fraction(0), Fraction(1))
