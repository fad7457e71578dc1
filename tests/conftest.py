"""Hypothesis profiles for the whole test suite (see docs/audit.md).

``DPP_HYPOTHESIS_PROFILE`` selects one:

- ``ci`` (default): few examples, derandomized (the same examples on every run), no example
  database, no deadline — fast and reproducible;
- ``audit``: thousands of examples per property, random seeds, the example database on
  (failures are replayed first on the next run) — a property-based campaign;
- ``dev``: in between (200 examples, random), for local work.
"""

from __future__ import annotations

import os

import pytest
from hypothesis import HealthCheck, Phase, settings

PROFILE_VARIABLE = "DPP_HYPOTHESIS_PROFILE"

_slow_ok = [HealthCheck.too_slow, HealthCheck.data_too_large]

settings.register_profile(
    "ci", max_examples=30, derandomize=True, database=None, deadline=None,
    suppress_health_check=_slow_ok, phases=[Phase.explicit, Phase.generate, Phase.shrink],
    print_blob=True)
settings.register_profile(
    "dev", max_examples=200, deadline=None, suppress_health_check=_slow_ok, print_blob=True)
settings.register_profile(
    "audit", max_examples=2000, deadline=None, suppress_health_check=_slow_ok, print_blob=True)

_profile = os.environ.get(PROFILE_VARIABLE, "ci")
if _profile not in ("ci", "dev", "audit"):
    raise pytest.UsageError(f"{PROFILE_VARIABLE}={_profile!r}: expected ci, dev or audit")
settings.load_profile(_profile)
