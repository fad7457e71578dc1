"""The obstacle-density sweep of the paper's Sec. VII-D (Fig. 9), reproducible and parallel.

For each density and sample: draw a grid (:mod:`solver.experiments.sampling`), build the
game (same start, goals and prior for every grid), evaluate the six (Defender, Attacker)
pairs of :data:`solver.literature.strategy_pairs.PAIRS` exactly and record VoI. The work is
cut into tasks of :attr:`DensityConfig.chunk` samples; a task's result depends only on its
inputs, so local processes, one process, or a Dask scheduler give identical rows.
"""

from __future__ import annotations

import contextlib
import csv
import io
import math
import os
from collections.abc import Callable, Iterable, Iterator
from dataclasses import asdict, dataclass
from fractions import Fraction
from typing import Any

from solver.errors import InvalidInstanceError
from solver.experiments.dask_tasks import dask_completed
from solver.experiments.sampling import Cell, sample_grid
from solver.game.instance import Instance
from solver.literature.strategy_pairs import PAIRS, PairEvaluator

__all__ = ["CSV_FIELDS", "DensityConfig", "Row", "Task", "rows_to_csv", "run_density",
           "run_task", "tasks_of"]


@dataclass(frozen=True)
class DensityConfig:
    """The sweep's parameters (defaults: the paper's 20×20, 0-40 %, 200 samples, b = 0.6/0.4).

    Start (19, 0) (bottom-left), g1 = (0, 19) (top-right, prior 3/5), g2 = (0, 0)
    (top-left, prior 2/5): the 10×10 comparison map's layout scaled up. The paper does not
    give its start and goal cells.
    """

    size: int = 20
    densities: tuple[int, ...] = (0, 10, 20, 30, 40)
    samples: int = 200
    seed: int = 0
    start: Cell = (19, 0)
    goals: tuple[Cell, Cell] = ((0, 19), (0, 0))
    prior: tuple[str, str] = ("3/5", "2/5")
    chunk: int = 25

    def __post_init__(self) -> None:
        if self.size < 2:
            raise InvalidInstanceError(f"grid size must be at least 2, got {self.size}")
        if self.samples < 1:
            raise InvalidInstanceError(f"--samples must be at least 1, got {self.samples}")
        if not self.densities:
            raise InvalidInstanceError("give at least one density")
        for cell in (self.start, *self.goals):
            if not all(0 <= x < self.size for x in cell):
                raise InvalidInstanceError(f"cell {cell} is outside the {self.size}x"
                                           f"{self.size} grid")
        if len({self.start, *self.goals}) != 3:
            raise InvalidInstanceError("start and the two goals must be three different cells")
        for d in self.densities:
            if not 0 <= d < 100:
                raise InvalidInstanceError(f"density must be a percentage in [0, 100), got {d}")
        p = [Fraction(x) for x in self.prior]
        if not (0 < p[0] < 1 and p[0] + p[1] == 1):
            raise InvalidInstanceError(f"prior must be two numbers in (0, 1) summing to 1, "
                                       f"got {self.prior}")


@dataclass(frozen=True)
class Task:
    """Samples ``first .. first + count - 1`` at one density."""

    config: DensityConfig
    density: int
    first: int
    count: int


@dataclass(frozen=True)
class Row:
    """One (sample, pair) result; exact values as ``p/q`` strings."""

    density: int
    sample: int
    attempts: int
    obstacles: int
    defender: str
    attacker: str
    U1: str
    U2: str
    U: str
    U_bar: str
    VoI: str
    VoI_float: float


CSV_FIELDS = tuple(Row.__dataclass_fields__)


def tasks_of(config: DensityConfig) -> list[Task]:
    """The sweep cut into tasks of ``config.chunk`` samples, in (density, sample) order.

    Parameters
    ----------
    config : DensityConfig
        The sweep.

    Returns
    -------
    list of Task

    Examples
    --------
    Three samples per density in chunks of two: two tasks per density.

    >>> cfg = DensityConfig(size=4, start=(3, 0), goals=((0, 3), (0, 0)), densities=(0, 25),
    ...                     samples=3, chunk=2)
    >>> [(t.density, t.first, t.count) for t in tasks_of(cfg)]
    [(0, 0, 2), (0, 2, 1), (25, 0, 2), (25, 2, 1)]
    """
    return [Task(config, d, first, min(config.chunk, config.samples - first))
            for d in config.densities for first in range(0, config.samples, config.chunk)]


def run_task(task: Task) -> list[Row]:
    """Evaluate every pair on every sample of a task (a pure function of ``task``).

    Parameters
    ----------
    task : Task
        One chunk of the sweep (:func:`tasks_of`).

    Returns
    -------
    list of Row
        One row per sample and pair of :data:`solver.literature.strategy_pairs.PAIRS`, in that
        order.

    Examples
    --------
    Sample 2 at density 0 is the empty 4×4 grid: the primary walks 6 steps, the secondary
    3, and ``U* = 18/5`` against ``Ū = 3/5 · 6 + 2/5 · 3 = 24/5``.

    >>> cfg = DensityConfig(size=4, start=(3, 0), goals=((0, 3), (0, 0)), densities=(0, 25),
    ...                     samples=3, chunk=2)
    >>> rows = run_task(tasks_of(cfg)[1])
    >>> len(rows), rows[0].sample, rows[0].obstacles, (rows[0].defender, rows[0].attacker)
    (6, 2, 0, ('sigma*', 'gamma*'))
    >>> rows[0].U, rows[0].U_bar, rows[0].VoI, rows == run_task(tasks_of(cfg)[1])
    ('18/5', '24/5', '1/4', True)
    """
    cfg = task.config
    rows = []
    for k in range(task.first, task.first + task.count):
        grid = sample_grid(cfg.size, task.density, k, cfg.seed, cfg.start, cfg.goals)
        game = PairEvaluator.of(Instance.from_grid(grid.blocked, cfg.start, cfg.goals, cfg.prior))
        for r in game.compare(PAIRS):
            rows.append(Row(task.density, k, grid.attempts, int(grid.blocked.sum()),
                            r.defender, r.attacker, str(r.U1), str(r.U2), str(r.U),
                            str(r.U_bar), str(r.VoI), float(r.VoI)))
    return rows


def run_density(config: DensityConfig, *, workers: int | None = None,
                dask_address: str | None = None,
                progress: Callable[[int], None] | None = None) -> list[Row]:
    """Run the sweep; rows sorted by (density, sample, pair order).

    Parameters
    ----------
    workers : int, optional
        Local processes (default: ``os.cpu_count()``); 1 runs in this process.
    dask_address : str, optional
        A ``dask.distributed`` scheduler address (``tcp://host:8786``, or a ``LocalCluster``'s
        ``scheduler_address``): the same tasks are sent there instead.
    progress : callable, optional
        Called with the number of samples each finished task covered (e.g. ``tqdm.update``).

    Examples
    --------
    >>> rows = run_density(DensityConfig(size=8, start=(7, 0), goals=((0, 7), (0, 0)),
    ...                                  densities=(0, 20), samples=2), workers=1)
    >>> len(rows), rows[0].defender, rows[0].attacker
    (24, 'sigma*', 'gamma*')
    """
    tasks = tasks_of(config)
    if dask_address is not None:
        results = _run_dask(tasks, dask_address, progress)
    else:
        n = workers if workers is not None else (os.cpu_count() or 1)
        if n < 1:
            raise InvalidInstanceError(f"--workers must be at least 1, got {n}")
        results = _run_local(tasks, n, progress)
    order = {pair: i for i, pair in enumerate(PAIRS)}
    rows = [row for chunk in results for row in chunk]
    rows.sort(key=lambda r: (config.densities.index(r.density), r.sample,
                             order[(r.defender, r.attacker)]))
    return rows


def _run_local(tasks: list[Task], workers: int,
               progress: Callable[[int], None] | None) -> list[list[Row]]:
    if workers == 1 or len(tasks) == 1:
        out = []
        for t in tasks:
            out.append(run_task(t))
            if progress:
                progress(t.count)
        return out
    from solver.experiments.local_pool import completed

    results = []
    # closed on the way out, whatever ends the loop: a signal raised here, between two
    # results, ends the pool at once (local_pool.completed), not when the generator is
    # collected after the exit message — when a worker still starting may find its
    # semaphores gone and print a traceback (SemLock._rebuild: FileNotFoundError)
    with contextlib.closing(completed(run_task, tasks, min(workers, len(tasks)))) as done:
        for task, rows in done:
            results.append(rows)
            if progress:
                progress(task.count)
    return results


def _run_dask(tasks: list[Task], address: str,
              progress: Callable[[int], None] | None) -> list[list[Row]]:
    results = []
    with contextlib.closing(dask_completed(run_task, tasks, address)) as done:
        for task, rows in done:
            results.append(rows)
            if progress:
                progress(task.count)
    return results


def rows_to_csv(rows: Iterable[Row]) -> str:
    """The rows as CSV text (header :data:`CSV_FIELDS`).

    Parameters
    ----------
    rows : iterable of Row
        E.g. :func:`run_density`'s.

    Returns
    -------
    str
        What :func:`rows_from_csv` reads back.

    Examples
    --------
    >>> cfg = DensityConfig(size=4, start=(3, 0), goals=((0, 3), (0, 0)), densities=(0, 25),
    ...                     samples=3, chunk=2)
    >>> text = rows_to_csv(run_task(tasks_of(cfg)[1])[:2])
    >>> print(text, end="")
    density,sample,attempts,obstacles,defender,attacker,U1,U2,U,U_bar,VoI,VoI_float
    0,2,1,0,sigma*,gamma*,6,0,18/5,24/5,1/4,0.25
    0,2,1,0,sigma',gamma*,6,0,18/5,24/5,1/4,0.25
    >>> [r["VoI_float"] for r in rows_from_csv(text)]
    [0.25, 0.25]
    """
    buf = io.StringIO()
    writer = csv.DictWriter(buf, fieldnames=CSV_FIELDS, lineterminator="\n")
    writer.writeheader()
    for r in rows:
        writer.writerow(asdict(r))
    return buf.getvalue()


def rows_from_csv(text: str) -> Iterator[dict[str, Any]]:
    """Read back what :func:`rows_to_csv` wrote (density as int, VoI_float as a finite
    float); anything else (a field too large for CSV, a number that is not one) is a one-line
    :class:`~solver.errors.InvalidInstanceError`.

    Examples
    --------
    >>> text = ",".join(CSV_FIELDS) + chr(10) + "0,2,1,0,sigma*,gamma*,6,0,18/5,24/5,1/4,1e999"
    >>> list(rows_from_csv(text))
    Traceback (most recent call last):
    solver.errors.InvalidInstanceError: CSV line 2: VoI_float '1e999' is not a finite number
    """
    reader = csv.DictReader(io.StringIO(text))
    try:
        for rec in reader:
            missing = set(CSV_FIELDS) - set(rec)
            if missing:
                raise InvalidInstanceError(f"CSV lacks column(s) {sorted(missing)}")
            yield _density_row(rec, reader.line_num)
    except csv.Error as exc:
        raise InvalidInstanceError(f"CSV line {reader.line_num}: {exc}") from None


def _density_row(rec: dict[str, Any], line: int) -> dict[str, Any]:
    out: dict[str, Any] = dict(rec)
    for key in ("density", "sample"):
        text = str(rec[key])
        if not (text.isdigit() and len(text) <= 10):
            raise InvalidInstanceError(f"CSV line {line}: {key} {text[:40]!r} is not a count")
        out[key] = int(text)
    text = str(rec["VoI_float"])
    try:
        voi = float(text) if len(text) <= 40 else math.nan
    except ValueError:
        voi = math.nan
    if not math.isfinite(voi):
        raise InvalidInstanceError(f"CSV line {line}: VoI_float {text[:40]!r} is not a finite "
                                   "number")
    out["VoI_float"] = voi
    return out
