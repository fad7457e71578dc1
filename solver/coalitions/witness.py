"""The solver's ``dpp-witness/1`` for the guarantee rule (``docs/formats.md`` §5, proofs/KERNEL.md
K.7), from the construction's own fields: what ``dpp solve --witness`` writes for N goals.

- ``m``: the written rule's labels ``m_a(v)`` (:meth:`CoalitionEquilibrium.rule_values`, the
  certified fixpoint), integers over the denominator ``S`` (the network's, times what the
  labels need).
- ``covers``: for every vertex ``λ`` of the packing polytope that the DP's equations do not
  imply (:func:`~solver.coalitions.vertex_tables.packing_vertices`), the cheapest cover of
  ``y_λ`` by the normals (:func:`~solver.coalitions.vertex_tables.vertex_table`) at each
  non-goal node, each distinct one once.
- ``steps``: at every prefix of the profile's walks (in the profile's order), σ of the rule
  (:func:`~solver.coalitions.guarantee_rule.rule_step`) and, per lexicographic stage, a dual
  found by complementary slackness (:func:`stage_dual`).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from fractions import Fraction
from typing import Any

import numpy as np

from solver.coalitions.construction import CoalitionEquilibrium, arc_graph
from solver.coalitions.guarantee_rule import priority_order, rule_step
from solver.coalitions.normal_dp import normal_dp
from solver.coalitions.vertex_tables import Normal, packing_vertices, vertex_table
from solver.game.profile_writing import WITNESS_FORMAT
from solver.numbers import solve_exact

Labels = list[list[Fraction | None]]


def guarantee_witness(eq: CoalitionEquilibrium, *, instance_sha256: str, profile_sha256: str
                      ) -> dict[str, Any]:
    """The witness of the construction's guarantee rule (KERNEL K.7).

    Examples
    --------
    >>> from dppverify.game.examples import star3_document
    >>> from solver.coalitions.construction import coalition_equilibrium
    >>> from solver.game.instance_reading import instance_from_json
    >>> w = guarantee_witness(coalition_equilibrium(instance_from_json(star3_document())),
    ...                       instance_sha256="0" * 64, profile_sha256="1" * 64)
    >>> w["denominator"], w["guarantee"]["m"][0], len(w["guarantee"]["steps"])
    (1, [2, 1, 0, 2, 2], 4)
    """
    inst, fix = eq.instance, eq.fixpoint
    assert fix is not None
    normals = fix.system.normals
    n, den = inst.network.n_nodes, inst.denominator
    cols = _rule_labels(eq)
    rows: Labels = [[cols[v][j] for v in range(n)] for j in range(len(normals))]
    S = math.lcm(den, *(x.denominator for row in rows for x in row if x is not None))
    m = [[None if x is None else int(x * S) for x in row] for row in rows]
    dist = [[None if not np.isfinite(float(x)) else int(x) * (S // den) for x in d.tolist()]
            for d in inst.dist_to]
    tails = [v for v in range(n) if cols[v][0] is not None and v not in inst.targets]
    return {"format": WITNESS_FORMAT, "instance_sha256": instance_sha256,
            "profile_sha256": profile_sha256, "denominator": S, "distances": dist,
            "guarantee": {"m": m, "covers": _covers(normals, rows, tails, len(eq.normals) > 0),
                          "steps": _steps(eq, normals, cols)}}


def _rule_labels(eq: CoalitionEquilibrium) -> list[list[Fraction | None]]:
    """``m_a(v)`` of the written rule at every node from which a goal is reachable (None
    elsewhere): the construction's DP with the written rule's normals, rerun on the whole
    graph (the construction's fixpoint covers the walkable part only; on it the two agree,
    the DP's labels depending on the nodes downstream alone)."""
    assert eq.fixpoint is not None
    graph, labels = arc_graph(eq.instance, whole=True)
    fix = normal_dp(graph, eq.fixpoint.system, 20 * graph.n_nodes + 200)
    k = len(eq.fixpoint.system.normals)
    out: list[list[Fraction | None]] = [[None] * k for _ in range(eq.instance.network.n_nodes)]
    for i, v in enumerate(labels.tolist()):
        if fix.finite[i]:
            out[v] = [fix.value(j, i) for j in range(k)]
    return out


def _covers(normals: tuple[Normal, ...], rows: Labels, tails: list[int], extras: bool
            ) -> list[list[str]]:
    """The cheapest cover of each packing direction the DP's equations leave to test, at
    every tail, each distinct cover once (in the order of the sorted vertices ``λ``, then of
    the cover table sorted by its lowest-terms numerators)."""
    out: list[list[str]] = []
    for lam in packing_vertices(normals):
        y = [sum((c * a[i] for c, a in zip(lam, normals, strict=True)), Fraction(0))
             for i in range(len(normals[0]))]
        if not any(lam) or (sum(map(bool, lam)) == 1 and max(y) == 1) or (
                not extras and set(y) <= {0, 1}):
            continue
        scale = math.lcm(*(x.denominator for x in y))
        vt = vertex_table(normals, [int(x * scale) for x in y])
        table = sorted((_lowest_terms(c, vt.columns) for c in vt.vertices()),
                       key=lambda kc: kc[0])
        if not tails or not table:
            continue
        best = set()
        for v in tails:  # the first cheapest cover (exact: Fractions)
            costs = [sum((c * _finite(rows[j][v]) for j, c in mu.items()), Fraction(0))
                     for _, mu in table]
            best.add(costs.index(min(costs)))
        for t in sorted(best):
            mu = table[t][1]
            out.append([str(mu.get(j, Fraction(0)) / scale) for j in range(len(normals))])
    return out


def _finite(x: Fraction | None) -> Fraction:
    """A label at a tail (finite there: every normal's label is, where one is)."""
    assert x is not None
    return x


def _lowest_terms(mu: dict[int, Fraction], columns: tuple[int, ...]
                  ) -> tuple[tuple[tuple[int, ...], int], dict[int, Fraction]]:
    """A cover's sort key (its numerators over its common denominator on the table's
    columns, then that denominator) and the cover."""
    den = math.lcm(*(x.denominator for x in mu.values()))
    return (tuple(int(mu.get(j, 0) * den) for j in columns), den), mu


def _steps(eq: CoalitionEquilibrium, normals: tuple[Normal, ...],
           cols: list[list[Fraction | None]]) -> list[dict[str, Any]]:
    """σ and its stage duals at every prefix of the profile's walks, each prefix once."""
    inst = eq.instance
    order = priority_order(inst.prior)
    children: dict[tuple[int, int], int] = {}
    state: list[tuple[Fraction, ...]] = [tuple(eq.h)]
    steps: list[dict[str, Any]] = []
    for mix in eq.mixtures:
        for walk, _ in mix:
            p = -1
            for v, u in itertools.pairwise(walk):
                q = children.setdefault((p, u), len(steps))
                if q == len(steps):
                    r = state[p + 1]
                    w = Fraction(int(inst.network.arc_weight(v, u) or 0), inst.denominator)
                    sigma, _ = rule_step(r, normals, cols[u], w, order)
                    beta = [(sum((x * y for x, y in zip(a, r, strict=True)), Fraction(0))
                             - Fraction(mu)) / w  # type: ignore[arg-type]
                            for a, mu in zip(normals, cols[u], strict=True)]
                    steps.append({"sigma": [str(x) for x in sigma],
                                  "duals": [stage_dual(normals, beta, sigma, order, k)
                                            for k in range(len(sigma) - 1)]})
                    state.append(tuple(x - w * y for x, y in zip(r, sigma, strict=True)))
                p = q
    return steps


def stage_dual(A: Sequence[Sequence[int]], beta: Sequence[Fraction], sigma: Sequence[Fraction],
               order: Sequence[int], k: int) -> dict[str, Any]:
    """An optimal dual of stage ``k`` of the lexicographic minimum ``σ``: ``y >= 0``, ``z``,
    ``ζ`` with ``Σ_a y_a a + z·1 + Σ_{j<k} ζ_j e_{o_j} <= e_{o_k}`` and ``β·y + z + Σ_j ζ_j
    σ_{o_j} = σ_{o_k}``, found by complementary slackness: ``y_a > 0`` only where ``a·σ =
    β_a``, slack only where ``σ_i = 0``; a basic solution of that system, fewest columns first.

    Examples
    --------
    ``F = {σ ∈ Δ^2 : σ_1 >= 1/2}`` in the order (1, 0): σ = (1/2, 1/2); stage 0's dual puts
    ``y = 1`` on the tight normal (0, 1):

    >>> half = Fraction(1, 2)
    >>> stage_dual([(1, 0), (0, 1)], [Fraction(-1), half], [half, half], (1, 0), 0)
    {'y': ['0', '1'], 'z': '0', 'fix': []}
    """
    N = len(sigma)
    free = [tuple(Fraction(1) for _ in range(N))]
    free += [tuple(Fraction(int(i == order[j])) for i in range(N)) for j in range(k)]
    tight = [t for t, a in enumerate(A)
             if sum((x * s for x, s in zip(a, sigma, strict=True)), Fraction(0)) == beta[t]]
    nonneg = [tuple(Fraction(x) for x in A[t]) for t in tight]
    nonneg += [tuple(Fraction(int(i == j)) for i in range(N)) for j in range(N) if sigma[j] == 0]
    target = tuple(Fraction(int(i == order[k])) for i in range(N))
    for size in range(N - k):
        for B in itertools.combinations(range(len(nonneg)), size):
            x = _combination([*free, *(nonneg[b] for b in B)], target)
            if x is None or any(c < 0 for c in x[k + 1:]):
                continue
            y = [Fraction(0)] * len(A)
            for b, c in zip(B, x[k + 1:], strict=True):
                if b < len(tight):
                    y[tight[b]] = c
            return {"y": [str(c) for c in y], "z": str(x[0]), "fix": [str(c) for c in x[1:k + 1]]}
    raise ValueError(f"stage {k}: no dual proves σ the lexicographic minimum")


def _combination(columns: list[tuple[Fraction, ...]], target: tuple[Fraction, ...]
                 ) -> list[Fraction] | None:
    """The unique ``x`` with ``Σ_j x_j columns[j] = target`` (independent columns), or None:
    the normal equations solved exactly, the solution checked."""
    gram = [[sum((p * q for p, q in zip(a, b, strict=True)), Fraction(0)) for b in columns]
            for a in columns]
    rhs = [sum((p * q for p, q in zip(a, target, strict=True)), Fraction(0)) for a in columns]
    x = solve_exact(gram, rhs)
    if x is None:
        return None
    got = tuple(sum((c * col[i] for c, col in zip(x, columns, strict=True)), Fraction(0))
                for i in range(len(target)))
    return x if got == target else None
