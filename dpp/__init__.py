"""The ``dpp`` command: the solver's commands and the checker's in one click group.

This is the one module that imports both command lines: the solver's commands
(:data:`solver.cli.HOMES`) and the checker's (:data:`dppverify.cli.HOMES`), each command's
module imported when it runs (:class:`dppio.cli.lazy.LazyCommands`), share only
the conventions of :mod:`dppio.cli`, and neither imports the other (import-linter enforces
it). Every command reports bad input as one line on stderr (``error: ...``) and exits 2; an
unexpected internal failure prints one line and exits 3 (set ``DPP_DEBUG=1`` for the
traceback). ``python -m dpp`` is the same command.
"""

from __future__ import annotations

import click

import solver.threads  # noqa: F401  (first: one BLAS thread, before numpy loads)
from dppio.cli.lazy import LazyCommands
from dppio.errors import DppioError
from dppverify import cli as checker_cli
from dppverify.cli.errors import CheckerGroup
from dppverify.errors import CheckerError
from solver import cli as solver_cli
from solver.errors import DPPError

__all__ = ["console", "main"]


class _DppGroup(CheckerGroup):
    """The checker's error-reporting group, also treating solver errors as bad input."""

    user_errors = (DPPError, CheckerError, DppioError)


@click.group(cls=_DppGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="dppverify")
def main() -> None:
    """Deceptive path planning games: solve, certify, audit, experiment."""


main.commands = LazyCommands({**solver_cli.HOMES, **checker_cli.HOMES})  # imported when run


def console() -> None:
    """The ``dpp`` program as a console script: :data:`main` under the name ``dpp``, whichever
    file started it.

    Examples
    --------
    >>> import sys
    >>> from unittest import mock
    >>> with mock.patch.object(sys, "argv", ["/any/launcher", "--version"]):
    ...     try:
    ...         console()
    ...     except SystemExit as exc:
    ...         print("exit", exc.code)  # doctest: +ELLIPSIS
    dpp, version ...
    exit 0
    """
    main(prog_name="dpp")
