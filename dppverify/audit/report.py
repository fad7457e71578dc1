"""The audit's result and its files: :class:`AuditReport`, the failure directory, the text.

The failure directory (``--out``) holds ``instance.json``, ``profile.json`` (when the solver
answered with a JSON object), ``certificate.json`` (when the answer could be certified) and
``failure.json`` (check id, the failure's identity — check id, or exception type and place —,
message, seed, and the solver's traceback when it raised). It is written through
:func:`dppverify.formats.files.write_files` — every write commits all files together or none — as
soon as the first failure is found, and rewritten in place whenever shrinking finds a
smaller failure.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import Any

from dppio.text import count
from dppverify.audit.examine import Outcome
from dppverify.formats.files import write_files

__all__ = ["FAILURE_FILES", "AuditReport", "format_report", "write_failure"]

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
            return (f"audit PASS: {count(self.examples, 'example')} certified{skipped} "
                    f"(seed {self.seed}, at most {count(self.max_nodes, 'node')})")
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

    Returns
    -------
    str
        The summary line; for a failure also the failing check, the failing instance (one
        line of JSON; "minimal" only when shrinking finished). ``dpp audit`` prints the files
        written on stderr.

    Examples
    --------
    >>> from hypothesis import strategies as st
    >>> from dppverify.audit import run_audit
    >>> from dppverify.game.examples import triangle_document
    >>> report = run_audit(lambda doc: 1 / 0, examples=5, shrink=False,
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
    docs["failure.json"] = {"check": outcome.check, "identity": outcome.identity,
                            "message": outcome.message, "seed": seed,
                            "traceback": outcome.traceback or None}
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
