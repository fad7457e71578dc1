"""The goal-selection game's instance, read by the checker itself (``docs/formats.md`` §1,
"Goal selection").

A goal-selection document is an instance document (or a compact ``dpp-map-instance/1``) with
``"goal_selection": true``, no ``"prior"`` and optional goal values ``"goal_values"``. The
checker reads it into a :class:`SelectionInstance`: the game as the one
:class:`~dppverify.game.instance.Instance` type at the *reference* prior (uniform on the goals;
nothing the checker decides about the goal-selection game depends on it) and the values
``r_i``. :meth:`SelectionInstance.at_choice` is the game with the Attacker's choice ``q`` as
its prior, zeros allowed: the game the equilibrium conditions of a choice are checked on.
Goal-selection games are exact and take 2 to 5 goals.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from typing import Any

from dppio.text import json_shown
from dppverify.errors import InvalidInstanceError
from dppverify.exact import INF
from dppverify.formats.json_reading import JsonReadError, parse_json_text, parse_number, show_node
from dppverify.formats.map_instance import MAP_INSTANCE_FORMAT
from dppverify.game.instance import Instance, instance_from_json, read_instance_document
from dppverify.game.instance_reading import arc_arrays, goal_distance_fields, remember_arrays
from dppverify.limits import MAX_GOALS

__all__ = ["GOAL_SELECTION", "GOAL_VALUES", "SELECTION_MAX_GOALS", "SelectionInstance",
           "is_selection_document", "load_selection", "selection_from_json"]

GOAL_SELECTION = "goal_selection"
"""The key that marks a goal-selection instance (its value must be ``true``)."""

GOAL_VALUES = "goal_values"
"""The optional key of the goal values ``r_i``."""

SELECTION_MAX_GOALS = 5
"""The most goals of a goal-selection game (the guarantee sets' tables, as for ``dpp value``)."""


@dataclass(frozen=True, eq=False)
class SelectionInstance:
    """A goal-selection game: the graph, start and goals of :attr:`game` and the goal values.

    Attributes
    ----------
    game : Instance
        The game at the reference prior (uniform); the prior is not part of the game.
    values : tuple of Fraction
        ``values[i] = r_i``: type ``i`` pays its cost minus ``r_i``.

    Examples
    --------
    >>> from dppverify.game.examples import triangle_document
    >>> doc = {**triangle_document(), "goal_selection": True}
    >>> del doc["prior"]
    >>> sel = selection_from_json(doc)
    >>> sel.game.prior, sel.at_choice([Fraction(0), Fraction(1)]).prior
    ((Fraction(1, 2), Fraction(1, 2)), (Fraction(0, 1), Fraction(1, 1)))
    """

    game: Instance
    values: tuple[Fraction, ...]

    @property
    def n_goals(self) -> int:
        """``N``, the number of goals."""
        return self.game.n_goals

    def at_choice(self, choice: Sequence[Fraction]) -> Instance:
        """The game with the Attacker's choice ``q`` as its prior (entries in [0, 1] summing
        to 1; zeros allowed, unlike an instance document's prior).

        Raises
        ------
        ValueError
            If ``choice`` is not a distribution over the goals.
        """
        q = tuple(Fraction(x) for x in choice)
        if len(q) != self.n_goals or any(x < 0 for x in q) or sum(q) != 1:
            raise ValueError(f"a choice is a distribution over the {self.n_goals} goals, got "
                             f"{[str(x) for x in q]}")
        game = dataclasses.replace(self.game, prior=q)
        remember_arrays(game, arc_arrays(self.game), goal_distance_fields(self.game))
        return game


def is_selection_document(doc: Any) -> bool:
    """True when an instance document carries the goal-selection mark (whatever its value:
    :func:`selection_from_json` checks it).

    Examples
    --------
    >>> is_selection_document({"goal_selection": True}), is_selection_document({"prior": []})
    (True, False)
    """
    return isinstance(doc, Mapping) and GOAL_SELECTION in doc


def selection_from_json(doc: Any, *, base: Path | None = None) -> SelectionInstance:
    """Read and validate a goal-selection instance document (dict or JSON text).

    Raises
    ------
    InvalidInstanceError
        One line naming what is wrong: the mark, a ``prior``, the goal values, float numbers,
        more than five goals, or anything the instance reader refuses.

    Examples
    --------
    >>> from dppverify.game.examples import star3_document
    >>> doc = {**star3_document(), "goal_selection": True, "goal_values": [0, 0, "1/2"]}
    >>> del doc["prior"]
    >>> selection_from_json(doc).values
    (Fraction(0, 1), Fraction(0, 1), Fraction(1, 2))
    >>> selection_from_json({**doc, "goal_values": [0, 1]})
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: goal_values: must be a list of 3 numbers (one per \
goal), got [0, 1]
    """
    if isinstance(doc, str | bytes):
        try:
            doc = parse_json_text(doc)
        except JsonReadError as exc:
            raise InvalidInstanceError(str(exc)) from None
    if not isinstance(doc, Mapping):
        raise InvalidInstanceError(f"instance must be a JSON object, got {type(doc).__name__}")
    if doc.get(GOAL_SELECTION) is not True:
        raise InvalidInstanceError(f"{GOAL_SELECTION}: must be true in a goal-selection "
                                   f"instance (omit the key for a game with a prior), got "
                                   f"{json_shown(doc.get(GOAL_SELECTION))}")
    if "prior" in doc:
        raise InvalidInstanceError("prior: a goal-selection instance has no prior (the "
                                   "Attacker chooses its goal); drop \"prior\", or drop "
                                   "\"goal_selection\" for the game with a prior")
    goals = doc.get("goals")
    limit = min(MAX_GOALS, SELECTION_MAX_GOALS)
    if not isinstance(goals, list) or not 2 <= len(goals) <= limit:
        raise InvalidInstanceError(f"goals: a goal-selection instance lists 2 to {limit} "
                                   f"goals, got {json_shown(goals)[:200]}")
    if doc.get("numbers", "exact") != "exact" or (
            doc.get("format") == MAP_INSTANCE_FORMAT and doc.get("connectivity", 4) != 4):
        raise InvalidInstanceError("a goal-selection instance is exact: \"numbers\": \"float\" "
                                   "and connectivity 8 are not supported")
    n = len(goals)
    values = _values(doc.get(GOAL_VALUES), n)
    rest = {k: v for k, v in doc.items() if k not in (GOAL_SELECTION, GOAL_VALUES)}
    rest["prior"] = [f"1/{n}"] * n
    game = instance_from_json(rest, base=base)
    _check_reachable(game)
    return SelectionInstance(game, values)


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


def _check_reachable(game: Instance) -> None:
    """Every goal reachable from the start and from every goal (the N-goal reader checks this;
    the two-goal reader too: kept here so that the rule does not depend on N)."""
    for t, g in enumerate(game.goals):
        for v in (game.start, *game.goals):
            if game.dist_to[t][v] == INF:  # pragma: no cover - the instance reader refuses it
                raise InvalidInstanceError(f"goal {show_node(game.nodes[g])} is unreachable "
                                           f"from {show_node(game.nodes[v])}")


def load_selection(path: str | Path) -> SelectionInstance:
    """Read a goal-selection instance file (errors name the file).

    Examples
    --------
    >>> load_selection("/nonexistent.json")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: /nonexistent.json: cannot read instance file ...
    """
    doc = read_instance_document(path)  # the prior game's reader reads the file
    try:
        return selection_from_json(doc, base=Path(path).parent)
    except InvalidInstanceError as exc:
        raise InvalidInstanceError(f"{path}: {exc}") from None
