"""The output file of ``dpp batch``: its columns, the rows already done (resuming), appending
rows durably, the lock that keeps two runs apart, and a one-line summary."""

from __future__ import annotations

import csv
import io
import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from dppio.text import count, decimal
from solver.errors import InvalidInstanceError
from solver.literature.path_metrics import METRIC_FIELDS

__all__ = ["FIELDS", "CsvAppender", "lock_output", "read_done", "summarize_file"]

FIELDS = ("line", "status", "map", "start", "goal", "fake_goal", "prior", "primary",
          "scen_optimal", "distance", "U1", "U2", "U", "U_bar", "VoI", "VoI_float",
          *METRIC_FIELDS, "verdict", "nash_conv", "route", "solve_seconds", "certify_seconds",
          "reason", "config")
"""The CSV columns. Cells are ``row,col``; values are exact ``p/q``; ``verdict`` is the
certificate's; times in seconds; ``reason`` is empty on ``ok`` rows. The published length,
our distance, the path metrics and ``nash_conv``: :mod:`solver.experiments.batch_columns`."""

def read_done(path: str | Path, key: str) -> set[int]:
    """The lines already in an output file (after dropping a torn last row), checked: every
    row's ``config`` column must be ``key`` (the configuration's hash, ``BatchConfig.key``).

    Raises
    ------
    InvalidInstanceError
        The file is not a batch CSV, repeats a line, or was written for another
        configuration.

    Examples
    --------
    >>> import tempfile
    >>> p = Path(tempfile.mkdtemp()) / "b.csv"
    >>> read_done(p, "0123456789ab")
    set()
    >>> _ = p.write_text(",".join(FIELDS) + "\\n3,ok" + "," * (len(FIELDS) - 2) + "0123456789ab"
    ...                  + "\\n2,o")
    >>> read_done(p, "0123456789ab"), p.read_text().endswith("\\n")
    ({3}, True)
    """
    p = Path(path)
    if not p.exists():
        return set()
    try:
        raw = p.read_bytes()
    except OSError as exc:
        raise InvalidInstanceError(f"{path}: cannot read ({exc.strerror or exc})") from None
    if raw and not raw.endswith(b"\n"):  # a torn last row: the run was killed mid-write
        cut = raw.rfind(b"\n") + 1
        with open(p, "r+b") as fh:
            fh.truncate(cut)
            fh.flush()
            os.fsync(fh.fileno())
        raw = raw[:cut]
    if not raw:
        return set()
    try:
        reader = csv.reader(io.StringIO(raw.decode("utf-8")))
        header = next(reader)
    except (UnicodeDecodeError, StopIteration, csv.Error):
        raise InvalidInstanceError(f"{path}: not a dpp batch CSV; give another --output")\
            from None
    if tuple(header) != FIELDS:
        raise InvalidInstanceError(f"{path}: not a dpp batch CSV (its header differs); give "
                                   "another --output")
    done: set[int] = set()
    for rec in reader:
        try:
            if len(rec) != len(FIELDS):
                raise ValueError
            line = int(rec[0])
        except ValueError:
            raise InvalidInstanceError(f"{path}: a malformed row ({','.join(rec)[:60]!r}); "
                                       "give another --output") from None
        if rec[-1] != key:
            raise InvalidInstanceError(
                f"{path}: written for another configuration (config {rec[-1]}, now "
                f"{key}: another .scen file, seed, prior or connectivity); give another "
                "--output or remove it")
        if line in done:
            raise InvalidInstanceError(f"{path}: line {line} appears twice")
        done.add(line)
    return done


class CsvAppender:
    """Appends rows to the output, each flushed and fsync-ed (the header first if new)."""

    def __init__(self, path: str | Path) -> None:
        p = Path(path)
        new = not p.exists() or p.stat().st_size == 0
        try:
            self.fh = open(p, "a", encoding="utf-8", newline="")  # noqa: SIM115
        except OSError as exc:
            raise InvalidInstanceError(f"{path}: cannot write ({exc.strerror or exc})") \
                from None
        if new:
            self._write(FIELDS)

    def _write(self, values: Sequence[str]) -> None:
        buf = io.StringIO()
        csv.writer(buf, lineterminator="\n").writerow(values)
        self.fh.write(buf.getvalue())
        self.fh.flush()
        os.fsync(self.fh.fileno())

    def row(self, row: dict[str, str]) -> None:
        self._write([row[k] for k in FIELDS])

    def close(self) -> None:
        self.fh.close()


def lock_output(path: str | Path) -> tuple[Any, bool]:
    """Open ``path`` (creating it) and take an exclusive advisory lock on it, so two runs
    never append to one file; returns the handle (closing it releases the lock) and whether
    the file was created.

    Examples
    --------
    >>> import tempfile
    >>> out = Path(tempfile.mkdtemp()) / "b.csv"
    >>> fh, created = lock_output(out)
    >>> created, lock_output(out)[1]  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    solver.errors.InvalidInstanceError: .../b.csv: another dpp batch is writing it
    >>> fh.close()
    """
    p = Path(path)
    created = not p.exists()
    try:
        fh = open(p, "ab")  # noqa: SIM115 - held for the whole run
    except OSError as exc:
        raise InvalidInstanceError(f"{path}: cannot write ({exc.strerror or exc})") from None
    if os.name == "posix":
        import fcntl

        try:
            fcntl.flock(fh.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            fh.close()
            raise InvalidInstanceError(f"{path}: another dpp batch is writing it") from None
    return fh, created


def summarize_file(path: str | Path) -> str:
    """One line about a batch CSV: rows, ok/error, verdicts, mean VoI and times.

    Examples
    --------
    >>> import tempfile
    >>> out = Path(tempfile.mkdtemp()) / "b.csv"
    >>> ok = dict.fromkeys(FIELDS, "") | {"status": "ok", "verdict": "pass", "VoI_float": "0.25",
    ...                                   "solve_seconds": "0.5", "certify_seconds": "1"}
    >>> bad = dict.fromkeys(FIELDS, "") | {"status": "error", "reason": "no fake goal"}
    >>> lines = [",".join(FIELDS)] + [",".join(r[k] for k in FIELDS) for r in (ok, ok, bad)]
    >>> _ = out.write_text(chr(10).join(lines) + chr(10))
    >>> summarize_file(out)
    '3 rows: 2 ok (verdict pass 2), 1 error; mean VoI 0.25; solve 1 s, certify 2 s in total'
    """
    with open(path, encoding="utf-8", newline="") as fh:
        rows = list(csv.DictReader(fh))
    ok = [r for r in rows if r["status"] == "ok"]
    verdicts: dict[str, int] = {}
    for r in ok:
        verdicts[r["verdict"]] = verdicts.get(r["verdict"], 0) + 1
    vs = ", ".join(f"verdict {k} {v}" for k, v in sorted(verdicts.items()))
    voi = sum(float(r["VoI_float"]) for r in ok) / len(ok) if ok else float("nan")
    solve_s = sum(float(r["solve_seconds"]) for r in ok)
    cert_s = sum(float(r["certify_seconds"]) for r in ok)
    errors = len(rows) - len(ok)
    return (f"{count(len(rows), 'row')}: {len(ok)} ok ({vs}), {count(errors, 'error')}; "
            f"mean VoI {decimal(voi)}; solve {decimal(solve_s)} s, certify {decimal(cert_s)} s in "
            "total")
