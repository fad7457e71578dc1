"""The solver's error hierarchy: every user-facing failure is one of these."""

from __future__ import annotations

__all__ = ["DPPError", "InstanceFormatError", "InvalidInstanceError", "NotTwoGoalsError",
           "OutputError"]


class DPPError(Exception):
    """Base class of every error the solver raises on bad input."""


class InvalidInstanceError(DPPError, ValueError):
    """An instance that is well-formed but violates the game's assumptions.

    Examples: an unknown start node, equal goals, a non-positive weight, a prior
    outside (0, 1), a goal unreachable from the start.
    """


class InstanceFormatError(InvalidInstanceError):
    """A file or document that cannot be parsed (malformed JSON, a bad map header...)."""


class NotTwoGoalsError(InvalidInstanceError):
    """A two-goal view (the paper's primary and secondary goals) asked of an instance with
    ``N != 2`` goals."""


class OutputError(DPPError, OSError):
    """An output location cannot be written (missing permission, full disk, a folder...)."""
