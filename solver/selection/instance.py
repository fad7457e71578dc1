"""The goal-selection game's instance: a game without a prior, whose Attacker chooses its goal.

A goal-selection document is an instance document (``docs/formats.md`` §1, or a compact
``dpp-map-instance/1``, §1c) with ``"goal_selection": true`` and no ``"prior"``, and optional
goal values ``"goal_values": [r_1, …, r_N]`` (type ``i`` pays its cost minus ``r_i``; default
0). The solver reads it into a :class:`SelectionInstance`: the game itself (an
:class:`~solver.game.instance.Instance` at the *reference* prior, uniform on the goals, which is
the prior the summaries compare with; nothing of the construction depends on it) and the goal
values. Goal-selection games are exact and take 2 to 5 goals.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np

from dppio.text import json_shown
from solver.errors import InstanceFormatError, InvalidInstanceError
from solver.formats.json_text import parse_json_text, read_json
from solver.formats.map_instance import MAP_INSTANCE_FORMAT
from solver.game.instance import MAX_GOALS, Instance
from solver.game.instance_reading import instance_from_json
from solver.game.instance_writing import instance_to_json
from solver.numbers import format_number, parse_number

GOAL_SELECTION = "goal_selection"
"""The key that marks a goal-selection instance (its value must be ``true``)."""

GOAL_VALUES = "goal_values"
"""The optional key of the goal values ``r_i``."""


@dataclass(frozen=True, eq=False)
class SelectionInstance:
    """A goal-selection game: the graph, start and goals of :attr:`game`, and goal values.

    Attributes
    ----------
    game : Instance
        The game at the reference prior (uniform on the goals); its prior is not part of the
        goal-selection game.
    values : tuple of Fraction
        ``values[i] = r_i``: type ``i`` pays its cost minus ``r_i``.

    Examples
    --------
    >>> from solver.game.instance import triangle
    >>> doc = {**triangle().to_json(), "goal_selection": True}
    >>> del doc["prior"]
    >>> sel = selection_from_json(doc)
    >>> sel.n_goals, sel.values, sel.game.prior
    (2, (Fraction(0, 1), Fraction(0, 1)), (Fraction(1, 2), Fraction(1, 2)))
    >>> sorted(sel.to_json())
    ['goal_selection', 'goals', 'graph', 'start']
    """

    game: Instance
    values: tuple[Fraction, ...]

    @property
    def n_goals(self) -> int:
        """``N``, the number of goals."""
        return self.game.n_goals

    def to_json(self) -> dict[str, Any]:
        """The goal-selection instance document (``docs/formats.md`` §1, "Goal selection")."""
        return _marked(instance_to_json(self.game), self.values)


def _marked(doc: dict[str, Any], values: tuple[Fraction, ...]) -> dict[str, Any]:
    doc = {k: v for k, v in doc.items() if k != "prior"}
    doc[GOAL_SELECTION] = True
    if any(values):
        doc[GOAL_VALUES] = [format_number(r) for r in values]
    return doc


def is_selection_document(doc: Any) -> bool:
    """True when an instance document is marked as a goal-selection instance (whatever the
    value of the mark: :func:`selection_from_json` checks it).

    Examples
    --------
    >>> is_selection_document({"goal_selection": True}), is_selection_document({"prior": []})
    (True, False)
    """
    return isinstance(doc, Mapping) and GOAL_SELECTION in doc


def selection_from_json(data: Mapping[str, Any] | str, *, base: Path | None = None
                        ) -> SelectionInstance:
    """Read a goal-selection instance document (dict or JSON text).

    Raises
    ------
    InstanceFormatError, InvalidInstanceError
        One line naming what is wrong: the mark, a ``prior``, the goal values, float numbers,
        or anything the instance reader refuses.

    Examples
    --------
    >>> doc = {"graph": {"nodes": [{"id": x} for x in "sab"],
    ...        "edges": [{"source": "s", "target": "a"}, {"source": "s", "target": "b"}]},
    ...        "start": "s", "goals": ["a", "b"], "goal_selection": True,
    ...        "goal_values": [0, "1/2"]}
    >>> selection_from_json(doc).values
    (Fraction(0, 1), Fraction(1, 2))
    >>> selection_from_json({**doc, "prior": ["1/2", "1/2"]})  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    solver.errors.InstanceFormatError: prior: a goal-selection instance has no prior ...
    """
    if isinstance(data, str):
        data = parse_json_text(data)
    if not isinstance(data, Mapping):
        raise InstanceFormatError(f"instance must be a JSON object, got {type(data).__name__}")
    if data.get(GOAL_SELECTION) is not True:
        raise InstanceFormatError(f"{GOAL_SELECTION}: must be true in a goal-selection instance "
                                  f"(omit the key for a game with a prior), got "
                                  f"{json_shown(data.get(GOAL_SELECTION))}")
    if "prior" in data:
        raise InstanceFormatError("prior: a goal-selection instance has no prior (the Attacker "
                                  "chooses its goal); drop \"prior\", or drop \"goal_selection\" "
                                  "for the game with a prior")
    goals = data.get("goals")
    if not isinstance(goals, list) or not 2 <= len(goals) <= MAX_GOALS:
        raise InstanceFormatError(f"'goals' must be a list of 2 to {MAX_GOALS} goals, got "
                                  f"{json_shown(goals)}")
    n = len(goals)
    if data.get("numbers", "exact") != "exact" or (
            data.get("format") == MAP_INSTANCE_FORMAT and data.get("connectivity", 4) != 4):
        raise InvalidInstanceError("a goal-selection instance is exact: \"numbers\": \"float\" "
                                   "and --connectivity 8 are not supported")
    values = _values(data.get(GOAL_VALUES), n)
    rest = {k: v for k, v in data.items() if k not in (GOAL_SELECTION, GOAL_VALUES)}
    rest["prior"] = [f"1/{n}"] * n
    game = instance_from_json(dict(rest), base=base)
    _check_reachable(game)
    return SelectionInstance(game, values)


def _values(raw: Any, n: int) -> tuple[Fraction, ...]:
    if raw is None:
        return (Fraction(0),) * n
    if not isinstance(raw, list) or len(raw) != n:
        raise InstanceFormatError(f"{GOAL_VALUES}: must be a list of {n} numbers (one per "
                                  f"goal), got {json_shown(raw)}")
    return tuple(Fraction(parse_number(x, where=f"{GOAL_VALUES}[{i}]"))
                 for i, x in enumerate(raw))


def _check_reachable(game: Instance) -> None:
    """Every goal reachable from the start and from every other goal (finite terminal
    costs); the N-goal rules check this on reading, the two-goal rules on solving."""
    labels = game.network.labels
    for t, g in enumerate(game.targets):
        for v, what in ((game.s0, "the start"), *((h, f"goal {labels[h]!r}")
                                                   for h in game.targets)):
            if not np.isfinite(float(game.dist_to[t][v])):
                raise InvalidInstanceError(f"goal {labels[g]!r} is not reachable from {what}")


def load_selection(path: str | Path) -> SelectionInstance:
    """Read a goal-selection instance file (errors name the file).

    Examples
    --------
    >>> load_selection("/nonexistent.json")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    solver.errors.InstanceFormatError: ...nonexistent.json...
    """
    doc = read_json(path)
    try:
        return selection_from_json(doc, base=Path(path).parent)
    except InstanceFormatError as exc:
        raise InstanceFormatError(f"{path}: {exc}") from None
    except InvalidInstanceError as exc:
        raise InvalidInstanceError(f"{path}: {exc}") from None


def as_selection(instance: SelectionInstance | Mapping[str, Any] | str | Path
                 ) -> SelectionInstance:
    """A :class:`SelectionInstance` from itself, a document or a file path.

    Examples
    --------
    >>> as_selection(3)
    Traceback (most recent call last):
    solver.errors.InvalidInstanceError: a goal-selection instance must be a SelectionInstance, \
a document (dict) or a file path; got int
    """
    if isinstance(instance, SelectionInstance):
        return instance
    if isinstance(instance, Mapping):
        return selection_from_json(instance)
    if isinstance(instance, str | Path):
        return load_selection(instance)
    raise InvalidInstanceError("a goal-selection instance must be a SelectionInstance, a "
                               f"document (dict) or a file path; got {type(instance).__name__}")
