"""Peer cross-checks of the goal-selection game: Gambit and OpenSpiel solve the ``.efg`` export
whose root is the Attacker's choice of its goal, and must agree with our exact value.

Marked ``peers`` (run with ``.venv/bin/pytest -m peers tests/peers``). The export
(:func:`dppverify.tree_route.efg.to_efg` with ``goal_values``) replaces the chance node by an
Attacker decision ``choose <goal>`` and shifts each payoff by the chosen goal's value. Ours is
:func:`dppverify.structured.selection_value.selection_value` at the same horizon: the
coalition DP's layer ``H`` at the start, ``min_S (m_S(s0, H) − r(S))/|S|`` (proofs/SELECT.md
SELECT.9), which shares no code with the export or the peers. Gambit's
``lp_solve(rational=True)`` must equal it exactly, OpenSpiel's sequence-form LP within 1e-9;
where ``H`` covers the untruncated equilibrium's walks the untruncated ``V_sel`` equals both as
well.
"""

from __future__ import annotations

from fractions import Fraction
from pathlib import Path
from types import ModuleType
from typing import Any

import pytest

from dppverify.game.instance import instance_from_json
from dppverify.structured.selection_value import selection_value
from dppverify.tree_route.efg import to_efg
from tests.dppverify._helpers import triangle_doc
from tests.dppverify.tree_route._efg_reader import FRACTIONAL, GRID, KITE, LADDER, THIRDS
from tests.dppverify.tree_route.test_efg_any_n import DROP3, GRID3, KITE3, STAR3, STAR4
from tests.peers.test_peers import _gambit_solve, _openspiel_value, gambit, openspiel

pytestmark = pytest.mark.peers

__all__ = ["gambit", "openspiel"]  # the fixtures, shared with the prior game's peer tests

TOLERANCE = 1e-9
"""Absolute agreement of OpenSpiel's float LP value with the exact value."""

GAMES = [("triangle", triangle_doc(), 1), ("kite", KITE, 2), ("kite", KITE, 3),
         ("ladder", LADDER, 1), ("ladder", LADDER, 2), ("thirds", THIRDS, 2),
         ("thirds", THIRDS, 3), ("fractional", FRACTIONAL, 2), ("fractional", FRACTIONAL, 3),
         ("grid", GRID, 3), ("star3", STAR3, 2), ("drop3", DROP3, 2), ("drop3", DROP3, 3),
         ("kite3", KITE3, 2), ("grid3", GRID3, 2), ("star4", STAR4, 2)]
CASES = [(name, doc, h, with_values) for name, doc, h in GAMES for with_values in (False, True)
         if not (name == "star4" and with_values)]  # Gambit takes 20 s on that one
IDS = [f"{name}-H{h}{'-values' if v else ''}" for name, _, h, v in CASES]


def _selection(doc: dict[str, Any], with_values: bool) -> dict[str, Any]:
    out = {k: v for k, v in doc.items() if k != "prior"}
    out["goal_selection"] = True
    if with_values:  # r = (0, 1/2, 1, ...): the Attacker prefers the later goals
        out["goal_values"] = [str(Fraction(i, 2)) for i in range(len(doc["goals"]))]
    return out


def _ours(doc: dict[str, Any], horizon: int) -> tuple[Any, Fraction]:
    sel = instance_from_json(doc)
    v = selection_value(sel, horizon)
    assert v.value is not None, v.reason
    return sel, v.value


@pytest.mark.parametrize(("name", "doc", "horizon", "with_values"), CASES, ids=IDS)
def test_gambit_exact_lp_gives_exactly_the_selection_value(
        gambit: ModuleType, tmp_path: Path, name: str, doc: dict[str, Any], horizon: int,
        with_values: bool) -> None:
    sel, exact = _ours(_selection(doc, with_values), horizon)
    eq = _gambit_solve(gambit, to_efg(sel, horizon, goal_values=sel.goal_values), tmp_path)
    defender, attacker = eq.payoffs["Defender"], eq.payoffs["Attacker"]
    assert isinstance(defender, Fraction)
    assert defender == exact and attacker == -exact
    assert eq.agent_max_regret() == 0


@pytest.mark.parametrize(("name", "doc", "horizon", "with_values"), CASES, ids=IDS)
def test_openspiel_sequence_form_lp_gives_the_selection_value(
        openspiel: Any, name: str, doc: dict[str, Any], horizon: int,
        with_values: bool) -> None:
    sel, exact = _ours(_selection(doc, with_values), horizon)
    v0, v1, nash_conv = _openspiel_value(openspiel,
                                         to_efg(sel, horizon, goal_values=sel.goal_values))
    assert abs(-v0 - float(exact)) <= TOLERANCE
    assert abs(v1 - float(exact)) <= TOLERANCE
    assert 0 <= nash_conv <= TOLERANCE


def test_the_peers_see_the_choice_gain_over_chance(gambit: ModuleType, tmp_path: Path) -> None:
    """The same game with chance at the uniform prior is worth more to the Defender when
    choosing gains the Attacker something: ``thirds`` at H = 2, 2 against 7/2 (the Attacker
    always picks g2), and Gambit sees both."""
    sel, chosen = _ours(_selection(THIRDS, False), 2)
    uniform = _gambit_solve(gambit, to_efg(sel, 2), tmp_path).payoffs["Defender"]
    assert (chosen, uniform) == (2, Fraction(7, 2))
