"""Which route computes a result, chosen here only: the walk tree, the structured route, or both.

For any number of goals ``N >= 2``. ``auto`` takes the tree when the truncated game's tree
fits ``max_prefixes`` and the structured route otherwise; ``both`` runs both and treats any
disagreement as an error of the checker (docs/checker.md, "Routes"). :func:`resolve_route`
is the one place a route is chosen (for ``certify`` and ``value`` alike), and
:func:`routed_value` is ``dppverify.value``'s (and ``dpp value``'s) engine: the two-goal
structured route is the three-field DP (:mod:`dppverify.twogoal.value_dp`), the N-goal one the
guarantee sets (:func:`dppverify.structured.proved_value.nvalue`: the coalition DP over the goal
subsets, the value for N <= 3 (``proofs/NGOAL.md`` NG.3, NG.4) and for N = 4, 5 where its
certificate (NG.8) holds, else an exact bracket naming both bounds).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

from dppverify.errors import HorizonError, OptionError, TreeTooLargeError
from dppverify.exact import Number
from dppverify.game.instance import Instance
from dppverify.numbers import NumberMode
from dppverify.structured.coalition import too_many_goals
from dppverify.structured.cover import MAX_BALANCED
from dppverify.structured.proved_value import NValue, nvalue
from dppverify.tree_route.lp import lp_agrees
from dppverify.tree_route.tree import DEFAULT_MAX_PREFIXES, tree_fits
from dppverify.tree_route.value_lp import GameValue, game_value
from dppverify.twogoal.value_dp import StructuredValue, structured_value

__all__ = ["ROUTES", "Chosen", "Route", "RoutedValue", "resolve_route", "routed_value",
           "tree_fits", "values_agree"]

Route = Literal["auto", "tree", "structured", "both"]
Chosen = Literal["tree", "structured", "both"]
ROUTES: tuple[Route, ...] = ("auto", "tree", "structured", "both")


def resolve_route(route: Route, instance: Instance, horizon: int | None,
                  max_prefixes: int, *, certifying: bool = False,
                  table: bool = False) -> Chosen:
    """The route(s) to run on ``instance``'s game at ``horizon`` (None: the untruncated game).

    The one place a route is chosen, for any number of goals: ``auto`` is the walk tree when
    it fits ``max_prefixes`` and the structured route otherwise; the untruncated game has no
    walk tree. ``certifying``: for ``certify`` (the tree must cover the walks to the nearest
    goal; ``table``: the profile's Defender is a two-goal table, which only the tree
    certifies on a truncated game); otherwise for ``value`` (more than
    :data:`~dppverify.structured.cover.MAX_BALANCED` goals: the tree route only).

    Raises
    ------
    HorizonError
        The tree route (or ``both``) with the untruncated game (``horizon=None``).
    TreeTooLargeError
        ``table`` on a truncated game whose tree is too large, or with the structured route.
    OptionError
        ``value`` with more goals than the structured route takes, where it is needed.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> inst = triangle()
    >>> resolve_route("auto", inst, 3, 100), resolve_route("auto", inst, 3, 2)
    ('tree', 'structured')
    >>> resolve_route("tree", inst, None, 100)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.HorizonError: the tree route needs a finite horizon ...
    >>> resolve_route("auto", inst, 3, 2, certifying=True, table=True)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.TreeTooLargeError: a table Defender on a truncated game can only be ...
    """
    if route not in ROUTES:
        raise ValueError(f"unknown route {route!r}")
    if horizon is None and route in ("tree", "both"):
        raise HorizonError(_NO_TREE_CERTIFY.format(route=route) if certifying else _NO_TREE)
    n_goals = len(instance.goals)
    tree_only = not certifying and n_goals > MAX_BALANCED
    if tree_only and (horizon is None or route in ("structured", "both")):
        raise OptionError(too_many_goals(n_goals))
    if horizon is None:
        return "structured"
    if route == "auto":
        size = max(horizon, instance.hops[instance.start]) if certifying else horizon
        if tree_fits(instance, size, max_prefixes) or tree_only:
            return "tree"
        if table:
            raise TreeTooLargeError(_TABLE_REFUSED.format(
                why=f"the H = {horizon} walk tree has more than {max_prefixes} prefixes"))
        return "structured"
    if route in ("structured", "both") and table:
        raise TreeTooLargeError(_TABLE_REFUSED.format(why=f"--route {route} was asked for"))
    return route


_NO_TREE = ("the tree route needs a finite horizon --horizon H (without a horizon, or with inf, "
            "the game is the untruncated one: the structured route)")
_NO_TREE_CERTIFY = ("--route {route} needs a finite horizon: the walk tree is the truncated "
                    "game's (give --horizon H; without a horizon the untruncated game is "
                    "certified by the structured route)")
_TABLE_REFUSED = ("a table Defender on a truncated game can only be certified on the walk "
                  "tree, and {why}; use --route tree with a horizon whose tree fits "
                  "--max-prefixes, or omit --horizon to certify the untruncated game")


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
    if not lp_agrees(tree.lp, structured):
        return (f"the routes disagree: structured V_H = {structured}, tree LP value "
                f"{tree.value!r}")
    return None


@dataclass(frozen=True)
class RoutedValue:
    """``V_H`` by the route(s) asked for, for any number of goals.

    Attributes
    ----------
    route : {"tree", "structured", "both"}
        The route(s) that ran (``auto`` resolved).
    horizon : int or None
        ``H`` (None: the untruncated game).
    tree : GameValue, GameValue or None
        The tree route's result (LP plus exact bracket).
    structured : StructuredValue, NValue or None
        The structured route's result (two goals: the three-field DP; more: the guarantee
        sets, exact or an exact bracket).
    disagreement : str or None
        With ``both``: why the routes disagree (None when they agree).
    goals : int
        The number of goals ``N``.

    ``value``, ``lower`` and ``upper`` read the result whatever the route: ``V_H`` when it is
    known (exactly; a float in float mode), else None, and the bounds ``lower <= V_H <= upper``.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> r = routed_value(triangle(), 4, route="tree")
    >>> r.value, r.lower, r.upper
    (Fraction(12, 5), Fraction(12, 5), Fraction(12, 5))
    >>> from dppverify.game.examples import star3
    >>> r = routed_value(star3(), None)
    >>> r.value, r.lower, r.upper, r.goals
    (Fraction(3, 2), Fraction(3, 2), Fraction(3, 2), 3)
    """

    route: Chosen
    horizon: int | None
    tree: GameValue | GameValue | None
    structured: StructuredValue | NValue | None
    disagreement: str | None = None
    goals: int = 2

    def bounds(self) -> tuple[Number, Number]:
        """``(lower, upper)`` with ``lower <= V_H <= upper`` (both the value when known).

        Examples
        --------
        >>> from dppverify.game.examples import star3
        >>> routed_value(star3(), 2, route="tree").bounds()
        (Fraction(3, 2), Fraction(3, 2))
        """
        s = self.structured
        if isinstance(s, StructuredValue):
            return s.value, s.value
        if s is not None:
            return s.lower, s.upper
        assert self.tree is not None  # one route always ran
        return self.tree.bracket.lower, self.tree.bracket.upper

    @property
    def lower(self) -> Number:
        """A lower bound on ``V_H`` (the value itself when known)."""
        return self.bounds()[0]

    @property
    def upper(self) -> Number:
        """An upper bound on ``V_H`` (the value itself when known)."""
        return self.bounds()[1]

    @property
    def value(self) -> Number | None:
        """``V_H`` when known (the structured route's, or a closed exact bracket), else None."""
        if self.structured is not None and self.structured.value is not None:
            return self.structured.value
        return self.tree.bracket.exact if self.tree is not None else None


def routed_value(instance: Instance, horizon: int | None, *, route: Route = "auto",
                 max_prefixes: int = DEFAULT_MAX_PREFIXES,
                 progress: bool = False,
                 phase: Callable[[str], None] | None = None) -> RoutedValue:
    """``V_H`` of ``instance`` by the tree route, the structured route, or both.

    Parameters
    ----------
    instance : Instance
        The game (two or N goals).
    horizon : int or None
        ``H``; None for the untruncated game (structured route only).
    route : {"auto", "tree", "structured", "both"}
        ``auto``: the tree when it fits ``max_prefixes``, else the structured route.
    max_prefixes : int
        Size guard of the walk tree.
    progress : bool
        Progress bars on stderr (two-goal tree route).
    phase : callable, optional
        Called with a short description of each phase of the N-goal structured route (the
        ``--progress`` line of ``dpp value``).

    Returns
    -------
    RoutedValue

    Raises
    ------
    HorizonError, TreeTooLargeError
        As :func:`~dppverify.tree_route.value_lp.game_value` and
        :func:`~dppverify.twogoal.value_dp.structured_value`; the tree route with
        ``horizon=None``.
    OptionError
        More than five goals where the structured route is needed (``H = inf``,
        ``--route structured`` or ``both``).

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> r = routed_value(triangle(), 3, route="both")
    >>> r.route, r.structured.value, r.tree.bracket.exact, r.disagreement
    ('both', Fraction(12, 5), Fraction(12, 5), None)
    >>> routed_value(triangle(), None).route
    'structured'
    >>> from dppverify.game.examples import star3
    >>> r = routed_value(star3(), 3, route="both")
    >>> r.tree.bracket.exact, r.structured.value, r.disagreement
    (Fraction(3, 2), Fraction(3, 2), None)
    """
    chosen = resolve_route(route, instance, horizon, max_prefixes)
    two = instance.n_goals == 2  # N = 2: the three-field DP, fast on million-cell maps
    tree = structured = None
    if chosen in ("structured", "both"):
        structured = (structured_value(instance, horizon) if two
                      else nvalue(instance, horizon, progress=phase))
    if chosen in ("tree", "both"):
        assert horizon is not None  # resolve_route: the tree route needs a finite horizon
        tree = game_value(instance, horizon, max_prefixes=max_prefixes, progress=progress)
    why = None
    if tree is not None and isinstance(structured, StructuredValue):
        why = values_agree(tree, structured.value, instance.numbers)
    elif tree is not None and isinstance(structured, NValue):
        why = _brackets_agree(tree, structured, horizon)
    return RoutedValue(route=chosen, horizon=horizon, tree=tree, structured=structured,
                       disagreement=why, goals=instance.n_goals)


def _brackets_agree(tree: GameValue, dp: NValue, horizon: int | None) -> str | None:
    """None when the tree's exact bracket and the guarantee sets' value or bracket agree."""
    b = tree.bracket
    overlap = dp.lower <= b.upper and b.lower <= dp.upper
    exact_ok = dp.value is None or (b.lower <= dp.value <= b.upper
                                    and lp_agrees(tree.lp, dp.value))
    if overlap and exact_ok:
        return None
    return (f"the routes disagree at H = {horizon}: structured route [{dp.lower}, {dp.upper}], "
            f"tree route in [{b.lower}, {b.upper}] (LP {tree.value!r}) — a bug; please keep "
            f"this instance")
