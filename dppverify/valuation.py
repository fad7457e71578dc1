"""``dppverify.value``: the value of the game, untruncated by default, from any instance form.

One entry point over the two- and N-goal value routes (:func:`~dppverify.routes.routed_value`,
:func:`~dppverify.ngoal.routes.nrouted_value`); it takes the inputs ``certify`` takes (an
instance object, a document, a file path, or any object with ``to_json()``) and the horizon
as :func:`~dppverify.horizons.parse_horizon` reads it (default ``"inf"``: the untruncated
game, by the structured route).
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from dppverify.game.instance import (
    Instance,
    as_instance,
    goal_count,
    instance_from_json,
    load_instance,
)
from dppverify.horizons import parse_horizon
from dppverify.ngoal.routes import NRoutedValue, is_ngoal_file, nrouted_value
from dppverify.routes import Route, RoutedValue, routed_value
from dppverify.tree_route.tree import DEFAULT_MAX_PREFIXES

__all__ = ["game_of", "value"]


def game_of(instance: Any) -> Instance:
    """The two-goal or N-goal instance of any accepted form.

    Examples
    --------
    >>> from dppverify.game.examples import star3_document
    >>> type(game_of(star3_document())).__name__
    'Instance'
    """
    if isinstance(instance, Instance):
        return instance
    if isinstance(instance, str | Path):
        if is_ngoal_file(instance):
            return load_instance(instance)
        return as_instance(instance, two_goals=True)
    doc = instance
    if not isinstance(instance, Mapping):
        to_json = getattr(instance, "to_json", None)
        if callable(to_json):
            doc = to_json()
    if isinstance(doc, Mapping) and (goal_count(doc) or 0) > 2:
        return instance_from_json(doc)
    return as_instance(doc, two_goals=True)


def value(instance: Instance | Mapping[str, Any] | str | Path | Any,
          horizon: int | str | float | None = "inf", *, route: Route = "auto",
          max_prefixes: int = DEFAULT_MAX_PREFIXES,
          progress: bool = False) -> RoutedValue | NRoutedValue:
    """The value ``V_H`` of ``instance``'s game (default: the untruncated game, ``H = inf``).

    Parameters
    ----------
    instance : Instance, Mapping, str, Path or an object with ``to_json()``
        The game, in any form :func:`dppverify.certify` accepts; two or N goals.
    horizon : "inf", None, math.inf or int
        ``"inf"`` (default), None or ``math.inf``: the untruncated game (structured route).
        An integer ``H``: the game truncated at ``H``.
    route : {"auto", "tree", "structured", "both"}
        As ``dpp value --route``.
    max_prefixes : int
        Size guard of the walk tree.
    progress : bool
        Progress bars on stderr (two-goal tree route).

    Returns
    -------
    RoutedValue or NRoutedValue
        Two goals: :class:`~dppverify.routes.RoutedValue`; more:
        :class:`~dppverify.ngoal.routes.NRoutedValue`. ``horizon`` is None for the
        untruncated game. Both have ``value`` (``V_H`` when proved, else None), ``lower``
        and ``upper`` (the bounds, equal when proved), whatever the route.

    Raises
    ------
    HorizonError
        A horizon that is neither ``"inf"`` nor a non-negative integer (one line).
    CheckerError
        Bad instance, or as the route functions.

    Examples
    --------
    >>> from dppverify.game.examples import triangle_document
    >>> r = value(triangle_document())
    >>> r.route, r.horizon, r.value          # r.lower, r.upper: the bounds
    ('structured', None, Fraction(12, 5))
    >>> value(triangle_document(), 2).tree.bracket.exact
    Fraction(12, 5)
    >>> value(triangle_document(), "soon")
    Traceback (most recent call last):
    dppverify.errors.HorizonError: the horizon must be a non-negative integer or 'inf', got 'soon'
    """
    h = parse_horizon(horizon)
    game = game_of(instance)
    if game.n_goals > 2:
        return nrouted_value(game, h, route=route, max_prefixes=max_prefixes)
    return routed_value(game, h, route=route, max_prefixes=max_prefixes, progress=progress)
