"""The checker's one door (``dppverify.game.inputs``): every form of an instance and a profile
gives the same typed objects, a networkx graph included, and what was parsed is what the
certificate's provenance hashes."""

from __future__ import annotations

import hashlib
import json
from pathlib import Path
from typing import Any

import networkx as nx
import pytest

from dppverify import certify, value
from dppverify.errors import InvalidInstanceError, ProfileError
from dppverify.game.examples import (
    kite_document,
    star3,
    star3_document,
    star3_profile,
    triangle,
    triangle_document,
    triangle_profile,
)
from dppverify.game.inputs import Parsed, as_instance, as_profile, read_instance, read_profile
from dppverify.game.instance import Instance


def _same_game(a: Instance, b: Instance) -> None:
    assert (a.nodes, a.directed, a.start, a.goals, a.prior, a.dist_to, a.hops, a.exact) == (
        b.nodes, b.directed, b.start, b.goals, b.prior, b.dist_to, b.hops, b.exact)
    assert [sorted(a.succ[v]) for v in range(a.n_nodes)] == [
        sorted(b.succ[v]) for v in range(b.n_nodes)]


def _graph(doc: dict[str, Any], attr: str = "weight") -> nx.Graph:
    g = nx.DiGraph() if doc["graph"].get("directed", False) else nx.Graph()
    g.add_nodes_from(n["id"] if not isinstance(n["id"], list) else tuple(n["id"])
                     for n in doc["graph"]["nodes"])
    for e in doc["graph"]["edges"]:
        g.add_edge(e["source"], e["target"], **{attr: e.get("weight", 1)})
    return g


class Foreign:
    """Any object that can write its JSON (as the solver's results can)."""

    def __init__(self, doc: dict[str, Any]) -> None:
        self.doc = doc

    def to_json(self) -> dict[str, Any]:
        return self.doc


def test_every_form_of_an_instance_gives_the_same_game(tmp_path: Path) -> None:
    doc = triangle_document()
    path = tmp_path / "t.json"
    path.write_text(json.dumps(doc), encoding="utf-8")
    inst = triangle()
    forms = [doc, json.dumps(doc).encode(), str(path), path, Foreign(doc), Parsed(inst),
             _graph(doc), inst]
    for form in forms:
        kw = ({"start": "s", "goals": ["g1", "g2"], "prior": ["7/10", "3/10"]}
              if isinstance(form, nx.Graph) else {})
        _same_game(as_instance(form, **kw), inst)
    assert as_instance(inst) is inst


def test_what_was_parsed_is_kept(tmp_path: Path) -> None:
    doc = triangle_document()
    path = tmp_path / "t.json"
    path.write_text(json.dumps(doc, indent=3), encoding="utf-8")
    assert read_instance(str(path)).data == path.read_bytes()
    assert read_instance(doc).data is doc
    assert read_instance(triangle()).data is None
    prof = triangle_profile()
    assert read_profile(prof, triangle()).data is prof
    assert read_profile(json.dumps(prof).encode(), triangle()).data == json.dumps(prof).encode()


def test_a_networkx_graph_is_certified_as_its_document_is() -> None:
    """The same certificate but for the provenance (a graph object has no bytes)."""
    doc = kite_document()
    g = _graph(doc, attr="cost")
    keys = {"start": "s", "goals": ["g1", "g2"], "prior": ["3/5", "2/5"], "weight": "cost"}
    cert = certify(g, triangle_profile(), **keys).to_json()
    want = certify(doc, triangle_profile()).to_json()
    assert cert["provenance"]["instance"] == {"sha256": None, "bytes": "object"}
    cert.pop("provenance")
    want.pop("provenance")
    assert cert == want
    assert value(g, **keys).value == value(doc).value


def test_networkx_grid_cells_and_n_goals() -> None:
    g = nx.grid_2d_graph(3, 4)  # cells (r, c), no weight attribute: weight 1
    inst = as_instance(g, start=(0, 1), goals=[(2, 0), (2, 3), (0, 3)],
                       prior=["1/2", "1/3", "1/6"])
    assert inst.n_goals == 3 and inst.nodes[inst.start] == (0, 1)
    assert inst.dist_to[0][inst.start] == 3
    assert not inst.directed
    unit = as_instance(nx.DiGraph([(0, 1, {"weight": 5}), (1, 2, {}), (2, 1, {})]), start=0,
                       goals=[2, 1], prior=["1/2", "1/2"], weight=None)
    assert unit.directed and unit.dist_to[0][unit.start] == 2


@pytest.mark.parametrize(("keys", "message"), [
    ({}, r"needs the keywords start=, goals= and prior= \(missing: start=, goals=, prior=\)"),
    ({"start": "s", "goals": ["g1", "g2"]}, r"\(missing: prior=\)"),
    ({"start": "s", "goals": "g1", "prior": ["1/2", "1/2"]}, "goals=: must be a list"),
    ({"start": "x", "goals": ["g1", "g2"], "prior": ["1/2", "1/2"]}, "start: unknown node"),
])
def test_a_networkx_graph_without_its_keywords_is_one_line(keys: dict[str, Any],
                                                           message: str) -> None:
    with pytest.raises(InvalidInstanceError, match=message) as info:
        as_instance(_graph(triangle_document()), **keys)
    assert "\n" not in str(info.value)


def test_networkx_refusals() -> None:
    multi = nx.MultiGraph([("s", "g1"), ("s", "g1")])
    with pytest.raises(InvalidInstanceError, match="MultiGraph may hold parallel edges"):
        as_instance(multi, start="s", goals=["g1", "s"], prior=["1/2", "1/2"])
    with pytest.raises(InvalidInstanceError, match="go with a networkx graph"):
        as_instance(triangle_document(), start="s")
    with pytest.raises(InvalidInstanceError, match="go with a networkx graph"):
        certify(triangle_document(), triangle_profile(), prior=["1/2", "1/2"])


def test_every_form_of_a_profile_gives_the_same_profile(tmp_path: Path) -> None:
    inst = star3()
    prof = star3_profile()
    path = tmp_path / "p.json"
    path.write_text(json.dumps(prof), encoding="utf-8")
    want = as_profile(prof, inst)
    for form in (json.dumps(prof).encode(), str(path), path, Foreign(prof), want,
                 Parsed(want)):
        got = as_profile(form, inst)
        assert (got.attacker, got.defender, got.format, got.stated) == (
            want.attacker, want.defender, want.format, want.stated)


def test_profile_refusals_are_one_line(tmp_path: Path) -> None:
    path = tmp_path / "p.json"
    path.write_text(json.dumps(triangle_profile()), encoding="utf-8")
    with pytest.raises(ProfileError, match=r'p\.json: "format" must be "dpp-ngoal-profile/1" '
                                           "for an instance with more than two goals") as info:
        as_profile(str(path), star3())
    assert info.value.stated.goals == ("g1", "g2")  # what it looks made for
    with pytest.raises(ProfileError, match="a dpp-profile/1 document must be a JSON object"):
        as_profile(b"[1]", triangle())
    with pytest.raises(ProfileError, match="got int"):
        as_profile(3, triangle())


def test_provenance_hashes_the_bytes_parsed(tmp_path: Path) -> None:
    inst_path, prof_path = tmp_path / "i.json", tmp_path / "p.json"
    inst_path.write_text(json.dumps(star3_document(), indent=2), encoding="utf-8")
    prof_path.write_text(json.dumps(star3_profile(), indent=2), encoding="utf-8")
    prov = certify(str(inst_path), str(prof_path), horizon=2).provenance
    assert prov is not None
    for name, path in (("instance", inst_path), ("profile", prof_path)):
        assert prov[name] == {"sha256": hashlib.sha256(path.read_bytes()).hexdigest(),
                              "bytes": "file"}
    obj = certify(star3(), star3_profile(), horizon=2).provenance  # any N: always recorded
    assert obj is not None and obj["instance"] == {"sha256": None, "bytes": "object"}
