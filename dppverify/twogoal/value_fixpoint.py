"""The goal-terminal arcs of the three-field DP, and its fixpoint by three Dijkstra runs.

The fixpoint fields of :mod:`dppverify.twogoal.value_dp` are shortest-path fields (``D1``,
``D2`` from the goals, ``m`` from every node's split value; proofs/DP.md DP.5). A
lexicographic (value, steps) Dijkstra also gives the first step at which each node's fields
are final, hence the step the iteration would stop at and whether ``H`` reaches it.
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass

import numpy as np

from dppverify.exact import Number
from dppverify.game.distances import EXACT_FLOAT_LIMIT, common_denominator, sparse_dijkstra
from dppverify.game.instance import Instance, Roles, arc_arrays

INT64_LIMIT = 2**60
"""Finite field values must stay below this for ``int64`` (sums of two sentinels fit)."""


@dataclass(frozen=True, eq=False)
class Arcs:
    """The arcs leaving non-goal nodes, grouped by tail, with weights scaled for the DP.

    Attributes
    ----------
    tails : numpy.ndarray
        Distinct tails (non-goal nodes with at least one arc), increasing.
    starts : numpy.ndarray
        ``starts[i]`` = first arc of ``tails[i]`` (for ``numpy.minimum.reduceat``).
    heads : numpy.ndarray
        Head of every arc.
    weights : numpy.ndarray
        Scaled weight of every arc: ``int64``, or ``object`` (Python integers) when a weight
        does not fit, or ``float64`` in float mode.
    scale : int
        Common denominator the exact weights were multiplied by (1 in float mode).
    """

    tails: np.ndarray
    starts: np.ndarray
    heads: np.ndarray
    weights: np.ndarray
    scale: int



def goal_terminal_arcs(instance: Instance, *, extra: tuple[Number, ...] = ()) -> Arcs:
    """The arcs leaving non-goal nodes (goals are terminal), weights scaled to integers.

    Parameters
    ----------
    instance : Instance
        The game.
    extra : tuple of Number
        Further exact numbers (terminal costs) whose denominators the scale must clear.

    Returns
    -------
    Arcs

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> a = goal_terminal_arcs(triangle())   # only s has arcs: s -> g1 (3), s -> g2 (2)
    >>> a.tails.tolist(), a.heads.tolist(), a.weights.tolist(), a.scale
    ([0], [1, 2], [3, 2], 1)
    """
    inst = instance
    arrays = arc_arrays(inst)
    is_goal = np.zeros(inst.n_nodes, dtype=bool)
    is_goal[list(inst.goals)] = True
    keep = ~is_goal[arrays.tails]
    tails_all, heads, codes = arrays.tails[keep], arrays.heads[keep], arrays.codes[keep]
    first = np.ones(tails_all.size, dtype=bool)  # the first arc of each tail
    first[1:] = tails_all[1:] != tails_all[:-1]
    starts = np.flatnonzero(first).astype(np.int64)
    tails = tails_all[starts]
    if not inst.exact:
        return Arcs(tails=tails, starts=starts, heads=heads,
                    weights=np.asarray([float(w) for w in arrays.values],
                                       dtype=np.float64)[codes], scale=1)
    # the weights of these arcs only, as a loop over them (np.unique's sorted codes)
    used = np.flatnonzero(np.bincount(codes, minlength=len(arrays.values))).tolist()
    values = [arrays.values[c] for c in used]
    scale = common_denominator([*values, *extra])
    scaled = [int(w * scale) for w in values]
    dtype: type = np.int64 if max(scaled, default=0) < INT64_LIMIT else object
    table: np.ndarray = np.zeros(len(arrays.values), dtype=dtype)
    table[used] = scaled
    return Arcs(tails=tails, starts=starts, heads=heads, weights=table[codes], scale=scale)


@dataclass(frozen=True, eq=False)
class Fixpoint:
    """The fixpoint fields by three Dijkstra runs, with the step each entry becomes final.

    Attributes
    ----------
    d1, d2, m : numpy.ndarray
        ``int64`` scaled fixpoint fields (``sentinel`` where no goal is reachable).
    h1, h2, hm : numpy.ndarray
        The fewest steps of an optimal walk (the first ``k`` with ``D1_k(v) = D1(v)``, etc.).
    last : int
        ``K``: the largest of them over all nodes; the fields at step ``k`` equal the fixpoint
        exactly when ``k >= K``, so the iteration stops after step ``K + 1``.
    """

    d1: np.ndarray
    d2: np.ndarray
    m: np.ndarray
    h1: np.ndarray
    h2: np.ndarray
    hm: np.ndarray
    last: int


_FIXPOINTS: weakref.WeakKeyDictionary[Instance, dict[tuple[int, int], Fixpoint | None]] = \
    weakref.WeakKeyDictionary()


def fixpoint_fields(instance: Instance, roles: Roles | None = None, *,
                    arcs: Arcs | None = None) -> Fixpoint | None:
    """The fixpoint of the three fields by Dijkstra (exact mode; cached per instance).

    None when the DP is not in ``int64`` arithmetic or the encoded numbers would pass 2**53
    (then only the layered iteration is used). Weights are encoded as ``w·B + 1`` with ``B``
    above every step count, so one float64 Dijkstra (scipy) on these exact integers finds the
    least value and, among the optimal walks, the fewest steps (proofs/DP.md, DP.5).
    ``arcs``: the goal-terminal arcs of :func:`goal_terminal_arcs` with the terminal costs as
    ``extra``, when the caller has them already.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> fx = fixpoint_fields(triangle())
    >>> fx.d1.tolist(), fx.m.tolist(), fx.hm.tolist(), fx.last
    ([3, 0, 2], [4, 2, 2], [1, 0, 0], 1)
    """
    r = instance.roles() if roles is None else roles
    cache = _FIXPOINTS.setdefault(instance, {})
    key = (r.g1, r.g2)
    if key not in cache:
        cache[key] = _fixpoint(instance, r, arcs)
    return cache[key]


def _reversed_arrays(inst: Instance, r: Roles, scale: int, base: int) -> tuple[
        np.ndarray, np.ndarray, np.ndarray, int]:
    """The reversed arcs ``u -> v`` for ``v -> u`` as CSR arrays (weights encoded with
    ``base``), with room for a last row: a source node ``n`` with an arc to every seed, which
    each run of the fixpoint writes after the arcs. It is the instance's reversed graph (built
    once per instance, shared with the other shortest-path passes); the arcs out of a goal
    (goals are terminal) weigh inf, which no shortest path uses. Returns the weights, heads,
    row pointers and the number of arcs."""
    n = inst.n_nodes
    arrays = arc_arrays(inst)
    rows_r, cols, order = arrays.rows(n, reverse=True)
    codes = arrays.codes if order is None else arrays.codes[order]
    from_goal = (cols == r.g1) | (cols == r.g2)
    table = np.full(len(arrays.values), np.inf)
    used = np.flatnonzero(np.bincount(codes[~from_goal], minlength=table.size))
    table[used] = [float(int(arrays.values[c] * scale) * base + 1) for c in used.tolist()]
    m_arcs = cols.size
    weights = np.empty(m_arcs + n, dtype=np.float64)
    np.take(table, codes, out=weights[:m_arcs])
    weights[:m_arcs][from_goal] = np.inf
    heads = np.empty(m_arcs + n, dtype=np.int32)
    heads[:m_arcs] = cols
    indptr = np.empty(n + 2, dtype=np.int32 if m_arcs + n < 2**31 else np.int64)
    indptr[:n + 1] = rows_r
    return weights, heads, indptr, m_arcs


def _fixpoint(inst: Instance, r: Roles, given: Arcs | None, *,
              prune: bool = True) -> Fixpoint | None:
    if not inst.exact:
        return None
    n = inst.n_nodes
    d12, d21 = r.d2[r.g1], r.d1[r.g2]
    arcs = goal_terminal_arcs(inst, extra=(d12, d21)) if given is None else given
    if arcs.weights.dtype != np.int64:
        return None
    wmax = int(arcs.weights.max()) if arcs.weights.size else 0
    term = int(max(d12, d21) * arcs.scale)
    base = 2 * n + 3  # above every step count (at most 2n - 2, DP.3)
    vmax = 2 * ((n - 1) * wmax + term) + 1  # above every finite fixpoint value
    if (vmax + 1) * base + 1 >= EXACT_FLOAT_LIMIT:  # float64 holds every encoded number exactly
        return None
    from scipy.sparse import csr_matrix

    g1, g2 = r.g1, r.g2
    weights, heads, indptr, m_arcs = _reversed_arrays(inst, r, arcs.scale, base)
    big = np.iinfo(np.int64).max

    # seed pruning is exact while a seed plus one arc stays below 2**53 in the encoding
    can_prune = (prune and arcs.heads.size > 0
                 and (vmax + wmax + 1) * base + 1 < EXACT_FLOAT_LIMIT)
    fwd_w = arcs.weights.astype(np.float64) * base + 1.0

    def run(src: np.ndarray, cost: np.ndarray, hops: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        # the reversed goal-terminal arcs, plus a last row: a source node n with an arc to
        # every seed (weight + 1, so that no arc weighs 0)
        seed_w = cost.astype(np.float64) * base + hops + 1.0
        if can_prune and src.size > 2:
            # a seed u with an arc u -> x such that seed(x) + arc <= seed(u) is never needed:
            # every walk from it is matched by x's seed and that arc (encoded, so also in
            # steps); the distances are the same, the heap starts far smaller
            full = np.full(n, np.inf)
            full[src] = seed_w
            best = np.minimum.reduceat(full[arcs.heads] + fwd_w, arcs.starts)
            dominated = np.zeros(n, dtype=bool)
            dominated[arcs.tails] = best <= full[arcs.tails]
            keep = ~dominated[src]
            src, seed_w = src[keep], seed_w[keep]
        end = m_arcs + src.size
        indptr[n + 1] = end
        weights[m_arcs:end] = seed_w
        heads[m_arcs:end] = src
        mat = csr_matrix((weights[:end], heads[:end], indptr), shape=(n + 1, n + 1), copy=False)
        dist = sparse_dijkstra(mat, n)[:n]
        finite = np.isfinite(dist)
        enc = np.where(finite, dist - 1.0, 0.0).astype(np.int64)
        val, hop = np.divmod(enc, base)
        return np.where(finite, val, big), np.where(finite, hop, 0)

    goals = np.array([g1, g2], dtype=np.int64)
    zero2 = np.zeros(2, dtype=np.int64)
    d1, h1 = run(goals, np.array([0, int(d21 * arcs.scale)]), zero2)
    d2, h2 = run(goals, np.array([int(d12 * arcs.scale), 0]), zero2)
    seeds = np.flatnonzero((d1 < big) & (d2 < big))
    is_goal = np.zeros(n, dtype=bool)
    is_goal[[g1, g2]] = True
    cost = d1[seeds] + d2[seeds]
    cost[seeds == g1] = int(d12 * arcs.scale)  # m at the goals: their terminal sums
    cost[seeds == g2] = int(d21 * arcs.scale)
    seed_hops = np.where(is_goal[seeds], 0, np.maximum(h1[seeds], h2[seeds]))
    m, hm = run(seeds, cost, seed_hops)
    last = int(max(h1.max(initial=0), h2.max(initial=0), hm.max(initial=0)))
    return Fixpoint(d1=d1, d2=d2, m=m, h1=h1, h2=h2, hm=hm, last=last)
