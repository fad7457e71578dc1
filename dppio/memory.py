"""How much memory a ``dpp`` command may use: the process's address-space limit
(``RLIMIT_AS``, e.g. ``ulimit -v``) or, without one, the memory the system has available.

The commands refuse an input whose estimated memory is beyond this before they build it
(:func:`check_memory`), and turn a ``MemoryError`` met anyway into one line (exit 2) instead
of a traceback or an internal error.
"""

from __future__ import annotations

import contextlib
from fractions import Fraction
from pathlib import Path

from dppio.errors import ErrorClass, LimitError
from dppio.text import decimal


def _rlimit_as() -> int | None:
    with contextlib.suppress(ImportError, OSError, ValueError):
        import resource

        soft, _ = resource.getrlimit(resource.RLIMIT_AS)
        if soft != resource.RLIM_INFINITY:
            return int(soft)
    return None


def _mem_available() -> int | None:
    with contextlib.suppress(OSError, ValueError, IndexError):
        for line in Path("/proc/meminfo").read_text().splitlines():
            if line.startswith("MemAvailable:"):
                return int(line.split()[1]) * 1024
    return None


def _rss() -> int:
    with contextlib.suppress(OSError, ValueError, IndexError):
        for line in Path("/proc/self/status").read_text().splitlines():
            if line.startswith("VmSize:"):  # address space in use (what RLIMIT_AS counts)
                return int(line.split()[1]) * 1024
    return 0


def available_memory() -> int | None:
    """Bytes this process may still allocate: its ``RLIMIT_AS`` minus what it uses, or the
    system's available memory; None when neither is known.

    Examples
    --------
    >>> m = available_memory()
    >>> m is None or m > 0
    True
    """
    limit = _rlimit_as()
    free = _mem_available()
    room = None if limit is None else max(0, limit - _rss())
    if room is None:
        return free
    return room if free is None else min(room, free)


def memory_limit_text() -> str:
    """The memory limit in words, for an error message.

    Examples
    --------
    >>> memory_limit_text().startswith(("an address-space limit", "the system's", "unknown"))
    True
    """
    limit = _rlimit_as()
    if limit is not None:
        return f"an address-space limit of {decimal(Fraction(limit, 2**30))} GiB (ulimit -v)"
    free = _mem_available()
    if free is not None:
        return f"the system's available memory, {decimal(Fraction(free, 2**30))} GiB"
    return "unknown limit"


def check_memory(need: int, *, what: str, error: ErrorClass = LimitError) -> None:
    """Refuse in one line when ``need`` bytes (an estimate) are beyond
    :func:`available_memory`.

    Raises
    ------
    LimitError
        (or ``error``) One line naming ``what``, the estimate and the limit.

    Examples
    --------
    >>> check_memory(1, what="a tiny map")
    >>> check_memory(1 << 62, what="a huge map")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppio.errors.LimitError: a huge map needs about 4.295×10^9 GiB of memory; ...
    """
    room = available_memory()
    if room is not None and need > room:
        gib_need, gib_room = decimal(Fraction(need, 2**30)), decimal(Fraction(room, 2**30))
        raise error(f"{what} needs about {gib_need} GiB of memory; this process may use "
                    f"{gib_room} GiB more ({memory_limit_text()}); give a smaller input or more "
                    "memory")

