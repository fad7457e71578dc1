"""The value of the goal-selection game, ``V_sel``, exact where proved, else a named bracket
(proofs/SELECT.md).

``V_sel = min_q [V(q) − q·r] = sup_σ min_i (c_i(σ) − r_i)`` (SELECT.1). With the guarantee
sets ``F_v = {x : a·x <= m_a(v), a ∈ A}`` of the untruncated game (the checker's own
:func:`~dppverify.structured.proved_value.infinite_sets`, at no prior: the sets do not depend on
one)::

    V_sel = max {t : t·1 + r ∈ F_s0} = min_a (m_a(s0) − a·r) / |a|     (SELECT.2)

when ``F`` are the exact sets (N <= 3 always, NG.4; N = 4, 5 when their arc condition holds).
Any DP's sets contain the exact ones, so the same number is an upper bound; below, the uniform
Defender (every type pays at least ``d(s0, g^i)/N``) and NG.10's translated sets give lower
bounds. ``q*`` is the barycentre of ``a/|a|`` over the normals attaining the minimum (SELECT.3).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from fractions import Fraction

from dppverify.exact import Bracket, normalize
from dppverify.game.instance import Instance
from dppverify.structured.cover import Normal, min_cover_vectors, zero_one_normals
from dppverify.structured.dp_certificate import certified_coalition_dp
from dppverify.structured.lower_bounds import translation_at_start
from dppverify.structured.normal_fixpoint import NormalSets
from dppverify.structured.proved_value import NValue, infinite_sets, nvalue


@dataclass(frozen=True, kw_only=True)
class SelectionValue(Bracket):
    """``V_sel`` (a :class:`~dppverify.exact.Bracket`: closed when proved) and how it was found.

    Attributes
    ----------
    choice : tuple of Fraction or None
        ``q*`` when the value is proved (the barycentre of the binding normals), else None.
    binding : tuple of tuple of int
        The normals ``a`` attaining ``(m_a(s0) − a·r)/|a| = V_sel`` (of the upper bound's sets).
    normals : tuple of tuple of int
        The extra facet normals of the sets used (beyond the 0/1 vectors).
    uniform : NValue
        The game's value at the uniform prior (the payoff without the values ``r``).
    values : tuple of Fraction
        The goal values ``r``.
    """

    choice: tuple[Fraction, ...] | None
    binding: tuple[Normal, ...]
    normals: tuple[Normal, ...]
    uniform: NValue
    values: tuple[Fraction, ...]

    @property
    def value(self) -> Fraction | None:
        """``V_sel`` when proved, else None."""
        return None if self.exact is None else Fraction(self.exact)

    @property
    def uniform_payoff(self) -> Bracket:
        """The uniform prior's value in the selection payoff, ``V(1/N, …) − mean(r)``."""
        shift = sum(self.values, Fraction(0)) / len(self.values)
        u = self.uniform
        return Bracket(normalize(Fraction(u.lower) - shift), normalize(Fraction(u.upper) - shift),
                       u.lower_source, u.upper_source, u.reason)


def diagonal_bound(normals: Sequence[Normal], column: Sequence[Fraction],
                   values: Sequence[Fraction]) -> tuple[Fraction, tuple[Normal, ...]]:
    """``max {t : t·1 + r ∈ F}`` for ``F = {x : a·x <= column[a]}``, ``min_a (m_a − a·r)/|a|``,
    and the normals attaining it.

    Examples
    --------
    paper10.map's start: ``d1 = 18``, ``d2 = 17``, ``M = 25``:

    >>> diagonal_bound([(1, 0), (0, 1), (1, 1)], [18, 17, 25], [0, 0])
    (Fraction(25, 2), ((1, 1),))
    """
    best: Fraction | None = None
    at: list[Normal] = []
    for a, m in zip(normals, column, strict=True):
        x = (Fraction(m) - sum((ai * Fraction(r) for ai, r in zip(a, values, strict=True)),
                               Fraction(0))) / sum(a)
        if best is None or x < best:
            best, at = x, [tuple(a)]
        elif x == best:
            at.append(tuple(a))
    assert best is not None
    return best, tuple(at)


def barycentre(binding: Sequence[Normal]) -> tuple[Fraction, ...]:
    """The choice ``q*``: the mean of ``a/|a|`` over the binding normals.

    Examples
    --------
    >>> barycentre([(0, 1), (1, 1)])
    (Fraction(1, 4), Fraction(3, 4))
    """
    n = len(binding[0])
    return tuple(sum((Fraction(a[t], sum(a)) for a in binding), Fraction(0)) / len(binding)
                 for t in range(n))


def _column(sets: NormalSets) -> list[Fraction]:
    col = sets.column(sets.instance.start)
    assert col is not None  # every goal is reachable from the start
    return col


def goal_values(instance: Instance) -> tuple[Fraction, ...]:
    """The goal values of a goal-selection game (all 0 for a game with a prior).

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> goal_values(triangle())
    (Fraction(0, 1), Fraction(0, 1))
    """
    return instance.goal_values or (Fraction(0),) * instance.n_goals


def selection_value(instance: Instance, horizon: int | None = None,
                    progress: Callable[[str], None] | None = None) -> SelectionValue:
    """``V_sel`` of a goal-selection game, exact where proved, else a bracket naming its bounds.

    ``horizon``: the game truncated at ``H`` steps (SELECT.9: the coalition DP's layer ``H``,
    exact for N <= 3 and where its certificate holds at every layer); None (the default) is
    the untruncated game.

    Examples
    --------
    >>> from dppverify.game.examples import triangle_document
    >>> from dppverify.game.instance import instance_from_json
    >>> doc = {**triangle_document(), "goal_selection": True}
    >>> del doc["prior"]
    >>> v = selection_value(instance_from_json(doc))
    >>> v.value, v.choice, v.binding, v.uniform.value
    (Fraction(2, 1), (Fraction(1, 4), Fraction(3, 4)), ((0, 1), (1, 1)), 2)
    """
    game, r = instance, goal_values(instance)
    if horizon is not None:
        return _truncated(instance, horizon)
    found = infinite_sets(game, progress)
    sets = found.sets
    upper, binding = diagonal_bound(sets.normals, _column(sets), r)
    if found.exact:
        src = ("the exact guarantee sets at the start: "
               + (f"{len(sets.extras)} extra facet normals, certified at every arc "
                  "(NRULE NR.1(e))" if sets.extras else
                  "the coalition DP (NG.3, NG.4)" if game.n_goals <= 3 else
                  "the coalition DP, certified at every arc (NG.8)")
               + "; V_sel = max t with t·1 + r in G_s0 (SELECT.2)")
        return SelectionValue(upper, upper, src, src, None, choice=barycentre(binding),
                              binding=binding, normals=sets.extras, uniform=found.value,
                              values=r)
    coal_upper, coal_binding = diagonal_bound(found.coalition.normals, _column(found.coalition),
                                              r)
    up_src = (f"the DP over {len(sets.extras)} extra normals (its sets contain the exact "
              "ones; SELECT.2)" if sets.extras else
              "the coalition DP (its sets contain the exact ones; SELECT.2)")
    if coal_upper < upper:
        upper, binding = coal_upper, coal_binding
        up_src = "the coalition DP (its sets contain the exact ones; SELECT.2)"
    n = game.n_goals
    lower = min(Fraction(game.dist_to[t][game.start]) / n - r[t] for t in range(n))
    lo_src = "the uniform Defender: every type pays at least d(s0, g^i)/N (SELECT.2)"
    shift = translation_at_start(found.coalition)
    if shift is not None and coal_upper - shift > lower:
        lower = coal_upper - shift
        lo_src = ("the coalition DP's sets translated into a sub-fixpoint along the diagonal "
                  "(NG.10, SELECT.2)")
    reason = found.value.reason or "the sets are not certified at every arc"
    if lower == upper:
        src = f"{up_src} meeting {lo_src}"
        return SelectionValue(upper, upper, src, src, None, choice=None, binding=binding,
                              normals=sets.extras, uniform=found.value, values=r)
    return SelectionValue(lower, upper, lo_src, up_src, reason, choice=None, binding=binding,
                          normals=sets.extras, uniform=found.value, values=r)


def value_at(sets: NormalSets, choice: Sequence[Fraction]) -> Fraction:
    """``V(q)``: the sets' support function at the choice ``q`` (the exact cover LP).

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> from dppverify.structured.normal_fixpoint import normal_sets
    >>> value_at(normal_sets(star3()), [Fraction(1, 3)] * 3)
    Fraction(4, 3)
    """
    return Fraction(min_cover_vectors(sets.normals, _column(sets), list(choice)).value)


def _truncated(instance: Instance, horizon: int) -> SelectionValue:
    """SELECT.9: ``V_{H,sel}`` from the coalition DP's layer ``H`` at the start."""
    game, r = instance, goal_values(instance)
    n = game.n_goals
    coal, fails, _ = certified_coalition_dp(game, horizon, None)
    normals = zero_one_normals(n)
    column = [Fraction(coal.coalition_costs[mask]) for mask in range(1, 1 << n)]
    upper, binding = diagonal_bound(normals, column, r)
    uniform = nvalue(game, horizon)
    if not fails:
        src = (f"the coalition DP at H = {horizon} ("
               + ("NG.3, NG.4: the exact sets" if n <= 3 else "certified at every layer, NG.8")
               + "); V_sel = max t with t·1 + r in G_s0 (SELECT.2, SELECT.9)")
        return SelectionValue(upper, upper, src, src, None, choice=barycentre(binding),
                              binding=binding, normals=(), uniform=uniform, values=r)
    lower = min(Fraction(game.dist_to[t][game.start]) / n - r[t] for t in range(n))
    v, u, _ = fails[0]
    return SelectionValue(lower, upper, "the uniform Defender: every type pays at least "
                          "d(s0, g^i)/N (SELECT.2)", f"the coalition DP at H = {horizon} (an "
                          "upper bound, NG.2)", f"the coalition DP's certificate fails at arc "
                          f"{game.nodes[v]!r} -> {game.nodes[u]!r}", choice=None,
                          binding=binding, normals=(), uniform=uniform, values=r)
