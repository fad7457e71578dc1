"""How the checker's commands fail: the checker's errors on the shared one-line rule.

The one-line rule of every ``dpp`` command is :mod:`dppio.cli.errors`; here the checker adds
its own: a :class:`~dppverify.errors.CheckerError` (bad input) is ``error: ...`` and exit 2,
a :class:`~dppverify.errors.UndecidedError` is ``undecided: ...`` and exit 3, and an
:class:`~dppverify.errors.LPError` (a numerical solver failed on a valid input) is ``error:
could not decide: ...`` and exit 3. Commands report their own errors with :func:`fail`, so
that they behave the same inside the ``dpp`` group and ``python -m dppverify``
(:class:`CheckerGroup`).
"""

from __future__ import annotations

from typing import NoReturn

import click

from dppio.cli import errors as shared
from dppio.errors import DppioError
from dppio.text import terminal_line
from dppverify.errors import CheckerError, LPError, UndecidedError


class CheckerGroup(shared.ErrorReportingGroup):
    """The shared error-reporting group with the checker's errors (:func:`fail`)."""

    user_errors: tuple[type[Exception], ...] = (CheckerError, DppioError)

    def report(self, exc: Exception) -> NoReturn:
        """Report a user error the checker's way (:func:`fail`)."""
        fail(exc)


def error_code(exc: Exception) -> int:
    """The exit code of an error: 3 ("could not decide") when a numerical solver failed on
    input that passed every check (:class:`~dppverify.errors.LPError`), else 2 (bad input).

    Examples
    --------
    >>> from dppverify.errors import OptionError
    >>> error_code(LPError("x")), error_code(OptionError("y"))
    (3, 2)
    """
    return 3 if isinstance(exc, LPError) else 2


def error_line(exc: Exception) -> str:
    """The one line printed for an error (:func:`error_code` tells its exit code).

    Examples
    --------
    >>> error_line(LPError("value LP: CLARABEL returned status 'infeasible'"))
    "error: could not decide: value LP: CLARABEL returned status 'infeasible' (a numerical \
failure of the checker on a valid input, not an error in it)"
    """
    text = " ".join(str(exc).split())
    if isinstance(exc, LPError):
        return terminal_line(f"error: could not decide: {text} (a numerical failure of the "
                             "checker on a valid input, not an error in it)")
    return terminal_line(f"error: {text}")


def fail(exc: Exception) -> NoReturn:
    """Report a user error in one line and exit: ``undecided: ...`` (exit 3) for an
    :class:`~dppverify.errors.UndecidedError`, else :func:`dppio.cli.errors.fail` with
    :func:`error_line` and :func:`error_code` (an interruption: the signal's line and code).

    Examples
    --------
    >>> from dppverify.errors import OptionError
    >>> try:
    ...     fail(OptionError("no such option"))
    ... except click.exceptions.Exit as exc:
    ...     print("exit", exc.exit_code)
    exit 2
    """
    if isinstance(exc, UndecidedError):  # "could not decide": exit 3, never a verdict
        click.echo(terminal_line(f"undecided: {' '.join(str(exc).split())}"), err=True)
        raise click.exceptions.Exit(3)
    shared.fail(exc, line=error_line(exc), code=error_code(exc))
