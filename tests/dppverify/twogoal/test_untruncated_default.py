"""A PASS means an equilibrium of the game the user asked about.

Without a horizon ``certify`` (CLI and API, two and N goals), ``value`` and the audit work on
the untruncated game; a finite horizon names the truncated game everywhere; the paper's
lemmas are facts beside the verdict; table Defenders with a default are certified at
``H = inf`` (proofs/TABLEBR.md); a table without default is undecided (exit 3).
"""

from __future__ import annotations

import json
import math
from fractions import Fraction
from pathlib import Path
from typing import Any

import pytest
from click.testing import CliRunner
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import dppverify
from dppverify import certify
from dppverify.certificate import Certificate
from dppverify.cli.certify import certify_command
from dppverify.cli.value import value_command
from dppverify.errors import HorizonError, UndecidedError
from dppverify.game.examples import (
    kite,
    kite_document,
    kite_naive_profile,
    star3_document,
    star3_profile,
)
from dppverify.game.instance import instance_from_json
from dppverify.game.profile import ProgressRule, TableRule
from dppverify.strategies import instances, weighted_graphs
from dppverify.structured.table_br_twogoal import table_minima
from dppverify.twogoal.progress_br import walk_minima
from tests.dppverify._helpers import make_doc

Doc = dict[str, Any]


def _write(tmp_path: Path, name: str, doc: Doc) -> str:
    p = tmp_path / name
    p.write_text(json.dumps(doc), "utf-8")
    return str(p)


def _table(goal: str, entries: list[tuple[list[str], Any]], default: Any = None) -> Doc:
    d: Doc = {"rule": "table", "goal": goal,
              "entries": [{"walk": w, "probability": p} for w, p in entries]}
    if default is not None:
        d["default"] = default
    return d


# ----------------------------------------------------------------------------- the kite
def test_kite_is_refuted_by_default_on_the_cli(tmp_path: Path) -> None:
    inst = _write(tmp_path, "kite.json", kite_document())
    prof = _write(tmp_path, "naive.json", kite_naive_profile())
    r = CliRunner().invoke(certify_command, [inst, prof])
    assert r.exit_code == 1, r.output
    head = r.output.splitlines()[0]
    assert head.startswith("verdict: FAIL for the untruncated game (H = inf)")
    assert "pbne.attacker_br.secondary   fail" in r.output
    assert "V_H (H = inf) = 8/5 but U = 2" in r.output


def test_kite_truncated_pass_names_the_truncated_game(tmp_path: Path) -> None:
    inst = _write(tmp_path, "kite.json", kite_document())
    prof = _write(tmp_path, "naive.json", kite_naive_profile())
    r = CliRunner().invoke(certify_command, [inst, prof, "--horizon", "1"])
    assert r.exit_code == 0, r.output
    lines = r.output.splitlines()
    assert lines[0].startswith("verdict: PASS for the game truncated at H = 1 (")
    assert lines[1].startswith("note: this certifies the game truncated at H = 1 only, not the "
                               "full (untruncated) game")
    r = CliRunner().invoke(certify_command, [inst, prof, "--horizon", "1", "--json"])
    doc = json.loads(r.output)
    assert doc["game"]["horizon"] == 1 and doc["game"]["truncated"] is True
    assert "not the full" in doc["game"]["note"]
    assert Certificate.from_json(doc).truncated


def test_untruncated_certificate_game_record() -> None:
    cert = certify(kite_document(), kite_naive_profile())
    doc = cert.to_json()
    assert doc["game"] == {"horizon": "inf", "truncated": False}
    assert cert.horizon is None and cert.route == "structured"
    forged = dict(doc, game={"horizon": 1, "truncated": True})
    with pytest.raises(dppverify.CertificateError, match="game record"):
        Certificate.from_json(forged)


@pytest.mark.parametrize("horizon", [None, "inf", float("inf"), "INF"])
def test_api_default_and_inf_spellings_are_the_untruncated_game(horizon: Any) -> None:
    cert = certify(kite_document(), kite_naive_profile(), horizon=horizon)
    assert cert.verdict == "fail" and cert.horizon is None


@pytest.mark.parametrize("horizon", [-1, 2.5, "soon", [1], True])
def test_bad_horizon_is_one_line_horizon_error(horizon: Any) -> None:
    with pytest.raises(HorizonError) as info:
        certify(kite_document(), kite_naive_profile(), horizon=horizon)
    assert "\n" not in str(info.value)
    with pytest.raises(HorizonError):
        dppverify.value(kite_document(), horizon)


# ----------------------------------------------------------------------------- detour family
def _detour(k: int) -> Doc:
    """The kite stretched: ``s–g1``, ``s–g2`` of weight 2; a detour ``s a1 … ak`` of ``k``
    steps of weight ``1/k`` (each one progress towards g1, so free for the secondary against
    σ*) whose end ``ak`` is one step (weight 1) from each goal. The secondary's detour has
    ``k + 1`` steps, longer than the naive one-step walks, and costs 1 < 2; ``k = 1`` is the
    kite."""
    w = str(Fraction(1, k))
    edges: list[tuple[Any, Any, Any]] = [("s", "g1", 2), ("s", "g2", 2), ("s", "a1", w)]
    edges += [(f"a{i}", f"a{i + 1}", w) for i in range(1, k)]
    edges += [(f"a{k}", "g1", 1), (f"a{k}", "g2", 1)]
    return make_doc(edges, "s", ["g1", "g2"], ["3/5", "2/5"])


@pytest.mark.parametrize("k", [1, 2, 3, 5, 8])
def test_detour_family_naive_profile_is_refuted(k: int) -> None:
    doc = _detour(k)
    cert = certify(doc, kite_naive_profile())
    assert cert.verdict == "fail"
    assert cert.check("pbne.attacker_br.secondary").status == "fail"
    # the detour is k + 1 steps, longer than the profile's one-step walks: the old default
    # (the profile's own length) passed it
    assert certify(doc, kite_naive_profile(), horizon=1).verdict == "pass"
    v = dppverify.value(doc)
    assert v.structured is not None and v.structured.value < 2
    assert cert.check("pbne.attacker_br.secondary").numbers["min_over_walks"] == 1


# ----------------------------------------------------------------------------- verdict vs lemmas
def _issue_example_beliefs() -> tuple[Doc, Doc]:
    doc = make_doc([(0, 1, 1), (2, 1, 2), (3, 1, 1), (2, 0, 2)], 0, [1, 2], ["2/5", "3/5"])
    prof = {"format": "dpp-profile/1", "goals": {"primary": 2, "secondary": 1},
            "defender": {"rule": "progress", "goal": 2},
            "attacker": {"primary": [{"path": [0, 2], "probability": "11/12"},
                                     {"path": [0, 1], "probability": "1/12"}],
                         "secondary": [{"path": [0, 1], "probability": 1}]}}
    return doc, prof


def _issue_example_mixing() -> tuple[Doc, Doc]:
    doc = make_doc([(1, 0, 1), (1, 2, 1), (3, 0, 2), (0, 2, 1)], 0, [1, 2], ["3/5", "2/5"])
    prof = {"format": "dpp-profile/1", "goals": {"primary": 1, "secondary": 2},
            "defender": {"rule": "progress", "goal": 1},
            "attacker": {"primary": [{"path": [0, 1], "probability": 1}],
                         "secondary": [{"path": [0, 2], "probability": "3/4"},
                                       {"path": [0, 1], "probability": "1/4"}]}}
    return doc, prof


@pytest.mark.parametrize("example", [_issue_example_beliefs, _issue_example_mixing])
@pytest.mark.parametrize("horizon", [None, 1, 3])
def test_issue_equilibria_off_the_paper_pass(example: Any, horizon: Any) -> None:
    doc, prof = example()
    cert = certify(doc, prof, horizon=horizon)
    assert cert.verdict == "pass", [(c.id, c.status, c.message) for c in cert.failed()]
    l5 = cert.check("lemma.L5.induced_beliefs")
    assert l5.kind == "fact" and l5.status != "pass"   # not the paper's construction
    assert cert.check("value.U").numbers["U"] == dppverify.value(doc).structured.value


# ----------------------------------------------------------------------------- table Defenders
def test_table_with_default_is_certified_untruncated(tmp_path: Path) -> None:
    doc = kite_document()
    prof = dict(kite_naive_profile(), defender=_table("g1", [(["s", "g1"], 1)], "progress"))
    cert = certify(doc, prof)
    assert cert.horizon is None and cert.route == "structured"
    assert cert.check("pbne.attacker_br.secondary").status == "fail"
    assert "TABLEBR" in (cert.check("pbne.attacker_br.secondary").relies_on or "")


def test_table_without_default_is_undecided(tmp_path: Path) -> None:
    prof = dict(kite_naive_profile(), defender=_table("g1", [(["s", "g1"], 1),
                                                             (["s", "g2"], 0)]))
    with pytest.raises(UndecidedError, match="default"):
        certify(kite_document(), prof)
    inst = _write(tmp_path, "kite.json", kite_document())
    p = _write(tmp_path, "table.json", prof)
    r = CliRunner().invoke(certify_command, [inst, p])
    assert r.exit_code == 3
    assert r.output.count("\n") == 1 and "would decide" in r.output
    assert CliRunner().invoke(certify_command, [inst, p, "-H", "1"]).exit_code in (0, 1)


def test_ngoal_default_is_untruncated_and_no_default_is_undecided() -> None:
    cert = certify(star3_document(), star3_profile())
    assert cert.horizon is None and cert.route == "structured" and cert.verdict == "fail"
    assert certify(star3_document(), star3_profile(), horizon=2).verdict == "pass"
    nodef = star3_profile()
    nodef["defender"].pop("default", None)
    nodef["defender"]["entries"] += [{"walk": ["s", "m"], "probabilities": [1, 0, 0]},
                                     {"walk": ["s", "m", "a"], "probabilities": [1, 0, 0]}]
    with pytest.raises(UndecidedError, match="would decide"):
        certify(star3_document(), nodef)


def test_progress_default_table_equals_the_progress_rule() -> None:
    inst = kite()
    r = inst.roles()
    for goal in (r.g1, r.g2):
        tm = table_minima(inst, r, TableRule(goal=goal, entries={}, default=ProgressRule(goal)))
        wm = walk_minima(inst, goal)
        same = goal == r.g1
        assert (tm.primary, tm.secondary) == ((wm.same, wm.other) if same else
                                              (wm.other, wm.same))


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(instances(graphs=weighted_graphs(min_nodes=3, max_nodes=5, max_weight=4)),
       st.data())
def test_table_minima_against_walk_formula_and_tree(doc: Doc, data: st.DataObject) -> None:
    """The table route's minimum over all walks: equal to WALKBR's closed form for an empty
    progress table; never above the tree route's minimum over walks of <= H steps."""
    inst = instance_from_json(doc)
    assume(inst.start not in inst.goals)
    r = inst.roles()
    goal = data.draw(st.sampled_from([r.g1, r.g2]))
    wm = walk_minima(inst, goal)
    tm = table_minima(inst, r, TableRule(goal=goal, entries={}, default=ProgressRule(goal)))
    assert {tm.primary, tm.secondary} == {wm.same, wm.other}
    # a random table: entries on a few walks of the 2-step tree, a random default
    from dppverify.tree_route.tree import build_tree
    tree = build_tree(inst, 2)
    walks = [tree.walk(p) for p in range(1, tree.n_prefixes)]
    chosen = data.draw(st.lists(st.sampled_from(walks), max_size=4, unique=True))
    entries = {tuple(w): Fraction(data.draw(st.integers(0, 4)), 4) for w in chosen}
    default: Fraction | ProgressRule = data.draw(st.sampled_from(
        [ProgressRule(goal), Fraction(0), Fraction(1), Fraction(1, 3)]))
    rule = TableRule(goal=goal, entries=entries, default=default)
    tm = table_minima(inst, r, rule)
    from dppverify.tree_route.best_response import attacker_best_response
    from dppverify.tree_route.tree_defender import tree_defender
    for h in (2, 4):
        t = build_tree(inst, h)
        td = tree_defender(t, r, rule)
        for theta in (1, 2):
            br = attacker_best_response(t, r, td, theta)
            assert tm.of(theta) <= br.value


def test_table_without_default_table_minima_refuses() -> None:
    inst = kite()
    r = inst.roles()
    with pytest.raises(UndecidedError):
        table_minima(inst, r, TableRule(goal=r.g1, entries={}, default=None))


# ----------------------------------------------------------------------------- value entry point
def test_value_entry_point_forms(tmp_path: Path) -> None:
    path = _write(tmp_path, "kite.json", kite_document())

    class Foreign:
        def to_json(self) -> Doc:
            return kite_document()

    for form in (kite_document(), path, Path(path), Foreign(), kite()):
        v = dppverify.value(form)
        assert v.horizon is None and v.structured is not None
        assert v.structured.value == Fraction(8, 5)
    assert dppverify.value(kite_document(), 1).tree.bracket.exact == 2  # type: ignore[union-attr]
    assert dppverify.value(kite_document(), math.inf).horizon is None
    assert dppverify.value(star3_document()).structured is not None


def test_value_cli_default_is_untruncated(tmp_path: Path) -> None:
    path = _write(tmp_path, "kite.json", kite_document())
    r = CliRunner().invoke(value_command, [path])
    assert r.exit_code == 0 and "V_H (H = inf) = 8/5 (≈ 1.6) exactly" in r.output


@pytest.mark.parametrize("h", [float("inf"), "inf", None])
def test_game_value_with_infinite_horizon_is_one_line(h: Any) -> None:
    with pytest.raises(HorizonError, match=r"dppverify\.value"):
        dppverify.game_value(kite_document(), h)


@pytest.mark.parametrize("goal", ["g1", "g2"])
def test_progress_default_means_progress_towards_the_tables_own_goal(goal: str) -> None:
    """docs/formats.md: ``"default": "progress"`` is the progress rule towards the table's
    ``goal`` (σ* only when that goal is g1); an empty table with it certifies exactly like
    the progress rule towards that goal, record by record."""
    from dppverify.game.examples import triangle_document, triangle_profile

    rule = certify(triangle_document(), dict(triangle_profile(),
                                             defender={"rule": "progress", "goal": goal}))
    table = certify(triangle_document(), dict(triangle_profile(), defender=_table(
        goal, [], "progress")))
    assert [(c.id, c.status, dict(c.numbers)) for c in rule.checks] == \
        [(c.id, c.status, dict(c.numbers)) for c in table.checks]
    assert rule.verdict == ("pass" if goal == "g1" else "fail")


def test_table_without_default_undefined_on_a_played_walk_is_refuted() -> None:
    prof = dict(kite_naive_profile(), defender=_table("g1", [(["s", "g1"], 1)]))
    cert = certify(kite_document(), prof)
    rec = cert.check("profile.wellformed")
    assert cert.verdict == "fail" and rec.status == "fail"
    assert "no entry for walk" in rec.message and "no default" in rec.message


def test_table_without_default_listing_every_walk_is_decided() -> None:
    """On a game whose walks are finitely many (a one-way kite), a table listing them all
    needs no default: the untruncated game is decided, as the tree route at H = 2 (the
    whole game) decides it."""
    doc = kite_document()
    doc["graph"]["directed"] = True
    doc["graph"]["edges"] += [{"source": "g1", "target": "g2", "weight": 3},
                              {"source": "g2", "target": "g1", "weight": 3}]
    walks = [["s", "g1"], ["s", "g2"], ["s", "a"], ["s", "a", "g1"], ["s", "a", "g2"]]
    for secondary, verdict in ((["s", "a", "g2"], "pass"), (["s", "g2"], "fail")):
        prof = dict(kite_naive_profile(), defender=_table(
            "g1", [(w, 1 if w[-1] in ("g1", "a") else 0) for w in walks]))
        prof["attacker"] = {"primary": [{"path": ["s", "g1"], "probability": 1}],
                            "secondary": [{"path": secondary, "probability": 1}]}
        inf, tree = certify(doc, prof), certify(doc, prof, horizon=2)
        assert inf.horizon is None and inf.route == "structured"
        assert [(c.id, c.status) for c in inf.checks if c.kind == "check"] == \
            [(c.id, c.status) for c in tree.checks if c.kind == "check"]
        assert (inf.check("pbne.attacker_br.secondary").status == "pass") == (verdict == "pass")


@pytest.mark.parametrize("horizon,route", [("inf", "auto"), (4, "tree"), (4, "structured"),
                                           (4, "both")])
def test_value_reads_the_same_whatever_the_route(horizon: Any, route: Any) -> None:
    r = dppverify.value(kite_document(), horizon, route=route)
    assert r.value == r.lower == r.upper == Fraction(8, 5)   # kite: V = 8/5


def test_ngoal_value_reads_the_bounds_whatever_the_route() -> None:
    from dppverify.game.examples import hub4_document

    for h, route in (("inf", "auto"), (5, "tree"), (5, "structured")):
        r = dppverify.value(hub4_document(), h, route=route)
        assert r.value == r.lower == r.upper == Fraction(12, 7), (h, route)  # not DP's 25/14


def test_api_certify_dispatches_on_the_number_of_goals(tmp_path: Path) -> None:
    """dppverify.certify, like dpp certify and dppverify.value, takes N-goal games too."""
    from dppverify.provenance import verify_provenance

    inst, prof = tmp_path / "i.json", tmp_path / "p.json"
    inst.write_text(json.dumps(star3_document()))
    prof.write_text(json.dumps(star3_profile()))
    for args in ((star3_document(), star3_profile()), (str(inst), str(prof)),
                 (inst, prof.read_bytes())):
        cert = dppverify.certify(*args, horizon=2)
        assert cert.verdict == "pass" and cert.check("value.U").status == "pass"
        assert cert.to_json()["game"] == {"horizon": 2, "truncated": True,
                                          "note": cert.to_json()["game"]["note"]}
    cert = dppverify.certify(str(inst), str(prof), horizon=2)
    assert verify_provenance(cert.to_json(), str(inst), str(prof)).ok
    via_api = dppverify.certify(star3_document(), star3_profile(), horizon=2)
    direct = certify(star3_document(), star3_profile(), horizon=2)
    assert [(c.id, c.status, c.message) for c in via_api.checks] == \
        [(c.id, c.status, c.message) for c in direct.checks]
