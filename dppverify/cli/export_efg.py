"""``dpp export-efg``: write an instance's game truncated at H steps as a Gambit ``.efg`` file."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar

import click

from dppio.cli.conventions import output_file_option, progress_option, status, want_progress
from dppio.examples import INSTANCE_FILE
from dppverify.cli.errors import fail
from dppverify.cli.inputs import load_game, max_prefixes_option
from dppverify.cli.map_options import MapRequest, map_options
from dppverify.cli.selection import selection_options
from dppverify.errors import CheckerError, TreeTooLargeError
from dppverify.formats.files import refuse_input_as_output
from dppverify.limits import MAX_HORIZON
from dppverify.tree_route.efg import DEFAULT_MAX_EFG_NODES, write_efg
from dppverify.tree_route.tree import build_tree

__all__ = ["efg_game_options", "export_efg_command"]

F = TypeVar("F", bound=Callable[..., Any])


def efg_game_options(fn: F) -> F:
    """The options that say which ``.efg`` game of an instance: ``--attacker-observes/
    --attacker-blind``, ``--forced-moves``, ``--max-prefixes``, ``--max-nodes`` — one spelling
    for ``export-efg`` and ``import-profile`` (which rebuilds the game the export wrote).

    Examples
    --------
    >>> from click.testing import CliRunner
    >>> cmd = click.command()(efg_game_options(lambda **kw: click.echo(sorted(kw.items()))))
    >>> CliRunner().invoke(cmd, ["--attacker-blind"]).output  # doctest: +ELLIPSIS
    "[('attacker_observes', False), ('forced_moves', False), ('max_nodes', 2000000), ..."
    """
    for option in reversed((
            click.option("--attacker-observes/--attacker-blind", default=True,
                         show_default=True,
                         help="Whether the Attacker's information sets include the Defender's "
                              "past allocations (the value is the same either way)."),
            click.option("--forced-moves", is_flag=True,
                         help="Also write the Attacker's one-action decision nodes (skipped by "
                              "default: Gambit 17.0.0b2's lp_solve mis-solves one-action "
                              "information sets)."),
            max_prefixes_option(),
            click.option("--max-nodes", type=click.IntRange(min=1), default=DEFAULT_MAX_EFG_NODES,
                         show_default=True, help="Refuse games with more nodes than this."))):
        fn = option(fn)
    return fn


@click.command("export-efg", short_help="Write the truncated game as a Gambit .efg file.")
@click.argument("instance", required=False, type=INSTANCE_FILE)
@selection_options
@map_options
@click.option("-H", "--horizon", type=click.IntRange(min=0, max=MAX_HORIZON), required=True,
              help="Horizon H of the truncated game.")
@output_file_option("The .efg file to write (atomically).", required=True)
@efg_game_options
@progress_option
def export_efg_command(instance: str | None, grid: MapRequest | None, horizon: int,
                       output: str, attacker_observes: bool, forced_moves: bool,
                       max_prefixes: int, max_nodes: int, goal_selection: bool,
                       goal_values: str | None, progress: bool | None) -> None:
    """Write INSTANCE's game truncated at H steps as a Gambit .efg file.

    Chance draws the Attacker's goal, the Attacker picks each next node, the Defender
    allocates each step to a goal (information set: the walk plus its own past allocations,
    so the game has perfect recall); payoffs sit on the leaves only. Gambit and OpenSpiel
    read the file; every copy of a t-step walk prefix appears 2^t times (N^t with N goals:
    an instance may list N > 2 goals, docs/formats.md), so keep H small. In the
    goal-selection game (a goal-selection INSTANCE, or --goal-selection with --map) the root is
    the Attacker's own choice of its goal instead of chance, and it pays its cost minus the
    goal's value (proofs/SELECT.md).

    \b
    Examples:
      dpp export-efg examples:triangle --horizon 2 -o triangle.efg
      dpp export-efg examples:triangle -H 3 -o game.efg --attacker-blind
      dpp export-efg --map m.map --start 2,0 --goals 0,3 0,0 --prior 0.6,0.4 -H 2 -o g.efg
      dpp export-efg --goal-selection --map m.map --start 2,0 --goals 0,3 0,0 -H 2 -o s.efg
    """
    try:
        refuse_input_as_output(output, [instance, grid.path if grid is not None else None])
        game = load_game(instance, grid, "dpp export-efg")
        show = want_progress(progress)
        tree = build_tree(game, horizon, max_prefixes=max_prefixes, progress=show)
        size = write_efg(output, tree, attacker_observes=attacker_observes,
                         forced_moves=forced_moves, max_nodes=max_nodes, progress=show,
                         goal_values=game.goal_values)
    except TreeTooLargeError as exc:  # a Gambit game is the walk tree: no other route
        fail(TreeTooLargeError(str(exc).replace("use --route structured, or lower the horizon",
                                                "lower the horizon (a Gambit game is the walk "
                                                "tree itself)")))
    except CheckerError as exc:
        fail(exc)
    goals = f"N = {len(game.goals)} goals, " if len(game.goals) > 2 else ""
    if game.goal_selection:
        goals = f"goal selection, {goals}"
    status(f"wrote {output}: {goals}H = {horizon}, {size.nodes} game nodes ({size.terminals} "
           f"terminals), {size.attacker_infosets} Attacker and {size.defender_infosets} "
           f"Defender information sets")
