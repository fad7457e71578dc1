"""Where ``dpp batch`` writes: its output CSV is never anything but a batch CSV of the run's
configuration, and no other file is ever changed.

The rule (``docs/limits.md``, "Output files"):

- **resume** only ever appends to a file that is *provably* a batch CSV of the same
  configuration: its first line is the batch header byte for byte and every row is a
  well-formed batch row (:func:`solver.experiments.batch_csv.parse_row`) whose ``config``
  column is the run's configuration hash and whose line is a line of the ``.scen`` file, no
  line twice. A torn last row (a kill mid-write) is the only thing ever removed.
- **everything else is refused before a byte is written**: a file of other content (a JSON
  file, the ``.scen`` file, a ``.map``), a batch CSV of another configuration, a folder, a
  device, a FIFO, a socket (never opened, so never a hang or an endless read), an input of
  the run by any path or link, a name the file system cannot hold.
- a **new** file appears only with its header and first row (written to a temporary file
  next to it and linked into place), so a run that fails before its first row leaves nothing
  behind; a missing folder on the way is created then. A symlink is followed and kept: the
  file it points to is the output (a dangling link: that file is created at the first row).
- rows are **appended durably** (written, then ``fsync``-ed); a write that fails (a full
  disk, a file size limit) is rolled back to the last whole row and reported in one line,
  the rows before it kept for the next run.
- an exclusive advisory lock (``flock``, :func:`dppio.locks.try_lock`) on the file keeps
  two runs apart, and a run from a ``dpp batch merge`` that reads the file as a shard or
  writes it (the merge takes the same locks): each refuses the other in one line.
"""

from __future__ import annotations

import contextlib
import os
import stat
import tempfile
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path

from dppio.files import file_mode, make_parents, remove_created, short_path
from dppio.locks import BUSY, try_lock
from solver.errors import InvalidInstanceError, OutputError
from solver.experiments.batch_csv import HEADER, BatchTally, format_rows, parse_row, read_rows

NAME_MAX = 255
"""Longest file name (bytes) on the file systems the batch writes to (Linux: 255)."""

PATH_MAX = 4096
"""Longest path (bytes, Linux)."""


class BatchOutput:
    """The open output CSV of one batch run: the lines it already holds, the tally of its
    rows, durable appends, the lock. Open it with :meth:`open`; :meth:`close` it (or use it as
    a context manager).

    Examples
    --------
    >>> import tempfile
    >>> from tests.solver.experiments.doctest_inputs import example_row
    >>> d = Path(tempfile.mkdtemp())
    >>> row = example_row(2, reason="x")
    >>> with BatchOutput.open(d / "b.csv", "0123456789ab", lines={2, 3}) as out:
    ...     print(out.done, (d / "b.csv").exists())
    ...     out.append([row])
    set() False
    >>> with BatchOutput.open(d / "b.csv", "0123456789ab", lines={2, 3}) as out:
    ...     print(out.done, out.tally.summary()[:35])
    {2} 1 row: 0 ok, 1 error (first: line 2
    >>> _ = (d / "notes.json").write_text('{"my": "notes"}')
    >>> BatchOutput.open(d / "notes.json", "0123456789ab", lines={2})  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    solver.errors.OutputError: -o .../notes.json is not a dpp batch CSV: its first line is not \
the batch header; dpp batch only appends to a batch CSV of the same configuration (give a new \
file)
    >>> (d / "notes.json").read_text()
    '{"my": "notes"}'
    """

    def __init__(self, shown: str, target: Path, fd: int | None, done: set[int],
                 tally: BatchTally) -> None:
        self.shown = shown
        """The path as the user gave it (for messages)."""
        self.target = target
        """The file written (a symlink resolved)."""
        self.done = done
        """The scenario lines the file held when opened."""
        self.tally = tally
        """Every row of the file: those it held and those appended."""
        self.written = 0
        """Rows appended by this run."""
        self._fd = fd
        self._created: list[Path] = []

    @property
    def exists(self) -> bool:
        """True once the file exists (it held rows, or this run wrote one)."""
        return self._fd is not None

    @classmethod
    def open(cls, output: str | Path, key: str, *, lines: Iterable[int],
             inputs: Iterable[str | Path] = ()) -> BatchOutput:
        """Check ``output`` and open it for appending rows of configuration ``key``.

        Parameters
        ----------
        output : path
            The ``-o`` path.
        key : str
            The configuration hash (``BatchConfig.key``), every existing row's ``config``.
        lines : iterable of int
            The scenario lines of the ``.scen`` file: an existing row names one of them.
        inputs : iterable of paths
            The run's input files (the ``.scen`` file, the maps): never the output.

        Raises
        ------
        OutputError
            One line, before any byte is written: the rule of this module.
        """
        shown = short_path(output)
        if shown == "":
            raise OutputError("-o: the output path is empty")
        if str(output) == "-":
            raise OutputError("-o - (standard output): dpp batch appends its rows to a CSV it "
                              "reads back to resume; give a file (a file named - is ./-)")
        if str(output).endswith(("/", os.sep)):  # Path() would drop the slash
            raise OutputError(f"-o {shown} names a folder (a trailing /); give a file name")
        st_link = _stat_or_none(os.lstat, output, shown)
        target = Path(output)
        if st_link is not None and stat.S_ISLNK(st_link.st_mode):
            target = Path(os.path.realpath(output))  # follow the link, keep it
        st = _stat_or_none(os.stat, target, shown)
        if st is None:
            _check_new(shown, target)
            return cls(shown, target, None, set(), BatchTally())
        if stat.S_ISDIR(st.st_mode):
            raise OutputError(f"-o {shown} is a folder; give a file path")
        if not stat.S_ISREG(st.st_mode):
            raise OutputError(f"-o {shown} is not a regular file ({_kind(st.st_mode)}); dpp "
                              "batch appends rows to a CSV file it can read back to resume "
                              "(give a file path)")
        for path in inputs:
            if _same_file(st, path):
                raise OutputError(f"-o {shown} is an input of this command ({path}); "
                                  "refusing to write to it (give another path)")
        try:
            fd = os.open(target, os.O_RDWR | os.O_NONBLOCK | os.O_NOCTTY | os.O_CLOEXEC)
        except OSError as exc:
            raise _cannot(shown, exc) from None
        try:
            return cls._existing(shown, target, fd, st, key, set(lines))
        except BaseException:
            os.close(fd)
            raise

    @classmethod
    def _existing(cls, shown: str, target: Path, fd: int, st: os.stat_result, key: str,
                  lines: set[int]) -> BatchOutput:
        now = os.fstat(fd)
        if (now.st_dev, now.st_ino) != (st.st_dev, st.st_ino) or not stat.S_ISREG(now.st_mode):
            raise OutputError(f"-o {shown} changed while it was being opened; run again")
        _lock(fd, shown)
        done: set[int] = set()
        tally = BatchTally()
        end = 0
        try:
            for offset, row in read_rows(_read_chunks(fd), key, where=f"-o {shown}"):
                end = offset
                if row.line in done:
                    raise InvalidInstanceError(f"-o {shown} is not a dpp batch CSV of this "
                                               f"run: line {row.line} appears twice")
                if row.line not in lines:
                    raise InvalidInstanceError(f"-o {shown} is not a dpp batch CSV of this "
                                               f"run: it has a row for line {row.line}, which "
                                               "the .scen file does not have")
                done.add(row.line)
                tally.add(row)
        except InvalidInstanceError as exc:
            raise OutputError(f"{exc}; dpp batch only appends to a batch CSV of the same "
                              "configuration (give a new file)") from None
        except OSError as exc:
            raise _cannot(shown, exc) from None
        size = os.fstat(fd).st_size
        if size == 0:  # an empty file: nothing to lose; the header comes with the first row
            return cls(shown, target, fd, done, tally)
        end = max(end, len(HEADER))
        if end < size:  # a torn last row (read_rows checked it looks like one): drop it
            try:
                os.ftruncate(fd, end)
                os.fsync(fd)
            except OSError as exc:
                raise _cannot(shown, exc) from None
        return cls(shown, target, fd, done, tally)

    def append(self, rows: list[dict[str, str]]) -> None:
        """Append ``rows`` durably (the header first in a new or empty file).

        Raises
        ------
        OutputError
            The write failed (e.g. a full disk); the file is rolled back to its last whole
            row, so the next run continues from there.
        """
        if not rows:
            return
        data = format_rows(rows)
        infos = [parse_row(line) for line in data.splitlines()]  # readable back, or nothing
        if self._fd is None:
            self._create(HEADER + data)
        else:
            pos = os.lseek(self._fd, 0, os.SEEK_END)
            complete = False
            try:
                _write_all(self._fd, (HEADER if pos == 0 else b"") + data)
                os.fsync(self._fd)
                complete = True
            except BaseException as exc:  # a full disk, a signal: back to the last whole row
                if not complete:
                    with contextlib.suppress(OSError):
                        os.ftruncate(self._fd, pos)
                if isinstance(exc, OSError):
                    raise OutputError(f"cannot write {self.shown}: {exc.strerror or exc}; "
                                      f"{self._kept()}") from None
                raise
        self.written += len(rows)
        for info in infos:
            self.tally.add(info)

    def rows_in_file(self) -> int:
        """The rows the file holds now, counted from the file itself (when a signal ended
        the run between a write and its count); 0 when there is no file."""
        if self._fd is None:
            return 0
        try:
            with open(self.target, "rb") as fh:
                return sum(1 for _ in read_rows(iter(lambda: fh.read(1 << 20), b"")))
        except (OSError, InvalidInstanceError):
            return self.tally.rows

    def _kept(self) -> str:
        rows = self.tally.rows
        if rows == 0:
            return "nothing was written"
        held = "1 row finished before is" if rows == 1 else f"{rows} rows finished before are"
        return f"{held} in it: run the same command again to continue"

    def _create(self, data: bytes) -> None:
        """The new file, with its header and first rows: written next to it, then linked into
        place (it never exists half-written)."""
        folder = self.target.parent
        tmp = None
        fd = None
        try:
            make_parents(folder, self._created)
            fd, tmp = tempfile.mkstemp(dir=folder, prefix=".dpp-batch.", suffix=".tmp")
            _write_all(fd, data)
            os.fchmod(fd, file_mode())
            os.fsync(fd)
            _lock(fd, self.shown)
            try:
                os.link(tmp, self.target)
            except FileExistsError:
                raise OutputError(f"-o {self.shown} appeared while the batch ran (another "
                                  "program made it); the rows are not written") from None
            self._fd = fd  # linked: the file exists now, whatever happens next
            os.unlink(tmp)
            tmp = None
            with contextlib.suppress(OSError):
                dfd = os.open(folder, os.O_RDONLY)
                try:
                    os.fsync(dfd)
                finally:
                    os.close(dfd)
        except BaseException as exc:  # an error, a signal: nothing stays unless it was linked
            if tmp is not None:
                Path(tmp).unlink(missing_ok=True)
            if self._fd is not None:  # linked: the file stands (a failed folder fsync too)
                if isinstance(exc, Exception):
                    return
                raise
            if fd is not None:
                os.close(fd)
            remove_created(self._created)
            if isinstance(exc, OSError) and not isinstance(exc, OutputError):
                raise OutputError(f"cannot write {self.shown}: {exc.strerror or exc}; nothing "
                                  "was written") from None
            raise

    def close(self) -> None:
        """Release the file (and its lock); folders made for a file never written go."""
        if self._fd is None:
            remove_created(self._created)
        elif self._fd >= 0:
            with contextlib.suppress(OSError):
                os.close(self._fd)
            self._fd = -1  # closed; the file exists

    def __enter__(self) -> BatchOutput:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def _stat_or_none(how: Callable[[str | Path], os.stat_result], path: str | Path, shown: str
                  ) -> os.stat_result | None:
    """``how(path)`` (``os.stat`` or ``os.lstat``), None when nothing is there; any other
    failure is the one-line :func:`_cannot`."""
    try:
        return how(path)
    except FileNotFoundError:
        return None
    except OSError as exc:
        raise _cannot(shown, exc) from None


def _cannot(shown: str, exc: OSError) -> OutputError:
    return OutputError(f"cannot write {shown}: {exc.strerror or exc}")


def _same_file(st: os.stat_result, path: str | Path) -> bool:
    try:
        other = os.stat(path)
    except (OSError, ValueError):
        return False
    return (other.st_dev, other.st_ino) == (st.st_dev, st.st_ino)


def _kind(mode: int) -> str:
    if stat.S_ISFIFO(mode):
        return "a FIFO"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "not a file"


def _check_new(shown: str, target: Path) -> None:
    """Refuse at once a new output the file system could not hold (a name too long, a path
    through a file, a folder that cannot be written), instead of after the first row."""
    absolute = Path(os.path.abspath(target))
    if len(os.fsencode(str(absolute))) >= PATH_MAX:
        raise OutputError(f"cannot write {shown}: the path is longer than {PATH_MAX} bytes")
    folder = absolute.parent
    missing = [absolute.name]
    while True:
        try:
            st = os.stat(folder)
            break
        except FileNotFoundError:
            missing.append(folder.name)
            folder = folder.parent
        except OSError as exc:
            raise _cannot(shown, exc) from None
    for name in missing:
        if len(os.fsencode(name)) > NAME_MAX:
            raise OutputError(f"cannot write {shown}: a file name longer than {NAME_MAX} "
                              "bytes")
    if not stat.S_ISDIR(st.st_mode):
        raise OutputError(f"cannot write {shown}: {folder} is not a folder")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise OutputError(f"cannot write {shown}: {folder} is not writable")


def _lock(fd: int, shown: str) -> None:
    """The run's exclusive lock on its CSV (:func:`dppio.locks.try_lock`, the discipline
    ``dpp batch merge`` follows too): refused while another batch writes the file or a merge
    reads it as a shard or writes it."""
    if not try_lock(fd):
        raise OutputError(f"-o {shown}: {BUSY}")


def _read_chunks(fd: int, size: int = 1 << 20) -> Iterator[bytes]:
    pos = 0
    while chunk := os.pread(fd, size, pos):
        pos += len(chunk)
        yield chunk


def _write_all(fd: int, data: bytes) -> None:
    view = memoryview(data)
    while view:
        n = os.write(fd, view)
        view = view[n:]
