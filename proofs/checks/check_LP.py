"""Checks for proofs/LP.md (compact value LP; observing the Defender is worthless).

The symbolic part verifies the per-prefix algebra. The exact part builds, by brute force, the
normal form of a small truncated game in which the Attacker OBSERVES the Defender's first
action before its second step, solves it as a matrix game (scipy/HiGHS, explicit tolerance
1e-9), and compares with the exact value of the compact LP from ``dppverify.game_value``
(no reacting strategies there) — LP.2 says they are equal.
"""

from __future__ import annotations

import itertools
from fractions import Fraction

import networkx as nx
import numpy as np
import sympy as sp
from scipy.optimize import linprog

from dppverify import game_value, instance_from_json
from proofs.checks._sym import is_nonneg, is_zero, nonneg

TOL = 1e-9  # tolerance between the float matrix-game value and the exact V_H


def test_LP_defender_max_per_prefix_is_the_epigraph_value() -> None:
    big_b, gap = nonneg("B gap")
    sigma = sp.Symbol("sigma", real=True)
    for big_a, big_bb in ((big_b + gap, big_b), (big_b, big_b + gap)):  # A >= B, A <= B
        f = sigma * big_a + (1 - sigma) * big_bb  # affine in sigma: max at an end point
        ends = (f.subs(sigma, 0), f.subs(sigma, 1))
        top = sp.Max(big_a, big_bb)
        assert all(is_nonneg(top - v) for v in ends) and any(is_zero(top - v) for v in ends)
        # epigraph: z >= A, z >= B  <=>  z >= max(A, B)
        z_slack, = nonneg("z_slack")
        z = top + z_slack
        assert is_nonneg(z - big_a) and is_nonneg(z - big_bb)


EDGES = (("s", "a", 1), ("a", "g1", 1), ("a", "g2", 1), ("s", "g1", 2), ("s", "g2", 2))
PRIOR = (Fraction(3, 5), Fraction(2, 5))


def _doc() -> dict[str, object]:
    return {"graph": {"directed": False,
                      "nodes": [{"id": v} for v in ("s", "a", "g1", "g2")],
                      "edges": [{"source": u, "target": v, "weight": w} for u, v, w in EDGES]},
            "start": "s", "goals": ["g1", "g2"], "prior": [str(p) for p in PRIOR]}


def _observing_game_value() -> float:
    """Value of the H = 2 game where the Attacker sees the Defender's first action."""
    g = nx.Graph()
    g.add_weighted_edges_from(EDGES)
    d = dict(nx.all_pairs_dijkstra_path_length(g))
    goals = ("g1", "g2")
    # Attacker pure strategies: first step to a goal, or to "a" then a reaction map a1 -> goal
    attacker = [("direct", x) for x in goals] + [
        ("via", dict(zip(goals, r, strict=True))) for r in itertools.product(goals, repeat=2)]
    # Defender infosets: (s,g1), (s,g2), (s,a), then (s,a,x) given its own first action a1
    infosets = [("s", "g1"), ("s", "g2"), ("s", "a")] + [
        ("s", "a", x, a1) for x in goals for a1 in goals]
    defender = [dict(zip(infosets, acts, strict=True))
                for acts in itertools.product(goals, repeat=len(infosets))]

    def cost(theta: int, strat: tuple[str, object], pi: dict[object, str]) -> Fraction:
        true = goals[theta]
        if strat[0] == "direct":
            x = str(strat[1])
            return Fraction(g["s"][x]["weight"]) * (pi[("s", x)] == true) + d[x][true]
        a1 = pi[("s", "a")]
        reaction = strat[1]
        assert isinstance(reaction, dict)
        x = reaction[a1]
        return (Fraction(g["s"]["a"]["weight"]) * (a1 == true)
                + Fraction(g["a"][x]["weight"]) * (pi[("s", "a", x, a1)] == true) + d[x][true])

    pairs = list(itertools.product(attacker, attacker))
    mat = np.array([[float(PRIOR[0] * cost(0, s1, pi) + PRIOR[1] * cost(1, s2, pi))
                     for pi in defender] for s1, s2 in pairs])
    # Attacker (rows) minimises: min v s.t. sum_i p_i M[i, j] <= v for all j, p in simplex
    n_rows, n_cols = mat.shape
    c = np.r_[np.zeros(n_rows), 1.0]
    a_ub = np.c_[mat.T, -np.ones(n_cols)]
    a_eq = np.r_[np.ones(n_rows), 0.0][None, :]
    res = linprog(c, A_ub=a_ub, b_ub=np.zeros(n_cols), A_eq=a_eq, b_eq=[1.0],
                  bounds=[(0, None)] * n_rows + [(None, None)], method="highs")
    assert res.status == 0
    return float(res.fun)


def test_LP_observing_the_defender_does_not_change_the_value() -> None:
    inst = instance_from_json(_doc())
    gv = game_value(inst, 2)
    assert gv.bracket.closed
    v_blind = gv.bracket.exact
    v_obs = _observing_game_value()
    assert abs(v_obs - float(v_blind)) <= TOL * max(1.0, abs(float(v_blind)))
    # and the instance is not degenerate: the Attacker really has a reacting choice at "a"
    assert gv.leaves == 4
