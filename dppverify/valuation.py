"""``dppverify.value``: the value of the game, untruncated by default, from any instance form.

One entry point for two and N goals (:func:`~dppverify.routes.routed_value`); it takes the
inputs ``certify`` takes (an instance object, a document, a file path, or any object with
``to_json()``) and the horizon as :func:`~dppverify.horizons.parse_horizon` reads it (default
``"inf"``: the untruncated game, by the structured route). :func:`game_of` is the one place
where the number of goals decides which game an input is, reading a file once.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from dppverify.errors import InvalidInstanceError
from dppverify.game.instance import (
    Instance,
    as_instance,
    goal_count,
    instance_from_json,
    read_instance_document,
)
from dppverify.horizons import parse_horizon
from dppverify.routes import Route, RoutedValue, routed_value
from dppverify.tree_route.tree import DEFAULT_MAX_PREFIXES

__all__ = ["game_of", "value"]


def game_of(instance: Any, *, ngoal: bool = False) -> Instance:
    """The two-goal or N-goal instance of any accepted form, each file read once.

    Parameters
    ----------
    instance : Instance, Instance, Mapping, str, Path or an object with ``to_json()``
        Returned as is, parsed, loaded, or parsed from ``to_json()``. A document listing
        more than two goals is an :class:`~dppverify.game.instance.Instance`, else an
        :class:`~dppverify.game.instance.Instance`.
    ngoal : bool
        Read a document as an :class:`~dppverify.game.instance.Instance` whatever its
        number of goals (a two-goal game certified against a ``dpp-ngoal-profile/1``).

    Raises
    ------
    InvalidInstanceError
        One line (``PATH: what is wrong`` for a file).

    Examples
    --------
    >>> from dppverify.game.examples import star3_document
    >>> type(game_of(star3_document())).__name__
    'Instance'
    >>> from dppverify.game.examples import triangle_document
    >>> [type(game_of(triangle_document(), ngoal=n)).__name__ for n in (False, True)]
    ['Instance', 'Instance']
    >>> game_of("/nonexistent.json")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: /nonexistent.json: cannot read instance file ...
    """
    if isinstance(instance, Instance):
        return instance
    if isinstance(instance, str | Path):
        path = Path(instance)
        doc = read_instance_document(path)
        try:
            if ngoal or _n_goals(doc):
                return instance_from_json(doc, two_goals=False, base=path.parent)
            return instance_from_json(doc, two_goals=True, base=path.parent)
        except InvalidInstanceError as exc:
            raise InvalidInstanceError(f"{path}: {exc}") from None
    doc = instance
    if not isinstance(instance, Mapping):
        to_json = getattr(instance, "to_json", None)
        if callable(to_json):
            doc = to_json()
    if isinstance(doc, Mapping) and (ngoal or _n_goals(doc)):
        return instance_from_json(doc, two_goals=False)
    return as_instance(doc)


def _n_goals(doc: Any) -> bool:
    """True when the instance document lists more than two goals."""
    return (goal_count(doc) or 0) > 2


def value(instance: Instance | Mapping[str, Any] | str | Path | Any,
          horizon: int | str | float | None = "inf", *, route: Route = "auto",
          max_prefixes: int = DEFAULT_MAX_PREFIXES,
          progress: bool = False) -> RoutedValue:
    """The value ``V_H`` of ``instance``'s game (default: the untruncated game, ``H = inf``).

    Parameters
    ----------
    instance : Instance, Mapping, str, Path or an object with ``to_json()``
        The game, in any form :func:`dppverify.certify` accepts; two or N goals.
    horizon : "inf", None, math.inf or int
        ``"inf"`` (default), None or ``math.inf``: the untruncated game (structured route).
        An integer ``H``: the game truncated at ``H``.
    route, max_prefixes, progress
        As :func:`~dppverify.routes.routed_value` (``route`` as ``dpp value --route``).

    Returns
    -------
    RoutedValue
        ``horizon`` is None for the untruncated game; ``value`` (``V_H`` when proved, else
        None), ``lower`` and ``upper`` (the bounds, equal when proved), whatever the route.

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
    return routed_value(game_of(instance), h, route=route, max_prefixes=max_prefixes,
                        progress=progress)
