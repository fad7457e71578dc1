"""The errors of the shared edges: an output that cannot be written, a limit exceeded.

Each package raises its own error classes at its edges: the checks and writers of
:mod:`dppio` take ``error=`` (the class to raise, called with the one-line message) and default
to the classes here. The ``dpp`` command line treats a :class:`DppioError` as bad input too
(one line, exit 2).
"""

from __future__ import annotations

from collections.abc import Callable

ErrorClass = Callable[[str], Exception]
"""What a check or a writer raises: called with the one-line message."""


class DppioError(Exception):
    """Base class of the errors raised by :mod:`dppio`."""


class OutputError(DppioError, OSError):
    """An output location cannot be written (missing permission, full disk, a folder...)."""


class InputError(DppioError, ValueError):
    """An input file that cannot be used as it is (larger than the limit, not UTF-8 text)."""


class LimitError(InputError):
    """An input beyond one of the limits of :mod:`dppio.limits`."""


class OptionError(DppioError, ValueError):
    """A command-line option (of the shared ``--map`` group, :mod:`dppio.cli.map_options`) that
    cannot be used as given."""
