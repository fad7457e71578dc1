"""``dppverify.value``: the value of the game, untruncated by default, from any instance form.

One entry point for two and N goals (:func:`~dppverify.routes.routed_value`); it takes the
instances ``certify`` takes, converted once at the door
(:func:`~dppverify.game.inputs.as_instance`), and the horizon as
:func:`~dppverify.horizons.parse_horizon` reads it (default ``"inf"``: the untruncated game, by
the structured route).
"""

from __future__ import annotations

from typing import Any, Unpack

from dppverify.game.inputs import GraphKeys, as_instance
from dppverify.horizons import parse_horizon
from dppverify.routes import Route, RoutedValue, routed_value
from dppverify.tree_route.tree import DEFAULT_MAX_PREFIXES


def value(instance: Any, horizon: int | str | float | None = "inf", *, route: Route = "auto",
          max_prefixes: int = DEFAULT_MAX_PREFIXES, progress: bool = False,
          **graph: Unpack[GraphKeys]) -> RoutedValue:
    """The value ``V_H`` of ``instance``'s game (default: the untruncated game, ``H = inf``).

    Parameters
    ----------
    instance : Instance, Mapping, bytes, str, Path, networkx graph, or an object with ``to_json()``
        The game, in any form :func:`dppverify.certify` accepts
        (:func:`~dppverify.game.inputs.as_instance`); two or N goals.
    horizon : "inf", None, math.inf or int
        ``"inf"`` (default), None or ``math.inf``: the untruncated game (structured route).
        An integer ``H``: the game truncated at ``H``.
    route, max_prefixes, progress
        As :func:`~dppverify.routes.routed_value` (``route`` as ``dpp value --route``).
    **graph : GraphKeys
        ``start``, ``goals``, ``prior`` and ``weight`` of a networkx graph ``instance``.

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
    game = as_instance(instance, **graph)
    return routed_value(game, parse_horizon(horizon), route=route, max_prefixes=max_prefixes,
                        progress=progress)
