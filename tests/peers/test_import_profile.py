"""``dpp import-profile`` on the peers' own outputs for the games of docs/peers.md: what
OpenSpiel and Gambit compute on our ``.efg`` export comes back as a ``dpp`` profile of the
truncated game, and ``dppverify.certify`` states its exact exploitability.

- OpenSpiel's CFR (300 iterations, its average policy saved with ``json.dump(policy.to_dict())``)
  is **refuted**, and the certificate's exact NashConv of the rationalised profile is
  OpenSpiel's own ``nash_conv`` of the float policy (within what the rationalisation moved
  each probability: at most 1e-9 to the simplest rational, then a scaling to sum 1) on the
  ``--attacker-blind`` export; on the default export, where CFR's
  Attacker conditions on the Defender's past allocations, the command says so in a note;
- OpenSpiel's sequence-form LP (floats, HiGHS) **passes** once rationalised, with NashConv
  exactly 0;
- Gambit's exact LP (``lp_solve(rational=True)``), written as the ``NE,...`` line its command
  line tools print, **passes** exactly, in both variants.

Marked ``peers`` (run by ``python3 dev.py test``; each peer skipped when absent).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest
from click.testing import CliRunner

from dppverify import certify
from dppverify.cli import main
from dppverify.game.examples import star3_document
from dppverify.game.instance import instance_from_json
from dppverify.tree_route.efg import to_efg
from tests.dppverify._helpers import triangle_doc
from tests.dppverify.tree_route._efg_reader import GRID, KITE, THIRDS
from tests.peers.test_peers import openspiel  # noqa: F401  (the fixture: HiGHS for the LP)

pytestmark = pytest.mark.peers

CASES = [("triangle", triangle_doc(), 2), ("kite", KITE, 3), ("thirds", THIRDS, 3),
         ("grid", GRID, 3), ("star3", star3_document(), 2)]
"""Games of docs/peers.md, two goals and three."""
CFR_CASES = [CASES[0], CASES[1], CASES[4]]
"""CFR (300 iterations) and the LP on three of them: two goals at H = 2 and 3, three goals."""

CFR_ITERATIONS = 300
NASHCONV_AGREEMENT = 1e-6
"""|ours − OpenSpiel's| for the CFR policy (each probability moved by < 1e-8)."""


def _import(tmp_path: Path, doc: dict[str, Any], horizon: int, peer: str, *,
            observes: bool) -> tuple[dict[str, Any], str]:
    (tmp_path / "instance.json").write_text(json.dumps(doc))
    (tmp_path / "peer").write_text(peer)
    out = tmp_path / "profile.json"
    args = ["import-profile", str(tmp_path / "instance.json"), str(tmp_path / "peer"),
            "-H", str(horizon), "-o", str(out)]
    result = CliRunner().invoke(main, [*args, *([] if observes else ["--attacker-blind"])])
    assert result.exit_code == 0, result.output
    return json.loads(out.read_text()), result.output


@pytest.mark.parametrize("observes", [False, True], ids=["blind", "observes"])
@pytest.mark.parametrize(("name", "doc", "horizon"), CFR_CASES, ids=[c[0] for c in CFR_CASES])
def test_openspiel_cfr_is_refuted_with_its_nash_conv_and_its_lp_passes(
        openspiel: Any, tmp_path: Path, name: str, doc: dict[str, Any], horizon: int,  # noqa: F811
        observes: bool) -> None:
    pyspiel, sequence_form_lp, exploitability, policy, highs = openspiel
    cfr = pytest.importorskip("open_spiel.python.algorithms.cfr")
    game = pyspiel.load_efg_game(to_efg(instance_from_json(doc), horizon,
                                        attacker_observes=observes))
    solver = cfr.CFRSolver(game)
    for _ in range(CFR_ITERATIONS):
        solver.evaluate_and_update_policy()
    average = solver.average_policy()
    theirs = float(exploitability.nash_conv(game, average))
    profile, said = _import(tmp_path, doc, horizon, json.dumps(average.to_dict()),
                            observes=observes)
    assert profile["solver"]["rationalised"]["max_change"] <= 1e-8  # snap, then scale to 1
    cert = certify(doc, profile, horizon=horizon)
    e = cert.exploitability
    assert e is not None and e.exact and e.decided
    assert not cert.passed and e.nash_conv > 0  # 300 iterations are not an equilibrium
    if not observes or "note:" not in said:
        assert abs(float(e.nash_conv) - theirs) <= NASHCONV_AGREEMENT, (e.summary(), theirs)
    _, _, p0, p1 = sequence_form_lp.solve_zero_sum_game(game, solver=highs)
    lp = policy.merge_tabular_policies([p0, p1], game)
    profile, _ = _import(tmp_path, doc, horizon, json.dumps(lp.to_dict()), observes=observes)
    cert = certify(doc, profile, horizon=horizon)
    assert cert.passed and cert.exploitability.nash_conv == 0, cert.exploitability.summary()


def test_the_observing_export_notes_a_history_dependent_attacker(
        openspiel: Any, tmp_path: Path) -> None:  # noqa: F811
    """CFR on the kite's default export conditions on the allocations: the note says so, and
    the exploitability then differs from OpenSpiel's (another strategy)."""
    pyspiel, _, exploitability, _, _ = openspiel
    cfr = pytest.importorskip("open_spiel.python.algorithms.cfr")
    game = pyspiel.load_efg_game(to_efg(instance_from_json(KITE), 3))
    solver = cfr.CFRSolver(game)
    for _ in range(CFR_ITERATIONS):
        solver.evaluate_and_update_policy()
    average = solver.average_policy()
    profile, said = _import(tmp_path, KITE, 3, json.dumps(average.to_dict()), observes=True)
    assert "note: at" in said and "--attacker-blind" in said
    e = certify(KITE, profile, horizon=3).exploitability
    assert abs(float(e.nash_conv) - float(exploitability.nash_conv(game, average))) > 1e-4


@pytest.mark.parametrize("observes", [False, True], ids=["blind", "observes"])
@pytest.mark.parametrize(("name", "doc", "horizon"), CASES, ids=[c[0] for c in CASES])
def test_gambit_exact_lp_passes_exactly(tmp_path: Path, name: str, doc: dict[str, Any],
                                        horizon: int, observes: bool) -> None:
    gbt = pytest.importorskip("pygambit")
    path = tmp_path / "game.efg"
    path.write_text(to_efg(instance_from_json(doc), horizon, attacker_observes=observes))
    game = gbt.read_efg(str(path))
    eq = gbt.nash.lp_solve(game, rational=True).equilibrium
    # the profile line gambit-lp prints: every player's information sets, their actions
    line = "NE," + ",".join(str(p) for player in ("Attacker", "Defender")
                            for _, row in eq[player] for _, p in row)
    profile, said = _import(tmp_path, doc, horizon, line + "\n", observes=observes)
    assert "every probability exact" in said
    cert = certify(doc, profile, horizon=horizon)
    assert cert.passed and cert.exploitability.nash_conv == 0
