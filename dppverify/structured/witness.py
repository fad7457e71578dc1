"""The engine's ``dpp-witness/1`` (``docs/formats.md`` §5): the exact numbers the trusted kernel
(``dppverify.kernel``, proofs/KERNEL.md) checks, computed with the checker's own mathematics.

For a progress or table Defender, per type: the exact cost-to-go at every prefix of the
Defender's trie (the backward induction of proofs/TABLEBR.md TB.3 / NWALKBR NW.1,
:func:`~dppverify.structured.table_br.trie_induction`), and off the trie either the exit costs
of a constant default (:func:`~dppverify.structured.table_br.exit_costs`) or the two labels of
the progress default's closed form ``min(P(v), Q(v) − c)`` (KERNEL K.3: ``P`` the exit cost at
full price, ``Q`` a multi-source Dijkstra from ``d(x, g) + P(x)``). The distances are the
instance's own (:mod:`dppverify.game.distances`). For a type with positive regret the walk that
attains its minimum is listed under ``counterexamples``.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from fractions import Fraction
from typing import Any

import numpy as np

from dppverify.exact import INF, Number
from dppverify.formats.json_reading import node_to_json
from dppverify.game.distances import EXACT_FLOAT_LIMIT, multi_source_dijkstra
from dppverify.game.instance import Instance
from dppverify.game.instance_reading import arc_arrays, goal_distance_fields
from dppverify.game.profile import GoalTable, GuaranteeRule, Profile, ProgressRule, TableRule
from dppverify.structured.cover import basic_solutions
from dppverify.structured.guarantee import guarantee_sets, guarantee_sigma, rule_order
from dppverify.structured.lexmin import simplex_min
from dppverify.structured.packing import packing_vertices
from dppverify.structured.table_br import trie_induction
from dppverify.structured.trie import build_walk_trie

WITNESS_FORMAT = "dpp-witness/1"
"""The witness document's ``format`` tag."""

Dist = tuple[Fraction, ...]


def _table(instance: Instance, profile: Profile) -> tuple[dict[tuple[int, ...], Dist], Any, int]:
    """The Defender as entries (goal distributions), a default (distribution, ``"progress"``
    or None) and the progress goal's index."""
    rule = profile.defender
    if isinstance(rule, GoalTable):
        return dict(rule.entries), rule.default, 0
    if not isinstance(rule, ProgressRule | TableRule):
        raise ValueError(f"no table witness for the Defender {type(rule).__name__}")
    j = instance.goals.index(rule.goal)

    def two(p: Fraction) -> Dist:
        return (p, 1 - p) if j == 0 else (1 - p, p)
    if isinstance(rule, ProgressRule):
        return {}, "progress", j
    default: Any = rule.default
    if isinstance(default, ProgressRule):
        default, j = "progress", instance.goals.index(default.goal)
    elif default is not None:
        default = two(Fraction(default))
    return {w: two(Fraction(p)) for w, p in rule.entries.items()}, default, j


def _labels(xs: Sequence[Number], S: int) -> list[int | None]:
    return [None if x == INF else int(Fraction(x) * S) for x in xs]


Scaled = tuple[np.ndarray, int]
"""A field of exact numbers ``array / scale`` (float64 holding integers below 2**53, or an
object array of Python integers; ``inf`` where the field is +∞)."""


def _ints(field: Scaled, S: int) -> list[int | None]:
    """The field's labels over the denominator ``S`` (a multiple of its scale)."""
    arr, scale = field
    k = S // scale
    return [None if x == INF else int(x) * k for x in arr.tolist()]


def _at(field: Scaled, v: int) -> Number:
    x = field[0][v]
    return INF if x == INF else Fraction(int(x), field[1])


def _distance_field(instance: Instance, j: int) -> Scaled:
    """``d(·, g^j)`` as a scaled field: the reader's own float64 field when it made one."""
    fields = goal_distance_fields(instance)
    if fields is not None:
        return np.asarray(fields[1][instance.goals[j]], dtype=np.float64), fields[0]
    d = instance.dist_to[j]
    scale = math.lcm(*(Fraction(x).denominator for x in d if x != INF))
    return np.array([INF if x == INF else int(Fraction(x) * scale) for x in d], dtype=object), \
        scale


def witness_document(instance: Instance, profile: Profile, *, instance_sha256: str,
                     profile_sha256: str) -> dict[str, Any]:
    """The witness of a well-formed progress- or table-rule ``profile`` on exact ``instance``.

    Examples
    --------
    >>> from dppverify.game.examples import triangle, triangle_profile
    >>> from dppverify.game.profile import profile_from_json
    >>> inst = triangle()
    >>> w = witness_document(inst, profile_from_json(triangle_profile(), inst),
    ...                      instance_sha256="0" * 64, profile_sha256="1" * 64)
    >>> w["distances"], w["types"]
    ([[3, 0, 2], [2, 2, 0]], [{'trie': [3]}, {'trie': [1], 'P': [2, 2, 0], 'Q': [4, 2, 2]}])
    """
    if isinstance(profile.defender, GuaranteeRule):
        return _guarantee_witness(instance, profile, profile.defender, instance_sha256,
                                  profile_sha256)
    table = _TableWitness(instance, profile)
    per_type = [table.type_labels(theta) for theta in range(instance.n_goals)]
    dist = [_distance_field(instance, j) for j in range(instance.n_goals)]
    S = math.lcm(*(scale for _, scale in dist), *(Fraction(x).denominator for _, rec, _ in per_type
                                                 for x in rec["trie"] if x != INF),
                 *(f[1] for _, rec, _ in per_type for k, f in rec.items() if k != "trie"))
    doc: dict[str, Any] = {
        "format": WITNESS_FORMAT, "instance_sha256": instance_sha256,
        "profile_sha256": profile_sha256, "denominator": S,
        "distances": [_ints(d, S) for d in dist],
        "types": [{k: _labels(v, S) if k == "trie" else _ints(v, S) for k, v in rec.items()}
                  for _, rec, _ in per_type]}
    walks = [{"type": theta, "walk": [node_to_json(x) for x in instance.labels(w)]}
             for theta, _, w in per_type if w]
    if walks:
        doc["counterexamples"] = walks
    return doc


class _TableWitness:
    """The exact labels of a table Defender (the progress rule is the empty table with the
    progress default) on the trie of its entries: KERNEL K.2 item 5, K.3, K.6."""

    def __init__(self, instance: Instance, profile: Profile) -> None:
        self.instance, self.profile = instance, profile
        self.entries, self.default, self.pj = _table(instance, profile)
        self.progress = self.default == "progress"
        self.dg = dg = instance.dist_to[self.pj]
        self.trie = trie = build_walk_trie(instance, list(self.entries))
        self.listed = {trie.find(w): d for w, d in self.entries.items()}
        self.cmin: list[Number] = []
        for p in range(len(trie)):
            here = dg[trie.node[p]]
            self.cmin.append(here if trie.parent[p] < 0 else min(self.cmin[trie.parent[p]], here))

    def sigma(self, p: int, c: int | None, w: Number, c2: Number | None = None) -> Dist | None:
        """σ on the step from trie prefix ``p`` to its child ``c`` (or off the trie, with the
        new running minimum ``c2``)."""
        if c is not None and c in self.listed:
            return self.listed[c]
        if self.progress:
            x = Fraction(self.cmin[p] - (self.cmin[c] if c is not None else c2)) / Fraction(w)  # type: ignore[operator]
            return (x, 1 - x) if self.pj == 0 else (1 - x, x)
        return self.default

    def walk_cost(self, walk: Sequence[int], theta: int) -> Fraction:
        """Type ``θ``'s cost of a walk against the table."""
        inst, dg = self.instance, self.dg
        p, c, total = 0, dg[walk[0]], Fraction(0)
        for v, u in itertools.pairwise(walk):
            w = Fraction(inst.weight(v, u))  # type: ignore[arg-type]
            q = self.trie.child(p, u) if p >= 0 else None
            s = self.listed.get(q) if q is not None else None
            if s is None and self.progress:
                x = Fraction(c - min(c, dg[u])) / w
                s = (x, 1 - x) if self.pj == 0 else (1 - x, x)
            total += w * (s or self.default)[theta]
            p, c = (-1 if q is None else q), min(c, dg[u])
        return total + Fraction(inst.dist_to[theta][walk[-1]])

    def type_labels(self, theta: int) -> tuple[int, dict[str, Any], list[int]]:
        """Type ``θ``'s labels (``trie`` and the exit labels) and, when its regret is positive,
        the walk that attains its minimum (else ``[]``)."""
        inst, dg, cmin = self.instance, self.dg, self.cmin
        rec: dict[str, Any] = {}
        P: Scaled = (np.zeros(0), 1)
        Q: Scaled = (np.zeros(0), 1)
        E: Scaled = (np.zeros(0), 1)
        via_p: list[int] = []
        via_q: list[int] = []
        term = _distance_field(inst, theta)
        at_goals = np.full(inst.n_nodes, INF, dtype=term[0].dtype)
        at_goals[list(inst.goals)] = term[0][list(inst.goals)]
        if self.progress and theta != self.pj:
            P, via_p = _sources_field(inst, (at_goals, term[1]), Fraction(1))
            dgs = _distance_field(inst, self.pj)
            scale = math.lcm(P[1], dgs[1])
            init = dgs[0] * (scale // dgs[1]) + P[0] * (scale // P[1])
            Q, via_q = _sources_field(inst, (init, scale), Fraction(1))
            rec = {"P": P, "Q": Q}
        elif not self.progress and self.default is not None:
            E, via_p = _sources_field(inst, (at_goals, term[1]), Fraction(self.default[theta]))
            rec = {"exit": E}

        def leave(p: int, u: int, w: Number) -> Number | None:
            c2 = min(cmin[p], dg[u])
            if self.progress:
                return cmin[p] if theta == self.pj else \
                    Fraction(w) - (cmin[p] - c2) + min(_at(P, u), _at(Q, u) - c2)
            return None if self.default is None else Fraction(w) * self.default[theta] + _at(E, u)

        def inside(p: int, c: int, w: Number) -> Number | None:
            s = self.sigma(p, c, w)
            return None if s is None else Fraction(w) * s[theta]

        J, choice, _ = trie_induction(inst, self.trie, inst.dist_to[theta], inside, leave)
        U = sum((mw.probability * self.walk_cost(mw.walk, theta)
                 for mw in self.profile.attacker[theta]), Fraction(0))
        walk: list[int] = []
        if J[0] != INF and J[0] < U:  # regret > 0: the walk that attains the minimum
            walk, p = [self.trie.node[0]], 0
            while (step := choice[p]) is not None:
                u, c = step
                if c >= 0:
                    walk.append(u)
                    p = c
                    continue
                x = u
                walk.append(x)
                if self.progress and theta == self.pj:  # a shortest path to the rule's goal
                    while not inst.is_goal(x):
                        x = next(y for y, w in inst.succ[x] if dg[y] != INF
                                 and dg[x] == Fraction(w) + dg[y])
                        walk.append(x)
                    break
                if self.progress and _at(Q, x) - min(cmin[p], dg[x]) < _at(P, x):
                    while via_q[x] >= 0:  # Q's chain to the node attaining the minimum
                        x = via_q[x]
                        walk.append(x)
                while not inst.is_goal(x):
                    x = via_p[x]
                    walk.append(x)
                break
        return theta, {"trie": J, **rec}, walk


def _sources_field(instance: Instance, init: Scaled, share: Fraction) -> tuple[Scaled, list[int]]:
    """``min over sources x of init(x) + share·d°(v, x)`` at every node ``v`` (``d°``: no arc
    leaving a goal: a walk ends at its first goal; the sources are where ``init`` is finite)
    and the next node towards it (``-1`` at a source or where none is reached). scipy's
    Dijkstra on a super-source when every sum is an integer below 2**53 (then exact), else the
    exact Python Dijkstra on integers."""
    arcs = arc_arrays(instance)
    keep = ~np.isin(arcs.tails, np.asarray(instance.goals))
    values = [Fraction(v) * share for v in arcs.values]
    scale = math.lcm(init[1], *(x.denominator for x in values))
    ints = [int(x * scale) for x in values]  # int64 unless a weight's numerator leaves it
    w = np.asarray(ints, dtype=np.int64 if max(ints, default=0) < 2**63 else object
                   )[arcs.codes[keep]]
    xs = np.flatnonzero(np.asarray(init[0] != INF, dtype=bool))
    cost = [int(c) * (scale // init[1]) for c in init[0][xs].tolist()]
    n = instance.n_nodes
    if share > 0 and int(w.sum()) + max(cost, default=0) + 1 < EXACT_FLOAT_LIMIT:
        import scipy.sparse as sp
        from scipy.sparse.csgraph import dijkstra

        m = sp.csr_matrix((np.concatenate([w.astype(float), np.asarray(cost, float) + 1]),
                           (np.concatenate([arcs.heads[keep], np.full(xs.size, n)]),
                            np.concatenate([arcs.tails[keep], xs]))), shape=(n + 1, n + 1))
        dist, pred = dijkstra(m, directed=True, indices=n, return_predecessors=True)
        via = np.where((pred[:n] >= 0) & (pred[:n] < n), pred[:n], -1)
        return (dist[:n] - 1, scale), via.tolist()
    rows: list[list[tuple[int, int]]] = [[] for _ in range(n)]
    for t, h, c in zip(arcs.tails[keep].tolist(), arcs.heads[keep].tolist(), w.tolist(),
                       strict=True):
        rows[h].append((t, c))
    keys, via_l = multi_source_dijkstra(rows, list(zip(xs.tolist(), cost, strict=True)))
    return (np.array(keys, dtype=object), scale), via_l


def _exact(x: Fraction) -> str:
    return str(Fraction(x))


def _guarantee_witness(instance: Instance, profile: Profile, rule: GuaranteeRule,
                       instance_sha256: str, profile_sha256: str) -> dict[str, Any]:
    """The guarantee rule's witness (KERNEL K.7): the DP labels, the covers of the packing
    directions the kernel tests, σ and its stage duals at every prefix of the profile's
    walks."""
    sets = guarantee_sets(instance, rule.normals)
    A, n, N = sets.normals, instance.n_nodes, instance.n_goals
    dist = instance.dist_to
    S = math.lcm(sets.scale, *(Fraction(x).denominator for d in dist for x in d if x != INF))
    m = [[int(row[v]) * (S // sets.scale) if sets.finite[v] else None for v in range(n)]
         for row in sets.rows]
    covers = []
    for lam, y in packing_vertices(A, every=True):
        if (sum(map(bool, lam)) == 1 and max(y) == 1) or (not sets.extras and set(y) <= {0, 1}):
            continue
        scale = math.lcm(*(Fraction(x).denominator for x in y))
        table = basic_solutions(A, [int(x * scale) for x in y])
        tails = [v for v in range(n) if sets.finite[v] and not instance.is_goal(v)]
        if not tails or not table.scaled.size:
            continue
        vals = np.array([[int(sets.rows[j][v]) for j in table.columns] for v in tails],
                        dtype=object)
        best = np.argmin(vals @ table.scaled.astype(object), axis=1)  # the cheapest cover
        for t in sorted(set(best.tolist())):  # at each tail, exactly (Python integers)
            mu = [Fraction(0)] * len(A)
            for k, col in enumerate(table.columns):
                mu[col] = Fraction(int(table.scaled[k, t]), table.lcm * scale)
            covers.append([_exact(c) for c in mu])
    order = rule_order(instance.prior)
    children: dict[tuple[int, int], int] = {}
    state: list[tuple[Fraction, ...]] = [tuple(rule.h)]
    steps: list[dict[str, Any]] = []
    for mix in profile.attacker:
        for mw in mix:
            p = -1
            for v, u in zip(mw.walk, mw.walk[1:], strict=False):
                q = children.setdefault((p, u), len(steps))
                if q == len(steps):
                    r, w = state[p + 1], Fraction(instance.weight(v, u))  # type: ignore[arg-type]
                    sigma, _ = guarantee_sigma(r, sets, u, w, order)
                    column = sets.column(u) or []
                    beta = [(sum(x * y for x, y in zip(a, r, strict=True)) - mv) / w
                            for a, mv in zip(A, column, strict=True)]
                    steps.append({"sigma": [_exact(x) for x in sigma],
                                  "duals": [_stage_dual(A, beta, sigma, order, k)
                                            for k in range(N - 1)]})
                    state.append(tuple(x - w * y for x, y in zip(r, sigma, strict=True)))
                p = q
    return {"format": WITNESS_FORMAT, "instance_sha256": instance_sha256,
            "profile_sha256": profile_sha256, "denominator": S,
            "distances": [_labels(d, S) for d in dist],
            "guarantee": {"m": m, "covers": covers, "steps": steps}}


def _stage_dual(A: Sequence[Sequence[int]], beta: Sequence[Fraction], sigma: Sequence[Fraction],
                order: Sequence[int], k: int) -> dict[str, Any]:
    """An optimal dual of stage ``k`` of the lexicographic minimum: ``max β·y + z + Σ_j
    σ_{o_j} ζ_j`` over ``y >= 0`` with ``Σ_a y_a a + z·1 + Σ_{j<k} ζ_j e_{o_j} <= e_{o_k}``
    (exact simplex on ``y, z⁺, z⁻, ζ⁺, ζ⁻`` and slacks)."""
    N, na = len(sigma), len(A)
    fixed = list(order[:k])
    width = na + 2 + 2 * k + N
    rows, rhs = [], []
    for i in range(N):
        row = [Fraction(a[i]) for a in A] + [Fraction(1), Fraction(-1)]
        row += [Fraction(int(j == i)) for j in fixed] + [Fraction(-int(j == i)) for j in fixed]
        row += [Fraction(int(t == i)) for t in range(N)]
        rows.append(row)
        rhs.append(Fraction(int(i == order[k])))
    cost = [-b for b in beta] + [Fraction(-1), Fraction(1)]
    cost += [-sigma[j] for j in fixed] + [sigma[j] for j in fixed] + [Fraction(0)] * N
    x = simplex_min(cost, rows, rhs)
    assert x is not None and len(x) == width
    zeta = [x[na + 2 + j] - x[na + 2 + k + j] for j in range(k)]
    return {"y": [_exact(v) for v in x[:na]], "z": _exact(x[na] - x[na + 1]),
            "fix": [_exact(v) for v in zeta]}
