"""ERRATA.md E1: the swapped reading of eq. (14) is exploitable; the smallest instance.

Re-derives the numbers quoted in ``proofs/ERRATA.md`` with the solver (profile) and the
checker (``dppverify.certify``), and compares them with the closed forms proved there:
``U* = b2 M + (b1 - b2) d(s0,g1)`` (XI2.md) and the Defender's exploit
``U* + sum over phase-II steps of w_t * (b1 - 2 b2) * (1 - sigma_t)`` when ``b1 > 2/3``,
``... * (2 b2 - b1) * sigma_t`` when ``b1 < 2/3`` (ERRATA.md, E1), both computed here
from the instance with networkx, independently of solver and checker.
"""

from __future__ import annotations

from fractions import Fraction

import networkx as nx

from proofs.checks.errata_search import (
    instance_doc,
    robust,
    search,
    swapped_outcome,
)

TRIANGLE = (("s", "g1", 3), ("s", "g2", 2), ("g1", "g2", 2))
TIED = (("s", "g1", 2), ("s", "g2", 2), ("g1", "g2", 1))
P7 = (Fraction(7, 10), Fraction(3, 10))
P3 = (Fraction(3, 5), Fraction(2, 5))


def _graph(edges: tuple[tuple[str, str, int], ...]) -> nx.Graph:
    g = nx.Graph()
    g.add_weighted_edges_from(edges)
    return g


def _closed_form(edges: tuple[tuple[str, str, int], ...], xi2: tuple[str, ...],
                 t_i: int, t_ii: int, prior: tuple[Fraction, Fraction]
                 ) -> tuple[Fraction, Fraction]:
    """(U*, exploit value) from the formulas of XI2.md and ERRATA.md E1."""
    g = _graph(edges)
    b1, b2 = prior
    d = dict(nx.all_pairs_dijkstra_path_length(g))
    m = min(d["s"][v] + d[v]["g1"] + d[v]["g2"] for v in g.nodes)
    u_star = b2 * m + (b1 - b2) * d["s"]["g1"]
    c = d["s"]["g1"]
    gain = Fraction(0)
    for t in range(1, len(xi2)):
        w = g[xi2[t - 1]][xi2[t]]["weight"]
        c_new = min(c, d[xi2[t]]["g1"])
        sigma = Fraction(c - c_new, w)
        c = c_new
        if t_i < t <= t_ii:
            gain += w * ((b1 - 2 * b2) * (1 - sigma) if b1 > 2 * b2 else (2 * b2 - b1) * sigma)
    return Fraction(u_star), u_star + gain


def test_errata_E1_triangle_numbers() -> None:
    for prior, u_quoted, exploit_quoted in ((P7, "12/5", "5/2"), (P3, "11/5", "12/5")):
        out = swapped_outcome(instance_doc(TRIANGLE, False, prior))
        assert out.exploitable
        assert out.phases == (0, 1, 1) and out.secondary_path == ("s", "g2")
        assert "pbne.defender_br" in out.failing and "pbne.sequential_rationality" in out.failing
        u_star, exploit = _closed_form(TRIANGLE, ("s", "g2"), 0, 1, prior)
        assert (out.U_star, out.exploit_value) == (u_star, exploit)
        assert (str(u_star), str(exploit)) == (u_quoted, exploit_quoted)


def test_errata_E1_triangle_is_smallest() -> None:
    found = search(P7, max_edges=3, max_weight=3)
    assert found is not None
    edges, directed, _ = found
    assert not directed and sorted(edges) == sorted(TRIANGLE)
    assert robust(edges, directed, P7)


def test_errata_E1_tied_triangle_depends_on_tie_break() -> None:
    default = swapped_outcome(instance_doc(TIED, False, P7))
    assert not default.exploitable and default.secondary_path == ("s", "g1")
    other = swapped_outcome(instance_doc(TIED, False, P7, ("s", "g2", "g1")))
    assert other.exploitable and other.secondary_path == ("s", "g2")
    u_star, exploit = _closed_form(TIED, ("s", "g2"), 0, 1, P7)
    assert (other.U_star, other.exploit_value) == (u_star, exploit)
    assert (str(u_star), str(exploit)) == ("17/10", "9/5")
    assert default.U_star == u_star  # both tie-breaks give the same value


def test_errata_E1_not_exploitable_at_two_thirds() -> None:
    out = swapped_outcome(instance_doc(TRIANGLE, False, (Fraction(2, 3), Fraction(1, 3))))
    assert not out.exploitable and out.failing == ()
