"""The ``dpp`` command line: solver commands here, checker commands from ``dppverify.cli``.

Every command reports bad input as one line on stderr (``error: ...``) and exits 2; an
unexpected internal failure prints one line and exits 3 (set ``DPP_DEBUG=1`` for the
traceback). ``dppverify`` never imports this module: the dependency points one way only.
"""

from __future__ import annotations

import sys
from typing import Any

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
from solver.equilibrium import solve
from solver.errors import DPPError, InvalidInstanceError
from solver.instance import Instance
from solver.instance_json import load_instance
from solver.io_utils import dumps, write_atomic
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


def _cell(text: str, what: str) -> tuple[int, int]:
    try:
        r, c = (int(x) for x in text.split(","))
    except ValueError:
        raise InvalidInstanceError(f"{what} must be 'ROW,COL', got {text!r}") from None
    return (r, c)


def _prior(text: str) -> tuple[str, str]:
    parts = [x.strip() for x in text.split(",")]
    if len(parts) != 2:
        raise InvalidInstanceError(f"--prior must be two numbers 'P,Q', got {text!r}")
    return (parts[0], parts[1])


@main.command("solve")
@click.argument("instance", required=False, type=click.Path(dir_okay=False))
@click.option("--map", "map_file", type=click.Path(dir_okay=False),
              help="A MovingAI .map grid instead of an instance JSON file.")
@click.option("--start", help="Start cell ROW,COL (with --map).")
@click.option("--goals", nargs=2, help="The two goal cells ROW,COL ROW,COL (with --map).")
@click.option("--prior", "prior_text", help="Priors of the two goals, e.g. 0.6,0.4 or 3/5,2/5.")
@click.option("--connectivity", type=click.Choice(["4", "8"]), default="4", show_default=True,
              help="Grid moves (with --map): 4-connected unit, or 8-connected octile.")
@click.option("--json", "as_json", is_flag=True, help="Print the dpp-profile/1 JSON.")
@output_file_option("Write the dpp-profile/1 JSON to this file (atomically).")
def solve_command(instance: str | None, map_file: str | None, start: str | None,
                  goals: tuple[str, str] | None, prior_text: str | None, connectivity: str,
                  as_json: bool, output: str | None) -> None:
    """Solve INSTANCE (a dpp instance JSON file) for the paper's PBNE.

    \b
    Examples:
      dpp solve examples/triangle.json
      dpp solve examples/triangle.json --json -o profile.json
      dpp solve --map examples/paper10.map --start 9,0 --goals 0,9 0,0 --prior 0.6,0.4
    """
    inst = _load(instance, map_file, start, goals, prior_text, int(connectivity))
    eq = solve(inst)
    doc = equilibrium_to_json(eq)
    if output:
        write_atomic(output, dumps(doc))
    if as_json:
        click.echo(dumps(doc), nl=False)
    elif not output:
        click.echo(summarize(eq))
    else:
        status(f"wrote {output}: U* = {doc['value']['U']}, VoI* = {doc['value']['VoI']}")


def _load(instance: str | None, map_file: str | None, start: str | None,
          goals: tuple[str, str] | None, prior_text: str | None, connectivity: int) -> Instance:
    if (instance is None) == (map_file is None):
        raise InvalidInstanceError("give exactly one of INSTANCE or --map FILE")
    if instance is not None:
        if start or goals or prior_text:
            raise InvalidInstanceError("--start/--goals/--prior go with --map, not INSTANCE")
        return load_instance(instance)
    if not (start and goals and prior_text):
        raise InvalidInstanceError("--map needs --start ROW,COL --goals R,C R,C --prior P,Q")
    blocked = read_map(str(map_file))
    return Instance.from_grid(blocked, _cell(start, "--start"),
                              (_cell(goals[0], "--goals"), _cell(goals[1], "--goals")),
                              _prior(prior_text), connectivity=connectivity)


# ---------------------------------------------------------------------- experiments
_MAP_OPTIONS = [
    click.argument("instance", required=False, type=click.Path(dir_okay=False)),
    click.option("--map", "map_file", type=click.Path(dir_okay=False),
                 help="A MovingAI .map grid (default: the bundled paper10.map)."),
    click.option("--start", help="Start cell ROW,COL (with --map)."),
    click.option("--goals", nargs=2, help="Goal cells ROW,COL ROW,COL (with --map)."),
    click.option("--prior", "prior_text", help="Priors of the two goals, e.g. 0.6,0.4."),
    click.option("--connectivity", type=click.Choice(["4", "8"]), default="4",
                 show_default=True, help="Grid moves (with --map)."),
]


def _map_options(fn: Any) -> Any:
    for option in reversed(_MAP_OPTIONS):
        fn = option(fn)
    return fn


def _experiment_instance(instance: str | None, map_file: str | None, start: str | None,
                         goals: tuple[str, str] | None, prior_text: str | None,
                         connectivity: str) -> Instance:
    if instance is None and map_file is None and not (start or goals or prior_text):
        from solver.experiments.compare import paper10_instance

        return paper10_instance()
    return _load(instance, map_file, start, goals, prior_text, int(connectivity))


@main.group("experiment")
def experiment_group() -> None:
    """The paper's Section VII experiments (baselines, comparison, density sweep)."""


@experiment_group.command("compare")
@_map_options
@output_dir_option("Also write compare.csv and compare.txt into this directory.")
@progress_option
def experiment_compare(instance: str | None, map_file: str | None, start: str | None,
                       goals: tuple[str, str] | None, prior_text: str | None,
                       connectivity: str, output_dir: str | None, progress: bool | None) -> None:
    """U1, U2, U, VoI of six (Defender, Attacker) pairs on one instance (exact).

    Without an instance: the bundled 10x10 map, start 9,0, goals 0,9 0,0, prior 0.6,0.4.

    \b
    Examples:
      dpp experiment compare
      dpp experiment compare --map examples/paper10.map --start 9,0 --goals 0,9 0,0 --prior 0.6,0.4
    """
    from pathlib import Path

    from tqdm import tqdm

    from solver.experiments.compare import compare_csv, compare_table, verdict
    from solver.pairs import PAIRS, PairEvaluator

    inst = _experiment_instance(instance, map_file, start, goals, prior_text, connectivity)
    game = PairEvaluator.of(inst)
    results = tuple(game.pair(d, a) for d, a in tqdm(
        PAIRS, desc="compare", unit="pair", file=sys.stderr, disable=not want_progress(progress),
        leave=False))
    text = compare_table(results) + "\n\n" + verdict(results) + "\n"
    click.echo(text, nl=False)
    if output_dir:
        d = Path(output_dir)
        d.mkdir(parents=True, exist_ok=True)
        write_atomic(d / "compare.csv", compare_csv(results))
        write_atomic(d / "compare.txt", text)
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
@click.option("--samples", default=200, show_default=True, help="Grids per density.")
@click.option("--densities", default="0,10,20,30,40", show_default=True,
              help="Obstacle densities in percent, comma-separated.")
@click.option("--seed", default=0, show_default=True, help="Seed: same seed, same grids.")
@click.option("--size", default=20, show_default=True, help="Grid side length.")
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
    from pathlib import Path

    from tqdm import tqdm

    from solver.experiments.density import DensityConfig, rows_to_csv, run_density
    from solver.experiments.summary import summarize_density

    if workers is not None and workers < 1:
        raise InvalidInstanceError(f"--workers must be at least 1, got {workers}")
    config = DensityConfig(size=size, densities=_int_list(densities, "--densities"),
                           samples=samples, seed=seed, start=(size - 1, 0),
                           goals=((0, size - 1), (0, 0)))
    with tqdm(total=samples * len(config.densities), unit="grid", file=sys.stderr,
              disable=not want_progress(progress), desc="density sweep") as bar:
        rows = run_density(config, workers=workers, dask_address=dask_address,
                           progress=bar.update)
    summary = summarize_density(rows)
    d = Path(output_dir)
    d.mkdir(parents=True, exist_ok=True)
    write_atomic(d / "density.csv", rows_to_csv(rows))
    write_atomic(d / "summary.txt", summary.text() + "\n")
    write_atomic(d / "summary.json", dumps({"config": {
        "size": size, "densities": list(config.densities), "samples": samples, "seed": seed,
        "start": list(config.start), "goals": [list(g) for g in config.goals],
        "prior": list(config.prior)}, **summary.to_json()}))
    click.echo(summary.text())
    status(f"wrote {d / 'density.csv'} ({len(rows)} rows), {d / 'summary.txt'}, "
           f"{d / 'summary.json'}")


# ---------------------------------------------------------------------- figures
_OUT_HELP = "Output file (.png or .svg), or a stem: writes STEM.png and STEM.svg."


@main.group("plot")
def plot_group() -> None:
    """Figures like the paper's Figs. 7-9 (PNG and SVG)."""


@plot_group.command("map")
@_map_options
@output_file_option(_OUT_HELP, required=True, deprecated="--out")
@click.option("--no-baselines", is_flag=True, help="Only the equilibrium panel.")
def plot_map_command(instance: str | None, map_file: str | None, start: str | None,
                     goals: tuple[str, str] | None, prior_text: str | None,
                     connectivity: str, output: str, no_baselines: bool) -> None:
    """Grid, obstacles, equilibrium paths by phase with mixing probabilities, baselines."""
    from solver.plots import plot_map, save_figure

    inst = _experiment_instance(instance, map_file, start, goals, prior_text, connectivity)
    files = save_figure(plot_map(inst, baselines=not no_baselines), output)
    status("wrote " + ", ".join(map(str, files)))


@plot_group.command("beliefs")
@_map_options
@output_file_option(_OUT_HELP, required=True, deprecated="--out")
@click.option("--defender", type=click.Choice(["sigma*", "sigma'"]), default="sigma*",
              show_default=True, help="Defender for the allocation panels.")
def plot_beliefs_command(instance: str | None, map_file: str | None, start: str | None,
                         goals: tuple[str, str] | None, prior_text: str | None,
                         connectivity: str, output: str, defender: str) -> None:
    """Belief b1_t and cumulative expected allocation to the true goal along each path."""
    from solver.plots import plot_beliefs, save_figure

    inst = _experiment_instance(instance, map_file, start, goals, prior_text, connectivity)
    files = save_figure(plot_beliefs(inst, defender=defender), output)
    status("wrote " + ", ".join(map(str, files)))


@plot_group.command("voi")
@click.argument("csv_file", type=click.Path(dir_okay=False))
@output_file_option(_OUT_HELP, required=True, deprecated="--out")
def plot_voi_command(csv_file: str, output: str) -> None:
    """VoI box plots by density and strategy pair from a density.csv."""
    from pathlib import Path

    from solver.experiments.density import rows_from_csv
    from solver.plots import plot_voi, save_figure

    try:
        text = Path(csv_file).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise InvalidInstanceError(f"{csv_file}: cannot read file ({exc})") from None
    files = save_figure(plot_voi(list(rows_from_csv(text))), output)
    status("wrote " + ", ".join(map(str, files)))


for _command in checker_cli.COMMANDS:
    main.add_command(_command)
