"""Properties tying the solver to the independent checker on generated instances:
everything `solve` outputs is certified, its value is V_H, exact and float modes agree, and
the JSON documents (instance, profile, certificate) round-trip losslessly.

Example counts follow the hypothesis profile (DPP_HYPOTHESIS_PROFILE; docs/audit.md)."""

from __future__ import annotations

import json
from fractions import Fraction
from typing import Any

from hypothesis import given
from hypothesis import strategies as st

from dppverify import Certificate, certify, game_value, instance_from_json, value
from dppverify.formats.json_reading import parse_json
from dppverify.numbers import DEFAULT_REL_TOL
from dppverify.strategies import grid_worlds, instances, weighted_graphs
from solver import instance_from_json as solver_instance_from_json
from solver import instance_to_json
from solver.twogoal.equilibrium import paper_equilibrium
from tests.dppverify._helpers import tree_horizon
from tests.properties._reference import Game, key, to_float_doc

Doc = dict[str, Any]

exact_instances = st.one_of(
    instances(),
    instances(graphs=weighted_graphs(max_nodes=7, weights="fractions", max_weight=4)),
    instances(graphs=weighted_graphs(max_nodes=6, directed=True, strongly_connected=False)),
    grid_worlds(max_size=4, max_cells=9),
    grid_worlds(max_size=3, weights="integers", max_density=0.4),
)


def _profile(doc: Doc) -> Doc:
    """The solver's profile as the checker reads it: through JSON text."""
    text = json.dumps(paper_equilibrium(solver_instance_from_json(doc)).to_json())
    return parse_json(text)  # type: ignore[no-any-return]


@given(exact_instances)
def test_everything_solve_outputs_is_certified_and_its_value_is_V_H(doc: Doc) -> None:
    profile = _profile(doc)
    cert = certify(doc, profile, trials=2)  # the untruncated game
    assert cert.passed, [(c.id, c.message) for c in cert.failed()]
    u = Fraction(profile["value"]["U"])
    assert value(doc).structured.value == u  # type: ignore[union-attr]
    # the game truncated at the profile's length (the walk tree) certifies it too, and its
    # V_H recomputed from the instance alone (compact LP + exact bracket), not read back
    h = tree_horizon(doc, profile)
    assert certify(doc, profile, trials=2, horizon=h).passed
    v = game_value(instance_from_json(doc), h)
    assert v.bracket.exact == u
    assert abs(v.lp.value - float(u)) <= 1e-7 * max(1.0, float(u))
    # U* = b2·M + (b1 − b2)·d(s0,g1) (proofs/THM.md, THM.4) from the reference model
    g = Game.from_doc(doc)
    assert u == g.b2 * g.M + (g.b1 - g.b2) * g.d_to(g.start, g.g1)


@given(exact_instances)
def test_exact_and_float_modes_agree(doc: Doc) -> None:
    exact = paper_equilibrium(solver_instance_from_json(doc))
    fdoc = to_float_doc(doc)
    approx = paper_equilibrium(solver_instance_from_json(fdoc))
    assert not approx.numbers.exact and exact.numbers.exact
    for name in ("U1", "U2", "U", "U_bar", "VoI"):
        a, b = float(getattr(exact, name)), float(getattr(approx, name))
        assert abs(a - b) <= 1e-9 * max(1.0, abs(a)), name
    cert = certify(fdoc, parse_json(json.dumps(approx.to_json())), exact=False, trials=1)
    assert cert.passed, [(c.id, c.message) for c in cert.failed()]
    assert not cert.exact and cert.tolerance == DEFAULT_REL_TOL


@given(exact_instances)
def test_json_round_trips_are_lossless(doc: Doc) -> None:
    # instance: document -> solver Instance -> document -> Instance is a fixed point
    inst = solver_instance_from_json(json.dumps(doc))
    again = solver_instance_from_json(json.dumps(instance_to_json(inst)))
    assert instance_to_json(again) == instance_to_json(inst)
    assert {key(n["id"]) for n in instance_to_json(inst)["graph"]["nodes"]} == {
        key(n["id"]) for n in doc["graph"]["nodes"]}
    n_nodes = instance_from_json(json.dumps(instance_to_json(inst))).n_nodes
    assert n_nodes == len(doc["graph"]["nodes"])
    # profile: text -> dict -> text is the identity; the checker reads the same numbers
    profile = paper_equilibrium(inst).to_json()
    text = json.dumps(profile)
    assert json.dumps(json.loads(text)) == text
    assert paper_equilibrium(again).to_json() == profile
    # certificate: to_json -> text -> from_json -> to_json is the identity
    cert = certify(doc, parse_json(text), trials=1)
    cert_text = json.dumps(cert.to_json())
    back = Certificate.from_json(cert_text)
    assert back == cert
    assert json.dumps(back.to_json()) == cert_text
