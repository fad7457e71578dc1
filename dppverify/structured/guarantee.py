"""The guarantee-vector Defender rule of ``dpp-ngoal-profile/1`` (proofs/NSOLVE.md), evaluated
from the checker's own mathematics.

Profile: ``"defender": {"rule": "guarantee", "h": [h_1, …, h_N]}`` (``docs/formats.md`` §2b).
With ``m_S(v)`` the coalition DP at ``H = inf`` (:mod:`dppverify.structured.coalition`, the layer
that repeats) and ``G_v = { r : r(S) <= m_S(v) for every non-empty S }``:

- the state is ``r``, ``r = h`` at the start;
- on a step ``v -> u`` of weight ``w`` the Defender plays the lexicographic minimum, in the
  *priority order* (types by decreasing prior, ties by index), of
  ``F = { σ ∈ Δ^N : σ(S) >= (r(S) - m_S(u)) / w for every S }``, and ``r <- r - w σ``;
  when ``F`` is empty, all the weight on the first type of the priority order.

What the checker proves about it (NSOLVE.1-2), exactly:

- ``h ∈ G_{s0}``, and the **arc condition** ``G_v ⊆ G_u + wΔ^N`` on every arc ``(v, u)`` that a
  walk can take (``v`` not a goal, some goal reachable from ``u``). Then ``F`` is never empty
  on any walk, ``r`` stays in ``G``, and every walk costs type ``θ`` at least ``h_θ``: the
  minimum over ALL walks is ``>= h_θ`` (NSOLVE.1). The arc condition is verified as follows:
  ``m`` is a fixpoint of the DP (steps and splits), which gives it for every direction ``y``
  whose optimal covers regroup into fractional partitions of sets containing a type of largest
  ``y`` (NSOLVE.2); the remaining directions are the finitely many *non-pattern extreme rays*
  ``ρ`` of the cones ``{c >= 0 : y_c maximal at θ*}`` (:func:`bad_rays`: none for ``N <= 3``,
  the merging lemma), each checked on every arc: ``cov_v(y_ρ) <= cov_u(y_ρ) + w·max y_ρ``
  (the arc condition in the direction ``y_ρ``: necessary, and with the fixpoint sufficient).
- On the profile's walks the rule is evaluated step by step; a type paying exactly ``h_θ``
  has regret 0 over all walks of any length.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from functools import cache
from typing import Any

import numpy as np

from dppverify.exact import Number
from dppverify.formats.json_reading import parse_number
from dppverify.ngoal.instance import NInstance
from dppverify.structured.coalition import CoalitionValue, coalition_scale, splits
from dppverify.structured.cover import (
    cheapest,
    dets,
    members,
    min_cover,
    symmetric_table,
    zero_one_normals,
)

__all__ = ["ArcCondition", "GuaranteeRule", "GuaranteeSets", "arc_condition", "bad_rays",
           "guarantee_sets", "guarantee_sigma", "parse_guarantee", "rule_order"]

RULE = "guarantee"


@dataclass(frozen=True)
class GuaranteeRule:
    """The profile's guarantee rule: the starting state ``h``."""

    h: tuple[Fraction, ...]


def parse_guarantee(raw: Mapping[str, Any], n: int, defects: list[str]) -> GuaranteeRule | None:
    """Read ``{"rule": "guarantee", "h": [...]}``, recording defects (None when ill-formed).

    Examples
    --------
    >>> parse_guarantee({"rule": "guarantee", "h": ["1/2", 1, "3"]}, 3, []).h
    (Fraction(1, 2), Fraction(1, 1), Fraction(3, 1))
    >>> d = []; parse_guarantee({"rule": "guarantee", "h": [1]}, 3, d); d
    ['defender.h: must be a list of 3 numbers (one per goal)']
    """
    h = raw.get("h")
    extra = sorted(set(raw) - {"rule", "h"})
    if extra:
        defects.append(f"defender: unknown key(s) {', '.join(extra)} for the guarantee rule")
        return None
    if not isinstance(h, list) or len(h) != n:
        defects.append(f"defender.h: must be a list of {n} numbers (one per goal)")
        return None
    out = []
    for i, x in enumerate(h):
        try:
            out.append(Fraction(parse_number(x, where=f"defender.h[{i}]")))
        except ValueError as exc:
            defects.append(str(exc))
            return None
    return GuaranteeRule(tuple(out))


def rule_order(prior: Sequence[Fraction]) -> tuple[int, ...]:
    """The priority order: types by decreasing prior, ties by index.

    Examples
    --------
    >>> rule_order([Fraction(1, 6), Fraction(1, 2), Fraction(1, 3)])
    (1, 2, 0)
    """
    return tuple(sorted(range(len(prior)), key=lambda t: (-prior[t], t)))


@dataclass(frozen=True, eq=False)
class GuaranteeSets:
    """``m_S(v)`` of the coalition DP at ``H = inf`` at every node (scaled integers).

    Attributes
    ----------
    instance : NInstance
    scale : int
        ``m_S(v) = m[S][v] / scale``.
    big : int
        Values ``>= big`` mean: no goal reachable.
    m : Mapping
        Subset mask -> array over nodes.
    layers : int
        Label-setting passes (one per subset).
    """

    instance: NInstance
    scale: int
    big: int
    m: Mapping[int, np.ndarray]
    layers: int

    def value(self, mask: int, v: int) -> Fraction | None:
        """``m_S(v)`` exactly, None where no goal is reachable."""
        x = int(self.m[mask][v])
        return None if x >= self.big else Fraction(x, self.scale)


def guarantee_sets(instance: NInstance) -> GuaranteeSets:
    """``m_S`` at ``H = inf`` at every node: the unique solution of the DP's fixpoint equations.

    By increasing ``|S|``: the split ``min_λ Σ_T λ_T m_T(v)`` over the minimal balanced
    collections of ``S`` (:func:`dppverify.structured.cover.balanced_vertices`) is known from the
    smaller subsets, and ``m_S(v) = min_x [dist(v -> x) + init_S(x)]`` over walks whose interior
    avoids the goals (``init_S`` = the split off the goals, the terminal cost at a goal): one
    label-setting shortest-path pass per subset (NSOLVE.3: this is the limit ``H -> inf`` of
    the layered DP of :mod:`dppverify.structured.coalition`). Exact: integers scaled by
    ``W·L^(N-1)``, in float64 only while every value is an integer below 2**53.

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> g = guarantee_sets(star3())
    >>> g.value(0b111, star3().start), g.value(0b001, star3().start)
    (Fraction(4, 1), Fraction(2, 1))
    """
    inst = instance
    n_goals = inst.n_goals
    split_of = {sp.mask: sp for sp in splits(n_goals)}
    n = inst.n_nodes
    scale = coalition_scale(inst, list(split_of.values()))
    goal = [inst.is_goal(v) for v in range(n)]
    live = [not goal[v] and inst.hops[v] >= 0 for v in range(n)]
    rows = [v for v in range(n) if live[v]]
    tails: list[int] = []
    heads: list[int] = []
    weights: list[int] = []
    scaled: dict[Any, int] = {}
    for v in rows:
        for u, w in inst.succ[v]:
            tails.append(v)
            heads.append(u)
            if w not in scaled:
                scaled[w] = int(Fraction(w) * scale)
            weights.append(scaled[w])
    finite = [inst.dist_to[t][g] for t in range(n_goals) for g in inst.goals]
    top = (n_goals * (max(Fraction(x) for x in finite) * scale + sum(weights)) + 2) * 2
    big = int(top) + 1
    m: dict[int, np.ndarray] = {}
    idx = np.asarray(rows, dtype=np.int64)
    for mask in sorted(range(1, 1 << n_goals), key=lambda t: (bin(t).count("1"), t)):
        init = [-1] * n
        for g in inst.goals:
            init[g] = sum(int(Fraction(inst.dist_to[t][g]) * scale) for t in members(mask))
        split = split_of.get(mask)  # |S| >= 2
        if split is not None and rows:
            mat = np.stack([m[int(c)][idx].astype(object) for c in split.columns], axis=1)
            tot = mat.dot(split.scaled.astype(object))
            best = tot.min(axis=1)
            for v, x in zip(rows, best.tolist(), strict=True):
                if x % split.lcm:  # pragma: no cover - guaranteed by the scaling
                    raise AssertionError("guarantee_sets: a split is not a multiple of 1/scale")
                init[v] = x // split.lcm
        m[mask] = _label_setting(n, tails, heads, weights, init, big)
    return GuaranteeSets(inst, scale, big, m, (1 << n_goals) - 1)


def _label_setting(n: int, tails: list[int], heads: list[int], weights: list[int],
                   init: list[int], big: int) -> np.ndarray:
    """``min_x [dist(v -> x) + init[x]]`` (``init < 0``: no source there), ``big`` if none."""
    src = [x for x in range(n) if init[x] >= 0]
    out = np.full(n, big, dtype=object)
    if max((init[x] for x in src), default=0) + sum(weights) + 2 < 2 ** 53:
        from scipy.sparse import csr_matrix
        from scipy.sparse.csgraph import dijkstra

        # reversed arcs, and a root n with arcs n -> x of weight init[x] + 1 (positive)
        r = np.asarray(heads + [n] * len(src), dtype=np.int64)
        c = np.asarray(tails + src, dtype=np.int64)
        w = np.asarray(weights + [init[x] + 1 for x in src], dtype=np.float64)
        dist = dijkstra(csr_matrix((w, (r, c)), shape=(n + 1, n + 1)), directed=True,
                        indices=n)[:n]
        fin = np.flatnonzero(np.isfinite(dist))
        out[fin] = [int(x) - 1 for x in dist[fin].tolist()]
        return out
    import heapq

    pred: list[list[tuple[int, int]]] = [[] for _ in range(n)]
    for t, h, w2 in zip(tails, heads, weights, strict=True):
        pred[h].append((t, w2))
    best: dict[int, int] = {x: init[x] for x in src}
    heap = [(init[x], x) for x in src]
    heapq.heapify(heap)
    done = [False] * n
    while heap:
        k, x = heapq.heappop(heap)
        if done[x]:
            continue
        done[x] = True
        out[x] = k
        for t, w2 in pred[x]:
            if not done[t] and (t not in best or k + w2 < best[t]):
                best[t] = k + w2
                heapq.heappush(heap, (k + w2, t))
    return out


def dp_value(sets: GuaranteeSets) -> CoalitionValue:
    """The coalition DP's value at ``H = inf`` from the fixpoint (a ``CoalitionValue``).

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> dp_value(guarantee_sets(star3())).value
    Fraction(3, 2)
    """
    inst = sets.instance
    costs = {mask: Fraction(int(v[inst.start]), sets.scale) for mask, v in sets.m.items()}
    lp = min_cover(costs, inst.prior)
    return CoalitionValue(horizon=None, value=lp.value, layers=sets.layers,
                          coalition_costs=costs, cover=dict(lp.cover))


# ---------------------------------------------------------------- the rule's σ (lexmin)
def _vertex(rows: list[tuple[int, Fraction]], n: int) -> list[Fraction] | None:
    """Solve ``σ(T_i) = a_i`` (subset masks) with ``Σ σ = 1``; None if singular."""
    a = [[Fraction(t >> j & 1) for j in range(n)] + [v] for t, v in rows]
    a.append([Fraction(1)] * n + [Fraction(1)])
    for col in range(n):
        piv = None
        for r in range(col, n):
            if a[r][col]:
                piv = r
                break
        if piv is None:
            return None
        a[col], a[piv] = a[piv], a[col]
        p = a[col][col]
        for r in range(n):
            if r != col and a[r][col]:
                f = a[r][col] / p
                a[r] = [x - f * y for x, y in zip(a[r], a[col], strict=True)]
    return [a[i][n] / a[i][i] for i in range(n)]


def guarantee_sigma(r: Sequence[Fraction], sets: GuaranteeSets, u: int, w: Number,
                    order: Sequence[int]) -> tuple[tuple[Fraction, ...], bool]:
    """The rule's ``σ`` on a step into ``u`` of weight ``w`` from state ``r`` (and F ≠ ∅).

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> inst = star3()
    >>> g = guarantee_sets(inst)
    >>> sigma, ok = guarantee_sigma([Fraction(2), Fraction(1), Fraction(1)], g, 1, 1, (0, 1, 2))
    >>> [str(x) for x in sigma], ok
    (['1', '0', '0'], True)
    >>> guarantee_sigma([Fraction(3), Fraction(3), Fraction(0)], g, 1, 1, (0, 1, 2))[1]
    False
    """
    n = len(r)
    wf = Fraction(w)
    need: dict[int, Fraction] = {}
    for mask in range(1, 1 << n):
        m = sets.value(mask, u)
        if m is None:
            continue
        a = (sum((r[i] for i in range(n) if mask >> i & 1), Fraction(0)) - m) / wf
        if a > 0:
            need[mask] = a
    if not need:
        return tuple(Fraction(1) if i == order[-1] else Fraction(0) for i in range(n)), True
    # every S with a bound >= 1 holds all of σ: if they share exactly one type θ, F ⊆ {e_θ}
    common = (1 << n) - 1
    for mask, a in need.items():
        if a >= 1:
            common &= mask
    if common and not common & (common - 1):
        theta = common.bit_length() - 1
        fits = all(a <= (1 if mask >> theta & 1 else 0) for mask, a in need.items())
        if fits:
            return tuple(Fraction(int(i == theta)) for i in range(n)), True
    # σ_θ >= 0 is the subset {θ} with bound 0; keep the positive bounds not implied by a subset
    bounds = {1 << i: Fraction(0) for i in range(n)}
    for mask, a in need.items():
        if not any(t != mask and (t & mask) == t and b >= a for t, b in need.items()):
            bounds[mask] = max(a, bounds.get(mask, Fraction(0)))
    items = sorted(bounds.items())
    best: list[Fraction] | None = None
    for choice in itertools.combinations(items, n - 1):
        x = _vertex(list(choice), n)
        if x is None:
            continue
        if all(sum((x[j] for j in range(n) if t >> j & 1), Fraction(0)) >= b
               for t, b in items) and (best is None or [x[t] for t in order]
                                       < [best[t] for t in order]):
            best = x
    if best is None:
        return tuple(Fraction(1) if i == order[0] else Fraction(0) for i in range(n)), False
    return tuple(best), True


# ---------------------------------------------------------------- the arc condition
def _minors(mats: np.ndarray) -> np.ndarray:
    """Signed maximal minors of a batch of ``(j, j+1)`` integer matrices: ``x_c = (-1)^c
    det(A without column c)``, a null vector (exact integer determinants)."""
    batch, j, k = mats.shape
    if j == 0:
        return np.ones((batch, 1), dtype=np.int64)
    out = np.empty((batch, k), dtype=np.int64)
    for c in range(k):
        entries = [[np.ascontiguousarray(mats[:, r, cc]) for cc in range(k) if cc != c]
                   for r in range(j)]
        out[:, c] = dets(entries) * (-1 if c % 2 else 1)
    return out


@cache
def bad_rays(n: int) -> tuple[tuple[tuple[tuple[int, Fraction], ...], int], ...]:
    """Extreme rays of ``{c >= 0 : y_c(θ*) >= y_c(θ) ∀θ}`` (``y_c = Σ_S c_S 1_S``, any ``θ*``)
    that are not fractional partitions of a set containing ``θ*``; each as
    ``(((S, ρ_S), …), θ*)`` scaled so that ``max y_ρ = 1``.

    An extreme ray has ``k <= n`` positive entries and ``k - 1`` independent tight rows
    ``y(θ*) = y(θ)``; its direction is the null vector of those rows on its support (signed
    maximal minors, exact integers). Enumerated for ``θ* = 0``, then permuted.

    Examples
    --------
    >>> [len(bad_rays(n)) for n in (2, 3)]
    [0, 0]
    >>> rays = bad_rays(4)
    >>> len(rays), sorted(rays)[0]
    (36, (((3, Fraction(1, 2)), (5, Fraction(1, 2)), (14, Fraction(1, 2))), 0))
    """
    masks = np.arange(1, 1 << n, dtype=np.int64)
    bits = (masks[None, :] >> np.arange(n)[:, None]) & 1  # (n, M): bits[i, s] = [i ∈ S]
    diff = bits[0][None, :] - bits[1:]  # rows y(0) - y(θ), θ = 1..n-1
    base: set[tuple[tuple[int, Fraction], ...]] = set()
    for k in range(1, n + 1):
        sup = np.array(list(itertools.combinations(range(masks.size), k)), dtype=np.int64)
        for tight in itertools.combinations(range(n - 1), k - 1):
            mats = diff[np.asarray(tight, dtype=np.int64)][:, sup]  # (k-1, K, k)
            x = _minors(np.transpose(mats, (1, 0, 2)))  # (K, k)
            neg = np.all(x < 0, axis=1)
            x[neg] = -x[neg]
            ok = np.all(x > 0, axis=1)
            if not ok.any():
                continue
            xs, ss = x[ok], sup[ok]
            y = np.einsum("bk,ibk->bi", xs, bits[:, ss])  # (B, n) integer type masses
            ok2 = np.all(y[:, :1] >= y[:, 1:], axis=1) & (y[:, 0] > 0)
            pattern = np.all((y == 0) | (y == y[:, :1]), axis=1)
            for b in np.flatnonzero(ok2 & ~pattern):
                top = int(y[b, 0])
                base.add(tuple(sorted((int(masks[s]), Fraction(int(c), top))
                                      for s, c in zip(ss[b], xs[b], strict=True))))
    out: set[tuple[tuple[tuple[int, Fraction], ...], int]] = set()
    for ray in base:
        for perm in itertools.permutations(range(n)):
            moved = {sum(1 << perm[i] for i in range(n) if s >> i & 1): c for s, c in ray}
            out.add((tuple(sorted(moved.items())), perm[0]))
    return tuple(sorted(out))


@dataclass(frozen=True)
class ArcCondition:
    """Whether ``G_v ⊆ G_u + wΔ^N`` was established on every walkable arc.

    Attributes
    ----------
    holds : bool
    arcs : int
        Walkable arcs checked.
    rays : int
        Non-pattern extreme rays checked on each arc (0 for N <= 3).
    failure : tuple or None
        ``(v, u, ray)`` of the first arc where the ray inequality does not hold.
    """

    holds: bool
    arcs: int
    rays: int
    failure: tuple[int, int, tuple[tuple[int, Fraction], ...]] | None


def arc_condition(sets: GuaranteeSets) -> ArcCondition:
    """Check the arc condition exactly on every walkable arc (see the module docstring).

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> arc_condition(guarantee_sets(star3())).holds
    True
    """
    inst = sets.instance
    n = inst.n_goals
    tails, heads, wts = [], [], []
    reach = sets.m[1] < sets.big
    scaled: dict[Any, int] = {}
    for v in range(inst.n_nodes):
        if inst.is_goal(v) or not reach[v]:
            continue
        for u, w in inst.succ[v]:
            if not reach[u]:
                continue
            tails.append(v)
            heads.append(u)
            if w not in scaled:
                scaled[w] = int(Fraction(w) * sets.scale)
            wts.append(scaled[w])
    narcs = len(tails)
    if narcs == 0:
        return ArcCondition(True, 0, 0, None)
    t_idx = np.asarray(tails, dtype=np.int64)
    h_idx = np.asarray(heads, dtype=np.int64)
    w_scaled = np.array(wts, dtype=object)
    # the DP step inequality m_S(v) <= w + m_S(u) (a fixpoint property; checked, it is cheap)
    for mask, vals in sets.m.items():
        here = vals[t_idx].astype(object)
        step = w_scaled + vals[h_idx].astype(object)
        bad = np.flatnonzero(here > step)
        if bad.size:
            k = int(bad[0])
            return ArcCondition(False, narcs, 0, (tails[k], heads[k], ((mask, Fraction(1)),)))
    rays = bad_rays(n)
    if not rays:
        return ArcCondition(True, narcs, 0, None)
    # m at the tails and heads as integer matrices (one column per subset mask 1 … 2^n - 1)
    mt = np.stack([sets.m[s][t_idx] for s in range(1, 1 << n)], axis=1)
    mh = np.stack([sets.m[s][h_idx] for s in range(1, 1 << n)], axis=1)
    by_y: dict[tuple[Fraction, ...], list[tuple[tuple[int, Fraction], ...]]] = {}
    for ray, _star in rays:
        y = tuple(sum((c for s, c in ray if s >> i & 1), Fraction(0)) for i in range(n))
        by_y.setdefault(y, []).append(ray)
    zero_one = zero_one_normals(n)
    for y, group in by_y.items():
        den = math.lcm(*(v.denominator for v in y))
        table = symmetric_table(zero_one, tuple(int(v * den) for v in y))
        cols = np.asarray(table.columns, dtype=np.int64)
        vden = table.lcm * den
        # vden · cov(y) at every tail and head; AC at y: cov_v(y) <= cov_u(y) + w · max y
        lhs = cheapest(mt[:, cols], table.scaled).astype(object)
        rhs = cheapest(mh[:, cols], table.scaled).astype(object) + w_scaled * vden * max(y)
        worse = np.flatnonzero(lhs > rhs)
        if worse.size:
            k = int(worse[0])
            return ArcCondition(False, narcs, len(rays), (tails[k], heads[k], group[0]))
    return ArcCondition(True, narcs, len(rays), None)


def in_start_set(rule: GuaranteeRule, sets: GuaranteeSets) -> int | None:
    """The first subset mask with ``h(S) > m_S(s0)`` (None when ``h ∈ G_{s0}``)."""
    s0 = sets.instance.start
    for mask in sorted(sets.m, key=lambda t: (bin(t).count("1"), t)):
        m = sets.value(mask, s0)
        if m is not None and sum((rule.h[i] for i in range(len(rule.h)) if mask >> i & 1),
                                 Fraction(0)) > m:
            return mask
    return None


# ---------------------------------------------------------------- the structured route's records
NSOLVE = "relies on proofs/NSOLVE.md (NSOLVE.1: every walk costs type θ at least h_θ when " \
    "h ∈ G_s0 and the arc condition holds; NSOLVE.2: the arc condition from the DP fixpoint " \
    "and the non-pattern rays)"


def rule_on_trie(instance: NInstance, rule: GuaranteeRule, sets: GuaranteeSets,
                 parent: Sequence[int], node: Sequence[int]
                 ) -> tuple[dict[int, tuple[Fraction, ...]], bool]:
    """The rule's ``σ`` at every prefix of a prefix tree (``parent[p] < p``, root 0).

    Returns the distributions and whether ``F`` was non-empty at every prefix.
    """
    order = rule_order(instance.prior)
    state: dict[int, tuple[Fraction, ...]] = {0: rule.h}
    sigma: dict[int, tuple[Fraction, ...]] = {}
    feasible = True
    for p in range(1, len(node)):
        q = int(parent[p])
        r = state[q]
        v, u = int(node[q]), int(node[p])
        w = instance.weight(v, u)
        assert w is not None
        s, ok = guarantee_sigma(r, sets, u, w, order)
        feasible &= ok
        sigma[p] = s
        state[p] = tuple(x - Fraction(w) * y for x, y in zip(r, s, strict=True))
    return sigma, feasible


def guarantee_checks(instance: NInstance, profile: Any, horizon: int | None
                     ) -> tuple[list[Any], int]:
    """The structured route's records for a profile whose Defender is the guarantee rule.

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> from dppverify.ngoal.profile import nprofile_from_json
    >>> doc = {"format": "dpp-ngoal-profile/1",
    ...        "attacker": [[{"path": ["s", "m", "a"], "probability": 1}],
    ...                     [{"path": ["s", "m", "b"], "probability": 1}],
    ...                     [{"path": ["s", "m", "c"], "probability": 1}]],
    ...        "defender": {"rule": "guarantee", "h": [2, 1, 1]}}
    >>> recs, _ = guarantee_checks(star3(), nprofile_from_json(star3(), doc), None)
    >>> [(r.id, r.status) for r in recs][2]
    ('ngoal.pbne.attacker_br', 'pass')
    """
    from dppverify.ngoal.structured import _IDS, DOC, WALKS, _defender, _labels, _rec, _value
    from dppverify.ngoal.walk_br import TableDefender, build_walk_trie

    inst = instance
    n = inst.n_goals
    rule: GuaranteeRule = profile.rule
    walks = [mw.walk for mix in profile.attacker for mw in mix]
    trie = build_walk_trie(inst, walks)
    sets = guarantee_sets(inst)
    parent = trie.parent
    order_ok = all(parent[p] < p for p in range(1, len(trie)))
    assert order_ok  # the trie numbers prefixes in insertion order
    sigma, feasible = rule_on_trie(inst, rule, sets, parent, trie.node)
    tdef = TableDefender(trie=trie, sigma=sigma, default=None)
    mass: dict[int, list[Fraction]] = {}
    per_type: list[Fraction] = []
    for theta, mix in enumerate(profile.attacker):
        total = Fraction(0)
        for mw in mix:
            p = 0
            cost = Fraction(0)
            mass.setdefault(0, [Fraction(0)] * n)[theta] += mw.probability
            for k, v in enumerate(mw.walk[1:], start=1):
                p = trie.children[p][v]
                mass.setdefault(p, [Fraction(0)] * n)[theta] += mw.probability
                w = inst.weight(mw.walk[k - 1], v)
                assert w is not None
                cost += Fraction(w) * sigma[p][theta]
            total += mw.probability * (cost + Fraction(inst.dist_to[theta][mw.walk[-1]]))
        per_type.append(total)
    out = [_rec(_IDS[0], "pass", f"{n} types, {len(walks)} walks, Defender: the guarantee rule "
                f"with h = ({', '.join(map(str, rule.h))}) (defined on every walk)",
                {"walks": len(walks), "prefixes": len(trie)}, DOC, None)]
    u = sum((inst.prior[t] * per_type[t] for t in range(n)), Fraction(0))
    nums: dict[str, Number | None] = {f"U{t + 1}": per_type[t] for t in range(n)}
    nums["U"] = u
    ok = profile.claimed_u is None or profile.claimed_u == u
    said = "" if profile.claimed_u is None else f" (profile says {profile.claimed_u})"
    out.append(_rec("ngoal.value.U", "pass" if ok else "fail", f"U = {u}{said}", nums, WALKS))
    out.append(_attacker_record(inst, rule, sets, per_type, feasible, _rec, _labels))
    out += _defender(inst, tdef, mass, u)
    from dppverify.structured.proved_value import coalition_nvalue

    known = (coalition_nvalue(dp_value(sets), inst.n_goals)  # proved for N <= 3 (NG.4)
             if horizon is None and inst.n_goals <= 3 else None)
    out.append(_value(inst, u, horizon, all(r.passed for r in out), known))
    return out, len(trie)


def _direction(inst: NInstance, ray: tuple[tuple[int, Fraction], ...]) -> str:
    """A cover as text: ``1/2·{g1, g2} + …`` (goal ids)."""
    def goals(mask: int) -> str:
        return ", ".join(str(inst.nodes[inst.goals[i]]) for i in range(inst.n_goals)
                         if mask >> i & 1)

    return " + ".join(f"{c}·{{{goals(s)}}}" for s, c in ray)


def _attacker_record(inst: NInstance, rule: GuaranteeRule, sets: GuaranteeSets,
                     per_type: list[Fraction], feasible: bool, rec: Any, labels: Any) -> Any:
    cid = "ngoal.pbne.attacker_br"
    proof = "NSOLVE"
    bad_start = in_start_set(rule, sets)
    if bad_start is not None:
        members = [i + 1 for i in range(inst.n_goals) if bad_start >> i & 1]
        return rec(cid, "error", f"h is not in G_s0: h(S) > m_S(s0) for S = {members}; the rule "
                   f"guarantees nothing (could not decide the Attacker's regret)", None, NSOLVE,
                   proof)
    arc = arc_condition(sets)
    if not arc.holds:
        assert arc.failure is not None
        v, u, ray = arc.failure
        return rec(cid, "error", f"the arc condition G_v ⊆ G_u + wΔ fails on arc "
                   f"{inst.nodes[v]!r} -> {inst.nodes[u]!r} (direction {_direction(inst, ray)}; "
                   f"proofs/NSOLVE.md NSOLVE.2): no lower bound over all walks, could not "
                   f"decide the Attacker's regret", {"arcs": arc.arcs}, NSOLVE, proof)
    nums: dict[str, Number | None] = {f"regret{t + 1}": per_type[t] - rule.h[t]
                                      for t in range(inst.n_goals)}
    nums["arcs"] = arc.arcs
    below = [t for t in range(inst.n_goals) if per_type[t] < rule.h[t]]
    if below or not feasible:
        return rec(cid, "error", "a type pays less than its proved guarantee h: the checker's "
                   "computations disagree", nums, NSOLVE, proof)
    above = [t for t in range(inst.n_goals) if per_type[t] > rule.h[t]]
    if above:
        t = above[0]
        return rec(cid, "error", f"type {t + 1} pays {per_type[t]}, above its guarantee h = "
                   f"{rule.h[t]} (a lower bound over all walks): could not decide its regret",
                   nums, NSOLVE, proof)
    rays = f", {arc.rays} non-pattern directions" if arc.rays else ""
    return rec(cid, "pass", f"every type pays exactly h_θ, its minimum over all walks of any "
               f"length (arc condition on all {arc.arcs} walkable arcs{rays})", nums, NSOLVE,
               proof)
