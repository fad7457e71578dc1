"""The two routes side by side: the tree LP's exact bracket against the coalition DP.

The coalition DP (:mod:`dppverify.ngoal.coalition`) rests on a conjecture
(``proofs/NGOAL.md``); the tree route (:mod:`dppverify.ngoal.value_lp`) is the literal
definition of ``V_H``. On every instance where both run they must agree: the DP's exact value
lies in the tree route's exact bracket (and equals it when the bracket is closed), and the LP's
float value matches it within the LP tolerance. Anything else is a disagreement — a
counterexample to the conjecture or a bug — and is reported as such, never smoothed over.
"""

from __future__ import annotations

from dataclasses import dataclass

from dppverify.exact import Number
from dppverify.lp import LP_TOLERANCE, lp_agrees
from dppverify.ngoal.coalition import coalition_value
from dppverify.ngoal.instance import NInstance
from dppverify.ngoal.value_lp import NGameValue, ngame_value
from dppverify.tree import DEFAULT_MAX_PREFIXES

__all__ = ["RouteAgreement", "compare_routes"]


@dataclass(frozen=True)
class RouteAgreement:
    """The coalition DP's ``V_H`` next to the tree route's.

    Attributes
    ----------
    horizon : int
        ``H``.
    dp : Number
        ``V_H`` by the coalition DP (exact).
    tree : NGameValue
        The tree route: LP value and exact bracket.
    agree : bool
        True when the DP value lies in the exact bracket (equal to it when closed) and the
        LP value matches it within :data:`dppverify.lp.LP_TOLERANCE` (relative).
    """

    horizon: int
    dp: Number
    tree: NGameValue
    agree: bool

    @property
    def exact(self) -> bool:
        """True when the tree route's bracket is closed (the agreement is then exact)."""
        return self.tree.bracket.closed


def compare_routes(instance: NInstance, horizon: int, *,
                   max_prefixes: int = DEFAULT_MAX_PREFIXES) -> RouteAgreement:
    """Compute ``V_H`` by both routes and say whether they agree.

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> a = compare_routes(star3(), 3)
    >>> a.dp, a.tree.bracket.exact, a.agree, a.exact
    (Fraction(3, 2), Fraction(3, 2), True, True)
    """
    tree = ngame_value(instance, horizon, max_prefixes=max_prefixes)
    dp = coalition_value(instance, horizon).value
    b = tree.bracket
    agree = b.lower <= dp <= b.upper and lp_agrees(tree.value, dp, LP_TOLERANCE)
    return RouteAgreement(horizon=horizon, dp=dp, tree=tree, agree=bool(agree))
