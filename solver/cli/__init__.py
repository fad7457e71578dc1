"""The ``dpp`` command line: solver commands here, checker commands from ``dppverify.cli``.

Every command reports bad input as one line on stderr (``error: ...``) and exits 2; an
unexpected internal failure prints one line and exits 3 (set ``DPP_DEBUG=1`` for the
traceback). ``dppverify`` never imports this package: the dependency points one way only, and
this package is the one place the solver's side imports ``dppverify``. One module per command:
:mod:`~solver.cli.solve`, :mod:`~solver.cli.experiment` (and
:mod:`~solver.cli.experiment_ngoal`), :mod:`~solver.cli.batch`, :mod:`~solver.cli.plot`.
"""

from __future__ import annotations

import click

import solver.threads  # noqa: F401  (first: one BLAS thread, before numpy loads)
from dppio.errors import DppioError
from dppverify import cli as checker_cli
from dppverify.errors import CheckerError
from solver.cli.batch import batch_checker, batch_command
from solver.cli.experiment import experiment_group
from solver.cli.plot import plot_group
from solver.cli.solve import solve_command
from solver.errors import DPPError

__all__ = ["batch_checker", "console", "main"]


class _DppGroup(checker_cli.ErrorReportingGroup):
    """The checker's error-reporting group, also treating solver errors as bad input."""

    user_errors = (DPPError, CheckerError, DppioError)


@click.group(cls=_DppGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="dppverify")
def main() -> None:
    """Deceptive path planning games: solve, certify, audit, experiment."""


for _command in (solve_command, experiment_group, batch_command, plot_group,
                 *checker_cli.COMMANDS):
    main.add_command(_command)


def console() -> None:
    """The ``dpp`` program (the console script ``dpp-python``, which the ``dpp`` launcher runs:
    ``bin/dpp``): :data:`main` under the name ``dpp`` whichever file started it.

    Examples
    --------
    >>> import sys
    >>> saved, sys.argv = sys.argv, ["/venv/bin/dpp-python", "--version"]
    >>> try:
    ...     console()
    ... except SystemExit as exc:
    ...     print("exit", exc.code)
    ... finally:
    ...     sys.argv = saved  # doctest: +ELLIPSIS
    dpp, version ...
    exit 0
    """
    main(prog_name="dpp")
