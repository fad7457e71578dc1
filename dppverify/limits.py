"""The checker's own limits (its options); the numeric and size limits both packages share
are in :mod:`dppio.limits` (listed in the README, "Limits").

Beyond each limit the checker refuses with one line (exit code 2) instead of hanging or
exhausting memory.

Examples
--------
>>> MAX_HORIZON, MAX_TRIALS, MAX_AUDIT_EXAMPLES
(10000, 10000, 1000000)
"""

from __future__ import annotations

__all__ = ["MAX_AUDIT_EXAMPLES", "MAX_HORIZON", "MAX_TRIALS"]

MAX_HORIZON = 10_000
"""Largest horizon H of a truncated game (``--horizon``)."""

MAX_TRIALS = 10_000
"""Most random attackers per L3/L4 lemma check (``--trials``)."""

MAX_AUDIT_EXAMPLES = 1_000_000
"""Largest example budget of ``dpp audit --examples``."""
