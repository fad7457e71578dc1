"""The errors of the shared edges: an output that cannot be written, a limit exceeded.

Both command lines treat a :class:`DppioError` as bad input (one line, exit 2).
"""

from __future__ import annotations

__all__ = ["DppioError", "InputError", "LimitError", "OutputError"]


class DppioError(Exception):
    """Base class of the errors raised by :mod:`dppio`."""


class OutputError(DppioError, OSError):
    """An output location cannot be written (missing permission, full disk, a folder...)."""


class InputError(DppioError, ValueError):
    """An input file that cannot be used as it is (larger than the limit, not UTF-8 text)."""


class LimitError(InputError):
    """An input beyond one of the limits of :mod:`dppio.limits`."""
