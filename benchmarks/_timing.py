"""Wall-clock timing for the benchmarks: one call, its result and its seconds."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import ParamSpec, TypeVar

__all__ = ["timed"]

P = ParamSpec("P")
R = TypeVar("R")


def timed(f: Callable[P, R], *args: P.args, **kwargs: P.kwargs) -> tuple[R, float]:
    """``f(*args, **kwargs)`` and the wall-clock seconds it took.

    Examples
    --------
    >>> value, seconds = timed(sum, [1, 2, 3])
    >>> value, seconds >= 0
    (6, True)
    """
    t0 = time.perf_counter()
    out = f(*args, **kwargs)
    return out, time.perf_counter() - t0
