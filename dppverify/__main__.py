"""``python -m dppverify``: the checker's commands without the solver.

The same ``certify`` and ``value`` commands as ``dpp certify`` / ``dpp value``, in a tiny
group of their own, so that the checker is usable where the solver is not installed.
"""

from __future__ import annotations

import os
from typing import Any

import click

from dppverify import __version__
from dppverify.cli import COMMANDS
from dppverify.errors import CheckerError

__all__ = ["main"]


class _CheckerGroup(click.Group):
    """Bad input: one line, exit 2; anything unexpected: one line, exit 3 (no traceback)."""

    def invoke(self, ctx: click.Context) -> Any:
        try:
            return super().invoke(ctx)
        except CheckerError as exc:
            click.echo(f"error: {exc}", err=True)
            ctx.exit(2)
        except (click.exceptions.Exit, click.ClickException, click.Abort):
            raise
        except Exception as exc:
            if os.environ.get("DPP_DEBUG"):
                raise
            click.echo(f"internal error: {type(exc).__name__}: {exc} "
                       "(set DPP_DEBUG=1 for details)", err=True)
            ctx.exit(3)


@click.group(cls=_CheckerGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="dppverify")
def main() -> None:
    """dppverify: certify DPP game profiles independently of any solver."""


for _command in COMMANDS:
    main.add_command(_command)

if __name__ == "__main__":
    main(prog_name="python -m dppverify")
