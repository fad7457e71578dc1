"""The audit's result and its files: :class:`AuditReport`, the failure directory, the text.

The failure directory (``--out``) holds ``instance.json``, ``profile.json`` (when the solver
answered with a JSON object), ``certificate.json`` (when the answer could be certified) and
``failure.json`` (check id, the failure's identity — check id, or exception type and place —,
message, seed, the exit code ``dpp certify`` gives on the folder's instance and profile
(:func:`certify_exit`), the solver's traceback when it raised, and the certificate's
exploitability: every player's exact regret and NashConv, :mod:`dppverify.exploitability`). It
is written through
:func:`dppverify.formats.files.write_files` — every write commits all files together or none — as
soon as the first failure is found, and rewritten in place whenever shrinking finds a
smaller failure.
"""

from __future__ import annotations

import json
import os
import stat
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import Any

from dppio.files import short_path
from dppio.text import count
from dppverify.audit.examine import Outcome
from dppverify.formats.files import OutputError, write_files

FAILURE_FILES = ("instance.json", "profile.json", "certificate.json", "failure.json")
"""The files of a failure directory, in the order they are listed."""


@dataclass(frozen=True)
class AuditReport:
    """The result of :func:`~dppverify.audit.run_audit`.

    Attributes
    ----------
    passed : bool
        True when every example was certified.
    examples : int
        Examples solved and certified: all of them on success, else up to and including
        the first failing one (skipped examples not counted).
    skipped : int
        Examples skipped because the walk tree exceeded ``max_prefixes``.
    shrink_calls : int
        Solver calls spent shrinking the failure.
    failure : Outcome or None
        The smallest failing example found (None on success).
    first_failure : Outcome or None
        The failing example as first found, before shrinking.
    files : tuple of Path
        Files written for the failure.
    seed, max_nodes : int
        The campaign's settings.
    shrunk : bool
        Whether shrinking was asked for (``shrink=True``).
    budget_exhausted : bool
        Whether shrinking stopped because its budget was spent.
    """

    passed: bool
    examples: int
    skipped: int
    shrink_calls: int
    failure: Outcome | None
    first_failure: Outcome | None
    files: tuple[Path, ...] = field(default=())
    seed: int = 0
    max_nodes: int = 8
    shrunk: bool = True
    budget_exhausted: bool = False
    source: str = ""
    """Where the instances came from (``--instances DIR``, ``--scen FILE``); empty for the
    random campaign."""
    note: str = ""
    """Why a passing campaign certified fewer examples than its budget (empty otherwise)."""
    unwritten: str = ""
    """Why the failure's files could not be written to the output folder (empty when they
    were, or when no failure was found): the command then ends with this one line, exit 2,
    like every command whose output cannot be written."""

    def summary(self) -> str:
        """One line: the verdict and the examples used.

        Examples
        --------
        >>> AuditReport(True, 5, 0, 0, None, None).summary()
        'audit PASS: 5 examples certified (seed 0, at most 8 nodes)'
        """
        skipped = f", {self.skipped} skipped (tree too large)" if self.skipped else ""
        if self.source:
            return self._source_summary(skipped)
        if self.passed:
            note = f"; {self.note}" if self.note else ""
            return (f"audit PASS: {count(self.examples, 'example')} certified{skipped} "
                    f"(seed {self.seed}, at most {count(self.max_nodes, 'node')}{note})")
        how = self._how("shrinking", "shrunk")
        return (f"audit FAIL after {count(self.examples, 'example')}{skipped} (seed {self.seed}; "
                f"{how}): {self._message()}")

    def _source_summary(self, skipped: str) -> str:
        """The summary of an audit on the user's own instances (``source`` set)."""
        if self.passed:
            return (f"audit PASS: {count(self.examples, 'instance')} of {self.source} "
                    f"certified{skipped}")
        how = self._how("pruning", "pruned")
        return (f"audit FAIL after {count(self.examples, 'instance')} of {self.source}{skipped} "
                f"({how}): {self._message()}")

    def _message(self) -> str:
        """The failure's one line (``?`` if none is recorded)."""
        return self.failure.message if self.failure is not None else "?"

    def _how(self, doing: str, done: str) -> str:
        """How the failing example was reduced: ``doing``/``done`` name the reduction (the
        random campaign shrinks, an audit of the user's instances prunes)."""
        if not self.shrunk:
            return "no shrinking"
        if self.budget_exhausted:
            return f"{doing} stopped at its budget after {count(self.shrink_calls, 'solver call')}"
        return f"{done} with {count(self.shrink_calls, 'more solver call')}"


def format_report(report: AuditReport) -> str:
    """What ``dpp audit`` prints for a report.

    Parameters
    ----------
    report : AuditReport
        The result of :func:`~dppverify.audit.run_audit` or of an audit of given instances.

    Returns
    -------
    str
        The summary line; for a failure also the failing check, the failing instance (one
        line of JSON; "minimal" only when shrinking finished). ``dpp audit`` prints the files
        written on stderr.

    Examples
    --------
    >>> from hypothesis import strategies as st
    >>> from dppverify.audit import AuditConfig, run_audit
    >>> from dppverify.game.examples import triangle_document
    >>> report = run_audit(lambda doc: 1 / 0, AuditConfig(examples=5, shrink=False),
    ...                    strategy=st.just(triangle_document()))
    >>> print(format_report(report))  # doctest: +ELLIPSIS
    audit FAIL after 1 example (seed 0; no shrinking): the solver raised ZeroDivisionError: ...
    failing check: solver.error
    raised: ZeroDivisionError@...
    failing instance: {"graph": {"nodes": [{"id": "s"}, ...], "prior": ["7/10", "3/10"]}
    """
    lines = [report.summary()]
    fail = report.failure
    if fail is not None:
        lines.append(f"failing check: {fail.check}")
        cert = fail.certificate
        if cert is not None and cert.exploitability is not None:
            lines.append(f"exploitability on {cert.game_line()}: "
                         f"{cert.exploitability.summary()}")
        if fail.where:
            lines.append(f"raised: {fail.where}")
        if not report.shrunk:
            what = "failing instance"
        elif report.budget_exhausted:
            what = "smallest failing instance found"
        else:
            what = "minimal failing instance"
        lines.append(f"{what}: " + json.dumps(fail.instance))
    return "\n".join(lines)


def _number_default(x: Any) -> Any:
    if isinstance(x, Fraction):
        return f"{x.numerator}/{x.denominator}"
    raise TypeError(f"{type(x).__name__} is not JSON serializable")


def check_output_folder(out: str | Path) -> None:
    """Refuse, before any example is run, a failure folder that could not be written: a path
    through a file, a file in its place, a folder without write permission, a name the system
    refuses (too long). Nothing is created (the folder is made only when a failure is found).

    Raises
    ------
    OutputError
        One line naming the folder and why.

    Examples
    --------
    >>> import tempfile
    >>> d = Path(tempfile.mkdtemp())
    >>> _ = (d / "f").write_text("")
    >>> check_output_folder(d / "new" / "deeper")
    >>> check_output_folder(d / "f" / "sub")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.formats.files.OutputError: --output-dir .../f/sub: cannot be created: .../f is not \
a folder
    """
    folder = Path(out)
    if str(out) == "":
        raise OutputError("--output-dir: the path is empty")
    probe = folder
    while True:
        try:
            st = probe.stat()
        except (FileNotFoundError, NotADirectoryError):
            if probe.is_symlink():  # a link to nothing: mkdir would find it in the way
                raise OutputError(f"--output-dir {short_path(out)}: cannot be created: "
                                  f"{short_path(probe)} is a symbolic link to a missing "
                                  f"folder") from None
            if probe.parent == probe:
                break
            probe = probe.parent
            continue
        except OSError as exc:  # too long, a loop of links, not a folder on the way, ...
            raise OutputError(f"--output-dir {out}: cannot be created: "
                              f"{exc.strerror or exc}") from None
        if not stat.S_ISDIR(st.st_mode):
            raise OutputError(f"--output-dir {out}: cannot be created: {probe} is not a folder")
        if not os.access(probe, os.W_OK | os.X_OK):
            raise OutputError(f"--output-dir {out}: cannot be written: no write permission "
                              f"in {probe}")
        if probe == folder:  # the folder exists: its failure files must be writable files
            for name in FAILURE_FILES:
                if (folder / name).is_dir():
                    raise OutputError(f"--output-dir {short_path(out)}: cannot be written: "
                                      f"{name} in it is a folder")
        return
    raise OutputError(f"--output-dir {out}: cannot be created")


def certify_exit(outcome: Outcome) -> int | None:
    """The exit code of ``dpp certify instance.json profile.json`` on a failure's files (the
    one verdict of docs/formats.md: the CLI, ``dppverify.certify`` and the audit agree): 1 when
    the certificate refutes the profile, 3 when it could not decide (``certify.undecided``,
    an ``error`` or ``incomplete`` verdict), 2 when the profile is not a profile document of the
    instance's format (``profile.format``); None when the solver gave no profile.

    Examples
    --------
    >>> from dppverify.audit import examine
    >>> from dppverify.game.examples import triangle_document
    >>> doc = triangle_document()
    >>> [certify_exit(examine(f, doc)) for f in (lambda d: 1 / 0,
    ...                                          lambda d: {"format": "dpp-profile/2"},
    ...                                          lambda d: {"format": "dpp-profile/1"})]
    [None, 2, 1]
    """
    if outcome.profile is None:
        return None
    if outcome.check == "profile.format":
        return 2
    if outcome.certificate is None:
        return 3  # certify.undecided
    return {"pass": 0, "fail": 1}.get(outcome.certificate.verdict, 3)


def write_failure(outcome: Outcome, out: str | Path, *, seed: int = 0) -> tuple[Path, ...]:
    """Write a failing example's files into the directory ``out`` (all or none).

    Files of an earlier failure that the new one lacks (e.g. ``profile.json``) are removed.

    Parameters
    ----------
    outcome : Outcome
        The failing example (e.g. :attr:`AuditReport.failure`).
    out : str or Path
        The directory (created if missing).
    seed : int
        The campaign's seed, recorded in ``failure.json``.

    Returns
    -------
    tuple of Path
        The files written.

    Examples
    --------
    >>> import tempfile
    >>> from dppverify.audit import examine
    >>> from dppverify.game.examples import triangle_document
    >>> outcome = examine(lambda doc: 1 / 0, triangle_document())
    >>> with tempfile.TemporaryDirectory() as d:
    ...     files = write_failure(outcome, Path(d) / "fail", seed=7)
    ...     names = [f.name for f in files]
    ...     failure = json.loads(files[-1].read_text())
    >>> names
    ['instance.json', 'failure.json']
    >>> failure["check"], failure["seed"]
    ('solver.error', 7)
    """
    folder = Path(out)
    docs: dict[str, Any] = {"instance.json": outcome.instance}
    if outcome.profile is not None:
        docs["profile.json"] = outcome.profile
    if outcome.certificate is not None:
        docs["certificate.json"] = outcome.certificate.to_json()
    cert = outcome.certificate
    docs["failure.json"] = {"check": outcome.check, "identity": outcome.identity,
                            "message": outcome.message, "seed": seed,
                            "certify_exit": certify_exit(outcome),
                            "traceback": outcome.traceback or None,
                            "exploitability": None if cert is None or cert.exploitability is None
                            else cert.exploitability.to_json()}
    texts = {folder / name: json.dumps(doc, indent=2, default=_number_default) + "\n"
             for name, doc in docs.items()}
    # a file of an earlier, larger failure is removed only if this process wrote it: files
    # the user already had in the folder are never deleted
    stale = [folder / name for name in FAILURE_FILES
             if name not in docs and (folder / name).resolve() in _WRITTEN]
    written = write_files(texts, remove=stale)
    _WRITTEN.update(p.resolve() for p in written)
    return written


_WRITTEN: set[Path] = set()
"""Files :func:`write_failure` wrote in this process (the only ones it ever removes)."""


def save_failure(outcome: Outcome, out: str | Path, *, seed: int = 0,
                 unwritten: list[str] | None = None) -> tuple[Path, ...]:
    """:func:`write_failure`, but a folder that cannot be written (the audit checks it up
    front, :func:`check_output_folder`, so this is something like a full disk) is appended
    to ``unwritten`` in one line and the audit goes on to its end, which reports it
    (:attr:`AuditReport.unwritten`: exit 2); returns the files written (none then).

    Examples
    --------
    >>> import tempfile
    >>> from dppverify.audit import examine
    >>> from dppverify.game.examples import triangle_document
    >>> d = Path(tempfile.mkdtemp())
    >>> _ = (d / "f").write_text("")
    >>> why: list[str] = []
    >>> save_failure(examine(lambda doc: 1 / 0, triangle_document()), d / "f", unwritten=why)
    ()
    >>> why  # doctest: +ELLIPSIS
    ['cannot write the failing example (solver.error) to .../f: .../f is not a folder']
    """
    try:
        return write_failure(outcome, out, seed=seed)
    except OutputError as exc:
        if unwritten is not None:
            why = " ".join(str(exc).split()).split(": ", 1)[-1]
            unwritten.append(f"cannot write the failing example ({outcome.check}) to "
                             f"{short_path(out)}: {why}")
        return ()
