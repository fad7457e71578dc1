"""The checker's error hierarchy (independent of the solver's).

Every error the checker raises on bad input or a failed solve is a :class:`CheckerError`;
the ``dpp`` CLI prints it as one line and exits 2. A *refuted* profile is not an error: it
yields a certificate with failed checks.
"""

from __future__ import annotations

__all__ = ["AuditError", "CertificateError", "CheckerError", "HorizonError",
           "InvalidInstanceError", "LPError", "NotTwoGoalsError", "OptionError", "ProfileError",
           "TreeTooLargeError",
           "UndecidedError"]


class CheckerError(Exception):
    """Base class of every error the checker raises on bad input or failed solves."""


class InvalidInstanceError(CheckerError, ValueError):
    """The instance document is malformed or violates the game's assumptions."""


class ProfileError(CheckerError, ValueError):
    """The profile document cannot be parsed at all (not JSON, wrong format tag...).

    ``stated``: what the document says about the game it was made for, when it is a JSON
    object (:class:`dppverify.game.profile_types.Stated`; None otherwise), so that a command
    can say which game it looks made for.
    """

    def __init__(self, message: str, stated: object = None) -> None:
        super().__init__(message)
        self.stated = stated


class LPError(CheckerError, RuntimeError):
    """A linear program did not solve to status ``optimal``."""


class TreeTooLargeError(CheckerError, ValueError):
    """The truncated game tree would exceed the configured size limit."""


class HorizonError(CheckerError, ValueError):
    """The requested horizon is unusable (negative, shorter than a profile path, too short)."""


class CertificateError(CheckerError, ValueError):
    """A certificate document is malformed."""


class AuditError(CheckerError, ValueError):
    """Bad ``dpp audit`` input: a solver that cannot be imported or run, bad arguments."""


class OptionError(CheckerError, ValueError):
    """Command-line options that do not fit together or a malformed option value."""


class UndecidedError(CheckerError):
    """The checker cannot decide the question asked (exit 3, "could not decide"), e.g. a
    Defender form the untruncated game's structured route cannot evaluate. The message names
    what would decide it; it is never a PASS."""


class NotTwoGoalsError(InvalidInstanceError):
    """A two-goal view (the paper's primary and secondary goals) of an instance whose number
    of goals is not two."""
