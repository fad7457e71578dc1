"""The goal-selection mark of an instance document (``docs/formats.md`` §1, "Goal selection"),
and the game with a choice as its prior.

A goal-selection document is an instance document (or a compact ``dpp-map-instance/1``) with
``"goal_selection": true``, no ``"prior"`` and optional goal values ``"goal_values"``; the
one instance reader (:func:`dppverify.game.instance.instance_from_json`) reads it into an
:class:`~dppverify.game.instance_type.Instance` whose ``goal_values`` are set and whose prior
is the uniform reference prior: :func:`selection_parts` checks the mark and gives the document
the reader reads. :func:`with_choice` is the game with the Attacker's choice ``q`` as prior,
zeros allowed: the game the equilibrium conditions of a choice are checked on
(proofs/SELECT.md SELECT.6).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence
from fractions import Fraction
from typing import Any

from dppio.text import json_shown
from dppverify.errors import InvalidInstanceError
from dppverify.formats.json_reading import parse_number
from dppverify.formats.map_instance import MAP_INSTANCE_FORMAT
from dppverify.game.instance_reading import arc_arrays, goal_distance_fields, remember_arrays
from dppverify.game.instance_type import Instance

GOAL_SELECTION = "goal_selection"
"""The key that marks a goal-selection instance (its value must be ``true``)."""

GOAL_VALUES = "goal_values"
"""The optional key of the goal values ``r_i``."""

MAX_SELECTION_GOALS = 5
"""The most goals of a goal-selection game (the guarantee sets' tables, as for ``dpp value``)."""


def selection_document(document: Mapping[str, Any], goal_values: Sequence[str] | None = None
                       ) -> dict[str, Any]:
    """The goal-selection document of a game document with a prior: the prior dropped, the
    mark set, the goal values (as typed) added when given.

    Examples
    --------
    >>> selection_document({"start": [0, 0], "prior": ["1/2", "1/2"]}, ["0", "1/2"])
    {'start': [0, 0], 'goal_selection': True, 'goal_values': ['0', '1/2']}
    """
    doc = {k: v for k, v in document.items() if k != "prior"}
    doc[GOAL_SELECTION] = True
    if goal_values is not None:
        doc[GOAL_VALUES] = list(goal_values)
    return doc


def is_selection_document(doc: Any) -> bool:
    """True when an instance document carries the goal-selection mark (whatever its value:
    :func:`selection_parts` checks it).

    Examples
    --------
    >>> is_selection_document({"goal_selection": True}), is_selection_document({"prior": []})
    (True, False)
    """
    return isinstance(doc, Mapping) and GOAL_SELECTION in doc


def selection_parts(doc: Mapping[str, Any]) -> tuple[dict[str, Any], tuple[Fraction, ...]]:
    """The document the instance reader reads for a goal-selection document (its mark and
    values removed, the uniform reference prior added) and the goal values.

    Raises
    ------
    InvalidInstanceError
        One line naming what is wrong: the mark, a ``prior``, the goal values, float numbers,
        more than five goals.

    Examples
    --------
    >>> doc = {"graph": {}, "start": "s", "goals": ["a", "b"], "goal_selection": True,
    ...        "goal_values": [0, "1/2"]}
    >>> rest, values = selection_parts(doc)
    >>> rest["prior"], values
    (['1/2', '1/2'], (Fraction(0, 1), Fraction(1, 2)))
    >>> selection_parts({**doc, "goal_values": [0, 1, 2]})
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: goal_values: must be a list of 2 numbers (one per \
goal), got [0, 1, 2]
    """
    if doc.get(GOAL_SELECTION) is not True:
        raise InvalidInstanceError(f"{GOAL_SELECTION}: must be true in a goal-selection "
                                   f"instance (omit the key for a game with a prior), got "
                                   f"{json_shown(doc.get(GOAL_SELECTION))}")
    if "prior" in doc:
        raise InvalidInstanceError("prior: a goal-selection instance has no prior (the "
                                   "Attacker chooses its goal); drop \"prior\", or drop "
                                   "\"goal_selection\" for the game with a prior")
    goals = doc.get("goals")
    if not isinstance(goals, list) or not 2 <= len(goals) <= MAX_SELECTION_GOALS:
        raise InvalidInstanceError(f"goals: a goal-selection instance lists 2 to "
                                   f"{MAX_SELECTION_GOALS} goals, got {json_shown(goals)[:200]}")
    if doc.get("numbers", "exact") != "exact" or (
            doc.get("format") == MAP_INSTANCE_FORMAT and doc.get("connectivity", 4) != 4):
        raise InvalidInstanceError("a goal-selection instance is exact: \"numbers\": \"float\" "
                                   "and connectivity 8 are not supported")
    n = len(goals)
    rest = {k: v for k, v in doc.items() if k not in (GOAL_SELECTION, GOAL_VALUES)}
    rest["prior"] = [f"1/{n}"] * n
    return rest, _values(doc.get(GOAL_VALUES), n)


def _values(raw: Any, n: int) -> tuple[Fraction, ...]:
    if raw is None:
        return (Fraction(0),) * n
    if not isinstance(raw, list) or len(raw) != n:
        raise InvalidInstanceError(f"{GOAL_VALUES}: must be a list of {n} numbers (one per "
                                   f"goal), got {json_shown(raw)[:200]}")
    try:
        return tuple(Fraction(parse_number(x, where=f"{GOAL_VALUES}[{i}]"))
                     for i, x in enumerate(raw))
    except (ValueError, TypeError) as exc:
        raise InvalidInstanceError(str(exc)) from None


def marked(instance: Instance, values: tuple[Fraction, ...]) -> Instance:
    """``instance`` as the goal-selection game with ``values`` (its arrays kept).

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> game = marked(triangle(), (Fraction(0), Fraction(1)))
    >>> game.goal_selection, game.goal_values
    (True, (Fraction(0, 1), Fraction(1, 1)))
    """
    game = dataclasses.replace(instance, goal_values=values)
    remember_arrays(game, arc_arrays(instance), goal_distance_fields(instance))
    return game


def with_choice(instance: Instance, choice: Sequence[Fraction]) -> Instance:
    """The game with the Attacker's choice ``q`` as its prior (entries in [0, 1] summing to 1;
    zeros allowed, unlike an instance document's prior), goal values kept.

    Raises
    ------
    ValueError
        If ``choice`` is not a distribution over the goals.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> with_choice(triangle(), [Fraction(0), Fraction(1)]).prior
    (Fraction(0, 1), Fraction(1, 1))
    """
    q = tuple(Fraction(x) for x in choice)
    if len(q) != instance.n_goals or any(x < 0 for x in q) or sum(q) != 1:
        raise ValueError(f"a choice is a distribution over the {instance.n_goals} goals, got "
                         f"{[str(x) for x in q]}")
    game = dataclasses.replace(instance, prior=q)
    remember_arrays(game, arc_arrays(instance), goal_distance_fields(instance))
    return game
