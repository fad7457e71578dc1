"""How an audit runs: one frozen record, :class:`AuditConfig`, and every default and bound of
``dpp audit`` (its options' defaults and the bounds it keeps to).

The command line builds the record once from its options; every level below it (the campaign,
the examination of one instance, the pruning pass) takes the record, not its fields.

Examples
--------
>>> AUDIT_MAX_PREFIXES, AUDIT_TRIALS, DEFAULT_TIMEOUT, DEFAULT_SHRINK_CALLS
(200000, 2, 60.0, 500)
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path

from dppverify.errors import AuditError
from dppverify.limits import MAX_AUDIT_EXAMPLES

AUDIT_MAX_PREFIXES = 200_000
"""Default size guard of the walk tree per example; larger examples are skipped."""

AUDIT_TRIALS = 2
"""Random attackers per L3/L4 lemma check (the lemmas concern the instance, not the solver)."""

DEFAULT_TIMEOUT = 60.0
"""Seconds per solver run (Python callable or command)."""

READY_TIMEOUT = 60.0
"""Seconds a Python solver's module may take to import."""

DEFAULT_SHRINK_CALLS = 500
"""Default budget of solver calls spent shrinking a failure."""

DEFAULT_SHRINK_SECONDS = 120.0
"""Default budget of seconds spent shrinking a failure."""

HYPOTHESIS_SHARE = 0.5
"""Share of the shrinking budget hypothesis may use; the pruning pass gets the rest."""

MAX_AUDIT_INSTANCES = 100_000
"""Instances accepted from one folder or ``.scen`` file."""

SKIP_FACTOR = 10
"""A campaign of ``N`` examples stops after ``max(SKIP_FLOOR, SKIP_FACTOR * N)`` skipped ones
(walk trees larger than ``max_prefixes``), so that it always ends."""

SKIP_FLOOR = 100
"""See :data:`SKIP_FACTOR`."""


@dataclass(frozen=True)
class AuditConfig:
    """How an audit runs, checked once when the record is made.

    Attributes
    ----------
    examples : int
        The random campaign's example budget: its first ``examples`` distinct games
        (:func:`~dppverify.audit.run_audit`; an audit of given instances audits them all).
    seed : int
        Seed of the generation (same seed, same campaign) and of the certificates' random
        attackers.
    max_nodes : int
        Largest instance of the random campaign, in nodes.
    max_prefixes : int
        Examples whose walk tree is larger are skipped (``dppverify.certify``'s guard).
    trials : int
        Random attackers per L3/L4 lemma check.
    timeout : float
        Seconds per solver run, for a solver given as a callable (a runner has its own).
    shrink : bool
        Shrink the first failure.
    shrink_calls, shrink_seconds : int, float
        The shrinking budget: at most this many solver calls and seconds.
    out : str or Path, optional
        Directory for the failing instance, profile and certificate (None: nothing written).
    progress : bool
        A progress bar on stderr.

    Raises
    ------
    AuditError
        ``examples`` outside 1 .. :data:`~dppverify.limits.MAX_AUDIT_EXAMPLES`, a negative
        ``seed`` or shrinking budget, ``max_nodes`` below 2.

    Examples
    --------
    >>> AuditConfig(seed=3).budget().describe()
    '500 solver calls or 120 s'
    >>> AuditConfig(examples=0)
    Traceback (most recent call last):
    dppverify.errors.AuditError: examples=0 must be an integer between 1 and 1000000
    """

    examples: int = 100
    seed: int = 0
    max_nodes: int = 8
    max_prefixes: int = AUDIT_MAX_PREFIXES
    trials: int = AUDIT_TRIALS
    timeout: float = DEFAULT_TIMEOUT
    shrink: bool = True
    shrink_calls: int = DEFAULT_SHRINK_CALLS
    shrink_seconds: float = DEFAULT_SHRINK_SECONDS
    out: str | Path | None = None
    progress: bool = False

    def __post_init__(self) -> None:
        _check_int("examples", self.examples, 1, MAX_AUDIT_EXAMPLES)
        _check_int("seed", self.seed, 0)
        _check_int("max_nodes", self.max_nodes, 2)
        self.budget()  # its own checks, now

    def budget(self) -> ShrinkBudget:
        """A fresh shrinking budget of ``shrink_calls`` and ``shrink_seconds`` (not started)."""
        return ShrinkBudget(calls=self.shrink_calls, seconds=self.shrink_seconds)


def _check_int(name: str, value: object, low: int, high: int | None = None) -> None:
    if isinstance(value, bool) or not isinstance(value, int) or value < low or (
            high is not None and value > high):
        bound = f"between {low} and {high}" if high is not None else f">= {low}"
        raise AuditError(f"{name}={value!r} must be an integer {bound}")


class ShrinkBudget:
    """Solver calls and seconds left for shrinking (the clock starts at :meth:`start`).

    Examples
    --------
    >>> b = ShrinkBudget(calls=2, seconds=60).start()
    >>> b.spend(), b.spend(), b.spend()
    (True, True, False)
    >>> b.used, b.exhausted
    (2, True)
    """

    def __init__(self, *, calls: int = DEFAULT_SHRINK_CALLS,
                 seconds: float = DEFAULT_SHRINK_SECONDS) -> None:
        given: object = calls  # checked as given, whatever its type
        if isinstance(given, bool) or not isinstance(given, int) or given < 0:
            raise AuditError(f"shrink calls={calls!r} must be a non-negative integer")
        if not seconds >= 0:
            raise AuditError(f"shrink seconds={seconds!r} must be non-negative")
        self.calls, self.seconds = calls, float(seconds)
        self.used = 0
        self.started = 0.0
        self.deadline = float("inf")
        self.exhausted = False

    def start(self) -> ShrinkBudget:
        """Start the clock; returns ``self``."""
        self.started = time.monotonic()
        self.deadline = self.started + self.seconds
        return self

    def spend(self, share: float = 1.0) -> bool:
        """Take one solver call from the first ``share`` of the budget; False when none is
        left (with ``share`` 1, the budget is then exhausted)."""
        calls, deadline = self.calls * share, self.started + self.seconds * share
        if self.used >= calls or time.monotonic() > min(deadline, self.deadline):
            self.exhausted = self.exhausted or share >= 1.0
            return False
        self.used += 1
        return True

    def describe(self) -> str:
        """The budget in words, e.g. ``500 solver calls or 120 s``."""
        return f"{self.calls} solver calls or {self.seconds:g} s"


DEFAULT_CONFIG = AuditConfig()
"""The audit as ``dpp audit`` runs it without options."""
