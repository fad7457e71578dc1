"""Which route computes a result: the walk tree, the structured (tree-free) route, or both.

``auto`` takes the tree when the truncated game's tree fits ``max_prefixes`` and the
structured route otherwise; ``both`` runs both and treats any disagreement as an error of the
checker (docs/checker.md, "Routes"). :func:`routed_value` is ``dpp value``'s engine.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from dppverify.errors import HorizonError
from dppverify.exact import Number
from dppverify.game.instance import Instance
from dppverify.numbers import NumberMode
from dppverify.tree_route.lp import lp_agrees
from dppverify.tree_route.tree import DEFAULT_MAX_PREFIXES, count_prefixes
from dppverify.tree_route.value_lp import GameValue, game_value
from dppverify.twogoal.value_dp import StructuredValue, structured_value

__all__ = ["ROUTES", "Route", "RoutedValue", "resolve_route", "routed_value", "tree_fits",
           "values_agree"]

Route = Literal["auto", "tree", "structured", "both"]
ROUTES: tuple[Route, ...] = ("auto", "tree", "structured", "both")


def tree_fits(instance: Instance, horizon: int | None, max_prefixes: int) -> bool:
    """True when the pruned walk tree of ``horizon`` steps has at most ``max_prefixes`` prefixes.

    Counts with :func:`~dppverify.tree_route.tree.count_prefixes`, saturated just above
    ``max_prefixes`` and stopping as soon as the count exceeds it, so that huge trees are
    never counted in full. An untruncated game (``horizon=None``) never fits.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> inst = triangle()
    >>> tree_fits(inst, 5, 3), tree_fits(inst, 5, 2), tree_fits(inst, None, 10**9)
    (True, False, False)
    """
    if horizon is None:
        return False
    if horizon < 0:
        raise HorizonError(f"the horizon must be a non-negative integer, got {horizon}")
    return count_prefixes(instance, horizon, limit=max_prefixes) <= max_prefixes


def resolve_route(route: Route, instance: Instance, horizon: int | None,
                  max_prefixes: int) -> Literal["tree", "structured", "both"]:
    """The route ``auto`` stands for on this instance (others are returned unchanged).

    Raises
    ------
    HorizonError
        The tree route (or ``both``) with the untruncated game (``horizon=None``).

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> inst = triangle()
    >>> resolve_route("auto", inst, 3, 100), resolve_route("auto", inst, 3, 2)
    ('tree', 'structured')
    >>> resolve_route("tree", inst, None, 100)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.HorizonError: the tree route needs a finite horizon ...
    """
    if route == "auto":
        return "tree" if tree_fits(instance, horizon, max_prefixes) else "structured"
    if route in ("tree", "both") and horizon is None:
        raise HorizonError("the tree route needs a finite horizon --horizon H (without a "
                           "horizon, or with inf, the game is the untruncated one: the "
                           "structured route)")
    return route


def values_agree(tree: GameValue, structured: Number, numbers: NumberMode) -> str | None:
    """None when the tree route's ``V_H`` and the structured one agree, else why not.

    Exactly when the tree's exact bracket is closed (within the float tolerance in float
    mode); otherwise the structured value must lie in the bracket and agree with the LP.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> from dppverify.numbers import EXACT
    >>> from fractions import Fraction
    >>> v = game_value(triangle(), 2)
    >>> values_agree(v, Fraction(12, 5), EXACT) is None
    True
    >>> values_agree(v, Fraction(5, 2), EXACT)
    'the routes disagree: tree V_H = 12/5, structured V_H = 5/2'
    """
    b = tree.bracket
    if b.closed:
        assert b.exact is not None
        if numbers.equal(b.exact, structured):
            return None
        return f"the routes disagree: tree V_H = {b.exact}, structured V_H = {structured}"
    if not (numbers.at_most(b.lower, structured)
            and numbers.at_most(structured, b.upper)):
        return (f"the routes disagree: structured V_H = {structured} lies outside the tree's "
                f"exact bracket [{b.lower}, {b.upper}]")
    if not lp_agrees(tree.value, structured):
        return (f"the routes disagree: structured V_H = {structured}, tree LP value "
                f"{tree.value!r}")
    return None


@dataclass(frozen=True)
class RoutedValue:
    """``V_H`` by the route(s) asked for.

    Attributes
    ----------
    route : {"tree", "structured", "both"}
        The route(s) that ran (``auto`` resolved).
    horizon : int or None
        ``H`` (None: the untruncated game).
    tree : GameValue or None
        The tree route's result (LP plus exact bracket).
    structured : StructuredValue or None
        The structured route's result.
    disagreement : str or None
        With ``both``: why the routes disagree (None when they agree).

    ``value``, ``lower`` and ``upper`` read the result whatever the route: ``V_H`` when it is
    known (exactly; a float in float mode), else None, and the bounds ``lower <= V_H <= upper``.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> r = routed_value(triangle(), 4, route="tree")
    >>> r.value, r.lower, r.upper
    (Fraction(12, 5), Fraction(12, 5), Fraction(12, 5))
    """

    route: Literal["tree", "structured", "both"]
    horizon: int | None
    tree: GameValue | None
    structured: StructuredValue | None
    disagreement: str | None = None

    @property
    def lower(self) -> Number:
        """A lower bound on ``V_H`` (the value itself when known)."""
        if self.structured is not None:
            return self.structured.value
        assert self.tree is not None  # one route always ran
        return self.tree.bracket.lower

    @property
    def upper(self) -> Number:
        """An upper bound on ``V_H`` (the value itself when known)."""
        if self.structured is not None:
            return self.structured.value
        assert self.tree is not None
        return self.tree.bracket.upper

    @property
    def value(self) -> Number | None:
        """``V_H`` when known (the structured DP, or a closed exact bracket), else None."""
        if self.structured is not None:
            return self.structured.value
        assert self.tree is not None
        return self.tree.bracket.exact


def routed_value(instance: Instance, horizon: int | None, *, route: Route = "auto",
                 max_prefixes: int = DEFAULT_MAX_PREFIXES,
                 progress: bool = False) -> RoutedValue:
    """``V_H`` of ``instance`` by the tree route, the structured route, or both.

    Parameters
    ----------
    instance : Instance
        The game.
    horizon : int or None
        ``H``; None for the untruncated game (structured route only).
    route : {"auto", "tree", "structured", "both"}
        ``auto``: the tree when it fits ``max_prefixes``, else the structured route.
    max_prefixes : int
        Size guard of the walk tree.
    progress : bool
        Progress bars on stderr (tree route).

    Returns
    -------
    RoutedValue

    Raises
    ------
    HorizonError, TreeTooLargeError
        As :func:`~dppverify.tree_route.value_lp.game_value` and
        :func:`~dppverify.twogoal.value_dp.structured_value`.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> r = routed_value(triangle(), 3, route="both")
    >>> r.route, r.structured.value, r.tree.bracket.exact, r.disagreement
    ('both', Fraction(12, 5), Fraction(12, 5), None)
    >>> routed_value(triangle(), None).route
    'structured'
    """
    chosen = resolve_route(route, instance, horizon, max_prefixes)
    tree = sv = None
    if chosen in ("structured", "both"):
        sv = structured_value(instance, horizon)
    if chosen in ("tree", "both"):
        assert horizon is not None
        tree = game_value(instance, horizon, max_prefixes=max_prefixes, progress=progress)
    why = None
    if tree is not None and sv is not None:
        why = values_agree(tree, sv.value, instance.numbers)
    return RoutedValue(route=chosen, horizon=horizon, tree=tree, structured=sv, disagreement=why)
