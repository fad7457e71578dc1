"""The output file of ``dpp batch`` as a format: its columns, how a row is written and read
back (every field checked, so that a hand-edited file is refused in one line), the tally of
its rows, the one-line summary and the exit code.

What may be appended to, and how, is :mod:`solver.experiments.batch_output`.
"""

from __future__ import annotations

import csv
import io
import math
import re
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from pathlib import Path

from dppio.inputs import open_input
from dppio.text import count, decimal, escaped
from solver.errors import InvalidInstanceError
from solver.literature.path_metrics import METRIC_FIELDS

FIELDS = ("line", "status", "map", "start", "goal", "fake_goal", "prior", "primary",
          "scen_optimal", "distance", "U1", "U2", "U", "U_bar", "VoI", "VoI_float",
          *METRIC_FIELDS, "verdict", "nash_conv", "route", "solve_seconds", "certify_seconds",
          "reason", "config")
"""The CSV columns. Cells are ``row,col``; values are exact ``p/q``; ``verdict`` is the
certificate's; times in seconds; ``reason`` is empty on ``ok`` rows. The published length,
our distance, the path metrics and ``nash_conv``: :mod:`solver.experiments.batch_columns`."""

HEADER = (",".join(FIELDS) + "\n").encode()
"""The first line of every batch CSV, byte for byte."""

MAX_ROW_BYTES = 1 << 20
"""Longest row a batch writes (a map name is at most 4096 characters, a reason at most
:data:`MAX_REASON_CHARS`): a longer line was not written by ``dpp batch``."""

MAX_REASON_CHARS = 2000
"""A row's ``reason`` is cut to this many characters."""

VERDICTS = ("pass", "fail", "error", "incomplete")
"""The certificate verdicts an ``ok`` row may carry."""

_LINE = re.compile(r"[1-9][0-9]{0,9}")
_FLOAT = re.compile(r"[-+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]{1,3})?|nan|inf")
_CONTROL = re.compile(r"[\x00-\x1f\x7f\x85\u2028\u2029]")
_VALUE = re.compile(r"-?[0-9]{1,400}(?:/[1-9][0-9]{0,400})?"  # exact p/q, or a float's repr
                    r"|-?(?:[0-9]{1,400}\.[0-9]{0,400}|\.[0-9]{1,400})(?:e[-+]?[0-9]{1,3})?"
                    r"|-?[0-9]\.?[0-9]{0,20}e[-+]?[0-9]{1,3}", re.ASCII)
_CELL = re.compile(r"[0-9]{1,10},[0-9]{1,10}", re.ASCII)
_PRIOR = re.compile(r"[0-9./]{1,1000},[0-9./]{1,1000}", re.ASCII)
_LENGTH = re.compile(r"(?:[0-9]{1,30}(?:\.[0-9]{0,30})?|\.[0-9]{1,30})", re.ASCII)
_CONFIG = re.compile(r"[0-9a-f]{12}", re.ASCII)
_ROUTE = re.compile(r"[a-z][a-z-]{0,30}", re.ASCII)
_VALUES = ("distance", "U1", "U2", "U", "U_bar", "VoI", *METRIC_FIELDS)
"""The number columns of an ``ok`` row: exact ``p/q`` (exact mode) or a float (float mode)."""
_CELLS = ("start", "goal", "fake_goal", "primary")


@dataclass(frozen=True)
class RowInfo:
    """What the tally needs of one row (read back and checked by :func:`parse_row`)."""

    line: int
    status: str
    verdict: str = ""
    voi: float = 0.0
    solve_seconds: float = 0.0
    certify_seconds: float = 0.0
    reason: str = ""


def format_rows(rows: Iterable[dict[str, str]]) -> bytes:
    """The CSV lines of ``rows`` (UTF-8): one physical line per row, whatever the fields hold
    (line breaks and control characters become spaces, the reason is cut to
    :data:`MAX_REASON_CHARS`).

    Examples
    --------
    >>> from tests.solver.experiments.doctest_inputs import example_row
    >>> row = example_row(2, reason="two\\nlines")
    >>> format_rows([row]).endswith(b",two lines,0123456789ab\\n"), format_rows([row]).count(b"\\n")
    (True, 1)
    """
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    for row in rows:
        values = [_CONTROL.sub(" ", str(row.get(k, ""))) for k in FIELDS]
        values[FIELDS.index("reason")] = values[FIELDS.index("reason")][:MAX_REASON_CHARS]
        writer.writerow(values)
    return buf.getvalue().encode("utf-8", "backslashreplace")


def _number(text: str, column: str) -> float:
    if len(text) > 40 or not _FLOAT.fullmatch(text):
        raise ValueError(f"{column} {text[:40]!r} is not a number")
    x = float(text)
    if not math.isfinite(x):
        raise ValueError(f"{column} {text!r} is not a finite number")
    return x


def parse_row(raw: bytes, key: str | None = None) -> RowInfo:
    """Read back one row (a line without its newline), checking every field a batch writes;
    ``key``, when given, must be its ``config`` column.

    Raises
    ------
    ValueError
        Why the line is not a batch row (one short clause).

    Examples
    --------
    >>> from tests.solver.experiments.doctest_inputs import example_row
    >>> line = format_rows([example_row(7, "ok")]).rstrip(b"\\n")
    >>> parse_row(line, "0123456789ab").voi
    0.25
    >>> parse_row(line.replace(b"0.25", b"1e999999"))
    Traceback (most recent call last):
    ValueError: VoI_float '1e999999' is not a number
    >>> parse_row(format_rows([example_row(7, "ok", VoI="abc")]).rstrip(b"\\n"))
    Traceback (most recent call last):
    ValueError: VoI 'abc' is not a number
    """
    if len(raw) > MAX_ROW_BYTES:
        raise ValueError(f"a line of more than {MAX_ROW_BYTES} bytes")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ValueError(f"not CSV text ({exc})") from None
    if _CONTROL.search(text):  # format_rows writes none (a carriage return, an escape)
        raise ValueError("a control character in a cell (a batch writes none)")
    try:
        recs = list(csv.reader([text]))
    except csv.Error as exc:
        raise ValueError(f"not CSV text ({exc})") from None
    rec = recs[0] if len(recs) == 1 else []
    if len(rec) != len(FIELDS):
        raise ValueError(f"{len(rec)} fields, expected {len(FIELDS)}")
    row = dict(zip(FIELDS, rec, strict=True))
    if not _LINE.fullmatch(row["line"]):
        raise ValueError(f"line {row['line'][:40]!r} is not a line number")
    if key is not None and row["config"] != key:
        raise ValueError(f"written for another configuration (config {row['config'][:40]!r}, "
                         f"now {key}: another .scen file, seed, prior, connectivity or route, "
                         "or an earlier dpp whose columns meant something else)")
    _check(row, "config", _CONFIG, "is not a configuration hash (12 hex digits)")
    if row["status"] not in ("ok", "error"):
        raise ValueError(f"status {row['status'][:40]!r} is neither ok nor error")
    ok = row["status"] == "ok"
    for column in _CELLS:  # an error row has the cells it got to
        _check(row, column, _CELL, "is not a cell row,col", required=ok)
    _check(row, "prior", _PRIOR, "is not a prior P,Q", required=ok)
    _check(row, "scen_optimal", _LENGTH, "is not a finite non-negative decimal length",
           required=False)
    if not ok:
        if not row["reason"]:
            raise ValueError("an error row without its reason")
        return RowInfo(int(row["line"]), "error", reason=row["reason"])
    if row["reason"]:
        raise ValueError("an ok row with a reason")
    for column in _VALUES:
        _check(row, column, _VALUE, "is not a number")
    _check(row, "nash_conv", _VALUE, "is not a number", required=False)
    _check(row, "route", _ROUTE, "is not a route")
    if row["verdict"] not in VERDICTS:
        raise ValueError(f"verdict {row['verdict'][:40]!r} is not one of {', '.join(VERDICTS)}")
    return RowInfo(int(row["line"]), "ok", row["verdict"], _number(row["VoI_float"], "VoI_float"),
                   _number(row["solve_seconds"], "solve_seconds"),
                   _number(row["certify_seconds"], "certify_seconds"))


def _check(row: dict[str, str], column: str, pattern: re.Pattern[str], what: str, *,
           required: bool = True) -> None:
    """Refuse ``row[column]`` unless it matches ``pattern`` (or is empty, when not
    ``required``): a ``ValueError`` naming the column and the value, escaped and cut."""
    text = row[column]
    if (text or required) and not pattern.fullmatch(text):
        shown = repr(text[:40]) + ("…" if len(text) > 40 else "")
        raise ValueError(f"{column} {shown} {what}")


def read_rows(chunks: Iterable[bytes], key: str | None = None, *, where: str = "the file"
              ) -> Iterator[tuple[int, RowInfo]]:
    """``(end offset, row)`` for every complete row of a batch CSV given as byte chunks,
    after checking its header; a torn last row (no newline: the run was killed mid-write)
    is not yielded. Memory stays within one row.

    Raises
    ------
    InvalidInstanceError
        One line: the file is not a batch CSV (of configuration ``key``, when given).

    Examples
    --------
    >>> from tests.solver.experiments.doctest_inputs import example_row
    >>> ok = format_rows([example_row(3)])
    >>> rows = list(read_rows([HEADER + ok + b"4,o"]))  # (end offset, row); 4 is torn
    >>> [(end == len(HEADER + ok), r.line) for end, r in rows]
    [(True, 3)]
    >>> list(read_rows([b'{"my": "notes"}']))
    Traceback (most recent call last):
    solver.errors.InvalidInstanceError: the file is not a dpp batch CSV: its first line is not \
the batch header
    """
    pending = b""
    offset = 0
    header_done = False
    number = 0
    for chunk in chunks:
        pending += chunk
        while True:
            cut = pending.find(b"\n")
            if cut < 0:
                break
            line, pending = pending[:cut], pending[cut + 1:]
            offset += cut + 1
            number += 1
            if not header_done:
                if line + b"\n" != HEADER:
                    raise _not_batch(where, "its first line is not the batch header")
                header_done = True
                continue
            try:
                yield offset, parse_row(line, key)
            except ValueError as exc:
                raise _not_batch(where, f"file line {number}: {exc}") from None
        if len(pending) > max(MAX_ROW_BYTES, len(HEADER)):
            raise _not_batch(where, f"a line of more than {MAX_ROW_BYTES} bytes")
    if not header_done and (number or pending):
        raise _not_batch(where, "its first line is not the batch header")
    if header_done and pending and not re.fullmatch(rb"[0-9]{1,10}(,[^\n]*)?", pending):
        raise _not_batch(where, "its last line is neither a row nor the start of one")


def _not_batch(where: str, why: str) -> InvalidInstanceError:
    return InvalidInstanceError(f"{where} is not a dpp batch CSV: {why}")


@dataclass
class BatchTally:
    """The rows of a batch CSV counted as they are read or written: the summary line
    (:meth:`summary`) and the exit code (:meth:`exit_code`) come from here.

    Examples
    --------
    >>> t = BatchTally()
    >>> t.add(RowInfo(2, "ok", "pass", 0.25, 0.5, 1.0)); t.add(RowInfo(3, "error", reason="x"))
    >>> t.summary()
    '2 rows: 1 ok (verdict pass 1), 1 error (first: line 3: x); mean VoI 0.25; solve 0.5 s, \
certify 1 s in total'
    >>> t.exit_code()
    2
    """

    rows: int = 0
    ok: int = 0
    verdicts: dict[str, int] = field(default_factory=dict)
    errors: int = 0
    internal: int = 0
    first_error: tuple[int, str] | None = None
    voi: float = 0.0
    solve_seconds: float = 0.0
    certify_seconds: float = 0.0

    def add(self, row: RowInfo) -> None:
        """Count one row."""
        self.rows += 1
        if row.status == "ok":
            self.ok += 1
            self.verdicts[row.verdict] = self.verdicts.get(row.verdict, 0) + 1
            self.voi += row.voi
            self.solve_seconds += row.solve_seconds
            self.certify_seconds += row.certify_seconds
            return
        self.errors += 1
        self.internal += row.reason.startswith("internal error")
        if self.first_error is None or row.line < self.first_error[0]:
            self.first_error = (row.line, row.reason)

    def merge(self, other: BatchTally) -> None:
        """Count the rows of ``other`` too (another shard's rows).

        Examples
        --------
        >>> a, b = BatchTally(), BatchTally()
        >>> a.add(RowInfo(3, "error", reason="x")); b.add(RowInfo(2, "error", reason="y"))
        >>> a.merge(b); a.rows, a.first_error
        (2, (2, 'y'))
        """
        self.rows += other.rows
        self.ok += other.ok
        for k, v in other.verdicts.items():
            self.verdicts[k] = self.verdicts.get(k, 0) + v
        self.errors += other.errors
        self.internal += other.internal
        if other.first_error is not None and (self.first_error is None
                                              or other.first_error[0] < self.first_error[0]):
            self.first_error = other.first_error
        self.voi += other.voi
        self.solve_seconds += other.solve_seconds
        self.certify_seconds += other.certify_seconds

    def summary(self) -> str:
        """One line: rows, ok (by verdict), errors (the first by line), mean VoI, times."""
        vs = ", ".join(f"verdict {k} {v}" for k, v in sorted(self.verdicts.items()))
        ok = f"{self.ok} ok" + (f" ({vs})" if vs else "")
        err = count(self.errors, "error")
        if self.first_error is not None:
            line, reason = self.first_error  # from a file: escaped and bounded
            err += f" (first: line {line}: {escaped(reason, 100)})"
        voi = f"mean VoI {decimal(self.voi / self.ok)}" if self.ok else "no VoI (no ok row)"
        return (f"{count(self.rows, 'row')}: {ok}, {err}; {voi}; solve "
                f"{decimal(self.solve_seconds)} s, certify {decimal(self.certify_seconds)} s in "
                "total")

    def exit_code(self) -> int:
        """``dpp batch``'s exit code, from every row of the file: 1 if a certificate refuted
        a profile (verdict ``fail``); else 3 if one could not decide (verdict ``error`` or
        ``incomplete``) or a line met an internal error; else 2 if a line could not be made
        a game (a row with status ``error``: malformed, unknown map, no fake goal, ...);
        else 0 (every line solved and certified: verdict ``pass``)."""
        if self.verdicts.get("fail"):
            return 1
        if self.verdicts.get("error") or self.verdicts.get("incomplete") or self.internal:
            return 3
        return 2 if self.errors else 0


def _chunks(path: str | Path, size: int = 1 << 20) -> Iterator[bytes]:
    with open_input(path) as fh:
        while chunk := fh.read(size):
            yield chunk


def _checked(path: str | Path, key: str | None) -> Iterator[RowInfo]:
    seen: set[int] = set()
    try:
        for _, row in read_rows(_chunks(path), key, where=str(path)):
            if row.line in seen:
                raise InvalidInstanceError(f"{path} is not a dpp batch CSV: line {row.line} "
                                           "appears twice")
            seen.add(row.line)
            yield row
    except OSError as exc:
        raise InvalidInstanceError(f"{path}: cannot read ({exc.strerror or exc})") from None
