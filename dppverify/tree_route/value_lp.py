"""The value ``V_H`` of the truncated game: the compact LP of proofs/LP.md, plus an exact bracket.

One LP and one bracket for any number of goals ``N >= 2`` (two goals are ``N = 2``). LP
(cvxpy + Clarabel, vectorised, status checked)::

    V_H = min  Σ_θ b_θ Σ_leaves x_θ(ℓ) d(end ℓ, g^θ) + Σ_{p ≠ root} w_p z_p
          s.t. x_θ realization plans on the walk tree,  z_p >= b_θ x_θ(p)  for every θ.

The Defender's infoset is the walk prefix and its best response is greedy per infoset
(Lemma 3), so ``max_σ`` of the bilinear payoff is ``Σ_p w_p max_θ b_θ x_θ(p)``. The duals
``λ_θ(p)`` of ``z_p >= b_θ x_θ(p)`` sum to ``w_p`` (stationarity in ``z_p``), so
``σ(g^θ | p) = λ_θ(p) / w_p`` is an optimal Defender strategy.

Exact bracket (our choice of exact certificate, cheap and sound): for ANY rational Defender
strategy σ, ``Σ_θ b_θ min_walk U^θ(σ)`` (exact backward induction) is a lower bound on
``V_H``; for ANY rational Attacker realization plans, the exact greedy Defender value is an
upper bound. We round the LP's dual (Defender) and primal (Attacker) solutions to
small-denominator rationals, also try (two goals) the progress rule σ* or (N goals) the uniform
Defender and, when given, a profile's strategies; if the bracket is still open, the LP is
solved exactly (:mod:`dppverify.tree_route.lp_exact`: an optimal basis recovered from a float
vertex and solved in rationals) and its strategies are offered too, which closes it. ``V_H``
is reported exactly when the best bounds coincide; an open bracket carries its reason
(``Bracket.reason``). With a certified PBNE (both exact regrets 0) the bracket closes at
``U`` itself, so ``V_H = U`` exactly.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np
from tqdm import tqdm

from dppverify.errors import HorizonError
from dppverify.exact import Number
from dppverify.game.inputs import as_instance
from dppverify.game.instance import Instance, Roles
from dppverify.game.profile import ProgressRule
from dppverify.horizons import parse_horizon
from dppverify.tree_route.bracket import (
    Bracket,
    BracketSearch,
    lower_bound,
    rational_plan,
    rounded_defender,
    upper_bound,
)
from dppverify.tree_route.lp import (
    LP_TOLERANCE,
    LPStats,
    cost_scale,
    lp_agrees,
    realization_constraints,
    solve,
    unscaled,
)
from dppverify.tree_route.players import (
    AnyTypes,
    Plan,
    TreeStrategy,
    as_types,
    defender_from_rows,
    defender_from_table,
)
from dppverify.tree_route.tree import DEFAULT_MAX_PREFIXES, WalkTree, build_tree
from dppverify.tree_route.tree_defender import TreeDefender, tree_defender

if TYPE_CHECKING:  # imported where the LP is built: cvxpy's import costs ~0.5 s
    import cvxpy as cp



@dataclass(frozen=True)
class ValueLP:
    """The compact LP's solution: ``V_H`` (float) with the optimal strategies it found.

    Attributes
    ----------
    stats : LPStats
        Value, status, size, time.
    plans : numpy.ndarray
        ``plans[k]``: the realization plan of the ``k``-th type (one float per prefix).
    sigma : numpy.ndarray
        ``sigma[k][p]``: the Defender's probability on the ``k``-th type's goal at prefix ``p``
        (from the duals; ``nan`` at the root).
    """

    stats: LPStats
    plans: np.ndarray
    sigma: np.ndarray

    @property
    def value(self) -> float:
        """``V_H`` as computed by the LP."""
        return self.stats.value


def solve_value_lp(tree: WalkTree, types: AnyTypes) -> ValueLP:
    """Solve the compact LP of proofs/LP.md on ``tree`` (the types in ``types``' order).

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> from dppverify.tree_route.tree import build_tree
    >>> inst = triangle()
    >>> lp = solve_value_lp(build_tree(inst, 1), inst.roles())
    >>> round(lp.value, 6), [round(float(v), 4) for v in lp.plans[0]]
    (2.4, [1.0, 0.5714, 0.4286])
    >>> from dppverify.game.examples import star3
    >>> round(solve_value_lp(build_tree(star3(), 2), star3()).value, 6)
    1.5
    """
    import cvxpy as cp

    t = as_types(types)
    what = (f"value LP (H = {tree.horizon})" if len(t.keys) == 2 else
            f"N-goal value LP (N = {len(t.keys)}, H = {tree.horizon})")
    n = tree.n_prefixes
    leaf = tree.is_leaf_mask()
    node = tree.node
    xs = [cp.Variable(n) for _ in t.keys]
    cons: list[cp.Constraint] = []
    costs = [np.array([float(b) * float(d[int(v)]) if leaf[p] else 0.0
                       for p, v in enumerate(node)]) for b, d in zip(t.priors, t.dists,
                                                                     strict=True)]
    weights = tree.weight_float[1:]
    scale = cost_scale(weights, *costs)  # costs of size one (lp.py): 10^12 x weights too
    terms: list[cp.Expression] = []
    for cost, x in zip(costs, xs, strict=True):
        cons += realization_constraints(tree, x)
        terms.append((scale * cost) @ x)
    objective = terms[0]
    for term in terms[1:]:
        objective = objective + term
    duals: list[cp.Constraint] = []
    if n > 1:
        z = cp.Variable(n - 1)
        duals = [z >= float(b) * x[1:] for b, x in zip(t.priors, xs, strict=True)]
        cons += duals
        objective = objective + (scale * weights) @ z
    stats = unscaled(solve(cp.Problem(cp.Minimize(objective), cons), what), scale)
    sigma = np.full((len(xs), n), np.nan)
    for k, c in enumerate(duals):
        lam = np.asarray(c.dual_value, dtype=float).reshape(-1)
        sigma[k, 1:] = np.clip(lam / (scale * weights), 0.0, 1.0)
    plans = np.array([np.asarray(x.value, dtype=float).reshape(-1) for x in xs])
    return ValueLP(stats=stats, plans=plans, sigma=sigma)


def _candidates(tree: WalkTree, types: AnyTypes,
                defenders: Sequence[tuple[str, TreeStrategy]],
                sigma_star: TreeDefender | None) -> list[tuple[str, TreeStrategy]]:
    """The Defenders offered for lower bounds before the LP's: the given ones and, for the
    two-goal labelling, the progress rule to either goal (σ* reused when given and offered
    once); otherwise the uniform Defender first."""
    if isinstance(types, Roles):
        out = list(defenders)
        given = {id(tdef) for _, tdef in defenders}
        for g, name in ((types.g1, "sigma* (progress to g1)"), (types.g2, "progress to g2")):
            progress = (sigma_star if g == types.g1 and sigma_star is not None
                        else tree_defender(tree, types, ProgressRule(g)))
            if id(progress) not in given:
                out.append((name, progress))
        return out
    k = len(as_types(types).keys)
    uniform = defender_from_table(tree, {}, tuple(Fraction(1, k) for _ in range(k)))
    return [("uniform Defender", uniform), *defenders]


def exact_bracket(tree: WalkTree, types: AnyTypes, lp: ValueLP | None = None,
                  defenders: Sequence[tuple[str, TreeStrategy]] = (),
                  attackers: Iterable[tuple[str, Mapping[int, Plan]]] = (),
                  sigma_star: TreeDefender | None = None) -> Bracket:
    """Exact bounds on ``V_H`` from rational strategies (see the module docstring).

    Candidates: the given ``defenders`` and ``attackers`` (``plans[θ]`` per type); with the
    two-goal labelling (:class:`~dppverify.game.instance.Roles`) the progress rule σ* for
    either goal, else the uniform Defender; and the LP solution rounded at each denominator
    limit in :data:`DENOMINATORS` (stopping early once the bracket closes). ``sigma_star``,
    when given, is σ* (progress to ``g1``) already evaluated on ``tree``: it is reused, and
    not offered twice when it is also one of ``defenders``.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> from dppverify.tree_route.tree import build_tree
    >>> inst = triangle()
    >>> tree = build_tree(inst, 2)
    >>> b = exact_bracket(tree, inst.roles(), solve_value_lp(tree, inst.roles()))
    >>> b.exact
    Fraction(12, 5)
    >>> from dppverify.game.examples import star3
    >>> t = build_tree(star3(), 2)
    >>> b = exact_bracket(t, star3(), solve_value_lp(t, star3()))
    >>> b.exact, b.closed
    (Fraction(3, 2), True)
    """
    ts = as_types(types)
    search = BracketSearch()
    for src, tdef in _candidates(tree, types, defenders, sigma_star):
        search.offer_lower(lower_bound(tree, ts, tdef), src)
    for src, plans in attackers:
        search.offer_upper(upper_bound(tree, ts, plans), src)
    if lp is not None:
        search.rounded(
            lambda den: lower_bound(tree, ts, rounded_defender(tree, ts, lp.sigma, den)),
            lambda den: upper_bound(tree, ts, {who: rational_plan(tree, lp.plans[k], den)
                                               for k, who in enumerate(ts.keys)}))
        if tree.instance.exact:
            search.exact_lp(
                tree, ts, lambda sigma: lower_bound(tree, ts, defender_from_rows(tree, ts, sigma)),
                lambda plans: upper_bound(tree, ts, dict(zip(ts.keys, plans, strict=True))))
        else:
            search.reason = "float-mode instance: no exact LP closure"
    return search.bracket(lambda plan: upper_bound(tree, ts, dict.fromkeys(ts.keys, plan)),
                          tree)


class Bounds(Protocol):
    """A structured value or bracket: ``lower <= V_H <= upper``, ``value`` when proved."""

    @property
    def lower(self) -> Number: ...

    @property
    def upper(self) -> Number: ...

    @property
    def value(self) -> Number | None: ...


def structured_agrees(bracket: Bracket, lp: LPStats, structured: Bounds) -> bool:
    """True when a structured value or bracket agrees with the tree route's: the brackets
    overlap, and a proved structured value lies in the tree's exact bracket and matches the
    LP within :data:`~dppverify.tree_route.lp.LP_TOLERANCE` (the one rule of agreement; a
    disagreement is a bug, never smoothed over).

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> from dppverify.structured.proved_value import nvalue
    >>> v = game_value(star3(), 3)
    >>> structured_agrees(v.bracket, v.lp, nvalue(star3(), 3))
    True
    """
    b, sv = bracket, structured
    if not (sv.lower <= b.upper and b.lower <= sv.upper):
        return False
    return sv.value is None or bool(b.lower <= sv.value <= b.upper
                                    and lp_agrees(lp, sv.value, LP_TOLERANCE))


@dataclass(frozen=True)
class GameValue:
    """``V_H`` of an instance: the LP value, the exact bracket, and the tree's size.

    Attributes
    ----------
    horizon : int
        ``H``.
    lp : LPStats
        The compact LP's value (float), status, size and solve time.
    bracket : Bracket
        Exact bounds on ``V_H`` (closed when ``V_H`` is known exactly).
    prefixes, leaves : int
        Size of the walk tree.
    exact : bool
        False for float-mode instances (the bracket is then in floats).
    """

    horizon: int
    lp: LPStats
    bracket: Bracket
    prefixes: int
    leaves: int
    exact: bool

    @property
    def value(self) -> float:
        """``V_H`` from the LP."""
        return self.lp.value


def game_value(instance: Instance | Any, horizon: int, *,
               max_prefixes: int = DEFAULT_MAX_PREFIXES, progress: bool = False) -> GameValue:
    """``V_H`` of the truncated game of ``instance``: compact LP plus exact bracket.

    ``instance`` may be a game instance with any number of goals, or any form the door
    :func:`~dppverify.game.inputs.as_instance` takes (a document, bytes, a file path, any
    object with ``to_json()``). The value does not depend on which goal
    is called primary (the LP is symmetric in the types), so the instance's own labelling is
    used.

    Parameters
    ----------
    instance : Instance or document, path, object with ``to_json()``
        The game.
    horizon : int
        ``H >= 0``: the truncated game.
    max_prefixes : int
        The largest walk tree built (:func:`~dppverify.tree_route.tree.build_tree`).
    progress : bool
        Progress bars on stderr.

    Returns
    -------
    GameValue
        The LP's value, its exact bracket and the tree's size.

    Raises
    ------
    HorizonError
        No walk reaches a goal within ``horizon`` steps.
    TreeTooLargeError
        The walk tree (or its LP) is larger than allowed.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> v = game_value(triangle(), 3)
    >>> v.bracket.exact, round(v.value, 6), v.prefixes
    (Fraction(12, 5), 2.4, 3)
    >>> from dppverify.game.examples import star3
    >>> v = game_value(star3(), 2)
    >>> v.bracket.exact, round(v.value, 6), v.prefixes
    (Fraction(3, 2), 1.5, 6)
    """
    h = parse_horizon(horizon)
    if h is None:
        raise HorizonError("game_value is the truncated game's LP and needs a finite horizon; "
                           "dppverify.value(instance) gives the untruncated game's value")
    horizon = h
    game = as_instance(instance)
    tree = build_tree(game, horizon, max_prefixes=max_prefixes, progress=progress)
    types: AnyTypes = game.roles() if game.n_goals == 2 else game
    with tqdm(total=2, desc=f"value LP ({tree.n_prefixes} prefixes)", disable=not progress,
              leave=False) as bar:
        lp = solve_value_lp(tree, types)
        bar.update(1)
        bar.set_description("exact bracket")
        bracket = exact_bracket(tree, types, lp)
        bar.update(1)
    return GameValue(horizon=horizon, lp=lp.stats, bracket=bracket, prefixes=tree.n_prefixes,
                     leaves=tree.n_leaves, exact=game.exact)
