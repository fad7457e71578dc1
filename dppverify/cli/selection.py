"""The goal-selection game's options for the checker's commands (docs/formats.md §1, "Goal
selection"): ``--goal-selection`` and ``--goal-values``, read by the ``--map`` option group
(:mod:`dppverify.cli.map_options`); a goal-selection INSTANCE file needs neither (the one
instance reader reads its mark and values)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar

import click

F = TypeVar("F", bound=Callable[..., Any])


def selection_options(fn: F) -> F:
    """Add ``--goal-selection`` and ``--goal-values R1,R2,...`` to a command (the command gets
    ``goal_selection`` and ``goal_values``; put it above :func:`map_options`, whose grid then
    takes no ``--prior`` and carries the values).

    Examples
    --------
    >>> cmd = selection_options(click.command()(lambda goal_selection, goal_values: None))
    >>> sorted(p.name for p in cmd.params)
    ['goal_selection', 'goal_values']
    """
    fn = click.option("--goal-values", "goal_values", metavar="R1,R2,...",
                      help="With --goal-selection: the value r_i of each goal (the Attacker "
                           "pays its cost minus r_i); default 0.")(fn)
    return click.option("--goal-selection", is_flag=True,
                        help="The goal-selection game on the --map grid (no --prior): the "
                             "Attacker chooses its goal. A goal-selection INSTANCE needs no "
                             "flag.")(fn)
