"""The N-goal structured route: a profile on the game of ANY length, without the walk tree.

A hand-made equilibrium with mixing (``_doc``/``_profile``: the two-goal triangle with a third,
pendant goal and a costly dead-end loop ``s–h``) passes on the untruncated game; each
corruption is refuted by the check that names it; the tree and the structured routes agree
(property test on random instances and profiles, at horizons where every best response fits).
"""

from __future__ import annotations

import copy
import json
from fractions import Fraction
from pathlib import Path
from typing import Any

import pytest
from click.testing import CliRunner
from hypothesis import assume, event, given
from hypothesis import strategies as st

from dppverify.certificate import Certificate
from dppverify.certify import certify
from dppverify.cli.certify import certify_command
from dppverify.errors import HorizonError, UndecidedError
from dppverify.game.examples import star3_document, star3_profile
from dppverify.game.instance import Instance, instance_from_json
from dppverify.game.profile import profile_from_json
from dppverify.routes import tree_fits
from dppverify.strategies import many_goal_instances, weighted_graphs
from dppverify.structured.table_br import table_defender, walk_best_response
from dppverify.tree_route.tree import count_prefixes
from tests.dppverify._helpers import make_doc

MAX_PREFIXES = 3000


def _doc() -> dict[str, Any]:
    """s–g1 (3), s–g2 (2), g2–g1 (2), s–g3 (1), s–h (10); prior 1/2, 3/10, 1/5."""
    return make_doc([("s", "g1", 3), ("s", "g2", 2), ("g2", "g1", 2), ("s", "g3", 1),
                     ("s", "h", 10)], "s", ["g1", "g2", "g3"], ["1/2", "3/10", "1/5"])


def _profile() -> dict[str, Any]:
    """Type 1 mixes s g1 (2/5) and s g2 (3/5) so that s g2 leaves belief 1/2 on g1 and g2;
    the Defender splits there, guards the revealed goal elsewhere and plays uniform off the
    table (every loop through h then costs each type at least 20/3)."""
    return {"format": "dpp-ngoal-profile/1", "goals": ["g1", "g2", "g3"],
            "attacker": [[{"path": ["s", "g1"], "probability": "2/5"},
                          {"path": ["s", "g2"], "probability": "3/5"}],
                         [{"path": ["s", "g2"], "probability": 1}],
                         [{"path": ["s", "g3"], "probability": 1}]],
            "defender": {"rule": "table",
                         "entries": [{"walk": ["s", "g1"], "probabilities": [1, 0, 0]},
                                     {"walk": ["s", "g2"], "probabilities": ["1/2", "1/2", 0]},
                                     {"walk": ["s", "g3"], "probabilities": [0, 0, 1]}],
                         "default": ["1/3", "1/3", "1/3"]},
            "value": {"U": 2}}


def _failed(cert: Certificate) -> set[str]:
    return {c.id for c in cert.checks if c.status == "fail"}


def test_the_equilibrium_passes_on_the_untruncated_game() -> None:
    cert = certify(_doc(), _profile(), horizon="inf")
    assert cert.passed, cert.failed()
    assert cert.route == "structured" and cert.horizon is None
    assert set(cert.not_run) == {"game.value.structured"}
    assert [c.id for c in cert.checks] == ["profile.wellformed", "value.U",
                                           "pbne.attacker_br", "pbne.defender_br",
                                           "pbne.sequential_rationality", "game.value"]
    assert cert.check("value.U").numbers["U"] == 2
    assert cert.check("game.value").numbers["V_H"] == 2
    assert all(c.route == "structured" and c.relies_on for c in cert.checks)
    assert "NG.4" in (cert.check("game.value").relies_on or "")
    # the same verdict on the tree at every horizon, and both routes agree check by check
    for h in (1, 3, 5):
        both = certify(_doc(), _profile(), horizon=h, route="both")
        assert both.passed and both.route == "both", both.failed()
    # JSON round trip of a structured certificate
    assert Certificate.from_json(cert.to_json()) == cert


@pytest.mark.parametrize(("name", "change", "check", "words"), [
    ("wrong mixing", lambda p: p["attacker"][0][0].update(probability="1/2")
     or p["attacker"][0][1].update(probability="1/2"), "pbne.sequential_rationality",
     "less than maximal belief, e.g. after ['s', 'g2']"),
    ("a detour", lambda p: p["attacker"][1][0].update(path=["s", "h", "s", "g2"]),
     "pbne.attacker_br", "type 2 (goal 'g2') has regret 19/3: walk ['s', 'g2']"),
    ("Defender on a non-maximal goal",
     lambda p: p["defender"]["entries"][2].update(probabilities=[1, 0, 0]),
     "pbne.sequential_rationality",
     "after ['s', 'g3']: belief ['0', '0', '1'], Defender ['1', '0', '0']"),
    ("wrong default", lambda p: p["defender"].update(default=[1, 0, 0]),
     "pbne.attacker_br", "type 2 (goal 'g2') has regret 1: walk ['s', 'h', 's', 'g2']"),
])
def test_each_corruption_is_refuted_by_its_check(name: str, change: Any, check: str,
                                                 words: str) -> None:
    p = copy.deepcopy(_profile())
    p["value"].pop("U")
    change(p)
    cert = certify(_doc(), p, horizon="inf")
    assert cert.verdict == "fail", name
    rec = cert.check(check)
    assert rec.status == "fail" and words in rec.message, (name, rec.message)


def test_wrong_mixing_fails_the_defender_checks_only() -> None:
    # type 1 is indifferent between its walks, so U stays 2 = V; at s g2 the belief now
    # favours g2 (3/10 against 1/4) and the split costs the Defender 2 · (3/10 − 11/40)
    p = _profile()
    p["attacker"][0] = [{"path": ["s", "g1"], "probability": "1/2"},
                        {"path": ["s", "g2"], "probability": "1/2"}]
    p["value"].pop("U")
    cert = certify(_doc(), p, horizon="inf")
    assert _failed(cert) == {"pbne.defender_br", "pbne.sequential_rationality"}
    assert cert.check("pbne.defender_br").numbers["regret"] == Fraction(1, 20)
    assert cert.check("game.value").status == "pass"


def test_the_hub_profile_is_refuted_on_the_untruncated_game_only() -> None:
    # H = 2: the tree route certifies it; any length: type b loops s m s m b unguarded.
    assert certify(star3_document(), star3_profile(), horizon=2, route="tree").passed
    cert = certify(star3_document(), star3_profile(), horizon=None, route="structured")
    rec = cert.check("pbne.attacker_br")
    assert rec.status == "fail" and "['s', 'm', 's', 'm', 'b'] (4 steps) costs 0" in rec.message
    assert rec.numbers["regret2"] == 1 and rec.numbers["regret1"] == 0
    # at H = 2 that 4-step walk is not in the game: the structured route decides nothing
    # (skipped, the verdict incomplete), never a FAIL of the truncated game
    cert = certify(star3_document(), star3_profile(), horizon=2, route="structured")
    rec = cert.check("pbne.attacker_br")
    assert rec.status == "skipped" and "4 steps > H = 2" in rec.message
    assert cert.verdict == "incomplete"
    # both routes at H = 2: the tree route's pass stands
    both = certify(star3_document(), star3_profile(), horizon=2, route="both")
    assert both.check("pbne.attacker_br").status == "pass" and both.passed
    # at H = 4 the tree sees the loop too and both routes fail it
    both = certify(star3_document(), star3_profile(), horizon=4, route="both")
    assert both.check("pbne.attacker_br").status == "fail"


def test_a_two_goal_walk_longer_than_h_does_not_refute_the_truncated_game() -> None:
    # the kite's naive profile: the secondary's better walk has 2 steps; at H = 1 it is not a
    # walk of the game, so the structured route skips the check and both routes pass it
    from dppverify import certify
    from dppverify.game.examples import kite_document, kite_naive_profile
    cert = certify(kite_document(), kite_naive_profile(), horizon=1, route="structured")
    assert cert.check("pbne.attacker_br.secondary").status == "skipped"
    assert cert.verdict == "incomplete"
    assert certify(kite_document(), kite_naive_profile(), horizon=1, route="both").passed
    assert certify(kite_document(), kite_naive_profile(), horizon=None).verdict == "fail"


def _dag_star() -> dict[str, Any]:
    """The hub instance with one-way arcs: no loop, finitely many walks."""
    d = star3_document()
    d["graph"]["directed"] = True
    d["graph"]["edges"] += [{"source": g, "target": "m", "weight": 1} for g in "abc"]
    return d


def test_without_a_default_the_route_says_why_unless_the_table_covers_every_walk() -> None:
    p = star3_profile()
    p["defender"].pop("default")
    p["defender"]["entries"] += [{"walk": ["s", "m"], "probabilities": [1, 0, 0]},
                                 {"walk": ["s", "m", "a"], "probabilities": [1, 0, 0]}]
    # issue 18: on the untruncated game this is undecided (exit 3), never a verdict
    with pytest.raises(UndecidedError, match="would decide"):
        certify(star3_document(), p, horizon="inf")
    cert = certify(star3_document(), p, horizon=4, route="structured")
    rec = cert.check("pbne.attacker_br")
    assert rec.status == "error" and cert.verdict == "error"
    assert "no default and its table has no entry for walk ['s', 'a']" in rec.message
    # on the one-way hub the table lists every walk of the game but s a: still undefined
    with pytest.raises(UndecidedError):
        certify(_dag_star(), p, horizon="inf")
    p["defender"]["entries"].append({"walk": ["s", "a"], "probabilities": [1, 0, 0]})
    cert = certify(_dag_star(), p, horizon="inf")
    assert cert.passed, cert.failed()
    # a profile walk where the Defender is undefined is ill-formed on both routes
    q = star3_profile()
    q["defender"].pop("default")
    for route in ("tree", "structured"):
        cert = certify(star3_document(), q, horizon=2, route=route)  # type: ignore[arg-type]
        rec = cert.check("profile.wellformed")
        assert rec.status == "fail" and "no entry for walk ['s', 'm'] and no default" in \
            rec.message


def test_route_choice_and_errors() -> None:
    with pytest.raises(HorizonError, match="needs a finite horizon"):
        certify(_doc(), _profile(), horizon="inf", route="tree")
    with pytest.raises(HorizonError, match="needs a finite horizon"):
        certify(_doc(), _profile(), horizon="inf", route="both")
    # auto: the tree when it fits, else the untruncated game
    # issue 18: no horizon is the untruncated game (structured); a horizon the tree
    assert certify(_doc(), _profile()).route == "structured"
    assert certify(_doc(), _profile(), horizon=2).route == "tree"
    cert = certify(_doc(), _profile(), max_prefixes=2)
    assert cert.route == "structured" and cert.horizon is None and cert.passed
    cert = certify(_doc(), _profile(), horizon=3, max_prefixes=2)
    assert cert.route == "structured" and cert.horizon == 3


def test_cli_routes(tmp_path: Path) -> None:
    i = tmp_path / "i.json"
    i.write_text(json.dumps(_doc()))
    p = tmp_path / "p.json"
    p.write_text(json.dumps(_profile()))
    r = CliRunner().invoke(certify_command, [str(i), str(p), "-H", "inf"])
    assert r.exit_code == 0, r.output
    assert r.output.startswith("verdict: PASS for the untruncated game (H = inf) (6/6 checks "
                               "passed; structured route")
    assert "not run: game.value.structured" in r.output
    r = CliRunner().invoke(certify_command, [str(i), str(p), "-H", "2", "--route", "both",
                                             "--json"])
    assert r.exit_code == 0 and Certificate.from_json(r.output).route == "both"
    r = CliRunner().invoke(certify_command, [str(i), str(p), "-H", "inf", "--route", "tree"])
    assert r.exit_code == 2 and r.output.count("\n") == 1 and "finite horizon" in r.output


# -- agreement of the routes on random instances and profiles -----------------------------

@st.composite
def _cases(draw: st.DrawFn) -> tuple[dict[str, Any], dict[str, Any]]:
    doc = draw(many_goal_instances(min_goals=3, max_goals=3,
                               graphs=weighted_graphs(min_nodes=4, max_nodes=5, max_weight=3)))
    inst = instance_from_json(doc)
    ids = inst.nodes

    def walk() -> list[int]:
        w = [inst.start]
        while not inst.is_goal(w[-1]):
            live = [u for u, _ in inst.succ[w[-1]] if inst.is_goal(u) or inst.hops[u] >= 0]
            if len(w) > 3:  # finish along fewest hops
                live = [u for u in live if inst.is_goal(u) or inst.hops[u] < inst.hops[w[-1]]]
            w.append(draw(st.sampled_from(sorted(live))))
        return w

    n = inst.n_goals
    attacker = []
    for _ in range(n):
        ws = {tuple(walk()) for _ in range(draw(st.integers(1, 2)))}
        probs = ([Fraction(1)] if len(ws) == 1 else
                 [p := draw(st.sampled_from([Fraction(1, 3), Fraction(1, 2)])), 1 - p])
        attacker.append([{"path": [ids[v] for v in w], "probability": str(q)}
                         for w, q in zip(sorted(ws), probs, strict=True)])
    vertices = [[int(i == j) for i in range(n)] for j in range(n)]
    dists = [*vertices, ["1/3"] * n, ["1/2", "1/2", 0]]
    prefixes = sorted({tuple(e["path"][:k]) for mix in attacker for e in mix
                       for k in range(2, len(e["path"]) + 1)})
    entries = [{"walk": list(pf), "probabilities": draw(st.sampled_from(dists))}
               for pf in prefixes if draw(st.booleans())]
    prof = {"format": "dpp-ngoal-profile/1", "attacker": attacker,
            "defender": {"rule": "table", "entries": entries,
                         "default": draw(st.sampled_from(dists))}}
    return doc, prof


@given(_cases())
def test_tree_and_structured_routes_agree(case: tuple[dict[str, Any], dict[str, Any]]) -> None:
    doc, prof = case
    inst: Instance = instance_from_json(doc)
    p = profile_from_json(prof, inst)
    assert p.wellformed, p.defects
    walks = [mw.walk for mix in p.attacker for mw in mix]
    tdef = table_defender(inst, p.defender.entries, p.defender.default, walks)
    depth = max(tdef.trie.depth)
    # every best response over all walks has at most depth + 1 + (non-goal nodes) steps
    full = depth + 1 + inst.n_nodes - inst.n_goals
    h0 = max(p.longest, inst.hops[inst.start])
    # at the profile's own horizon the tree's minimum is over fewer walks: regret no larger
    tree_cert = certify(inst, prof, horizon=h0, route="tree")
    struct = certify(inst, prof, horizon="inf", route="structured")
    for t in range(1, inst.n_goals + 1):
        key = f"regret{t}"
        tr, sr = (c.check("pbne.attacker_br").numbers[key] for c in (tree_cert, struct))
        assert tr is not None and sr is not None and tr <= sr
    for cid in ("profile.wellformed", "value.U", "pbne.defender_br",
                "pbne.sequential_rationality"):
        assert tree_cert.check(cid).status == struct.check(cid).status, cid
    for cid in ("value.U", "pbne.defender_br", "pbne.sequential_rationality"):
        assert dict(tree_cert.check(cid).numbers) == dict(struct.check(cid).numbers), cid
    assume(count_prefixes(inst, full) <= MAX_PREFIXES)
    # where every best response fits, the regrets are equal and so are the verdicts
    both = certify(inst, prof, horizon=full, route="both", max_prefixes=MAX_PREFIXES)
    disagree = [c.message for c in both.checks if c.message.startswith("the routes disagree")]
    assert not disagree, (json.dumps(doc), json.dumps(prof), disagree)
    tree_full = certify(inst, prof, horizon=full, route="tree", max_prefixes=MAX_PREFIXES)
    assert tree_full.verdict == struct.verdict
    event(f"verdict {struct.verdict}; attacker_br {struct.check('pbne.attacker_br').status}")
    for t in range(inst.n_goals):
        br = walk_best_response(tdef, t)
        assert br.value is not None and len(br.walk) - 1 <= full
        key = f"regret{t + 1}"
        assert tree_full.check("pbne.attacker_br").numbers[key] == struct.check(
            "pbne.attacker_br").numbers[key]


@given(many_goal_instances(min_goals=3, max_goals=4,
                       graphs=weighted_graphs(min_nodes=4, max_nodes=7, max_weight=3)),
       st.integers(1, 200))
def test_the_saturating_size_count_decides_like_the_exact_count(doc: dict[str, Any],
                                                                  limit: int) -> None:
    inst = instance_from_json(doc)
    for h in range(0, 9):
        assert tree_fits(inst, h, limit) == (count_prefixes(inst, h) <= limit), h
