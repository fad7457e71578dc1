"""What every check needs, computed once.

:class:`Context`: the game side (the tree, the labelling, σ* on the tree) and the resolved
profile document, well-formed or not. :class:`EvaluatedContext` (a :class:`Context`): a
profile that can be evaluated, with its :class:`EvaluatedProfile` — the Defender on the tree,
the realization plans, the payoffs and the Bayes beliefs — computed once. Checks about the
profile take an :class:`EvaluatedContext`; ``certify`` records them as ``skipped`` for an
ill-formed profile without calling them.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from typing import cast

from dppverify.game.evaluation import Values, evaluate, realization
from dppverify.game.instance import Instance, Roles
from dppverify.game.profile import DefenderRule, Profile, ProgressRule
from dppverify.numbers import NumberMode
from dppverify.tree_route.best_response import AttackerBR, attacker_best_response
from dppverify.tree_route.best_response import beliefs as bayes_beliefs
from dppverify.tree_route.tree import WalkTree
from dppverify.tree_route.tree_defender import TreeDefender, tree_defender


@dataclass(frozen=True)
class EvaluatedProfile:
    """A well-formed profile evaluated on the walk tree (each part computed once).

    Attributes
    ----------
    rule : DefenderRule
        The profile's Defender rule.
    defender : TreeDefender
        That rule on every prefix of the tree.
    x1, x2 : dict
        The realization plans (reach probabilities) of the primary and secondary types:
        prefix index -> probability, reached prefixes only.
    values : Values
        U¹, U², U, Ū, VoI walk by walk (:func:`~dppverify.game.evaluation.evaluate`).
    beliefs : dict
        Closed-form Bayes beliefs ``b1 x1 / (b1 x1 + b2 x2)`` at every reached prefix.
    """

    rule: DefenderRule
    defender: TreeDefender
    x1: dict[int, Fraction]
    x2: dict[int, Fraction]
    values: Values
    beliefs: dict[int, Fraction]


@dataclass(frozen=True, eq=False)
class Context:
    """Shared inputs of the checks (the profile may be ill-formed).

    Attributes
    ----------
    instance, tree, profile
        The game, its walk tree at the chosen horizon, the resolved profile.
    roles : Roles
        The labelling the profile uses (primary = ``profile.primary_goal_index``).
    sigma_star : TreeDefender
        The paper's σ* (progress towards ``g1``) on every prefix: used by the lemma checks
        whatever Defender the profile proposes.
    seed, trials : int
        Random attackers of the L3/L4 checks: RNG seed and how many.
    undefined : tuple of int
        Prefixes where a table Defender without default has no entry.
    """

    instance: Instance
    tree: WalkTree
    profile: Profile
    roles: Roles
    sigma_star: TreeDefender
    seed: int
    trials: int
    undefined: tuple[int, ...] = ()
    _best_responses: dict[tuple[int, int], AttackerBR] = field(default_factory=dict, repr=False)

    @property
    def numbers(self) -> NumberMode:
        """The instance's number mode: exact comparisons, or float mode's tolerance."""
        return self.instance.numbers

    def _cached_defender(self, defender: TreeDefender) -> bool:
        return defender is self.sigma_star

    def best_response(self, defender: TreeDefender, role: int) -> AttackerBR:
        """Type ``role``'s best response over the whole tree against ``defender``.

        ``defender`` is :attr:`sigma_star` or (in an :class:`EvaluatedContext`) the profile's
        Defender; several checks need the same backward induction, so each result is
        computed once per context.

        Examples
        --------
        >>> from tests.dppverify.checks.doctest_inputs import triangle_context
        >>> ctx = triangle_context()
        >>> br = ctx.best_response(ctx.sigma_star, 2)
        >>> br.value, ctx.best_response(ctx.sigma_star, 2) is br
        (1, True)
        """
        if not self._cached_defender(defender):
            raise ValueError("best_response caches the context's own Defenders only")
        key = (id(defender), role)
        if key not in self._best_responses:
            self._best_responses[key] = attacker_best_response(self.tree, self.roles, defender,
                                                               role)
        return self._best_responses[key]


@dataclass(frozen=True, eq=False)
class EvaluatedContext(Context):
    """A :class:`Context` whose profile is well-formed and evaluated.

    Attributes
    ----------
    evaluated : EvaluatedProfile
        The profile's Defender on the tree, realization plans, payoffs and Bayes beliefs.
    """

    evaluated: EvaluatedProfile = field(kw_only=True)

    def _cached_defender(self, defender: TreeDefender) -> bool:
        return defender is self.sigma_star or defender is self.evaluated.defender


def make_context(instance: Instance, tree: WalkTree, profile: Profile,
                 *, seed: int, trials: int) -> Context:
    """Evaluate σ* on the tree and, when the profile is well-formed, the profile.

    Parameters
    ----------
    instance : Instance
        The game.
    tree : WalkTree
        Its walk tree at the chosen horizon.
    profile : Profile
        The resolved profile (:func:`~dppverify.game.profile.profile_from_json`).
    seed, trials : int
        Seed and number of the random attackers of the L3/L4 checks.

    Returns
    -------
    Context
        An :class:`EvaluatedContext` when the profile is well-formed and its Defender is
        defined on the whole tree; a plain :class:`Context` otherwise.

    Examples
    --------
    The triangle's equilibrium profile: the realization plans give the primary's mixture
    (4/7 to g1, 3/7 to g2) and σ* allocates ``s -> g2`` half to each goal.

    >>> from dppverify.game.examples import triangle
    >>> from dppverify.game.profile import profile_from_json
    >>> from dppverify.tree_route.tree import build_tree
    >>> inst = triangle()
    >>> doc = {"format": "dpp-profile/1",
    ...     "goals": {"primary": "g1", "secondary": "g2"},
    ...     "defender": {"rule": "progress", "goal": "g1"},
    ...     "attacker": {"primary": [{"path": ["s", "g1"], "probability": "4/7"},
    ...                              {"path": ["s", "g2"], "probability": "3/7"}],
    ...                  "secondary": [{"path": ["s", "g2"], "probability": 1}]}}
    >>> ctx = make_context(inst, build_tree(inst, 1), profile_from_json(doc, inst),
    ...                    seed=0, trials=2)
    >>> isinstance(ctx, EvaluatedContext), ctx.evaluated.x1
    (True, {0: Fraction(1, 1), 1: Fraction(4, 7), 2: Fraction(3, 7)})
    >>> ctx.evaluated.x2, ctx.evaluated.values.U
    ({0: Fraction(1, 1), 2: Fraction(1, 1)}, Fraction(12, 5))
    >>> ctx.evaluated.defender.sigma1 == ctx.sigma_star.sigma1 == (0, 1, Fraction(1, 2))
    True
    >>> bad = make_context(inst, build_tree(inst, 1),
    ...                    profile_from_json({"format": "dpp-profile/1"}, inst), seed=0, trials=2)
    >>> isinstance(bad, EvaluatedContext)
    False
    """
    roles = instance.roles(profile.primary_goal_index)
    sigma_star = tree_defender(tree, roles, ProgressRule(roles.g1))
    rule = cast(DefenderRule | None, profile.defender)  # the two-goal reader's rules only
    td = None
    if profile.wellformed and rule is not None:
        td = sigma_star if rule == ProgressRule(roles.g1) else tree_defender(tree, roles, rule)
    plans = None
    if rule is not None and td is not None and not td.undefined:
        try:
            plans = realization(tree, profile.primary), realization(tree, profile.secondary)
        except KeyError:  # pragma: no cover - the horizon covers every profile walk
            plans = None
    if rule is None or td is None or plans is None:
        return Context(instance=instance, tree=tree, profile=profile, roles=roles,
                       sigma_star=sigma_star, seed=seed, trials=trials,
                       undefined=() if td is None else td.undefined)
    x1, x2 = plans
    values = evaluate(instance, roles, rule, profile.primary, profile.secondary)
    mu = bayes_beliefs(tree, roles, {1: x1, 2: x2})
    evaluated = EvaluatedProfile(rule=rule, defender=td, x1=x1, x2=x2, values=values,
                                 beliefs={p: m[0] for p, m in mu.items()})
    return EvaluatedContext(instance=instance, tree=tree, profile=profile, roles=roles,
                            sigma_star=sigma_star, seed=seed, trials=trials,
                            evaluated=evaluated)
