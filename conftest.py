"""Fixtures for every test the default run collects, doctests of the packages included."""
from __future__ import annotations

import sys
from collections.abc import Iterator

import pytest


@pytest.fixture(autouse=True)
def _close_figures() -> Iterator[None]:
    """Close the figures a test or doctest drew (matplotlib warns past 20 open figures, and
    warnings are errors): without this, whether a doctest fails depends on what its worker ran
    before. Matplotlib is not imported here when no test has loaded it."""
    yield
    pyplot = sys.modules.get("matplotlib.pyplot")
    if pyplot is not None:
        pyplot.close("all")
