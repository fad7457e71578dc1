"""Wall-clock timing for the benchmarks: one call with its seconds, or the best of repeats."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import ParamSpec, TypeVar

__all__ = ["best", "timed"]

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


def best(fn: Callable[[], R], repeat: int) -> tuple[float, R]:
    """The least wall-clock seconds of ``repeat`` calls of ``fn`` (at least one), and the last
    call's result.

    Examples
    --------
    >>> calls = []
    >>> seconds, out = best(lambda: calls.append(1) or len(calls), 3)
    >>> out, len(calls), seconds >= 0
    (3, 3, True)
    """
    out, least = timed(fn)
    for _ in range(repeat - 1):
        out, seconds = timed(fn)
        least = min(least, seconds)
    return least, out
