"""Property tests of the trusted kernel against the engine (proofs/KERNEL.md K.4–K.6).

On random two-goal instances (the solver's equilibrium, and random tables with a constant or
progress default) and random N-goal instances (random tables with a default), with random
mixtures over walks: the kernel, given the engine's witness, PASSes exactly the profiles that
``dppverify.certify`` certifies on the untruncated game, and refutes exactly those it refutes
(with the counterexample walk or the greedy violation the witness and the masses give).
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import dppverify
from dppverify.game.instance import instance_from_json
from dppverify.strategies.graphs import weighted_graphs
from dppverify.strategies.instances import instances, many_goal_instances
from solver.adapter import solve_json
from tests.dppverify.kernel._witnesses import kernel_verdict

SETTINGS = settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
EXACT = weighted_graphs(min_nodes=3, max_nodes=6, weights="fractions", max_weight=3)
SHARES = [Fraction(0), Fraction(1), Fraction(1, 2), Fraction(1, 3), Fraction(2, 3)]


def _walks(draw: st.DrawFn, doc: dict[str, Any], count: int) -> list[list[Any]]:
    """``count`` random walks of the game (ending at a goal within a few steps)."""
    inst = instance_from_json(doc)
    out = []
    for _ in range(count):
        w = [inst.start]
        while not inst.is_goal(w[-1]):
            live = [u for u, _ in inst.succ[w[-1]] if inst.is_goal(u) or inst.hops[u] >= 0]
            if len(w) > 3:
                live = [u for u in live if inst.is_goal(u) or inst.hops[u] < inst.hops[w[-1]]]
            w.append(draw(st.sampled_from(sorted(live))))
        out.append([inst.nodes[v] for v in w])
    return out


def _mixture(draw: st.DrawFn, walks: list[list[Any]]) -> list[dict[str, Any]]:
    unique = sorted({tuple(w) for w in walks})
    if len(unique) == 1:
        return [{"path": list(unique[0]), "probability": "1"}]
    p = draw(st.sampled_from([Fraction(1, 3), Fraction(1, 2), Fraction(3, 4)]))
    return [{"path": list(unique[0]), "probability": str(p)},
            {"path": list(unique[1]), "probability": str(1 - p)}]


@st.composite
def two_goal_cases(draw: st.DrawFn) -> tuple[dict[str, Any], dict[str, Any]]:
    doc = draw(instances(graphs=EXACT))
    if draw(st.booleans()):
        return doc, solve_json(doc)
    g = draw(st.sampled_from(doc["goals"]))
    walks = [_walks(draw, doc, 2) for _ in range(2)]
    prefixes = sorted({tuple(w[:k]) for ws in walks for w in ws for k in range(2, len(w) + 1)})
    entries = [{"walk": list(p), "probability": str(draw(st.sampled_from(SHARES)))}
               for p in prefixes if draw(st.booleans())]
    default = draw(st.sampled_from(["progress", *map(str, SHARES)]))
    primary = 0 if Fraction(doc["prior"][0]) >= Fraction(doc["prior"][1]) else 1
    prof = {"format": "dpp-profile/1",
            "goals": {"primary": doc["goals"][primary], "secondary": doc["goals"][1 - primary]},
            "defender": {"rule": "table", "goal": g, "entries": entries, "default": default},
            "attacker": {"primary": _mixture(draw, walks[0]),
                         "secondary": _mixture(draw, walks[1])}}
    return doc, prof


@st.composite
def per_goal_cases(draw: st.DrawFn) -> tuple[dict[str, Any], dict[str, Any]]:
    doc = draw(many_goal_instances(min_goals=3, max_goals=4,
                               graphs=weighted_graphs(min_nodes=4, max_nodes=6, max_weight=3)))
    n = len(doc["goals"])
    walks = [_walks(draw, doc, 2) for _ in range(n)]
    dists = [[int(i == j) for i in range(n)] for j in range(n)] + [["1/3"] * 3 + [0] * (n - 3)]
    prefixes = sorted({tuple(w[:k]) for ws in walks for w in ws for k in range(2, len(w) + 1)})
    entries = [{"walk": list(p), "probabilities": draw(st.sampled_from(dists))}
               for p in prefixes if draw(st.booleans())]
    prof = {"format": "dpp-ngoal-profile/1", "attacker": [_mixture(draw, ws) for ws in walks],
            "defender": {"rule": "table", "entries": entries,
                         "default": draw(st.sampled_from(dists))}}
    return doc, prof


def _agree(doc: dict[str, Any], prof: dict[str, Any]) -> None:
    engine = dppverify.certify(doc, prof).verdict
    v = kernel_verdict(doc, prof)
    expected = {"pass": "pass", "fail": "refuted"}.get(engine, "undecided")
    assert v.status == expected, (engine, v)


@SETTINGS
@given(two_goal_cases())
def test_two_goals_the_kernel_agrees_with_the_engine(case: tuple[dict[str, Any], ...]) -> None:
    _agree(*case)


@SETTINGS
@given(per_goal_cases())
def test_n_goals_the_kernel_agrees_with_the_engine(case: tuple[dict[str, Any], ...]) -> None:
    _agree(*case)


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(many_goal_instances(min_goals=3, max_goals=3,
                       graphs=weighted_graphs(min_nodes=4, max_nodes=6, max_weight=3)))
def test_n_goals_the_solver_guarantee_rule_is_accepted(doc: dict[str, Any]) -> None:
    """``dpp solve``'s N-goal profiles (the guarantee rule) pass the kernel on the engine's
    witness: the DP labels, the arc condition and every stage dual."""
    prof = solve_json(doc)
    assert prof["defender"]["rule"] == "guarantee"
    v = kernel_verdict(doc, prof)
    assert v.status == "pass", v
