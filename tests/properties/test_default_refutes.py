"""The default ``certify`` (the untruncated game) refutes wrong profiles.

- The naive profile — each type walks a shortest path to its own goal, the Defender plays σ* —
  is refuted whenever its value differs from the solver's ``U*`` (it is then no equilibrium:
  an equilibrium's payoff is the game's value).
- Every mutant solver of ``tests/mutants/solvers.py`` is refuted on the first generated
  instance where its output differs from the real solver's (other Attacker strategies, or a
  payoff that is not ``U*``).

The solver is used only as a reference here; ``dppverify`` never imports it.
"""

from __future__ import annotations

import heapq
import json
from fractions import Fraction
from typing import Any

import pytest
from hypothesis import HealthCheck, Phase, assume, given, settings
from hypothesis import strategies as st

from dppverify import certify
from dppverify.audit import audit_instances
from dppverify.errors import ProfileError
from dppverify.formats.json_reading import parse_json
from dppverify.strategies import instances, priors, weighted_graphs
from solver.adapter import solve_json
from tests.mutants.solvers import MUTANTS
from tests.properties._reference import Game, Node

Doc = dict[str, Any]


def _shortest_walk(game: Game, goal: Node) -> tuple[Node, ...] | None:
    """A shortest path from s0 to ``goal`` cut at the first goal it reaches (a walk of the
    game), by Dijkstra over predecessors (plain, independent of both packages)."""
    dist: dict[Node, Fraction] = {game.start: Fraction(0)}
    prev: dict[Node, Node] = {}
    heap: list[tuple[Fraction, int, Node]] = [(Fraction(0), 0, game.start)]
    k = 0
    while heap:
        d, _, v = heapq.heappop(heap)
        if d != dist.get(v) or v == goal:
            continue
        for u, w in game.succ[v]:
            if d + w < dist.get(u, Fraction(10**18)):
                dist[u], prev[u] = d + w, v
                k += 1
                heapq.heappush(heap, (d + w, k, u))
    if goal not in dist:
        return None
    path = [goal]
    while path[-1] != game.start:
        path.append(prev[path[-1]])
    walk = path[::-1]
    cut = next(i for i, v in enumerate(walk) if game.is_goal(v))
    return tuple(walk[:cut + 1])


DENSE = instances(graphs=weighted_graphs(min_nodes=4, max_nodes=8, max_weight=4,
                                         max_extra_edges=10),
                  priors=priors(allow_half=False)).filter(
    lambda d: d["start"] not in d["goals"])
"""Denser weighted graphs, start off the goals: where the naive profile more often loses."""


def _json_node(doc: Doc, v: Node) -> Any:
    for n in doc["graph"]["nodes"]:
        nid = n["id"]
        if (tuple(nid) if isinstance(nid, list) else nid) == v:
            return nid
    raise KeyError(v)


@settings(max_examples=80, deadline=None, database=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(st.one_of(audit_instances(max_nodes=7), DENSE))
def test_naive_shortest_path_profile_is_refuted_when_its_value_is_not_the_games(doc: Doc) -> None:
    game = Game.from_doc(doc)
    walks = [_shortest_walk(game, g) for g in (game.g1, game.g2)]
    assume(all(w is not None for w in walks))
    prim, sec = walks
    assert prim is not None and sec is not None
    prof = {"format": "dpp-profile/1",
            "goals": {"primary": _json_node(doc, game.g1), "secondary": _json_node(doc, game.g2)},
            "defender": {"rule": "progress", "goal": _json_node(doc, game.g1)},
            "attacker": {"primary": [{"path": [_json_node(doc, v) for v in prim],
                                      "probability": 1}],
                         "secondary": [{"path": [_json_node(doc, v) for v in sec],
                                        "probability": 1}]}}
    u_star = Fraction(parse_json_value(solve_json(doc)["value"]["U"]))
    u_naive = game.b1 * Fraction(game.cost(prim, 1)) + game.b2 * Fraction(game.cost(sec, 2))
    cert = certify(doc, prof)
    assert cert.check("value.U").numbers["U"] == u_naive
    if u_naive != u_star:
        assert cert.verdict == "fail", (doc, u_naive, u_star)
    else:  # then it is an equilibrium exactly when the default certify passes; never undecided
        assert cert.verdict in ("pass", "fail")


def parse_json_value(x: Any) -> Fraction:
    return Fraction(str(x))


class _Differs(Exception):
    def __init__(self, doc: Doc, profile: Doc) -> None:
        super().__init__("differs")
        self.doc, self.profile = doc, profile


def _value(doc: Doc, profile: Doc) -> Fraction | None:
    """The profile's payoff ``U`` walk by walk (None when the document is not a profile).

    Only the checker's refusal of a document that is not a profile is a difference; any
    other exception is a checker crash, and fails the test instead of counting as a caught
    mutant (a refutation is the only way to catch one)."""
    try:
        rec = certify(doc, profile, route="structured").check("value.U")
    except ProfileError:
        return None
    u = rec.numbers.get("U")
    return None if rec.status == "skipped" or u is None else Fraction(u)


def _attacker(profile: Doc) -> Any:
    """The Attacker's mixed strategies, comparable (probabilities as fractions)."""
    def mix(items: list[Doc]) -> frozenset[tuple[str, Fraction]]:
        return frozenset((repr(i["path"]), Fraction(str(i["probability"]))) for i in items
                         if Fraction(str(i["probability"])) != 0)
    att = profile.get("attacker", {})
    return mix(att.get("primary", [])), mix(att.get("secondary", []))


def _first_difference(mutant: Any, examples: int = 300) -> tuple[Doc, Doc] | None:
    """The first instance of the audit's distribution (derandomized) on which the mutant's
    output differs from the solver's: its Attacker strategies differ, or its payoff is not
    the solver's value ``U*`` (or it is not a readable profile). A different Defender rule
    with the same Attacker and payoff may be another equilibrium (at prior 1/2 σ* towards
    either goal is one, footnote 2), so a different Defender rule alone is not enough."""
    @settings(max_examples=examples, database=None, deadline=None, derandomize=True,
              phases=[Phase.generate], suppress_health_check=list(HealthCheck))
    @given(audit_instances(max_nodes=8))
    def search(doc: Doc) -> None:
        try:
            theirs = parse_json(json.dumps(mutant(doc)))
        except Exception:
            return
        ours = solve_json(doc)
        u_star = Fraction(str(ours["value"]["U"]))
        if _attacker(theirs) != _attacker(ours) or _value(doc, theirs) != u_star:
            raise _Differs(doc, theirs)

    try:
        search()
    except _Differs as found:
        return found.doc, found.profile
    return None


@pytest.mark.parametrize("name", list(MUTANTS))
def test_every_mutant_is_refuted_on_its_first_differing_instance(name: str) -> None:
    found = _first_difference(MUTANTS[name])
    assert found is not None, f"{name}: its payoff never differs from U* in 300 examples"
    doc, profile = found
    cert = certify(doc, profile)
    assert cert.verdict == "fail", (name, doc, [(c.id, c.message) for c in cert.failed()])
