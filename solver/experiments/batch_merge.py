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
>>> from solver.experiments.batch_csv import FIELDS, HEADER, format_rows
>>> d = Path(tempfile.mkdtemp())
>>> def shard(name, *lines):
...     rows = [dict.fromkeys(FIELDS, "") | {"line": str(n), "status": "error",
...             "reason": "no fake goal", "config": "abc"} for n in lines]
...     (d / name).write_bytes(HEADER + format_rows(rows))
...     return d / name
>>> merge_shards([shard("a.csv", 5, 2), shard("b.csv", 3)], d / "all.csv")
3
>>> [r.split(",")[0] for r in (d / "all.csv").read_text().splitlines()]
['line', '2', '3', '5']
"""

from __future__ import annotations

import csv
import io
from collections.abc import Sequence
from pathlib import Path

from dppio.files import read_input, write_files
from solver.errors import InvalidInstanceError, OutputError
from solver.experiments.batch_csv import FIELDS, read_rows

__all__ = ["merge_shards", "read_shard"]


def read_shard(path: str | Path) -> list[list[str]]:
    """The rows of one shard's CSV (without the header), checked.

    Raises
    ------
    InvalidInstanceError
        Not a batch CSV, a torn last row, a malformed row or a line twice (one line).

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
        raw = read_input(path)
    except (OSError, ValueError) as exc:
        raise InvalidInstanceError(f"{path}: cannot read ({getattr(exc, 'strerror', None) or exc})"
                                   ) from None
    if raw and not raw.endswith(b"\n"):
        raise InvalidInstanceError(f"{path}: its last row is torn (the run was interrupted): "
                                   "run that shard again to finish it")
    try:
        reader = csv.reader(io.StringIO(raw.decode("utf-8")))
        header = next(reader)
        rows = list(reader)
    except (UnicodeDecodeError, StopIteration, csv.Error):
        raise InvalidInstanceError(f"{path}: not a dpp batch CSV") from None
    if tuple(header) != FIELDS:
        raise InvalidInstanceError(f"{path}: not a dpp batch CSV of this version (its header "
                                   "differs)")
    for _ in read_rows([raw], where=str(path)):  # every field a batch writes, checked
        pass
    seen: set[int] = set()
    for rec in rows:
        try:
            if len(rec) != len(FIELDS):
                raise ValueError
            line = int(rec[0])
        except ValueError:
            raise InvalidInstanceError(f"{path}: a malformed row ({','.join(rec)[:60]!r})") \
                from None
        if line in seen:
            raise InvalidInstanceError(f"{path}: line {line} appears twice")
        seen.add(line)
    return rows


def merge_shards(shards: Sequence[str | Path], output: str | Path) -> int:
    """Join the shards' rows into ``output`` (header, rows sorted by line); returns the rows.

    Raises
    ------
    InvalidInstanceError
        No shard, a shard that is not a complete batch CSV, shards of different
        configurations, or a line in two shards.
    OutputError
        ``output`` cannot be written (nothing is left behind).

    Examples
    --------
    >>> merge_shards([], "all.csv")
    Traceback (most recent call last):
    solver.errors.InvalidInstanceError: dpp batch merge needs at least one shard CSV
    """
    if not shards:
        raise InvalidInstanceError("dpp batch merge needs at least one shard CSV")
    out = Path(output)
    for s in shards:
        if Path(s).resolve() == out.resolve():
            raise InvalidInstanceError(f"-o {output}: is one of the shards (an input); give "
                                       "another output")
    owner: dict[int, str] = {}
    config: tuple[str, str] | None = None
    rows: list[list[str]] = []
    for s in shards:
        for rec in read_shard(s):
            if config is None:
                config = (rec[-1], str(s))
            elif rec[-1] != config[0]:
                raise InvalidInstanceError(
                    f"{s}: written for another configuration (config {rec[-1]}; {config[1]} "
                    f"has {config[0]}): merge only the shards of one dpp batch command")
            line = int(rec[0])
            if line in owner:
                raise InvalidInstanceError(f"line {line} is in {owner[line]} and in {s}: the "
                                           "shards overlap")
            owner[line] = str(s)
            rows.append(rec)
    rows.sort(key=lambda r: int(r[0]))
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(FIELDS)
    w.writerows(rows)
    write_files({out: buf.getvalue()}, error=OutputError)
    return len(rows)
