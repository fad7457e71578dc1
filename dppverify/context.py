"""What every check needs, computed once: the tree, the labelling, both Defenders on the tree,
and the profile's realization plans.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction

from dppverify.best_response import AttackerBR, attacker_best_response
from dppverify.defender import TreeDefender, tree_defender
from dppverify.evaluation import realization
from dppverify.instance import Instance, Roles
from dppverify.numbers import NumberMode
from dppverify.profile import Profile, ProgressRule
from dppverify.tree import WalkTree

__all__ = ["Context", "make_context"]


@dataclass(frozen=True, eq=False)
class Context:
    """Shared inputs of the checks.

    Attributes
    ----------
    instance, tree, profile
        The game, its walk tree at the chosen horizon, the resolved profile.
    roles : Roles
        The labelling the profile uses (primary = ``profile.primary_slot``).
    sigma_star : TreeDefender
        The paper's σ* (progress towards ``g1``) on every prefix: used by the lemma checks
        whatever Defender the profile proposes.
    defender : TreeDefender or None
        The profile's Defender on every prefix (None when the profile is ill-formed).
    x1, x2 : dict or None
        The profile's realization plans (None when the profile is ill-formed).
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
    defender: TreeDefender | None
    x1: dict[int, Fraction] | None
    x2: dict[int, Fraction] | None
    seed: int
    trials: int
    undefined: tuple[int, ...] = ()
    _best_responses: dict[tuple[int, int], AttackerBR] = field(default_factory=dict, repr=False)

    @property
    def numbers(self) -> NumberMode:
        """The instance's number mode: exact comparisons, or float mode's tolerance."""
        return self.instance.numbers

    @property
    def usable(self) -> bool:
        """True when the profile can be evaluated (well-formed, Defender defined on the tree)."""
        return self.defender is not None and self.x1 is not None and self.x2 is not None

    def best_response(self, defender: TreeDefender, theta: int) -> AttackerBR:
        """Type ``theta``'s best response over the whole tree against ``defender``.

        ``defender`` is :attr:`sigma_star` or :attr:`defender`; several checks need the same
        backward induction, so each result is computed once per context.

        Examples
        --------
        >>> from dppverify.examples import triangle_context
        >>> ctx = triangle_context()
        >>> br = ctx.best_response(ctx.sigma_star, 2)
        >>> br.value, ctx.best_response(ctx.sigma_star, 2) is br
        (1, True)
        """
        if defender is not self.sigma_star and defender is not self.defender:
            raise ValueError("best_response caches the context's own Defenders only")
        key = (id(defender), theta)
        if key not in self._best_responses:
            self._best_responses[key] = attacker_best_response(self.tree, self.roles, defender,
                                                               theta)
        return self._best_responses[key]


def make_context(instance: Instance, tree: WalkTree, profile: Profile,
                 *, seed: int, trials: int) -> Context:
    """Evaluate both Defenders on the tree and the profile's realization plans.

    Parameters
    ----------
    instance : Instance
        The game.
    tree : WalkTree
        Its walk tree at the chosen horizon.
    profile : Profile
        The resolved profile (:func:`~dppverify.profile.profile_from_json`).
    seed, trials : int
        Seed and number of the random attackers of the L3/L4 checks.

    Returns
    -------
    Context

    Examples
    --------
    The triangle's equilibrium profile: the realization plans give the primary's mixture
    (4/7 to g1, 3/7 to g2) and σ* allocates ``s -> g2`` half to each goal.

    >>> from dppverify.examples import triangle
    >>> from dppverify.profile import profile_from_json
    >>> from dppverify.tree import build_tree
    >>> inst = triangle()
    >>> prof = profile_from_json({"format": "dpp-profile/1",
    ...     "goals": {"primary": "g1", "secondary": "g2"},
    ...     "defender": {"rule": "progress", "goal": "g1"},
    ...     "attacker": {"primary": [{"path": ["s", "g1"], "probability": "4/7"},
    ...                              {"path": ["s", "g2"], "probability": "3/7"}],
    ...                  "secondary": [{"path": ["s", "g2"], "probability": 1}]}}, inst)
    >>> ctx = make_context(inst, build_tree(inst, 1), prof, seed=0, trials=2)
    >>> ctx.usable, ctx.x1
    (True, {0: Fraction(1, 1), 1: Fraction(4, 7), 2: Fraction(3, 7)})
    >>> ctx.x2
    {0: Fraction(1, 1), 2: Fraction(1, 1)}
    >>> ctx.defender.sigma1 == ctx.sigma_star.sigma1 == (0, 1, Fraction(1, 2))
    True
    """
    roles = instance.roles(profile.primary_slot)
    sigma_star = tree_defender(tree, roles, ProgressRule(roles.g1))
    defender = None
    x1 = x2 = None
    undefined: tuple[int, ...] = ()
    if profile.wellformed and profile.defender is not None:
        td = (sigma_star if profile.defender == ProgressRule(roles.g1)
              else tree_defender(tree, roles, profile.defender))
        undefined = td.undefined
        if not undefined:
            defender = td
        try:
            x1 = realization(tree, profile.primary)
            x2 = realization(tree, profile.secondary)
        except KeyError:  # pragma: no cover - the horizon covers every profile walk
            x1 = x2 = None
    return Context(instance=instance, tree=tree, profile=profile, roles=roles,
                   sigma_star=sigma_star, defender=defender, x1=x1, x2=x2, seed=seed,
                   trials=trials, undefined=undefined)
