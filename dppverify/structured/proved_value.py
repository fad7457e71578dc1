"""Exact N-goal values: the guarantee-set recursion, certified on a finite set of facet normals.

``proofs/NGOAL.md`` (NG.6) proves that the value of the truncated N-goal game is
``V_H = max { b·r : r ∈ G_{s0}^H }`` for the *guarantee sets*

    G_g = { r : r <= d(g, g^·) }  at a goal g,     G_v^0 = R^N  elsewhere,
    G_v^k = ∩_{(v,u)} ( G_u^{k-1} + w(v,u)·Δ^N ),

and that a *normal-restricted* DP over a finite set ``M`` of facet normals
(:mod:`dppverify.structured.normal_dp`; with ``M`` the 0/1 vectors it is the coalition DP of
:mod:`dppverify.structured.coalition`) describes outer sets ``F_v^k`` ⊇ ``G_v^k`` (an upper
bound on ``V_H``, NG.2/NG.7). The sets are the true ones — and the DP value is ``V_H`` — as
soon as every arc satisfies ``F_v^k ⊆ F_u^{k-1} + w·Δ^N`` (NG.8), which
:mod:`dppverify.structured.dp_certificate` checks on the finitely many directions ``y_λ`` of
the packing polytope's vertices: none for N = 3 (which proves NG.4: the coalition DP is the
value), the four permutations of (1, 1, 1, 1/2) for N = 4 and 45 vectors for N = 5.

:func:`nvalue` runs the coalition DP, certifies it (``H = inf``: at the repeated layer, NG.8
then gives ``V_H`` for every ``H`` from that layer on; finite ``H``: at every layer) and, when
an arc fails, adds the failing direction ``y_λ`` and its permutations to ``M`` as primitive
integer normals and re-runs the DP (vectorised, exact integers at a reduced common scale; for
``H = inf`` started from the coalition fixpoint), a few rounds. Where no certificate is found
it returns a bracket naming both bounds: the best DP above, and below the better of two simple
Defenders (NG.9) and the coalition fixpoint's sets translated into a sub-fixpoint (NG.10;
both in :mod:`dppverify.structured.lower_bounds`).
Everything is exact; vertices come from exact integer determinants of every basis
(:mod:`dppverify.structured.cover`; no polyhedral library: the normals form a fixed small
table, so each basis is enumerated once per table, and tables of permuted right-hand sides are
shared by symmetry).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from dppverify.errors import HorizonError, OptionError
from dppverify.exact import Bracket, Number, normalize
from dppverify.game.instance import Instance
from dppverify.structured.arc_condition import ArcCondition, arc_condition, walkable_arcs
from dppverify.structured.coalition import CoalitionRunner, CoalitionValue, too_many_goals
from dppverify.structured.cover import MAX_BALANCED, Normal, zero_one_normals
from dppverify.structured.dp_certificate import Arc, certified_coalition_dp
from dppverify.structured.guarantee import dp_value
from dppverify.structured.lower_bounds import (
    deflated_lower,
    lower_bound_simple,
    sets_value,
    translated_lower,
)
from dppverify.structured.normal_dp import BeyondExactRange, normal_dp_value
from dppverify.structured.normal_fixpoint import NormalSets, normal_sets

__all__ = [
    "InfiniteSets",
    "NValue",
    "coalition_nvalue",
    "extra_directions",
    "infinite_sets",
    "nvalue",
]

MAX_ROUNDS = 4
"""Refinement rounds of the general DP (each adds the failing directions as normals)."""

MAX_BASES = 1_000_000
"""Limit on the bases enumerated for the vertices of a refined normal set's tables."""


def extra_directions(ys: Sequence[Sequence[Fraction]]) -> list[Normal]:
    """The primitive integer vectors along the directions ``ys`` (new normals).

    Examples
    --------
    >>> extra_directions([(Fraction(1), Fraction(1), Fraction(1), Fraction(1, 2))])
    [(2, 2, 2, 1)]
    """
    out = []
    for y in ys:
        den = math.lcm(*(Fraction(x).denominator for x in y))
        ints = [int(Fraction(x) * den) for x in y]
        g = math.gcd(*ints)
        out.append(tuple(x // g for x in ints))
    return out


@dataclass(frozen=True, kw_only=True)
class NValue(Bracket):
    """``V_H`` of an N-goal instance by the guarantee sets: exact, or a named bracket.

    A :class:`~dppverify.exact.Bracket` (``closed`` when the value is proved, ``exact`` the
    value then) with how the structured route got it.

    Attributes
    ----------
    horizon : int or None
        The game's horizon, as in :attr:`coalition` (None: the untruncated game).
    lower, upper : Number
        Exact bounds ``lower <= V_H <= upper``; equal when the value is proved.
    lower_source, upper_source : str
        Where each bound comes from.
    layers : int
        DP layers of the run that gave ``upper`` (``H = inf``: its label-setting passes, one
        per normal; :attr:`effort` says which).
    normals : tuple of tuple of int
        The facet normals beyond the 0/1 vectors that the final DP used (empty for the
        coalition DP).
    reason : str or None
        Why the value is not proved (None when it is).
    coalition : CoalitionValue
        The coalition DP at ``H`` (its cover and coalition costs at the start).
    """

    horizon: int | None
    layers: int
    normals: tuple[Normal, ...]
    coalition: CoalitionValue

    @property
    def value(self) -> Number | None:
        """``V_H`` when proved, else None (:attr:`exact`, under the name the routes' values
        share)."""
        return self.exact

    @property
    def effort(self) -> str:
        """What :attr:`layers` counts, for messages: DP layers at a finite ``H``, label-setting
        passes (one per normal) at ``H = inf``.

        Examples
        --------
        >>> from dppverify.game.examples import star3
        >>> nvalue(star3(), None).effort, nvalue(star3(), 2).effort
        ('7 label-setting passes', '2 layers')
        """
        if self.horizon is None:
            return f"{self.layers} label-setting pass{'' if self.layers == 1 else 'es'}"
        return f"{self.layers} layer{'' if self.layers == 1 else 's'}"


def coalition_nvalue(coal: CoalitionValue, n_goals: int) -> NValue:
    """The proved value of an instance with ``n_goals <= 3`` from its coalition DP, already run.

    For two and three goals the coalition DP is the value (NG.3, NG.4), so a caller that has
    the DP (e.g. the guarantee rule's label-setting fixpoint, proofs/NSOLVE.md NSOLVE.3) need
    not run :func:`nvalue` again.

    Raises
    ------
    ValueError
        ``n_goals > 3``: there the DP is only an upper bound (NG.2); use :func:`nvalue`.

    Examples
    --------
    >>> from dppverify.structured.coalition import coalition_value
    >>> from dppverify.game.examples import star3
    >>> coalition_nvalue(coalition_value(star3(), None), 3).value
    Fraction(3, 2)
    """
    if n_goals > 3:
        raise ValueError(f"the coalition DP is the value only for N <= 3 goals, not {n_goals}")
    src = ("coalition DP (NG.3: the value for two goals)" if n_goals == 2 else
           "coalition DP (NG.4: the value for three goals)")
    v = normalize(Fraction(coal.value))
    return NValue(v, v, src, src, None,
                  horizon=coal.horizon, layers=coal.layers, normals=(),
                  coalition=coal)


MAX_EXTRAS = 64
"""The refinement stops once the extra normals would exceed this many (the profile format's
limit on ``normals``)."""


MAX_TRANSLATED_ARCS = 20_000
"""NG.10's translated lower bound (:func:`~dppverify.structured.lower_bounds.translated_lower`,
exact arithmetic per arc) is tried at ``H = inf`` only up to this many walkable arcs."""


@dataclass(frozen=True, eq=False)
class InfiniteSets:
    """What :func:`infinite_sets` found at ``H = inf``: the value at the prior, and the sets.

    Attributes
    ----------
    value : NValue
        ``V_inf`` at the instance's prior, exact or a bracket (:func:`nvalue`'s answer).
    sets : NormalSets
        The last sets computed (the coalition DP's, or its last refinement's).
    exact : bool
        Whether ``sets`` are the exact guarantee sets ``G_v`` (N <= 3: NG.4; else their arc
        condition holds at every walkable arc, NRULE NR.1(e)); then every prior's value is
        their support function, not only this prior's.
    coalition : NormalSets
        The coalition DP's sets (an outer bound; NG.10 translates them into inner ones).
    """

    value: NValue
    sets: NormalSets
    exact: bool
    coalition: NormalSets


def _proved(value: Fraction, src: str, *, horizon: int | None, layers: int,
            normals: tuple[Normal, ...], coalition: CoalitionValue) -> NValue:
    """The closed :class:`NValue` at ``value``, both bounds from ``src``."""
    v = normalize(value)
    return NValue(v, v, src, src, None, horizon=horizon, layers=layers, normals=normals,
                  coalition=coalition)


def infinite_sets(inst: Instance, progress: Callable[[str], None] | None = None
                  ) -> InfiniteSets:
    """:func:`nvalue` at ``H = inf`` with the sets behind it: label-setting fixpoints (NRULE
    NR.1), their arc test (NR.2) and a refinement with the failing directions as extra
    normals.

    Examples
    --------
    >>> from dppverify.game.examples import hub4
    >>> found = infinite_sets(hub4())
    >>> found.value.value, found.exact, found.sets.extras
    (Fraction(12, 7), True, ((2, 2, 2, 1),))
    """
    n = inst.n_goals
    say = progress or (lambda _msg: None)
    say("the coalition DP at H = inf (one label-setting pass per goal subset)")
    sets = normal_sets(inst)
    coal = dp_value(sets)
    if n <= 3:
        return InfiniteSets(coalition_nvalue(coal, n), sets, True, sets)
    say("the arc condition of the coalition sets on every walkable arc")
    arc = arc_condition(sets, inst.start)
    if arc.holds:
        src = "coalition DP, certified at every arc (NG.8, NRULE NR.1(e))"
        return InfiniteSets(_proved(Fraction(coal.value), src, horizon=None,
                                    layers=len(sets.normals), normals=(), coalition=coal),
                            sets, True, sets)
    return _refined_infinite(sets, coal, arc, say)


def _refined_infinite(coalition_sets: NormalSets, coal: CoalitionValue, arc: ArcCondition,
                      say: Callable[[str], None]) -> InfiniteSets:
    """:func:`infinite_sets` past a failing arc of the coalition sets: refinement rounds with
    the failing directions as extra normals, then, for a bracket, NG.10's translated bound."""
    inst, sets = coalition_sets.instance, coalition_sets
    upper, up_src = Fraction(coal.value), "coalition DP (NG.2: an upper bound)"
    reason = _arc_reason(inst, arc, "the coalition DP")
    lower, lo_src = lower_bound_simple(inst)
    extras: list[Normal] = []
    up_normals: tuple[Normal, ...] = ()
    for round_ in range(1, MAX_ROUNDS + 1):
        new = [d for d in dict.fromkeys(extra_directions(_failing_directions(arc)))
               if d not in extras and any(x > 1 for x in d)]
        if not new:
            reason += "; no new direction to refine with"
            break
        if len(extras) + len(new) > MAX_EXTRAS:
            reason += (f"; refining needs more than {MAX_EXTRAS} extra normals (the refinement "
                       f"budget)")
            break
        extras += sorted(new, reverse=True)
        say(f"refinement round {round_}: {len(extras)} extra normals")
        sets = normal_sets(inst, extras, base=sets)
        val = sets_value(sets)
        if val < upper:
            upper, up_normals = val, tuple(extras)
            up_src = (f"DP over {len(extras)} extra facet normals (NRULE NR.1(a): an upper "
                      f"bound)")
        say(f"refinement round {round_}: the arc condition with {len(extras)} extra normals")
        arc = arc_condition(sets, inst.start)
        if arc.holds:
            src = (f"DP over {len(extras)} extra facet normals, certified at every arc "
                   f"(NRULE NR.1(e))")
            return InfiniteSets(_proved(val, src, horizon=None, layers=len(sets.normals),
                                        normals=tuple(extras), coalition=coal), sets, True,
                                coalition_sets)
        if lower == upper:
            return InfiniteSets(_proved(upper, f"{up_src[:-1]}) meeting {lo_src}", horizon=None,
                                        layers=len(sets.normals), normals=up_normals,
                                        coalition=coal), sets, False, coalition_sets)
        reason = _arc_reason(inst, arc, f"the DP with {len(extras)} extra normals")
    else:
        reason += f"; {MAX_ROUNDS} refinement rounds (the refinement budget)"
    # NG.10 only for the bracket: a longest-path problem over every walkable arc in Fractions
    if len(walkable_arcs(coalition_sets, inst.start)[0]) <= MAX_TRANSLATED_ARCS:
        say("a lower bound from the coalition sets translated into a sub-fixpoint (NG.10)")
        shift = translated_lower(coalition_sets)
        if shift is not None and shift > lower:
            lower, lo_src = shift, ("the coalition DP's fixpoint sets translated into a "
                                    "sub-fixpoint (NG.10)")
        if lower == upper:
            src = f"{up_src[:-1]}) meeting the translated fixpoint bound (NG.10)"
            return InfiniteSets(_proved(upper, src, horizon=None, layers=len(sets.normals),
                                        normals=up_normals, coalition=coal), sets, False,
                                coalition_sets)
    else:
        lo_src += (f" (NG.10's translated bound not tried: more than {MAX_TRANSLATED_ARCS} "
                   f"walkable arcs)")
    return InfiniteSets(NValue(normalize(lower), normalize(upper), lo_src, up_src, reason,
                               horizon=None, layers=len(sets.normals), normals=up_normals,
                               coalition=coal), sets, False, coalition_sets)


def _failing_directions(arc: ArcCondition) -> list[tuple[Fraction, ...]]:
    assert arc.failure is not None
    return [tuple(Fraction(x) for x in arc.failure[2][0][1]), *arc.directions]


def _arc_reason(inst: Instance, arc: ArcCondition, what: str) -> str:
    assert arc.failure is not None
    v, u, ((_, y),) = arc.failure
    return (f"arc {inst.nodes[v]!r} -> {inst.nodes[u]!r} fails the certificate of {what} in "
            f"direction ({', '.join(str(x) for x in y)})")


def nvalue(instance: Instance, horizon: int | None, *, max_layers: int | None = None,
           progress: Callable[[str], None] | None = None) -> NValue:
    """``V_H`` of an N-goal instance (2 to 5 goals), exact where proved, else a bracket.

    For N <= 3 the coalition DP is the value (NG.3, NG.4). For N = 4, 5 the coalition DP is
    certified (NG.8) and, where it fails, refined with the failing directions (and their
    permutations) as extra facet normals, a few rounds (NG.7, NG.8; for ``H = inf`` started
    from the coalition fixpoint). ``horizon=None`` is ``H = inf``.

    Raises
    ------
    HorizonError
        If ``horizon`` is negative or no goal is reachable within it.
    OptionError
        For more than five goals.

    Examples
    --------
    >>> from dppverify.game.examples import hub4, star3
    >>> nvalue(star3(), None).value
    Fraction(3, 2)
    >>> v = nvalue(hub4(), None)
    >>> v.value, v.normals
    (Fraction(12, 7), ((2, 2, 2, 1),))
    """
    inst = instance
    if not 2 <= inst.n_goals <= MAX_BALANCED:
        raise OptionError(too_many_goals(inst.n_goals))
    if horizon is not None and horizon < 0:
        raise HorizonError(f"the horizon must be a non-negative integer, got {horizon}")
    if horizon is None:
        return infinite_sets(inst, progress).value
    coal, fails, start = certified_coalition_dp(inst, horizon, max_layers)
    upper, layers = Fraction(coal.value), coal.layers
    n = inst.n_goals
    src = ("coalition DP (NG.3: the value for two goals)" if n == 2 else
           "coalition DP (NG.4: the value for three goals)" if n == 3 else
           "coalition DP, certified at every arc (NG.8)")
    if not fails:
        return _proved(upper, src, horizon=horizon, layers=layers, normals=(), coalition=coal)
    up_src = "coalition DP (NG.2: an upper bound)"
    reason = _fail_reason(inst, fails[0], "the coalition DP")
    lower, lo_src = _finite_lower(inst, start, upper, max_layers)
    if lower == upper:
        src = "coalition DP (NG.2) meeting the translated fixpoint bound (NG.10)"
        return _proved(upper, src, horizon=horizon, layers=layers, normals=(), coalition=coal)
    extras: list[Normal] = []
    up_normals: tuple[Normal, ...] = ()
    cap = max_layers if max_layers is not None else 50 * inst.n_nodes + 100
    for _ in range(MAX_ROUNDS):
        new = [d for d in extra_directions(_permutations([fails[0][2]])) if d not in extras]
        if not new:
            break
        extras += sorted(new, reverse=True)
        normals = zero_one_normals(n) + tuple(extras)
        if math.comb(len(normals) + n, n) > MAX_BASES:
            reason += (f"; refining needs {len(extras)} extra normals, beyond the vertex "
                       f"enumeration's limit ({MAX_BASES:,} bases)")
            break
        try:
            val, layers_g, fails = normal_dp_value(inst, extras, horizon, cap, start)
        except (HorizonError, BeyondExactRange) as exc:
            reason += f"; the refined DP: {str(exc) or 'numbers beyond exact float64 range'}"
            break
        if val < upper:
            upper, layers, up_normals = val, layers_g, tuple(extras)
            up_src = f"DP over {len(extras)} extra facet normals (NG.7: an upper bound)"
        if not fails:
            src = f"DP over {len(extras)} extra facet normals, certified at every arc (NG.8)"
            return _proved(val, src, horizon=horizon, layers=layers_g, normals=tuple(extras),
                           coalition=coal)
        if lower == upper:
            return _proved(upper, f"{up_src[:-1]}) meeting {lo_src}", horizon=horizon,
                           layers=layers, normals=up_normals, coalition=coal)
        reason = _fail_reason(inst, fails[0], f"the DP with {len(extras)} extra normals")
    return NValue(normalize(lower), normalize(upper), lo_src, up_src, reason,
                  horizon=horizon, layers=layers, normals=up_normals,
                  coalition=coal)


def _finite_lower(inst: Instance, start: tuple[CoalitionRunner, dict[int, np.ndarray]] | None,
                  dp: Fraction, max_layers: int | None) -> tuple[Fraction, str]:
    """The better lower bound on ``V_H`` (finite ``H``) and its source: the simple Defenders
    (NG.9) or the coalition fixpoint translated into a sub-fixpoint (NG.10). ``start`` is the
    fixpoint when the coalition DP at ``H`` reached it (``dp`` its value), else None (then it
    is run to its fixpoint here)."""
    lower, lo_src = lower_bound_simple(inst)
    fixpoint = start  # the coalition fixpoint, for NG.10 (it bounds every H)
    if fixpoint is None:
        fix = certified_coalition_dp(inst, None, max_layers, certify=False)
        fixpoint, dp_inf = fix[2], Fraction(fix[0].value)
    else:
        dp_inf = dp
    assert fixpoint is not None
    shift = deflated_lower(*fixpoint)
    if shift is not None and dp_inf - shift > lower:
        return dp_inf - shift, ("the coalition DP's fixpoint sets translated into a "
                                "sub-fixpoint (NG.10)")
    return lower, lo_src


def _fail_reason(inst: Instance, arc: Arc, what: str) -> str:
    v, u, y = arc
    return (f"arc {inst.nodes[v]!r} -> {inst.nodes[u]!r} fails the certificate of {what} in "
            f"direction ({', '.join(str(x) for x in y)})")


def _permutations(ys: list[tuple[Fraction, ...]]) -> list[tuple[Fraction, ...]]:
    """Every permutation of every direction (the goals are symmetric in the tables)."""
    out: dict[tuple[Fraction, ...], None] = {}
    for y in ys:
        for p in itertools.permutations(y):
            out[p] = None
    return list(out)
