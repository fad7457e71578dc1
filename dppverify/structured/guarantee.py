"""The guarantee-vector Defender rule of ``dpp-ngoal-profile/1`` (proofs/NSOLVE.md), evaluated
from the checker's own mathematics.

Profile: ``"defender": {"rule": "guarantee", "h": [h_1, …, h_N]}`` (``docs/formats.md`` §2b; read
by :func:`dppverify.game.profile_types.parse_guarantee`).
With ``m_S(v)`` the coalition DP at ``H = inf`` (:mod:`dppverify.structured.coalition`, the layer
that repeats) and ``G_v = { r : r(S) <= m_S(v) for every non-empty S }``:

- the state is ``r``, ``r = h`` at the start;
- on a step ``v -> u`` of weight ``w`` the Defender plays the lexicographic minimum, in the
  *priority order* (types by decreasing prior, ties by goal index), of
  ``F = { σ ∈ Δ^N : σ(S) >= (r(S) - m_S(u)) / w for every S }``, and ``r <- r - w σ``;
  when ``F`` is empty, all the weight on the first type of the priority order.

What the checker proves about it (NSOLVE.1-2), exactly:

- ``h ∈ G_{s0}`` (:func:`in_start_set`), and the **arc condition** ``G_v ⊆ G_u + wΔ^N`` on
  every arc ``(v, u)`` that a walk can take (:mod:`dppverify.structured.arc_condition`). Then
  ``F`` is never empty on any walk, ``r`` stays in ``G``, and every walk costs type ``θ`` at
  least ``h_θ``: the minimum over ALL walks is ``>= h_θ`` (NSOLVE.1).
- On the profile's walks the rule is evaluated step by step (:func:`evaluate_rule_profile`); a
  type paying exactly ``h_θ`` has regret 0 over all walks of any length.
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np

from dppverify.exact import INF, Number
from dppverify.game.distances import EXACT_FLOAT_LIMIT, dijkstra, sparse_dijkstra
from dppverify.game.instance import Instance
from dppverify.game.profile_types import GuaranteeRule, StrategyWalk
from dppverify.structured.coalition import CoalitionValue, coalition_scale, splits
from dppverify.structured.cover import members, min_cover
from dppverify.structured.table_br import TableDefender
from dppverify.structured.trie import build_walk_trie

__all__ = ["GuaranteeRule", "GuaranteeSets", "RuleProfile", "dp_value", "evaluate_rule_profile",
           "guarantee_sets", "guarantee_sigma", "in_start_set", "rule_on_trie", "rule_order"]

def rule_order(prior: Sequence[Fraction]) -> tuple[int, ...]:
    """The priority order: types by decreasing prior, ties by goal index.

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
    instance : Instance
    scale : int
        ``m_S(v) = m[S][v] / scale``.
    big : int
        Values ``>= big`` mean: no goal reachable.
    m : Mapping
        Subset mask -> array over nodes.
    layers : int
        Label-setting passes (one per subset).
    """

    instance: Instance
    scale: int
    big: int
    m: Mapping[int, np.ndarray]
    layers: int

    def value(self, mask: int, v: int) -> Fraction | None:
        """``m_S(v)`` exactly, None where no goal is reachable."""
        x = int(self.m[mask][v])
        return None if x >= self.big else Fraction(x, self.scale)


def guarantee_sets(instance: Instance) -> GuaranteeSets:
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
    >>> from dppverify.game.examples import star3
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
    """``min_x [dist(v -> x) + init[x]]`` (``init < 0``: no source there), ``big`` if none.

    One shortest-path computation on the reversed arcs from a root ``n`` with an arc
    ``n -> x`` of weight ``init[x] + 1`` (positive) to every source ``x``: scipy's in float64
    while every distance is an integer below 2**53, else the exact one of
    :func:`dppverify.game.distances.dijkstra`.
    """
    src = [x for x in range(n) if init[x] >= 0]
    out = np.full(n, big, dtype=object)
    rows = heads + [n] * len(src)
    cols = tails + src
    lengths = weights + [init[x] + 1 for x in src]
    if max((init[x] for x in src), default=0) + sum(weights) + 2 < EXACT_FLOAT_LIMIT:
        from scipy.sparse import csr_matrix

        r = np.asarray(rows, dtype=np.int64)
        c = np.asarray(cols, dtype=np.int64)
        w = np.asarray(lengths, dtype=np.float64)
        dist = sparse_dijkstra(csr_matrix((w, (r, c)), shape=(n + 1, n + 1)), n)[:n]
        fin = np.flatnonzero(np.isfinite(dist))
        out[fin] = [int(x) - 1 for x in dist[fin].tolist()]
        return out
    adj: list[list[tuple[int, Number]]] = [[] for _ in range(n + 1)]
    for a, b, w2 in zip(rows, cols, lengths, strict=True):
        adj[a].append((b, w2))
    exact = dijkstra(adj, n)
    for v in range(n):
        if exact[v] != INF:
            out[v] = exact[v] - 1
    return out


def dp_value(sets: GuaranteeSets) -> CoalitionValue:
    """The coalition DP's value at ``H = inf`` from the fixpoint (a ``CoalitionValue``).

    Examples
    --------
    >>> from dppverify.game.examples import star3
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
    >>> from dppverify.game.examples import star3
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


def in_start_set(rule: GuaranteeRule, sets: GuaranteeSets) -> int | None:
    """The first subset mask with ``h(S) > m_S(s0)`` (None when ``h ∈ G_{s0}``).

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> sets = guarantee_sets(star3())
    >>> in_start_set(GuaranteeRule((Fraction(2), Fraction(1), Fraction(1))), sets)
    >>> in_start_set(GuaranteeRule((Fraction(3), Fraction(1), Fraction(1))), sets)
    1
    """
    s0 = sets.instance.start
    for mask in sorted(sets.m, key=lambda t: (bin(t).count("1"), t)):
        m = sets.value(mask, s0)
        if m is not None and sum((rule.h[i] for i in range(len(rule.h)) if mask >> i & 1),
                                 Fraction(0)) > m:
            return mask
    return None


def rule_on_trie(instance: Instance, rule: GuaranteeRule, sets: GuaranteeSets,
                 parent: Sequence[int], node: Sequence[int]
                 ) -> tuple[dict[int, tuple[Fraction, ...]], bool]:
    """The rule's ``σ`` at every prefix of a prefix tree (``parent[p] < p``, root 0).

    Returns the distributions and whether ``F`` was non-empty at every prefix.

    Examples
    --------
    The walk ``s m a`` of the star (prefixes 0, 1, 2 at nodes 0, 1, 2):

    >>> from dppverify.game.examples import star3
    >>> inst = star3()
    >>> rule = GuaranteeRule((Fraction(2), Fraction(1), Fraction(1)))
    >>> sigma, ok = rule_on_trie(inst, rule, guarantee_sets(inst), [0, 0, 1], [0, 1, 2])
    >>> {p: [str(x) for x in s] for p, s in sigma.items()}, ok
    ({1: ['1', '0', '0'], 2: ['1', '0', '0']}, True)
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


@dataclass(frozen=True)
class RuleProfile:
    """A guarantee-rule profile evaluated on the trie of its walks.

    Attributes
    ----------
    sets : GuaranteeSets
        ``m_S`` at every node (the rule's state space).
    defender : TableDefender
        The rule's ``σ`` at every prefix of the trie of the profile's walks.
    mass : dict
        Trie prefix -> every type's realization mass there (``mass[p][θ]``).
    per_type : tuple of Fraction
        Every type's expected cost ``U_θ`` under the profile.
    feasible : bool
        Whether ``F`` was non-empty at every prefix.
    walks : int
        The profile's walks (all types).
    """

    sets: GuaranteeSets
    defender: TableDefender
    mass: dict[int, list[Fraction]]
    per_type: tuple[Fraction, ...]
    feasible: bool
    walks: int


def evaluate_rule_profile(instance: Instance, rule: GuaranteeRule,
                          attacker: Sequence[Sequence[StrategyWalk]]) -> RuleProfile:
    """The guarantee rule on the trie of the Attacker's walks: ``σ``, masses and payoffs.

    ``attacker[θ]`` is type ``θ``'s mixed strategy (valid walks of the instance).

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> inst = star3()
    >>> attacker = [[StrategyWalk((0, 1, g), Fraction(1))] for g in inst.goals]
    >>> ev = evaluate_rule_profile(inst, GuaranteeRule((Fraction(2), Fraction(1),
    ...                                                 Fraction(1))), attacker)
    >>> [str(u) for u in ev.per_type], ev.feasible, len(ev.defender.trie)
    (['2', '1', '1'], True, 5)
    """
    inst = instance
    n = inst.n_goals
    walks = [mw.walk for mix in attacker for mw in mix]
    trie = build_walk_trie(inst, walks)
    sets = guarantee_sets(inst)
    parent = trie.parent
    order_ok = all(parent[p] < p for p in range(1, len(trie)))
    assert order_ok  # the trie numbers prefixes in insertion order
    sigma, feasible = rule_on_trie(inst, rule, sets, parent, trie.node)
    tdef = TableDefender(instance=inst, trie=trie, sigma=sigma, default=None)
    mass: dict[int, list[Fraction]] = {}
    per_type: list[Fraction] = []
    for theta, mix in enumerate(attacker):
        total = Fraction(0)
        for mw in mix:
            p = 0
            cost = Fraction(0)
            mass.setdefault(0, [Fraction(0)] * n)[theta] += mw.probability
            for k, v in enumerate(mw.walk[1:], start=1):
                p = trie.extend(p, v)
                mass.setdefault(p, [Fraction(0)] * n)[theta] += mw.probability
                w = inst.weight(mw.walk[k - 1], v)
                assert w is not None
                cost += Fraction(w) * sigma[p][theta]
            total += mw.probability * (cost + Fraction(inst.dist_to[theta][mw.walk[-1]]))
        per_type.append(total)
    return RuleProfile(sets=sets, defender=tdef, mass=mass, per_type=tuple(per_type),
                       feasible=feasible, walks=len(walks))
