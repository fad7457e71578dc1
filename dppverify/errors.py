"""The checker's error hierarchy (independent of the solver's)."""

from __future__ import annotations

__all__ = ["CertificateError", "CheckerError", "InvalidInstanceError", "LPError",
           "ProfileError", "TreeTooLargeError"]


class CheckerError(Exception):
    """Base class of every error the checker raises on bad input or failed solves."""


class InvalidInstanceError(CheckerError, ValueError):
    """The instance document is malformed or violates the game's assumptions."""


class ProfileError(CheckerError, ValueError):
    """The profile document cannot be parsed at all (not JSON, wrong format tag...)."""


class LPError(CheckerError, RuntimeError):
    """A linear program did not solve to status ``optimal``."""


class TreeTooLargeError(CheckerError, ValueError):
    """The truncated game tree would exceed the configured size limit."""


class CertificateError(CheckerError, ValueError):
    """A certificate document is malformed."""
