"""``dpp batch merge``: join the CSVs of a batch's shards into the single run's rows.

The shards of one configuration (``dpp batch SCEN --shard i/n``, same ``.scen`` file, seed,
prior, connectivity and route: the same ``config`` column) hold disjoint lines. The merge
checks that every input is a complete batch CSV of that one configuration (the header, every
row whole — a shard killed while writing must be run again to finish —, no line twice) and
writes the header and every row **sorted by line**: row for row what one ``dpp batch`` run of
the same lines writes, sorted by line, except the two times (``solve_seconds``,
``certify_seconds``), which measure the run that made the row.

Examples
--------
>>> import tempfile
>>> from pathlib import Path
>>> from solver.experiments.batch_csv import HEADER, format_rows
>>> from tests.solver.experiments.doctest_inputs import example_row
>>> d = Path(tempfile.mkdtemp())
>>> def shard(name, *lines):
...     (d / name).write_bytes(HEADER + format_rows([example_row(n) for n in lines]))
...     return d / name
>>> merge_shards([shard("a.csv", 5, 2), shard("b.csv", 3)], d / "all.csv").rows
3
>>> [r.split(",")[0] for r in (d / "all.csv").read_text().splitlines()]
['line', '2', '3', '5']
"""

from __future__ import annotations

import contextlib
import csv
import io
import os
import stat
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from dppio.files import refuse_input_as_output, write_files
from dppio.inputs import is_stdin, open_input, read_input
from dppio.limits import MAX_INPUT_BYTES
from dppio.locks import OutputLocks, try_lock
from dppio.text import escaped
from solver.errors import InvalidInstanceError, OutputError
from solver.experiments.batch_csv import FIELDS, HEADER, BatchTally, read_rows


def _shard_bytes(path: str | Path, locks: contextlib.ExitStack) -> bytes:
    """The bytes of one shard, read under its shared lock (kept in ``locks``): a shard that a
    running ``dpp batch`` holds is refused, and no batch can start on it while the merge runs.

    Raises
    ------
    InvalidInstanceError
        The shard cannot be read, is larger than the limit, or a batch is writing it.
    """
    if is_stdin(path):
        return read_input(path)
    fh = locks.enter_context(open_input(path))
    if stat.S_ISREG(os.fstat(fh.fileno()).st_mode) and not try_lock(fh.fileno(), shared=True):
        raise InvalidInstanceError(f"{path}: a dpp batch is still writing this shard; merge "
                                   "it once that run has finished")
    data = fh.read(MAX_INPUT_BYTES + 1)
    if len(data) > MAX_INPUT_BYTES:
        raise ValueError(f"larger than the limit of {MAX_INPUT_BYTES} bytes")
    return data


def read_shard(path: str | Path, locks: contextlib.ExitStack | None = None
               ) -> tuple[list[list[str]], BatchTally]:
    """The rows of one shard's CSV (without the header), every field checked as a resumed
    batch checks its CSV's rows, and their tally. With ``locks``, the shard is read under its
    shared lock, kept there (:func:`dppio.locks.try_lock`): a shard a running batch is still
    writing is refused.

    Raises
    ------
    InvalidInstanceError
        Not a batch CSV, a torn last row, a malformed row, a line twice, or a shard a batch
        is writing (one line).

    Examples
    --------
    >>> import tempfile
    >>> p = Path(tempfile.mkdtemp()) / "s.csv"
    >>> _ = p.write_text(",".join(FIELDS) + "\\n2,ok")
    >>> read_shard(p)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    solver.errors.InvalidInstanceError: ...s.csv: its last row is torn (the run was \
interrupted): run that shard again to finish it
    """
    try:
        with contextlib.ExitStack() as own:
            raw = _shard_bytes(path, own if locks is None else locks)
    except InvalidInstanceError:
        raise
    except (OSError, ValueError) as exc:
        raise InvalidInstanceError(f"{path}: cannot read ({getattr(exc, 'strerror', None) or exc})"
                                   ) from None
    if not raw:  # (a batch that wrote no row leaves no file at all)
        raise InvalidInstanceError(f"{path}: empty: not a dpp batch CSV")
    if not raw.endswith(b"\n"):
        raise InvalidInstanceError(f"{path}: its last row is torn (the run was interrupted): "
                                   "run that shard again to finish it")
    first = raw.split(b"\n", 1)[0]
    if first.startswith(b"line,") and first + b"\n" != HEADER:
        raise InvalidInstanceError(f"{path}: not a dpp batch CSV of this version (its header "
                                   "differs)")
    tally = BatchTally()
    seen: set[int] = set()
    for _, row in read_rows([raw], where=str(path)):  # every field a batch writes, checked
        if row.line in seen:
            raise InvalidInstanceError(f"{path}: line {row.line} appears twice")
        seen.add(row.line)
        tally.add(row)
    try:  # (every row checked above is one line without control characters)
        rows = list(csv.reader(io.StringIO(raw.decode("utf-8"))))[1:]
    except (UnicodeDecodeError, csv.Error):  # pragma: no cover - read_rows refused it
        raise InvalidInstanceError(f"{path}: not a dpp batch CSV") from None
    if len(rows) != tally.rows:
        raise InvalidInstanceError(f"{path}: not a dpp batch CSV (a row spans lines)")
    return rows, tally


@dataclass(frozen=True)
class MergeResult:
    """What :func:`merge_shards` wrote: the rows, and the tally of every row merged (the
    summary line and the exit code come from the rows, never from reading the output back,
    which may be a device or standard output)."""

    rows: int
    tally: BatchTally


def merge_shards(shards: Sequence[str | Path], output: str | Path) -> MergeResult:
    """Join the shards' rows into ``output`` (header, rows sorted by line): the output rule of
    every command (``dppio.files``), under the lock discipline of ``dpp batch``
    (:func:`dppio.locks.try_lock`): the output's lock is taken, and a shard or an output that
    a running batch holds is refused.

    Raises
    ------
    InvalidInstanceError
        No shard, a shard that is not a complete batch CSV (or that a batch is still
        writing), shards of different configurations, or a line in two shards.
    OutputError
        ``output`` is one of the shards (by any path or link), a batch is writing it, or it
        cannot be written (nothing is left behind).

    Examples
    --------
    >>> merge_shards([], "all.csv")
    Traceback (most recent call last):
    solver.errors.InvalidInstanceError: dpp batch merge needs at least one shard CSV
    """
    if not shards:
        raise InvalidInstanceError("dpp batch merge needs at least one shard CSV")
    refuse_input_as_output(output, shards, error=OutputError)  # hard links too
    owner: dict[int, str] = {}
    config: tuple[str, str] | None = None
    rows: list[list[str]] = []
    tally = BatchTally()
    # the output's lock first (a batch on it refuses, a batch already on it is refused), then
    # every shard's shared lock, all held until the merged file is in place
    with OutputLocks([output], error=OutputError) as held, contextlib.ExitStack() as locks:
        for s in shards:
            shard_rows, shard_tally = read_shard(s, locks)
            tally.merge(shard_tally)
            for rec in shard_rows:
                if config is None:
                    config = (rec[-1], str(s))
                elif rec[-1] != config[0]:
                    raise InvalidInstanceError(
                        f"{s}: written for another configuration (config "
                        f"{escaped(rec[-1], 40)}; {config[1]} has {escaped(config[0], 40)}): "
                        "merge only the shards of one dpp batch command")
                line = int(rec[0])
                if line in owner:
                    raise InvalidInstanceError(f"line {line} is in {owner[line]} and in {s}: "
                                               "the shards overlap")
                owner[line] = str(s)
                rows.append(rec)
        rows.sort(key=lambda r: int(r[0]))
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(FIELDS)
        w.writerows(rows)
        write_files({output: buf.getvalue()}, error=OutputError, lock=held)
    return MergeResult(len(rows), tally)
