"""The two routes side by side: the tree LP's exact bracket against the structured value.

The structured value (:func:`dppverify.structured.proved_value.nvalue`: exact where proved, else an
exact bracket; ``proofs/NGOAL.md``) and the tree route (:mod:`dppverify.tree_route.value_lp`, the
literal definition of ``V_H``) must agree wherever both run: the brackets overlap, and an exact
structured value lies in the tree route's exact bracket and matches the LP's float value within
the LP tolerance. Anything else is a bug, reported as such, never smoothed over. The coalition
DP's value is kept alongside: an upper bound (NG.2), the value for N <= 3 (NG.3, NG.4).
"""

from __future__ import annotations

from dataclasses import dataclass

from dppverify.exact import Number
from dppverify.game.instance import Instance
from dppverify.structured.proved_value import NValue, nvalue
from dppverify.tree_route.tree import DEFAULT_MAX_PREFIXES
from dppverify.tree_route.value_lp import GameValue, game_value, structured_agrees


@dataclass(frozen=True)
class RouteAgreement:
    """The coalition DP's ``V_H`` next to the tree route's.

    Attributes
    ----------
    horizon : int
        ``H``.
    dp : Number
        The coalition DP at ``H`` (exact; an upper bound on ``V_H``).
    structured : NValue
        The structured route's value or bracket.
    tree : GameValue
        The tree route: LP value and exact bracket.
    agree : bool
        True when the brackets overlap and an exact structured value lies in the tree's
        exact bracket and matches the LP within :data:`dppverify.tree_route.lp.LP_TOLERANCE`
        (relative).
    """

    horizon: int
    dp: Number
    structured: NValue
    tree: GameValue
    agree: bool

    @property
    def exact(self) -> bool:
        """True when the tree route's bracket is closed (the agreement is then exact)."""
        return self.tree.bracket.closed


def compare_routes(instance: Instance, horizon: int, *,
                   max_prefixes: int = DEFAULT_MAX_PREFIXES) -> RouteAgreement:
    """Compute ``V_H`` by both routes and say whether they agree.

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> a = compare_routes(star3(), 3)
    >>> a.dp, a.structured.value, a.tree.bracket.exact, a.agree, a.exact
    (Fraction(3, 2), Fraction(3, 2), Fraction(3, 2), True, True)
    """
    tree = game_value(instance, horizon, max_prefixes=max_prefixes)
    sv = nvalue(instance, horizon)
    return RouteAgreement(horizon=horizon, dp=sv.coalition.value, structured=sv, tree=tree,
                          agree=structured_agrees(tree.bracket, tree.lp, sv))
