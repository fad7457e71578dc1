"""Re-exports of :mod:`dppio.cli.conventions` for the command modules that still import them
from here (removed once those modules import :mod:`dppio.cli` directly)."""

from dppio.cli.conventions import (
    PhaseBar,
    emit,
    output_file_option,
    progress_option,
    status,
    want_progress,
)

__all__ = ["PhaseBar", "emit", "output_file_option", "progress_option", "status",
           "want_progress"]
