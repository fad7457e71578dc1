"""Checks for proofs/HORIZON.md (V_H non-increasing, V_H >= U*, V_H = U* for H >= H*)."""

from __future__ import annotations

from fractions import Fraction

import networkx as nx
import sympy as sp

from dppverify import game_value, instance_from_json
from proofs.checks._sym import is_nonneg, is_zero, nonneg, pos

e = sp.Symbol("e", nonnegative=True)
B2 = sp.Symbol("b2", positive=True)  # b1 = b2 + e >= b2 > 0 (the identities are homogeneous,
B1 = B2 + e  # so normalising b1 + b2 = 1 changes nothing)


def test_HORIZON_sigma_star_attains_the_defender_maximum_on_every_reached_prefix() -> None:
    sigma = sp.Symbol("sigma", real=True)
    p_ii = B2 / B1
    classes = (  # (x1, x2, sigma*) per class of reached prefix
        (1, 1, 1),  # phase I
        (p_ii, 1, sigma),  # phase II: any sigma
        (0, 1, 0),  # phase III
        (1 - p_ii, 0, 1),  # psi after xi^{1,I}
        (p_ii, 0, 1),  # psi after xi^{1,II}
    )
    for x1, x2, s in classes:
        top = sp.Max(sp.simplify(B1 * x1), sp.simplify(B2 * x2))
        assert is_zero(sp.simplify(top - (s * B1 * x1 + (1 - s) * B2 * x2)))


def test_HORIZON_lower_bound_algebra() -> None:
    c0, u2star, f1, f2 = nonneg("c0 U2star f1 f2")  # min over W_H >= global minima (f >= 0)
    p1, p2 = pos("p1 p2")
    lower = p1 * (c0 + f1) + p2 * (u2star + f2)
    assert is_nonneg(lower - (p1 * c0 + p2 * u2star))


EDGES = (("g1", "s", 1), ("s", "a", 1), ("a", "g2", 1))
PRIOR = (Fraction(7, 10), Fraction(3, 10))


def test_HORIZON_smallest_example_value_drops_to_u_star() -> None:
    g = nx.Graph()
    g.add_weighted_edges_from(EDGES)
    d = dict(nx.all_pairs_dijkstra_path_length(g))
    b1, b2 = PRIOR
    m = min(d["s"][v] + d[v]["g1"] + d[v]["g2"] for v in g.nodes)
    u_star = b2 * m + (b1 - b2) * d["s"]["g1"]
    v1_by_hand = 1 * max(b1, b2) + b2 * d["g1"]["g2"]  # H = 1: only s -> g1
    assert (u_star, v1_by_hand) == (Fraction(13, 10), Fraction(8, 5))
    doc = {"graph": {"directed": False, "nodes": [{"id": v} for v in ("s", "a", "g1", "g2")],
                     "edges": [{"source": u, "target": v, "weight": w} for u, v, w in EDGES]},
           "start": "s", "goals": ["g1", "g2"], "prior": [str(b1), str(b2)]}
    inst = instance_from_json(doc)
    values = [game_value(inst, h).bracket for h in (1, 2, 3)]
    assert all(v.closed for v in values)
    assert [v.exact for v in values] == [v1_by_hand, u_star, u_star]


def test_HORIZON_own_length_does_not_suffice_the_kite() -> None:
    """H.5: the naive profile is a PBNE of the game truncated at its own length, not of the
    game; the secondary's detour costs 1 and V_inf = 8/5 (also for the stretched kites)."""
    from dppverify import certify, value
    from dppverify.game.examples import kite_document, kite_naive_profile

    for k in (1, 2, 4):
        w = str(Fraction(1, k))
        edges = [("s", "g1", 2), ("s", "g2", 2), ("s", "a1", w)]
        edges += [(f"a{i}", f"a{i + 1}", w) for i in range(1, k)]
        edges += [(f"a{k}", "g1", 1), (f"a{k}", "g2", 1)]
        nodes = ["s", "g1", "g2", *(f"a{i}" for i in range(1, k + 1))]
        doc = {"graph": {"directed": False, "nodes": [{"id": v} for v in nodes],
                         "edges": [{"source": u, "target": v, "weight": x}
                                   for u, v, x in edges]},
               "start": "s", "goals": ["g1", "g2"], "prior": ["3/5", "2/5"]}
        if k == 1:
            assert instance_from_json(doc).n_nodes == instance_from_json(kite_document()).n_nodes
        prof = kite_naive_profile()
        assert certify(doc, prof, horizon=1).verdict == "pass"
        cert = certify(doc, prof)
        assert cert.verdict == "fail" and cert.horizon is None
        assert cert.check("pbne.attacker_br.secondary").numbers["min_over_walks"] == 1
        v = value(doc).structured
        assert v is not None and v.value == Fraction(8, 5)
