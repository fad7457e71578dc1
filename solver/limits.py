"""The solver's own limits (its options); the limits both packages share are in
:mod:`dppio.limits` (listed in the README, "Limits").

Beyond each limit the solver refuses with one line (exit code 2) instead of hanging or
exhausting memory. The shared checks raise the solver's
:class:`~solver.errors.InvalidInstanceError` when given ``error=InvalidInstanceError``.

Examples
--------
>>> MAX_DENSITY_SIZE, MAX_DENSITY_GRIDS
(200, 100000)
"""

from __future__ import annotations

__all__ = ["MAX_DENSITY_GRIDS", "MAX_DENSITY_SIZE"]

MAX_DENSITY_SIZE = 200
"""Largest grid side of ``dpp experiment density --size``."""

MAX_DENSITY_GRIDS = 100_000
"""Most grids of one density sweep (samples x densities)."""
