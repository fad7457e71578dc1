"""The guarantee-vector Defender rule of ``dpp-ngoal-profile/1``, evaluated from the checker's
own mathematics (``proofs/NSOLVE.md``, ``proofs/NRULE.md``).

Profile: ``"defender": {"rule": "guarantee", "h": [h_1, …, h_N], "normals": [[…], …]}``
(``docs/formats.md`` §2b; read by :func:`dppverify.game.profile_types.parse_guarantee`). With
``A`` the 0/1 vectors plus ``normals``, ``m_a(v)`` the normal-restricted DP at ``H = inf``
(:mod:`dppverify.structured.normal_fixpoint`; for ``normals = []`` the coalition DP) and
``F_v = { r : a·r <= m_a(v) for a ∈ A }``:

- the state is ``r``, ``r = h`` at the start;
- on a step ``v -> u`` of weight ``w`` the Defender plays the lexicographic minimum, in the
  *priority order* (types by decreasing prior, ties by goal index), of
  ``F = { σ ∈ Δ^N : a·σ >= (a·r - m_a(u)) / w for every a ∈ A }``, and ``r <- r - w σ``;
  when ``F`` is empty, all the weight on the first type of the priority order.

The Attacker's regret against the rule is decided by :mod:`dppverify.structured.rule_response`;
this module evaluates the rule on the profile's walks (:func:`evaluate_rule_profile`) and on any
prefix tree (:func:`rule_on_trie`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction

from dppverify.exact import Number
from dppverify.game.instance import Instance
from dppverify.game.profile_types import StrategyWalk
from dppverify.game.rules import GuaranteeRule
from dppverify.structured.coalition import CoalitionValue
from dppverify.structured.cover import Normal, min_cover
from dppverify.structured.lexmin import lexmin
from dppverify.structured.normal_fixpoint import NormalSets, normal_sets
from dppverify.structured.table_br import TableDefender
from dppverify.structured.trie import build_walk_trie


def rule_order(prior: Sequence[Fraction]) -> tuple[int, ...]:
    """The priority order: types by decreasing prior, ties by goal index.

    Examples
    --------
    >>> rule_order([Fraction(1, 6), Fraction(1, 2), Fraction(1, 3)])
    (1, 2, 0)
    """
    return tuple(sorted(range(len(prior)), key=lambda t: (-prior[t], t)))


def guarantee_sets(instance: Instance, normals: Sequence[Normal] = ()) -> NormalSets:
    """The guarantee rule's sets: ``m_a`` at ``H = inf`` for the 0/1 normals and ``normals``.

    :func:`dppverify.structured.normal_fixpoint.normal_sets`: one label-setting pass per normal
    (``proofs/NRULE.md`` NR.1; for the 0/1 normals NSOLVE.3: the limit ``H -> inf`` of the
    layered coalition DP of :mod:`dppverify.structured.coalition`).

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> g = guarantee_sets(star3())
    >>> g.value(0b111, star3().start), g.value(0b001, star3().start)
    (Fraction(4, 1), Fraction(2, 1))
    """
    return normal_sets(instance, normals)


def dp_value(sets: NormalSets) -> CoalitionValue:
    """The coalition DP's value at ``H = inf`` from the fixpoint's 0/1 rows (a
    ``CoalitionValue``).

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> dp_value(guarantee_sets(star3())).value
    Fraction(3, 2)
    """
    inst = sets.instance
    costs = {mask: sets.value(mask, inst.start) or Fraction(0)
             for mask in range(1, 1 << inst.n_goals)}
    lp = min_cover(costs, inst.prior)
    return CoalitionValue(horizon=None, value=lp.value, layers=len(sets.normals),
                          coalition_costs=costs, cover=dict(lp.cover))


# ---------------------------------------------------------------- the rule's σ (lexmin)
def guarantee_sigma(r: Sequence[Fraction], sets: NormalSets, u: int, w: Number,
                    order: Sequence[int]) -> tuple[tuple[Fraction, ...], bool]:
    """The rule's ``σ`` on a step into ``u`` of weight ``w`` from state ``r`` (and F ≠ ∅).

    ``σ`` is the lexicographic minimum in ``order`` of
    ``F = { σ ∈ Δ^N : a·σ >= (a·r - m_a(u)) / w  for every normal a }``
    (:func:`dppverify.structured.lexmin.lexmin`); all weight on ``order[0]`` when ``F`` is empty.

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
    m_u = sets.column(u)
    rows: list[tuple[tuple[int, ...], Fraction]] = []
    if m_u is not None:
        for a, m in zip(sets.normals, m_u, strict=True):
            need = (sum((r[i] * a[i] for i in range(n) if a[i]), Fraction(0)) - m) / wf
            if need > 0:
                rows.append((a, need))
    sigma = lexmin(rows, n, order)
    if sigma is None:
        return tuple(Fraction(int(i == order[0])) for i in range(n)), False
    return sigma, True


def in_start_set(rule: GuaranteeRule, sets: NormalSets) -> Normal | None:
    """The first normal ``a`` (0/1 by subset size, then the extras) with ``a·h > m_a(s0)``;
    None when ``h ∈ F_{s0}``.

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> sets = guarantee_sets(star3())
    >>> in_start_set(GuaranteeRule((Fraction(2), Fraction(1), Fraction(1))), sets)
    >>> in_start_set(GuaranteeRule((Fraction(3), Fraction(1), Fraction(1))), sets)
    (1, 0, 0)
    """
    s0 = sets.instance.start
    col = sets.column(s0)
    if col is None:
        return None
    for j in sorted(range(len(sets.normals)), key=lambda t: (sum(sets.normals[t]), t)):
        a = sets.normals[j]
        if sum((x * y for x, y in zip(a, rule.h, strict=True)), Fraction(0)) > col[j]:
            return a
    return None


def rule_on_trie(instance: Instance, rule: GuaranteeRule, sets: NormalSets,
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
    sets : NormalSets
        ``m_a`` at every node for the rule's normals (its state space).
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

    sets: NormalSets
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
    sets = guarantee_sets(inst, rule.normals)
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
