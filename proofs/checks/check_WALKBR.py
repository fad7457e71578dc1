"""Checks for proofs/WALKBR.md (best responses over all walks by three shortest paths)."""

from __future__ import annotations

import json
from pathlib import Path

import sympy as sp

from dppverify import build_tree, count_prefixes, instance_from_json
from dppverify.game.profile import ProgressRule
from dppverify.tree_route.best_response import attacker_best_response
from dppverify.tree_route.tree_defender import tree_defender
from dppverify.twogoal.progress_br import walk_minima
from proofs.checks._sym import is_nonneg, is_zero, nonneg

CASES = Path(__file__).resolve().parents[2] / "tests" / "data" / "conformance_cases.json"


def test_WALKBR_cost_identity_and_lower_bound() -> None:
    L, c0, cT, d_end = nonneg("L c0 cT d_end")
    progress = c0 - cT  # Σ w σ_g telescopes (TEL)
    cost_other = (L - progress) + d_end  # Σ w (1 − σ_g) + terminal
    assert is_zero(cost_other - (L - c0 + cT + d_end))
    # walk ending at g': L >= d'(s0,u) + d''(u,g') and cT = d(u,g): cost >= F(u) - c0
    d1, d2, slack = nonneg("d1 d2 slack")
    assert is_nonneg((d1 + d2 + slack) - c0 + cT - (d1 + cT + d2 - c0))
    # the same-goal type: c0 − cT + d(s_T, g) >= c0 because cT <= d(s_T, g)
    gap = sp.Symbol("gap", nonnegative=True)
    assert is_nonneg((c0 - cT + (cT + gap)) - c0)


def test_WALKBR_equals_exhaustive_backward_induction_over_all_walks() -> None:
    checked = 0
    for case in json.loads(CASES.read_text(encoding="utf-8")):
        inst = instance_from_json(case["instance"])
        h = 2 * inst.n_nodes  # every minimiser of WB.1/WB.2 has at most 2n - 2 steps
        if count_prefixes(inst, h) > 4000:
            continue
        tree = build_tree(inst, h)
        for slot in (0, 1):  # progress towards either goal (σ* and the "wrong goal" rule)
            roles = inst.roles(slot)
            rule = ProgressRule(roles.g1)
            td = tree_defender(tree, roles, rule)
            mins = walk_minima(inst, roles.g1)
            assert attacker_best_response(tree, roles, td, 1).value == mins.same, case["name"]
            assert attacker_best_response(tree, roles, td, 2).value == mins.other, case["name"]
        checked += 1
    assert checked >= 40
