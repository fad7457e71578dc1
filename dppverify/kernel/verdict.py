"""The kernel's one result record and the three ways a check stops short of a PASS.

Statuses and exit codes (proofs/KERNEL.md K.5): ``pass`` 0, ``refuted`` 1 (only with a
counterexample the kernel verified itself), ``bad-input`` 2, ``undecided`` 3 (the witness
proves nothing, or the kernel does not decide this game).
"""

from __future__ import annotations

from dataclasses import dataclass

EXIT_CODES = {"pass": 0, "refuted": 1, "bad-input": 2, "undecided": 3}
"""The exit code of ``dpp check`` for each status."""


@dataclass(frozen=True)
class Verdict:
    """What the kernel decided, with one line saying why.

    Examples
    --------
    >>> v = Verdict("undecided", "type 1, state (x, c): P(x) <= w + P(u) fails")
    >>> v.exit_code, v.accepted
    (3, False)
    """

    status: str
    message: str
    applicable: bool = True
    """False for a game the kernel does not decide (float mode, a size bound, a table
    undefined on a walk of the game): "undecided" then says nothing about the witness."""

    @property
    def exit_code(self) -> int:
        """``dpp check``'s exit code for this verdict."""
        return EXIT_CODES[self.status]

    @property
    def accepted(self) -> bool:
        """True exactly for a PASS."""
        return self.status == "pass"


class Stop(Exception):
    """A check that ends the kernel's run with a verdict other than PASS."""

    status = "undecided"


class BadInput(Stop):
    """A document that cannot be read as its format, or a witness for other bytes."""

    status = "bad-input"


class Refuted(Stop):
    """A verified counterexample: the profile is not a weak PBNE."""

    status = "refuted"


class Undecided(Stop):
    """The witness does not prove the claim, or the kernel does not decide this game."""


class Beyond(Undecided):
    """The kernel does not decide this game (float mode, a size bound, an undefined table)."""
