"""``python -m dppverify``: the checker's commands without the solver.

The same ``certify`` and ``value`` commands as ``dpp certify`` / ``dpp value``, in a tiny
group of their own, so that the checker is usable where the solver is not installed.
"""

from __future__ import annotations

import click

from dppverify import __version__
from dppverify.cli import COMMANDS, ErrorReportingGroup

__all__ = ["main"]


@click.group(cls=ErrorReportingGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="dppverify")
def main() -> None:
    """dppverify: certify DPP game profiles independently of any solver."""


for _command in COMMANDS:
    main.add_command(_command)

if __name__ == "__main__":
    main(prog_name="python -m dppverify")
