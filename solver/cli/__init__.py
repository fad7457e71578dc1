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

from typing import Any

import solver.threads  # noqa: F401  (first: one BLAS thread, before numpy loads)

HOMES: dict[str, tuple[str, str]] = {
    "solve": ("solver.cli.solve", "solve_command"),
    "experiment": ("solver.cli.experiment", "experiment_group"),
    "batch": ("solver.cli.batch", "batch_command"),
    "plot": ("solver.cli.plot", "plot_group"),
}
"""The solver's commands by name: each one's module and attribute (the ``dpp`` group,
:mod:`dpp`, adds the checker's and imports a command's module only when it runs)."""


def __getattr__(name: str) -> Any:
    """``COMMANDS``: the solver's commands (all imported), in ``HOMES`` order."""
    if name != "COMMANDS":
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    import importlib

    return [getattr(importlib.import_module(m), a) for m, a in HOMES.values()]
