"""No equilibrium is refuted or left open because it is not the paper's construction.

Equilibria built from the naive reference (tests/properties/_reference.py, imports neither
package): against σ* every primary walk of cost ``d(s0, g1)`` and every secondary simple path
of minimal cost are best responses (L1, L2, WALKBR: the minima over all walks); any mixture
of them has regret 0 for both types, and it is a weak PBNE exactly when σ* is greedy on the
Bayes belief at every reached prefix (checked here from eq. (2) and eq. (7), by the
reference). Mixtures are drawn on a grid of twelfths so that beliefs of exactly 1/2 occur.
Every such equilibrium must PASS the default ``certify`` (and the truncated game at its
length), whatever Lemma 5 and the phases say; a good share of them are not the paper's.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from fractions import Fraction
from typing import Any

from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from dppverify import certify
from dppverify.strategies import instances, weighted_graphs
from tests.properties._reference import Game, Node

HALF = Fraction(1, 2)
GRID = [Fraction(k, 12) for k in range(1, 12)]


def _mixtures(walks: Sequence[tuple[Node, ...]]) -> list[list[tuple[tuple[Node, ...], Fraction]]]:
    out: list[list[tuple[tuple[Node, ...], Fraction]]] = [[(w, Fraction(1))] for w in walks]
    for a, b in itertools.combinations(walks, 2):
        out += [[(a, q), (b, 1 - q)] for q in GRID]
    return out


def _is_pbne(game: Game, prim: list[tuple[tuple[Node, ...], Fraction]],
             sec: list[tuple[tuple[Node, ...], Fraction]]) -> bool:
    """σ* greedy on the Bayes belief at every reached prefix (regrets are 0 by construction)."""
    mass: dict[tuple[Node, ...], list[Fraction]] = {}
    for theta, mix in ((0, prim), (1, sec)):
        for w, p in mix:
            for t in range(2, len(w) + 1):
                mass.setdefault(w[:t], [Fraction(0), Fraction(0)])[theta] += p
    for p, (x1, x2) in mass.items():
        y1, y2 = game.b1 * x1, game.b2 * x2
        belief = y1 / (y1 + y2)
        s = game.sigma(p)[-1]
        if (belief > HALF and s != 1) or (belief < HALF and s != 0):
            return False
    return True


def _papers(game: Game, prim: list[tuple[tuple[Node, ...], Fraction]],
            sec: list[tuple[tuple[Node, ...], Fraction]]) -> bool:
    """True when the profile looks like the paper's construction: one secondary path ξ² with
    beliefs b1 on phase I, 1/2 on phase II and 0 on phase III (Lemma 5)."""
    if len(sec) != 1:
        return False
    xi = sec[0][0]
    t1, t2, _ = game.phases(xi)
    for t in range(len(xi)):
        p = xi[:t + 1]
        x1 = sum((q for w, q in prim if w[:t + 1] == p), Fraction(0))
        y1, y2 = game.b1 * x1, game.b2
        want = game.b1 if t <= t1 else (HALF if t <= t2 else Fraction(0))
        if y1 / (y1 + y2) != want:
            return False
    return True


def _doc(game: Game, prim: list[tuple[tuple[Node, ...], Fraction]],
         sec: list[tuple[tuple[Node, ...], Fraction]]) -> dict[str, Any]:
    def out(mix: list[tuple[tuple[Node, ...], Fraction]]) -> list[dict[str, Any]]:
        return [{"path": list(w), "probability": str(p)} for w, p in mix]
    return {"format": "dpp-profile/1", "goals": {"primary": game.g1, "secondary": game.g2},
            "defender": {"rule": "progress", "goal": game.g1},
            "attacker": {"primary": out(prim), "secondary": out(sec)}}


PRIORS = st.sampled_from([["3/5", "2/5"], ["2/5", "3/5"], ["7/10", "3/10"], ["5/9", "4/9"]])


@settings(max_examples=40, deadline=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(instances(graphs=weighted_graphs(min_nodes=3, max_nodes=6, max_weight=5), priors=PRIORS),
       st.data())
def test_equilibria_off_the_paper_pass(doc: dict[str, Any], data: st.DataObject) -> None:
    assume(doc["start"] not in doc["goals"])
    game = Game.from_doc(doc)
    c0 = game.d_to(game.start, game.g1)
    paths = list(game.simple_paths())
    prim_best = [p for p in paths if game.cost(p, 1) == c0][:3]
    _, sec_best = game.best_secondary()
    sec_best = sec_best[:3]
    candidates = [(a, b) for a in _mixtures(prim_best) for b in _mixtures(sec_best)
                  if _is_pbne(game, a, b)]
    assume(candidates)
    off = [c for c in candidates if not _papers(game, *c)]
    prim, sec = data.draw(st.sampled_from(off or candidates))
    prof = _doc(game, prim, sec)
    cert = certify(doc, prof)
    assert cert.verdict == "pass", [(c.id, c.message) for c in cert.failed()]
    longest = max(len(w) - 1 for w, _ in (*prim, *sec))
    truncated = certify(doc, prof, horizon=longest)
    assert truncated.verdict == "pass", [(c.id, c.message) for c in truncated.failed()]


def test_some_generated_equilibria_are_not_the_papers() -> None:
    """The generator reaches equilibria that Lemma 5 / the phases do not describe (the issue's
    first example: beliefs 1/9 on ξ², and its second: a mixing secondary)."""
    from tests.dppverify._helpers import make_doc
    doc = make_doc([(0, 1, 1), (2, 1, 2), (3, 1, 1), (2, 0, 2)], 0, [1, 2], ["2/5", "3/5"])
    game = Game.from_doc(doc)
    c0 = game.d_to(game.start, game.g1)
    prim_best = [p for p in game.simple_paths() if game.cost(p, 1) == c0]
    _, sec_best = game.best_secondary()
    found = [(a, b) for a in _mixtures(prim_best) for b in _mixtures(sec_best)
             if _is_pbne(game, a, b)]
    off_paper = 0
    for prim, sec in found:
        cert = certify(doc, _doc(game, prim, sec))
        assert cert.verdict == "pass"
        off_paper += cert.check("lemma.L5.induced_beliefs").status != "pass"
    assert off_paper >= 1
