"""``dpp value``: the value ``V_H`` of an instance's game, as text or JSON, for any N >= 2.

The value comes from :func:`dppverify.routes.routed_value` (the route is chosen there); this
module only prints it, :func:`routed_lines` as text and the ``dpp-value/1`` document of
:func:`dppverify.value_document.value_document` as JSON (one shape for every route and every
N: docs/formats.md §4). With ``--route both`` a disagreement of the routes is one line on
stderr and exit 1.
"""

from __future__ import annotations

import click

from dppio.cli.conventions import (
    PhaseBar,
    emit,
    output_file_option,
    progress_option,
    want_progress,
)
from dppio.examples import INSTANCE_FILE
from dppio.text import count, decimal
from dppverify.cli.errors import fail
from dppverify.cli.inputs import HORIZON, load_game, max_prefixes_option
from dppverify.cli.map_options import MapRequest, map_options
from dppverify.cli.selection import selection_options
from dppverify.errors import CheckerError, OptionError
from dppverify.formats.files import refuse_input_as_output
from dppverify.game.instance import Instance
from dppverify.routes import ROUTES, Route, RoutedValue, routed_value
from dppverify.structured.proved_value import NValue
from dppverify.structured.selection_value import selection_value
from dppverify.text import show, show_value
from dppverify.tree_route.lp import LP_SOLVER, LP_TOLERANCE
from dppverify.tree_route.value_lp import GameValue
from dppverify.twogoal.value_dp import StructuredValue
from dppverify.value_document import selection_lines, selection_value_document, value_document

__all__ = ["routed_lines", "value_command"]


@click.command("value", short_help="The value V_H of the game (untruncated unless --horizon H).")
@click.argument("instance", required=False, type=INSTANCE_FILE)
@selection_options
@map_options
@click.option("-H", "--horizon", type=HORIZON, default=None,
              help="Horizon H of the truncated game (an explicit request), or 'inf' for the "
                   "untruncated game (structured route; the default).")
@click.option("--json", "as_json", is_flag=True,
              help="Print the dpp-value/1 JSON document (docs/formats.md) instead of the text.")
@output_file_option("Write the dpp-value/1 JSON to this file (atomically); stdout stays "
                    "empty, the value is one line on stderr.")
@click.option("--route", type=click.Choice(ROUTES), default="auto", show_default=True,
              help="tree: the walk tree's LP; structured: the tree-free DP (docs/checker.md); "
                   "auto: the tree when it fits --max-prefixes, else structured; both: run "
                   "both, a disagreement is an error (exit 1).")
@max_prefixes_option()
@progress_option
def value_command(instance: str | None, grid: MapRequest | None, horizon: int | None,
                  as_json: bool, output: str | None, route: Route, max_prefixes: int,
                  goal_selection: bool, goal_values: str | None,
                  progress: bool | None) -> None:
    """Print the value of INSTANCE's game: untruncated (H = inf) unless --horizon H is given.

    Tree route: the compact LP (cvxpy + Clarabel) on the walk tree gives a float; rounding
    its primal and dual solutions to rationals gives exact bounds, which usually meet.
    Structured route: three hop-bounded Bellman-Ford fields (proofs/DP.md), exact on
    rational instances, polynomial in the graph; `--horizon inf` is the untruncated game.
    Instances with more than two goals: the tree LP with N types, and as structured route
    the guarantee sets: the coalition DP over goal subsets, the value for N <= 3 and, for
    N = 4, 5, where certified (else an exact bracket naming both bounds; proofs/NGOAL.md).

    \b
    Examples:
      dpp value examples:triangle
      dpp value examples:triangle --horizon 4
      dpp value examples:triangle -H 4 --json --route both
      dpp value examples:triangle -H 4 -o value.json
      dpp value --map m.map --start 2,0 --goals 0,3 0,0 --prior 0.6,0.4 -H 6
      dpp value examples:paper10-selection     # the goal-selection game: V_sel, q*

    Goal selection (a goal-selection INSTANCE, or --goal-selection with --map and no
    --prior): V_sel, the value when the Attacker chooses its goal, exactly or as a bracket
    naming both bounds, with the choice q* and the value at the uniform prior beside it
    (structured route; --json: a dpp-selection-value/1 document; proofs/SELECT.md).
    """
    show = want_progress(progress)
    bar = PhaseBar(show, "value", "reading the instance")
    try:
        refuse_input_as_output(output, [instance, grid.path if grid else None])
        game = load_game(instance, grid, "dpp value")
        if game.goal_selection:
            _selection_value(game, horizon, route, bar, as_json, output)
            return
        bar.phase(f"V_H (route {route})")
        r = routed_value(game, horizon, route=route, max_prefixes=max_prefixes,
                         progress=show, phase=bar.phase)
    except CheckerError as exc:
        bar.close()
        fail(exc)
    bar.close()
    lines = routed_lines(r)
    emit(value_document(r), "\n".join(lines), as_json=as_json, output=output,
         summary=lines[0] if lines else "")
    if r.disagreement is not None:
        click.echo(f"error: {r.disagreement}", err=True)
        raise click.exceptions.Exit(1)


def _selection_value(game: Instance, horizon: int | None, route: Route, bar: PhaseBar,
                     as_json: bool, output: str | None) -> None:
    """``dpp value`` on the goal-selection game (structured route only)."""
    if route == "tree" or route == "both":
        raise OptionError("the goal-selection value is computed by the structured route "
                          "(the guarantee sets); --route tree and both are for a game with a "
                          "prior (dpp export-efg writes the goal-selection tree for the peers)")
    bar.phase("V_sel (the guarantee sets)")
    v = selection_value(game, horizon, progress=bar.phase)
    bar.close()
    lines = selection_lines(v, horizon)
    emit(selection_value_document(v, horizon), "\n".join(lines), as_json=as_json,
         output=output, summary=lines[0])


def routed_lines(r: RoutedValue) -> list[str]:
    """The lines ``dpp value`` prints: one per route that ran.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> print(routed_lines(routed_value(triangle(), None))[0])  # doctest: +ELLIPSIS
    V_H (H = inf) = 12/5 (≈ 2.4) exactly; structured route (... DP steps, fixpoint reached, ...)
    """
    if r.goals > 2:
        return _per_goal_lines(r)
    tree = r.tree if isinstance(r.tree, GameValue) else None
    sv = r.structured if isinstance(r.structured, StructuredValue) else None
    return ([_tree_line(tree)] if tree is not None else []) + \
        ([_structured_line(sv)] if sv is not None else [])


def _show_horizon(h: int | None) -> str:
    return "inf" if h is None else str(h)


def _tree_line(v: GameValue) -> str:
    b = v.bracket
    exact = (f"{show_value(b.exact)} exactly" if b.closed and v.exact else
             f"in [{show_value(b.lower)}, {show_value(b.upper)}]"
             + (f" (open: {b.reason})" if b.reason else ""))
    return (f"V_H (H = {v.horizon}) = {exact}; LP value {show(v.lp.value)} "
            f"({LP_SOLVER}, agreement tolerance {LP_TOLERANCE:g} relative, "
            f"{count(v.prefixes, 'prefix')}, {decimal(v.lp.seconds)} s)")


def _structured_line(v: StructuredValue) -> str:
    how = "exactly" if v.exact else f"(float mode, {v.arithmetic})"
    fix = ", fixpoint reached" if v.fixpoint else ""
    return (f"V_H (H = {_show_horizon(v.horizon)}) = {show_value(v.value)} {how}; structured "
            f"route ({count(v.steps, 'DP step')}{fix}, {v.arithmetic}, {decimal(v.seconds)} s)")



def _per_goal_lines(r: RoutedValue) -> list[str]:
    """The lines ``dpp value`` prints for an N-goal instance.

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> print(_per_goal_lines(routed_value(star3(), None))[0])
    V_H (H = inf, N = 3 goals) = 3/2 (≈ 1.5) exactly; coalition DP (NG.4: the value for \
three goals) (7 label-setting passes)
    """
    assert isinstance(r.structured, NValue | None)  # N goals: the guarantee sets
    h = "inf" if r.horizon is None else str(r.horizon)
    lines = []
    if r.tree is not None:
        b = r.tree.bracket
        exact = (f"{show_value(b.exact)} exactly" if b.closed else
                 f"in [{show_value(b.lower)}, {show_value(b.upper)}] (open: {b.reason})")
        lines.append(f"V_H (H = {h}, N = {r.goals} goals) = {exact}; LP value "
                     f"{show(r.tree.value)} ({LP_SOLVER}, agreement tolerance {LP_TOLERANCE:g} "
                     f"relative, {count(r.tree.prefixes, 'prefix')}, "
                     f"{decimal(r.tree.lp.seconds)} s)")
    v = r.structured
    if v is not None:
        head = f"V_H (H = {h}, N = {r.goals} goals)"
        if v.value is not None:
            lines.append(f"{head} = {show_value(v.value)} exactly; {v.upper_source} "
                         f"({v.effort})")
        else:
            lines.append(f"{head} in [{show_value(v.lower)}, {show_value(v.upper)}]: lower "
                         f"bound from {v.lower_source}, upper bound from {v.upper_source}; "
                         f"not proved exact: {v.reason}")
    return lines
