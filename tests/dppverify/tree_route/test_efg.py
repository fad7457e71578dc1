"""The Gambit .efg export: an independent reader re-checks structure, payoffs and the value.

The reader and the sequence-form LP below are written from Gambit's format specification and
share no code with ``dppverify.tree_route.efg``: the tests parse the exported text back, check node
and
information-set counts against the walk tree, perfect recall, payoffs (on leaves only) against
costs recomputed from the instance document, the chance probabilities, OpenSpiel's action
ordering requirement, and that the sequence-form LP of the parsed game (scipy HiGHS) gives
``V_H`` from :func:`dppverify.game_value`.
"""


from __future__ import annotations

import json
from collections import defaultdict
from fractions import Fraction
from pathlib import Path
from typing import Any

import pytest

from dppverify import game_value
from dppverify.cli import COMMANDS
from dppverify.cli.export_efg import export_efg_command
from dppverify.errors import CheckerError
from dppverify.game.instance import instance_from_json
from dppverify.tree_route.efg import to_efg, write_efg
from dppverify.tree_route.tree import build_tree
from tests.dppverify._helpers import (
    make_doc,
)
from tests.dppverify.tree_route._efg_reader import (
    CASES,
    IDS,
    KITE,
    VARIANT_IDS,
    VARIANTS,
    Node,
    decode,
    export,
    label,
    own_history,
    parse,
    run_cli,
    sequence_form_value,
)

# ---------------------------------------------------------------------------------------------
# The tests
# ---------------------------------------------------------------------------------------------

def test_some_cases_have_forced_moves() -> None:
    # the forced-move variants above differ from the default ones only if moves are forced
    assert any(sum(1 for n in export(d, h, forced=True).nodes() if len(n.actions) == 1)
               for _, d, h in CASES)


@pytest.mark.parametrize(("observes", "forced"), VARIANTS, ids=VARIANT_IDS)
@pytest.mark.parametrize(("name", "doc", "horizon"), CASES, ids=IDS)
def test_perfect_recall_and_consistent_infosets(name: str, doc: dict[str, Any], horizon: int,
                                                observes: bool, forced: bool) -> None:
    game = export(doc, horizon, observes, forced)
    members: dict[tuple[int, int], list[Node]] = defaultdict(list)
    for n in game.nodes():
        if n.kind == "p":
            members[(n.player, n.infoset)].append(n)
    for (player, _), nodes in members.items():
        # perfect recall: the owner's own moves (infosets and actions) agree on every member
        assert len({own_history(n, player) for n in nodes}) == 1
        assert len({tuple(n.actions) for n in nodes}) == 1
        assert len({n.infoset_name for n in nodes}) == 1
        decoded = [decode(n, doc, horizon) for n in nodes]
        types = {g for g, _, _ in decoded}
        walks = {w for _, w, _ in decoded}
        if player == 2:
            # the Defender sees the walk and its own allocations, not the type
            assert len(nodes) == 2 and len(types) == 2 and len(walks) == 1
            assert len({tuple(a) for _, _, a in decoded}) == 1
        else:
            assert len(types) == 1 and len(walks) == 1
            if observes:  # it also sees the Defender's allocations: singletons
                assert len(nodes) == 1
            else:
                assert len(nodes) == 2 ** (len(decoded[0][1]) - 1)


@pytest.mark.parametrize(("name", "doc", "horizon"), CASES, ids=IDS)
def test_chance_draws_the_type_with_the_exact_prior(name: str, doc: dict[str, Any],
                                                    horizon: int) -> None:
    game = export(doc, horizon)
    chance = [n for n in game.nodes() if n.kind == "c"]
    assert chance == [game.root]
    assert sum(game.root.probs) == 1
    assert game.root.probs == [Fraction(b) for b in doc["prior"]]
    assert game.root.actions == [f"type {label(g)}" for g in doc["goals"]]


@pytest.mark.parametrize(("name", "doc", "horizon"), CASES, ids=IDS)
def test_actions_listed_in_first_appearance_order(name: str, doc: dict[str, Any],
                                                  horizon: int) -> None:
    # OpenSpiel 2.0.2 sorts a node's global action ids (numbered by first appearance in the
    # file) but not its children: any other order silently permutes the children.
    rank: dict[str, int] = {}
    for n in export(doc, horizon).nodes():
        if n.kind == "p":
            for a in n.actions:
                rank.setdefault(a, len(rank))
            ids = [rank[a] for a in n.actions]
            assert ids == sorted(ids)


@pytest.mark.parametrize(("observes", "forced"), VARIANTS, ids=VARIANT_IDS)
@pytest.mark.parametrize(("name", "doc", "horizon"), CASES[:-1], ids=IDS[:-1])
def test_sequence_form_lp_of_the_export_gives_v_h(name: str, doc: dict[str, Any], horizon: int,
                                                  observes: bool, forced: bool) -> None:
    value = game_value(instance_from_json(doc), horizon)
    assert value.bracket.closed
    exact = value.bracket.exact
    assert exact is not None
    lp = sequence_form_value(export(doc, horizon, observes, forced), minimizer=1,
                             maximizer=2)
    assert abs(lp - float(exact)) <= 1e-9 * max(1.0, abs(float(exact)))


def test_the_value_depends_on_the_horizon_in_the_export() -> None:
    # guards against a test instance where any export would match (V_2 != V_3 for KITE)
    v2 = sequence_form_value(export(KITE, 2), 1, 2)
    v3 = sequence_form_value(export(KITE, 3), 1, 2)
    assert v3 < v2 - 0.1


def test_quotes_in_node_ids_are_replaced_and_names_stay_distinct() -> None:
    doc = make_doc([('s"', "g\\1", 1), ('s"', "g2", 2)], 's"', ["g\\1", "g2"], ["1/2", "1/2"])
    text = to_efg(instance_from_json(doc), 1)
    game = parse(text)
    assert game.root.actions == ["type g/1", "type g2"]
    assert {a for n in game.nodes() for a in n.actions} >= {"go g/1", "go g2", "alloc g/1"}


def test_clashing_labels_get_index_prefixes() -> None:
    doc = make_doc([(1, "1", 1), (1, 2, 1)], 1, ["1", 2], ["1/2", "1/2"])
    game = parse(to_efg(instance_from_json(doc), 1))
    assert game.root.actions == ["type v1:1", "type v2:2"]


def test_float_instances_export_decimals() -> None:
    doc = make_doc([("s", "g1", 0.1), ("s", "g2", 2.5)], "s", ["g1", "g2"], ["1/2", "1/2"])
    doc["numbers"] = "float"
    text = to_efg(instance_from_json(doc), 1)
    assert "e-" not in text and "0.1" in text
    costs = {n.payoffs[1] for n in parse(text).nodes() if n.payoffs}
    assert Fraction("0.1") in costs and Fraction("2.5") in costs


def test_write_efg_is_atomic_and_reports_the_size(tmp_path: Path) -> None:
    target = tmp_path / "game.efg"
    target.write_text("old")
    size = write_efg(target, build_tree(instance_from_json(KITE), 2))
    assert list(tmp_path.iterdir()) == [target]
    game = parse(target.read_text())
    assert size.nodes == sum(1 for _ in game.nodes())
    with pytest.raises(CheckerError, match="cannot write"):  # a file where a folder must be
        write_efg(target / "g.efg", build_tree(instance_from_json(KITE), 2))
    assert list(tmp_path.iterdir()) == [target]


def test_cli_export_efg(tmp_path: Path) -> None:
    inst = tmp_path / "kite.json"
    inst.write_text(json.dumps(KITE))
    out = tmp_path / "kite.efg"
    r = run_cli([str(inst), "--horizon", "2", "-o", str(out)])
    assert r.exit_code == 0, r.output
    assert out.read_text() == to_efg(instance_from_json(KITE), 2)
    r = run_cli([str(inst), "-H", "2", "-o", str(out), "--attacker-blind"])
    assert r.exit_code == 0
    assert out.read_text() == to_efg(instance_from_json(KITE), 2, attacker_observes=False)
    assert export_efg_command in COMMANDS


def test_cli_export_efg_bad_input_exit_2(tmp_path: Path) -> None:
    bad = tmp_path / "bad.json"
    bad.write_text("{not json")
    r = run_cli([str(bad), "-H", "2", "-o", str(tmp_path / "g.efg")])
    assert r.exit_code == 2 and "Traceback" not in r.output
    good = tmp_path / "kite.json"
    good.write_text(json.dumps(KITE))
    r = run_cli([str(good), "-H", "2", "-o", str(bad / "g.efg")])  # bad.json is not a folder
    assert r.exit_code == 2 and "cannot write" in r.output
