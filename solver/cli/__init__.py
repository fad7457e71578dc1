"""The solver's commands of the ``dpp`` command line (the group is :mod:`dpp`).

One module per command: :mod:`~solver.cli.solve`, :mod:`~solver.cli.experiment` (and
:mod:`~solver.cli.experiment_ngoal`), :mod:`~solver.cli.batch`, :mod:`~solver.cli.plot`; what
they share of their own: :mod:`~solver.cli.common`. The conventions every ``dpp`` command
follows (options, progress, one-line errors, ``--map``) are :mod:`dppio.cli`; this package
imports nothing of the checker's command line. It is the one place of the solver that imports
``dppverify`` (``dpp solve`` and ``dpp batch`` certify what they solve); ``dppverify`` never
imports the solver.
"""

from __future__ import annotations

import click

import solver.threads  # noqa: F401  (first: one BLAS thread, before numpy loads)
from solver.cli.batch import batch_command
from solver.cli.experiment import experiment_group
from solver.cli.plot import plot_group
from solver.cli.solve import solve_command

COMMANDS: list[click.Command] = [solve_command, experiment_group, batch_command, plot_group]
"""The solver's commands (the ``dpp`` group, :mod:`dpp`, adds the checker's)."""
