"""The goal-selection equilibrium: the Attacker's choice ``q*``, its walks and the Defender's rule
(proofs/SELECT.md).

With the exact guarantee sets ``F_v = {x : a·x <= m_a(v), a ∈ A}`` of the game at ``H = inf``
(:func:`~solver.coalitions.construction.certified_sets`, proofs/NEXACT.md; they do not depend
on a prior) and goal values ``r``:

- **Value.** ``V_sel = max {t : t·1 + r ∈ F_s0} = min_a (m_a(s0) − a·r)/|a|`` (SELECT.2), the
  minimum over the normals ``a`` of ``A`` (``|a|`` the sum of its entries).
- **Choice.** ``q*`` is the barycentre of ``a/|a|`` over the normals attaining that minimum
  (the *binding* normals): the dual of the one small LP ``max t``, and the choice with the
  largest support among its optimal solutions (SELECT.3).
- **Defender.** The guarantee rule with ``h = V_sel·1 + r`` on the support of ``q*``; off the
  support each coordinate is raised, in goal order, to the largest value that keeps
  ``h ∈ F_s0`` (SELECT.4), so that the types the Attacker never chooses have a constructed
  cheapest walk of cost ``h_i`` too. Its priority order is that of ``q*``.
- **Attacker.** The normal-coalition pieces of proofs/NEXACT.md from the cover of ``q*``
  (every type chosen with positive probability); a type off the support follows the pieces of
  one binding normal of its raised coordinate.

Every type ``i`` pays exactly ``h_i`` on each of its walks (NEXACT NX.4), so ``c_i − r_i =
V_sel`` on the support of ``q*`` and ``>= V_sel`` off it. For two goals the Defender may instead
be the per-prefix mixture of the two progress rules (:mod:`solver.selection.mixture`,
SELECT.5).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import Any, Literal

from solver.coalitions.construction import (
    DEFAULT_BUDGET,
    CertifiedSets,
    FixpointNotReached,
    SetsNotCertified,
    certified_sets,
)
from solver.coalitions.guarantee_rule import priority_order
from solver.coalitions.guarantee_sets import Budget, Fixpoint
from solver.coalitions.normal_attacker import piece_walks
from solver.coalitions.normal_cover import normal_cover_lp
from solver.coalitions.vertex_tables import Normal
from solver.game.instance import Instance
from solver.game.profile_writing import selection_profile
from solver.game.walks import StrategyWalk
from solver.selection.instance import SelectionInstance, as_selection
from solver.selection.mixture import TwoGoalMixture, two_goal_mixture

Rule = Literal["guarantee", "mixture"]
Mixture = tuple[tuple[tuple[int, ...], Fraction], ...]

METHOD = ("goal selection (proofs/SELECT.md): V_sel = max t with t·1 + r in the exact guarantee "
          "set at the start (proofs/NEXACT.md); q* the barycentre of the binding normals; the "
          "normal-coalition Attacker from the cover of q*")


@dataclass(frozen=True, eq=False)
class SelectionEquilibrium:
    """The goal-selection profile and its exact values.

    Attributes
    ----------
    selection : SelectionInstance
        The game.
    value : Fraction
        ``V_sel = min_q [V(q) − q·r] = max_σ min_i (c_i(σ) − r_i)``.
    choice : tuple of Fraction
        ``q*``.
    h : tuple of Fraction
        The guarantee rule's vector (``V_sel + r_i`` on the support of ``q*``).
    costs : tuple of Fraction
        ``c_i``: type ``i``'s exact best-response cost against the Defender (``h_i``).
    binding : tuple of tuple of int
        The normals ``a`` with ``(m_a(s0) − a·r)/|a| = V_sel``.
    normals : tuple of tuple of int
        The rule's extra facet normals (not 0/1 vectors).
    mixtures : tuple
        ``mixtures[i]``: ``((walk as game node indices, probability), …)``.
    uniform_value : Fraction
        The value of the game with the uniform prior, in the same payoff:
        ``V(1/N, …, 1/N) − mean(r)``; ``uniform_value − value >= 0`` is what choosing gains.
    mixture : TwoGoalMixture or None
        Two goals with ``rule="mixture"``: the Defender mixing the two progress rules.
    layers, rounds : int
        The fixpoint's layer ``K`` and the refinement rounds.
    seconds : float
        Solve time.
    """

    selection: SelectionInstance = field(repr=False)
    value: Fraction
    choice: tuple[Fraction, ...]
    h: tuple[Fraction, ...]
    costs: tuple[Fraction, ...]
    binding: tuple[Normal, ...]
    normals: tuple[Normal, ...]
    mixtures: tuple[Mixture, ...] = field(repr=False)
    uniform_value: Fraction
    mixture: TwoGoalMixture | None = None
    layers: int = 0
    rounds: int = 0
    seconds: float = 0.0

    @property
    def gain(self) -> Fraction:
        """What choosing its goal gains the Attacker over the uniform prior (``>= 0``)."""
        return self.uniform_value - self.value

    @property
    def strategies(self) -> tuple[tuple[StrategyWalk, ...], ...]:
        """``strategies[i]``: type ``i``'s mixed strategy as walks with probabilities."""
        net = self.selection.game.network
        return tuple(tuple(StrategyWalk.along(net, w, p) for w, p in mix)
                     for mix in self.mixtures)

    @property
    def defender(self) -> dict[str, Any]:
        """The Defender's rule as the profile writes it (``docs/formats.md`` §2d)."""
        if self.mixture is not None:
            return self.mixture.rule_json(self.selection.game)
        out: dict[str, Any] = {"rule": "guarantee", "h": [str(x) for x in self.h]}
        if self.normals:
            out["normals"] = [list(a) for a in self.normals]
        return out

    def to_json(self) -> dict[str, Any]:
        """The ``dpp-selection-profile/1`` document (``docs/formats.md`` §2d).

        Examples
        --------
        >>> from solver.game.instance import triangle
        >>> doc = {**triangle().to_json(), "goal_selection": True}
        >>> del doc["prior"]
        >>> out = selection_equilibrium(doc).to_json()
        >>> out["format"], out["choice"], out["value"]["V"], out["defender"]["rule"]
        ('dpp-selection-profile/1', ['1/4', '3/4'], '2', 'guarantee')
        """
        values = {"V": str(self.value), "costs": [str(c) for c in self.costs],
                  "uniform": str(self.uniform_value), "gain": str(self.gain)}
        return selection_profile(
            self.selection.game, self.strategies, choice=self.choice, defender=self.defender,
            values=values, method=METHOD + (f"; Defender: {self.mixture.method}"
                                            if self.mixture is not None else ""),
            binding=[list(a) for a in self.binding], layers=self.layers,
            refinement_rounds=self.rounds)

    def summary(self) -> str:
        """One line: ``V_sel``, the uniform prior's value beside it, ``q*`` and the Defender.

        Examples
        --------
        >>> from solver.game.instance import triangle
        >>> doc = {**triangle().to_json(), "goal_selection": True}
        >>> del doc["prior"]
        >>> print(selection_equilibrium(doc).summary())
        goal selection, N = 2: V_sel = 2 (at the uniform prior: 2; choosing gains 0); \
q* = (1/4, 3/4); costs (2, 2); Defender: guarantee rule h = (2, 2)
        """
        game = self.selection.game
        q = ", ".join(map(str, self.choice))
        rule = (self.mixture.describe(game) if self.mixture is not None else
                f"guarantee rule h = ({', '.join(map(str, self.h))})"
                + (f" with {len(self.normals)} extra normals" if self.normals else ""))
        return (f"goal selection, N = {game.n_goals}: V_sel = {self.value} (at the uniform "
                f"prior: {self.uniform_value}; choosing gains {self.gain}); q* = ({q}); costs "
                f"({', '.join(map(str, self.costs))}); Defender: {rule}")


def _selection_bound(fix: Fixpoint, start: int, values: tuple[Fraction, ...]
                     ) -> tuple[Fraction, tuple[int, ...]]:
    """``min_a (m_a(s0) − a·r)/|a|`` over the fixpoint's normals, and the indices attaining it."""
    best: Fraction | None = None
    at: list[int] = []
    for j, a in enumerate(fix.system.normals):
        x = (fix.value(j, start) - sum((ai * r for ai, r in zip(a, values, strict=True)),
                                       Fraction(0))) / sum(a)
        if best is None or x < best:
            best, at = x, [j]
        elif x == best:
            at.append(j)
    assert best is not None
    return best, tuple(at)


def selection_value(fix: Fixpoint, start: int, values: tuple[Fraction, ...]) -> Fraction:
    """``max {t : t·1 + r ∈ F_s0}`` for the sets of a DP fixpoint: ``V_sel`` when the sets are
    the exact ones, an upper bound when they contain them (SELECT.2).

    Examples
    --------
    >>> from solver.coalitions.construction import certified_sets
    >>> from solver.game.instance import triangle
    >>> cs = certified_sets(triangle())   # d1 = 3, d2 = 2, M = 4: min(3, 2, 4/2)
    >>> selection_value(cs.found.fixpoint, cs.graph.start, (Fraction(0), Fraction(0)))
    Fraction(2, 1)
    """
    return _selection_bound(fix, start, values)[0]


def _not_reached(game: Instance, values: tuple[Fraction, ...], exc: SetsNotCertified
                 ) -> FixpointNotReached:
    """The exact bracket on ``V_sel`` when the sets are not certified."""
    if exc.fixpoint is not None and exc.certified:
        v = selection_value(exc.fixpoint, exc.start, values)
        src = "the certified fixpoint (proofs/SELECT.md SELECT.2)"
        return FixpointNotReached(exc.reason, v, src, v, src)
    n = game.n_goals
    lower = min(game.distance(t, game.s0) / n - values[t] for t in range(n))
    lo_src = "the uniform Defender: every type pays at least d(s0, g^i)/N (proofs/SELECT.md)"
    upper = None if exc.fixpoint is None else selection_value(exc.fixpoint, exc.start, values)
    up_src = ("none (no fixpoint of the DP)" if exc.fixpoint is None else
              "the normal-restricted DP's outer sets (proofs/SELECT.md SELECT.2)")
    return FixpointNotReached(exc.reason, lower, lo_src, upper, up_src)


def _raise_off_support(h: list[Fraction], choice: tuple[Fraction, ...],
                       normals: tuple[Normal, ...], m0: list[Fraction]) -> dict[int, int]:
    """SELECT.4: raise ``h_i`` for every ``i`` with ``q*_i = 0``, in goal order, to the largest
    value keeping ``h ∈ F_s0``; the binding normal of each (type -> normal index)."""
    tight: dict[int, int] = {}
    for i, q in enumerate(choice):
        if q:
            continue
        best: tuple[Fraction, int] | None = None
        for j, a in enumerate(normals):
            if a[i]:
                rest = sum((a[k] * h[k] for k in range(len(h)) if k != i), Fraction(0))
                x = (m0[j] - rest) / a[i]
                if best is None or x < best[0]:
                    best = (x, j)
        assert best is not None and best[0] >= h[i]  # the unit vector e_i is a normal
        h[i], tight[i] = best
    return tight


def _type_mixtures(leaves: tuple[tuple[tuple[int, ...], dict[int, Fraction]], ...],
                   normals: tuple[Normal, ...], weight: list[Fraction], types: list[int],
                   labels: Any) -> dict[int, Mixture]:
    """Type ``θ``'s walks: the ``θ``-mass ``Σ μ a_θ`` of the pieces ending on each walk, over
    ``weight[θ]`` (its total), for the types ``types``."""
    out: dict[int, dict[tuple[int, ...], Fraction]] = {t: {} for t in types}
    for walk, pieces in leaves:
        game_walk = tuple(int(labels[v]) for v in walk)
        for j, mass in pieces.items():
            for t in types:
                if normals[j][t]:
                    d = out[t]
                    d[game_walk] = d.get(game_walk, Fraction(0)) + mass * normals[j][t] / weight[t]
    return {t: tuple(sorted(d.items(), key=lambda kv: (-kv[1], kv[0]))) for t, d in out.items()}


def _attacker(cs: CertifiedSets, cover: dict[int, Fraction], choice: tuple[Fraction, ...],
              tight: dict[int, int]) -> dict[int, Mixture]:
    """Every type's walks: the pieces of the cover of ``q*`` for the types it chooses, and the
    pieces of the tight normal ``tight[i]`` (mass 1) for each type ``i`` it never chooses
    (SELECT.5)."""
    fix = cs.found.fixpoint
    normals = fix.system.normals
    n = len(choice)
    on = [t for t in range(n) if choice[t]]
    out = _type_mixtures(piece_walks(cs.graph, fix, cover), normals, list(choice), on,
                         cs.labels)
    for t, j in tight.items():
        out |= _type_mixtures(piece_walks(cs.graph, fix, {j: Fraction(1)}), normals,
                              [Fraction(normals[j][k]) for k in range(n)], [t], cs.labels)
    return out


def selection_equilibrium(instance: SelectionInstance | dict[str, Any] | str | Path, *,
                          rule: Rule = "guarantee", budget: Budget = DEFAULT_BUDGET
                          ) -> SelectionEquilibrium:
    """The exact goal-selection equilibrium of a game with 2 to 5 goals.

    Parameters
    ----------
    instance : SelectionInstance, dict, str or Path
        The goal-selection game (``docs/formats.md`` §1, "Goal selection").
    rule : {"guarantee", "mixture"}
        The Defender: the guarantee rule (any N), or for two goals the per-prefix mixture of
        the two progress rules.
    budget : Budget
        The refinement's limits (as ``dpp solve``'s).

    Raises
    ------
    FixpointNotReached
        When the budget ends before certified sets: an exact bracket on ``V_sel``.
    InvalidInstanceError
        ``rule="mixture"`` with more than two goals.

    Examples
    --------
    The hub of ``docs/formats.md`` §1: the three goals are one step past the hub ``m``, so the
    Attacker hides in the hub with all three (``V(q) = (4/3)`` at the uniform choice, against
    ``d(s0, g) = 2`` when the goal is known):

    >>> doc = {"graph": {"nodes": [{"id": x} for x in "smabc"],
    ...        "edges": [{"source": "s", "target": "m"}, {"source": "m", "target": "a"},
    ...                  {"source": "m", "target": "b"}, {"source": "m", "target": "c"},
    ...                  {"source": "s", "target": "a", "weight": 2}]},
    ...        "start": "s", "goals": ["a", "b", "c"], "goal_selection": True}
    >>> eq = selection_equilibrium(doc)
    >>> str(eq.value), [str(q) for q in eq.choice], [str(c) for c in eq.costs]
    ('4/3', ['1/3', '1/3', '1/3'], ['4/3', '4/3', '4/3'])
    """
    t0 = time.perf_counter()
    sel = as_selection(instance)
    game, values = sel.game, sel.values
    n = game.n_goals
    if rule == "mixture" and n != 2:
        from solver.errors import InvalidInstanceError
        raise InvalidInstanceError(f"the progress-rule mixture is a two-goal Defender; this "
                                   f"game has {n} goals (use the guarantee rule)")
    try:
        cs = certified_sets(game, budget)
    except SetsNotCertified as exc:
        raise _not_reached(game, values, exc) from None
    fix = cs.found.fixpoint
    normals = fix.system.normals
    start = cs.graph.start
    m0 = [fix.value(j, start) for j in range(len(normals))]
    value, at = _selection_bound(fix, start, values)
    binding = tuple(normals[j] for j in at)
    choice = tuple(sum((Fraction(a[t], sum(a)) for a in binding), Fraction(0)) / len(binding)
                   for t in range(n))
    h = [value + r for r in values]
    root = normal_cover_lp(normals, m0, list(choice), priority_order(choice))
    # h is an optimal dual at q* (SELECT.3): every root piece is tight at h
    assert root.value == value + sum((q * r for q, r in zip(choice, values, strict=True)),
                                     Fraction(0))
    assert all(sum((a * x for a, x in zip(normals[j], h, strict=True)), Fraction(0)) == m0[j]
               for j in root.cover)
    tight = _raise_off_support(h, choice, normals, m0)
    mixtures = _attacker(cs, root.cover, choice, tight)
    uniform = [Fraction(1, n)] * n
    uniform_value = (normal_cover_lp(normals, m0, uniform).value
                     - sum(values, Fraction(0)) / n)
    mixture = None
    if rule == "mixture":
        mixture = two_goal_mixture(game, values, m0[:3], choice, value)
        mixture.check_costs(game, mixtures, h)
    return SelectionEquilibrium(
        selection=sel, value=value, choice=choice, h=tuple(h), costs=tuple(h),
        binding=binding, normals=cs.found.extra_normals,
        mixtures=tuple(mixtures[t] for t in range(n)), uniform_value=uniform_value,
        mixture=mixture, layers=fix.layers, rounds=cs.found.rounds,
        seconds=time.perf_counter() - t0)
