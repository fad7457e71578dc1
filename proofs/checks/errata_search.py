"""Search for a smallest instance where the swapped reading of eq. (15) is exploitable.

ERRATA.md, erratum E1. The sentence before eq. (15) of the paper gives ``xi^{1,I}`` the
probability ``b2/b1`` and ``xi^{1,II}`` the probability ``1 - b2/b1`` (swapped); eq. (15)
gives the reverse. For each candidate instance, in order of size, this script

1. builds the equilibrium profile with ``solver.solve`` (eq. 15 mixing),
2. swaps the two primary probabilities (the sentence's reading), and
3. certifies the swapped profile with ``dppverify.certify``.

The reading is *exploitable* on an instance when the certificate of the swapped profile
fails ``pbne.defender_br`` (the Defender has a strictly profitable deviation); the exploit
value is that check's ``best_response`` (``max_sigma U(sigma, gamma_swapped)``).

Size order: fewest nodes, then fewest edges (an undirected edge counts once, a directed arc
once), then smallest largest weight, then smallest weight sum, then undirected before
directed, then lexicographic weights. Weights are integers ``1..max_weight``. The search
is over 3-node instances (2 nodes cannot work: ``s0`` is then a goal and ``T = 0``).
An instance is reported *robust* when the swapped reading is exploitable under every order
of the node list (the solver's tie-break among best responses ``xi2`` uses that order).

Run: ``.venv/bin/python proofs/checks/errata_search.py`` (a few seconds).
"""

from __future__ import annotations

import itertools
from collections.abc import Iterator
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import dppverify
from solver.errors import DPPError
from solver.game.instance_reading import instance_from_json
from solver.twogoal.equilibrium import paper_equilibrium

__all__ = ["Outcome", "candidates", "instance_doc", "robust", "search", "some_order",
           "swapped_outcome"]

NODES = ("s", "g1", "g2")
PAIRS_UNDIRECTED = (("s", "g1"), ("s", "g2"), ("g1", "g2"))
PAIRS_DIRECTED = tuple((u, v) for u in NODES for v in NODES if u != v)


@dataclass(frozen=True)
class Outcome:
    """The swapped reading on one instance (``None`` fields: not applicable)."""

    exploitable: bool
    U_star: Fraction | None
    exploit_value: Fraction | None
    failing: tuple[str, ...]
    secondary_path: tuple[Any, ...] | None
    phases: tuple[int, int, int] | None


def instance_doc(edges: tuple[tuple[str, str, int], ...], directed: bool,
                 prior: tuple[Fraction, Fraction] = (Fraction(7, 10), Fraction(3, 10)),
                 node_order: tuple[str, ...] = NODES) -> dict[str, Any]:
    """The instance JSON document of a 3-node candidate.

    Examples
    --------
    >>> doc = instance_doc((("s", "g1", 3), ("s", "g2", 2), ("g1", "g2", 2)), False)
    >>> doc["start"], doc["goals"], doc["prior"]
    ('s', ['g1', 'g2'], ['7/10', '3/10'])
    """
    return {
        "graph": {"directed": directed, "multigraph": False, "graph": {},
                  "nodes": [{"id": v} for v in node_order],
                  "edges": [{"source": u, "target": v, "weight": w} for u, v, w in edges]},
        "start": "s", "goals": ["g1", "g2"], "prior": [str(prior[0]), str(prior[1])],
    }


def swapped_outcome(doc: dict[str, Any]) -> Outcome:
    """Solve ``doc``, swap the two primary probabilities and certify the swapped profile.

    Examples
    --------
    >>> doc = instance_doc((("s", "g1", 3), ("s", "g2", 2), ("g1", "g2", 2)), False)
    >>> o = swapped_outcome(doc)
    >>> o.exploitable, str(o.U_star), str(o.exploit_value)
    (True, '12/5', '5/2')
    """
    try:
        eq = paper_equilibrium(instance_from_json(doc))
    except DPPError:
        return Outcome(False, None, None, (), None, None)
    profile = eq.to_json()
    primary = profile["attacker"]["primary"]
    phases = (eq.phases.t_I, eq.phases.t_II, eq.phases.T)
    if len(primary) != 2:  # one branch path (or b2/b1 = 1): nothing to swap here
        return Outcome(False, Fraction(eq.U), None, (), eq.secondary_path, phases)
    p0, p1 = primary[0]["probability"], primary[1]["probability"]
    primary[0]["probability"], primary[1]["probability"] = p1, p0
    cert = dppverify.certify(doc, profile)
    failing = tuple(r.id for r in cert.checks if r.status == "fail")
    numbers = cert.check("pbne.defender_br").numbers  # the Defender's greedy best response
    exploit = numbers.get("best_response", numbers.get("max_sigma_U"))
    return Outcome("pbne.defender_br" in failing, Fraction(eq.U),
                   Fraction(exploit) if exploit is not None else None, failing,
                   eq.secondary_path, phases)


def candidates(max_edges: int, max_weight: int) -> Iterator[tuple[tuple[tuple[str, str, int],
                                                                       ...], bool]]:
    """3-node candidates in size order (see the module docstring)."""
    for k in range(1, max_edges + 1):
        for top in range(1, max_weight + 1):
            batch = []
            for directed, pairs in ((False, PAIRS_UNDIRECTED), (True, PAIRS_DIRECTED)):
                for chosen in itertools.combinations(pairs, k):
                    for ws in itertools.product(range(1, top + 1), repeat=k):
                        if max(ws) != top:
                            continue
                        edges = tuple((u, v, w) for (u, v), w in zip(chosen, ws, strict=True))
                        batch.append((sum(ws), directed, ws, edges))
            batch.sort(key=lambda x: (x[0], x[1], x[2]))
            for _, directed, _, edges in batch:
                yield edges, directed


def robust(edges: tuple[tuple[str, str, int], ...], directed: bool,
           prior: tuple[Fraction, Fraction]) -> bool:
    """Exploitable under every node order (every tie-break of the solver)?"""
    return all(swapped_outcome(instance_doc(edges, directed, prior, order)).exploitable
               for order in itertools.permutations(NODES))


def some_order(edges: tuple[tuple[str, str, int], ...], directed: bool,
               prior: tuple[Fraction, Fraction]) -> Outcome | None:
    """The outcome under the first node order (tie-break) that makes the reading exploitable."""
    for order in itertools.permutations(NODES):
        out = swapped_outcome(instance_doc(edges, directed, prior, order))
        if out.exploitable:
            return out
    return None


def search(prior: tuple[Fraction, Fraction] = (Fraction(7, 10), Fraction(3, 10)),
           max_edges: int = 4, max_weight: int = 3, *, need_robust: bool = False
           ) -> tuple[tuple[tuple[str, str, int], ...], bool, Outcome] | None:
    """The first candidate (size order) where the swapped reading is exploitable."""
    for edges, directed in candidates(max_edges, max_weight):
        out = swapped_outcome(instance_doc(edges, directed, prior))
        if out.exploitable and (not need_robust or robust(edges, directed, prior)):
            return edges, directed, out
    return None


def main() -> None:
    """Print the smallest instances (tie-break dependent and robust) for a few priors."""
    prior7 = (Fraction(7, 10), Fraction(3, 10))
    for edges, directed in candidates(4, 3):
        out = some_order(edges, directed, prior7)
        if out is not None:
            print(f"prior 7/10 [some tie-break]: {'directed' if directed else 'undirected'} "
                  f"{edges}; xi2 = {out.secondary_path}; U* = {out.U_star}, "
                  f"exploit = {out.exploit_value}")
            break
    for prior in ((Fraction(7, 10), Fraction(3, 10)), (Fraction(3, 5), Fraction(2, 5))):
        for need_robust in (False, True):
            found = search(prior, need_robust=need_robust)
            label = "robust" if need_robust else "solver tie-break"
            if found is None:
                print(f"prior {prior[0]}: none found ({label})")
                continue
            edges, directed, out = found
            print(f"prior {prior[0]}/{prior[1]} [{label}]: "
                  f"{'directed' if directed else 'undirected'} {edges}; xi2 = "
                  f"{out.secondary_path}, phases {out.phases}; U* = {out.U_star}, "
                  f"exploit = {out.exploit_value}; failing {out.failing}; "
                  f"robust = {robust(edges, directed, prior)}")


if __name__ == "__main__":
    main()
