"""``dpp plot``: figures like the paper's Figures 7 to 9 (PNG, SVG or PDF by suffix)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import click

from dppio.cli.conventions import (
    PhaseBar,
    output_file_option,
    progress_option,
    status,
    want_progress,
)
from dppio.cli.map_options import MapRequest, map_options, two_goal_map_options
from dppio.examples import INSTANCE_FILE
from dppio.files import refuse_input_as_output
from dppio.inputs import read_text
from solver.cli.common import checker_game, experiment_instance
from solver.errors import InvalidInstanceError, OutputError

if TYPE_CHECKING:
    from solver.game.instance import Instance



_OUT_HELP = "The figure file: .png, .svg or .pdf (the suffix picks the format)."


@click.group("plot", short_help="Figures like the paper's Figures 7 to 9.")
def plot_group() -> None:
    """Figures like the paper's Figures 7 to 9 (PNG, SVG or PDF; the suffix of -o picks)."""


@plot_group.command("map", short_help="The grid with the equilibrium walks and baselines.")
@click.argument("instance", required=False, type=INSTANCE_FILE)
@map_options
@output_file_option(_OUT_HELP, required=True, deprecated="--out")
@click.option("--no-baselines", is_flag=True, help="Only the equilibrium panel.")
@progress_option
def plot_map_command(instance: str | None, grid: MapRequest | None,
                     output: str, no_baselines: bool, progress: bool | None) -> None:
    """Grid, obstacles, equilibrium walks by phase with mixing probabilities, baselines.

    INSTANCE is a grid instance: a --map grid, or the instance JSON that
    `dpp solve --map ... --save-instance FILE` writes. Without either: the bundled 10x10 map.
    With N > 2 goals: each type's walks of the N-goal equilibrium (dpp solve's), coloured by
    type, and the Defender's sigma over the goals along each type's walk (no baselines).

    \b
    Examples:
      dpp plot map -o map.pdf
      dpp plot map --map examples:paper10 --start 9,0 --goals 0,9 0,0 --prior 0.6,0.4 -o m.png
      dpp plot map room.json -o room.pdf --no-baselines
      dpp plot map --map examples:paper10 --start 9,0 --goals 0,9 0,0 9,9 \\
                   --prior 1/2,1/3,1/6 -o paper10-n3.png
    """
    from solver.plots import plot_map, save_figure

    refuse_input_as_output(output, [instance, grid.path if grid is not None else None],
                           error=OutputError)
    bar = PhaseBar(want_progress(progress), "plot map", "reading the instance")
    try:
        inst = experiment_instance(instance, grid, "dpp plot map", two_goals=False)
        if inst.n_goals > 2:
            bar.close()
            _plot_ngoal_map(inst, checker_game(grid) if grid is not None else instance, output,
                            want_progress(progress))
            return
        from solver.plots.style import check_suffix  # matplotlib: not at start-up

        check_suffix(output)  # after the inputs' mistakes, before the work
        bar.phase("solving and drawing")
        files = save_figure(plot_map(inst, baselines=not no_baselines), output)
    finally:
        bar.close()
    status("wrote " + ", ".join(map(str, files)))


def _plot_ngoal_map(game: Instance, checked: Any, output: str, progress: bool) -> None:
    """The N-goal figure of what ``dpp solve`` writes: the construction, certified by the
    checker on the untruncated game (else one line, exit 3, nothing drawn), then drawn."""
    from dppverify.certify import certify as certify_profile
    from solver.coalitions.construction import coalition_equilibrium
    from solver.plots import plot_ngoal_map, save_figure
    from solver.plots.grid import grid_array
    from solver.plots.style import check_suffix

    grid_array(game)  # a grid game, or one line before any work
    check_suffix(output)
    bar = PhaseBar(progress, "plot map", f"solving ({game.n_goals} goals)")
    try:
        eq = coalition_equilibrium(game)
        bar.phase("certifying (structured route, H = inf)")
        cert = certify_profile(checked, eq.to_json(), horizon="inf",
                               route="structured")
        if cert.verdict != "pass":
            raise click.ClickException("")  # reported below, after the bar is gone
        bar.phase("drawing")
        files = save_figure(plot_ngoal_map(eq), output)
    except click.ClickException:
        bar.close()
        click.echo("error: the coalition construction does not give a certified equilibrium "
                   "on this instance; nothing drawn (dpp value gives the game's value, or an "
                   "exact bracket)", err=True)
        raise click.exceptions.Exit(3) from None
    finally:
        bar.close()
    status("wrote " + ", ".join(map(str, files)))


@plot_group.command("beliefs", short_help="Beliefs and expected allocation along the walks.")
@click.argument("instance", required=False, type=INSTANCE_FILE)
@two_goal_map_options
@output_file_option(_OUT_HELP, required=True, deprecated="--out")
@click.option("--defender", type=click.Choice(["sigma*", "sigma'"]), default="sigma*",
              show_default=True, help="Defender for the allocation panels.")
@progress_option
def plot_beliefs_command(instance: str | None, grid: MapRequest | None,
                         output: str, defender: str, progress: bool | None) -> None:
    """Belief b1_t and cumulative expected allocation to the true goal along each walk.

    \b
    Examples:
      dpp plot beliefs -o beliefs.pdf
      dpp plot beliefs --defender "sigma'" -o beliefs-alt.png
    """
    from solver.plots import plot_beliefs, save_figure

    refuse_input_as_output(output, [instance, grid.path if grid is not None else None],
                           error=OutputError)
    bar = PhaseBar(want_progress(progress), "plot beliefs", "reading the instance")
    try:
        inst = experiment_instance(instance, grid, "dpp plot beliefs")
        from solver.plots.style import check_suffix  # matplotlib: not at start-up

        check_suffix(output)  # after the inputs' mistakes, before the work
        bar.phase("solving and drawing")
        files = save_figure(plot_beliefs(inst, defender=defender), output)
    finally:
        bar.close()
    status("wrote " + ", ".join(map(str, files)))


@plot_group.command("voi", short_help="VoI box plots by obstacle density (from density.csv).")
@click.argument("csv_file", type=click.Path(dir_okay=False))
@output_file_option(_OUT_HELP, required=True, deprecated="--out")
@progress_option
def plot_voi_command(csv_file: str, output: str, progress: bool | None) -> None:
    """VoI box plots by density and strategy pair from CSV_FILE, a density.csv.

    `dpp experiment density --output-dir DIR` writes DIR/density.csv.

    \b
    Examples:
      dpp experiment density --samples 20 --output-dir out/small
      dpp plot voi out/small/density.csv -o voi.pdf
    """
    from dppio.cli.hints import file_hint
    from solver.experiments.density import rows_from_csv
    from solver.plots import plot_voi, save_figure

    refuse_input_as_output(output, [csv_file], error=OutputError)
    try:
        text = read_text(csv_file)
    except (OSError, ValueError) as exc:
        raise InvalidInstanceError(f"{csv_file}: cannot read file ({exc})") from None
    try:
        rows = list(rows_from_csv(text))
    except InvalidInstanceError as exc:
        hint = file_hint(csv_file, "density CSV", "dpp plot voi")
        raise InvalidInstanceError(hint or f"{csv_file}: {exc}; make a density CSV with dpp "
                                   "experiment density --output-dir DIR (it writes "
                                   "DIR/density.csv)") from None
    if not rows:
        raise InvalidInstanceError(f"{csv_file}: no rows; make a density CSV with dpp "
                                   "experiment density --output-dir DIR")
    bar = PhaseBar(want_progress(progress), "plot voi", "drawing")
    try:
        files = save_figure(plot_voi(rows), output)
    finally:
        bar.close()
    status("wrote " + ", ".join(map(str, files)))
