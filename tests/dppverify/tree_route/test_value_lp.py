"""V_H: the compact LP (proofs/LP.md) against the conformance data and an independent normal
form."""

from __future__ import annotations

import itertools
from fractions import Fraction
from typing import Any

import numpy as np
import pytest
from scipy.optimize import linprog

from dppverify import TreeTooLargeError, game_value
from dppverify.game.instance import instance_from_json
from dppverify.tree_route.lp import lp_agrees
from dppverify.tree_route.tree import build_tree
from dppverify.tree_route.value_lp import exact_bracket, solve_value_lp
from tests.dppverify._helpers import (
    adjacency,
    all_walks,
    distances_to,
    grid_doc,
    load_cases,
    three_phase_doc,
    triangle_doc,
)

CASES = load_cases()


@pytest.mark.parametrize("case", CASES, ids=[f"{i}-{c['name']}" for i, c in enumerate(CASES)])
def test_conformance_value_at_horizon(case: dict[str, Any]) -> None:
    """Every conformance case: LP within tolerance of V_H, and V_H = U* exactly."""
    inst = instance_from_json(case["instance"])
    exp = case["expected"]
    v = game_value(inst, exp["H"])
    assert lp_agrees(v.value, Fraction(exp["value"]))
    assert abs(v.value - exp["VH"]) < 1e-7
    assert v.bracket.closed and v.bracket.exact == Fraction(exp["value"])


def _normal_form_value(doc: dict[str, Any], horizon: int) -> float:
    """V_H from the Defender's normal form (pure strategy = goal per walk prefix), by HiGHS."""
    adj = adjacency(doc)
    goals = doc["goals"]
    prior = [Fraction(p) for p in doc["prior"]]
    dist = [distances_to(doc, g) for g in goals]
    walks = list(all_walks(doc, horizon))
    prefixes = sorted({w[:k] for w in walks for k in range(2, len(w) + 1)}, key=str)
    index = {p: i for i, p in enumerate(prefixes)}
    pure = list(itertools.product((0, 1), repeat=len(prefixes)))  # 1 = allocate to goals[0]
    assert len(pure) <= 4096

    def cost(walk: tuple[Any, ...], theta: int, s: tuple[int, ...]) -> float:
        total = Fraction(0)
        for t in range(1, len(walk)):
            w = dict(adj[walk[t - 1]])[walk[t]]
            to0 = s[index[walk[:t + 1]]]
            total += w * (to0 if theta == 0 else 1 - to0)
        return float(total + dist[theta][walk[-1]])

    # variables: y (len(pure)), v0, v1; maximise b0 v0 + b1 v1
    n = len(pure)
    rows, rhs = [], []
    for theta in (0, 1):
        for w in walks:
            row = np.zeros(n + 2)
            row[:n] = [-cost(w, theta, s) for s in pure]
            row[n + theta] = 1.0
            rows.append(row)
            rhs.append(0.0)
    c = np.zeros(n + 2)
    c[n], c[n + 1] = -float(prior[0]), -float(prior[1])
    a_eq = np.zeros((1, n + 2))
    a_eq[0, :n] = 1
    res = linprog(c, A_ub=np.array(rows), b_ub=rhs, A_eq=a_eq, b_eq=[1],
                  bounds=[(0, None)] * n + [(None, None)] * 2, method="highs")
    assert res.status == 0
    return float(-res.fun)


@pytest.mark.parametrize(("make", "horizon"), [(triangle_doc, 1), (triangle_doc, 3),
                                               (three_phase_doc, 3), (three_phase_doc, 4)])
def test_compact_lp_equals_the_normal_form_value(make: Any, horizon: int) -> None:
    doc = make()
    inst = instance_from_json(doc)
    v = game_value(inst, horizon)
    nf = _normal_form_value(doc, horizon)
    assert abs(v.value - nf) < 1e-7
    assert float(v.bracket.lower) - 1e-9 <= nf <= float(v.bracket.upper) + 1e-9


def test_small_conformance_cases_against_the_normal_form() -> None:
    done = 0
    for case in CASES:
        doc = case["instance"]
        h = case["expected"]["H"]
        walks = list(all_walks(doc, h))
        if len({w[:k] for w in walks for k in range(2, len(w) + 1)}) > 9:
            continue
        assert abs(_normal_form_value(doc, h) - case["expected"]["VH"]) < 1e-7
        done += 1
    assert done >= 20


def test_value_is_non_increasing_in_the_horizon_and_reaches_u_star() -> None:
    for case in CASES[::15]:
        inst = instance_from_json(case["instance"])
        h = case["expected"]["H"]
        lo = max(1, inst.hops[inst.start])
        values = [game_value(inst, k) for k in range(lo, h + 3)]
        for a, b in itertools.pairwise(values):
            assert b.bracket.upper <= a.bracket.upper or b.value <= a.value + 1e-9
        assert values[-1].bracket.exact == Fraction(case["expected"]["value"])


def test_exact_bracket_contains_the_lp_value_on_a_grid() -> None:
    inst = instance_from_json(grid_doc(3, 3, (1, 0), [(0, 2), (2, 2)], ["3/5", "2/5"]))
    tree = build_tree(inst, 6)
    r = inst.roles()
    lp = solve_value_lp(tree, r)
    b = exact_bracket(tree, r, lp)
    assert float(b.lower) - 1e-7 <= lp.value <= float(b.upper) + 1e-7
    assert b.closed
    assert np.all(lp.plans[0] >= -1e-8) and abs(lp.plans[0][0] - 1) < 1e-8


def test_size_guard() -> None:
    inst = instance_from_json(grid_doc(3, 4, (0, 1), [(2, 0), (2, 3)], ["3/5", "2/5"]))
    # the count stops just above the limit (it has 136,711 prefixes: the slow test below)
    with pytest.raises(TreeTooLargeError, match=r"at least 100001 prefixes, more than the "
                                                r"limit of 100000 .*--route structured"):
        game_value(inst, 12, max_prefixes=100_000)


@pytest.mark.slow
def test_three_by_four_grid_at_horizon_12() -> None:
    """~137k prefixes: the LP and the exact bracket still agree (takes ~10 s)."""
    inst = instance_from_json(grid_doc(3, 4, (0, 1), [(2, 0), (2, 3)], ["3/5", "2/5"]))
    v = game_value(inst, 12)
    assert v.prefixes == 136_711
    assert v.bracket.closed and lp_agrees(v.value, v.bracket.lower)
