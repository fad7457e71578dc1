"""Every default and budget of ``dpp audit`` in one place (its options' defaults and the bounds
it keeps to).

Examples
--------
>>> AUDIT_MAX_PREFIXES, AUDIT_TRIALS, DEFAULT_TIMEOUT, DEFAULT_SHRINK_CALLS
(200000, 2, 60.0, 500)
"""

from __future__ import annotations

__all__ = ["AUDIT_MAX_PREFIXES", "AUDIT_TRIALS", "DEFAULT_SHRINK_CALLS", "DEFAULT_SHRINK_SECONDS",
           "DEFAULT_TIMEOUT", "HYPOTHESIS_SHARE", "MAX_AUDIT_INSTANCES", "READY_TIMEOUT",
           "SKIP_FACTOR", "SKIP_FLOOR"]

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
