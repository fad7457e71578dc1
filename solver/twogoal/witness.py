"""The solver's ``dpp-witness/1`` for the paper's equilibrium (``docs/formats.md`` §5), from its
own fields: what ``dpp solve --witness`` writes for the trusted kernel (proofs/KERNEL.md).

σ* is the progress rule towards ``g1`` (the empty table with the progress default), so the
witness is the two distance fields the solver already has, the primary type's potential
``d(s0, g1)`` at the start (``φ(v, c) = c``), and for the secondary type the two labels of
KERNEL K.3: ``P(v)``, the cheapest walk from ``v`` to its first goal with every step paid in
full and the terminal cost ``d(·, g2)``, and ``Q(v) = min(d(v, g1) + P(v), min over arcs of
w + Q(u))``; the secondary's potential at the start is ``min(P(s0), Q(s0) − d(s0, g1))``. All
are integer numerators over the network's common denominator.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from solver.game.instance import Instance
from solver.game.profile_writing import WITNESS_FORMAT
from solver.graph.distances import sources_to


def _labels(field: np.ndarray) -> list[int | None]:
    return [None if x == math.inf else int(x) for x in field.tolist()]


def twogoal_witness(inst: Instance, *, instance_sha256: str, profile_sha256: str
                    ) -> dict[str, Any]:
    """The witness of σ* (progress towards the primary goal) on an exact two-goal instance.

    Examples
    --------
    >>> from solver.game.instance import triangle
    >>> w = twogoal_witness(triangle(), instance_sha256="0" * 64, profile_sha256="1" * 64)
    >>> w["denominator"], w["distances"], w["types"]
    (1, [[3, 2, 0], [2, 0, 2]], [{'trie': [3]}, {'trie': [1], 'P': [2, 0, 2], 'Q': [4, 2, 2]}])
    """
    if not inst.network.numbers.exact:
        raise ValueError("the trusted kernel decides exact games only (this one is float)")
    one = inst.primary_goal_index
    d1, d2 = inst.dist_to[one], inst.dist_to[1 - one]
    goals = inst.targets
    s0 = inst.s0
    init = np.full(inst.network.n_nodes, np.inf, dtype=d2.dtype)
    init[list(goals)] = d2[list(goals)]
    P = sources_to(inst.network, init, stop=goals)
    Q = sources_to(inst.network, d1 + P, stop=goals)  # inf where either is
    phi = min(P[s0], Q[s0] - d1[s0])
    types: list[dict[str, Any]] = [{"trie": [int(d1[s0])]},
                                   {"trie": [int(phi)], "P": _labels(P), "Q": _labels(Q)}]
    return {"format": WITNESS_FORMAT, "instance_sha256": instance_sha256,
            "profile_sha256": profile_sha256, "denominator": inst.network.numbers.denominator,
            "distances": [_labels(f) for f in inst.dist_to],
            "types": types if one == 0 else types[::-1]}
