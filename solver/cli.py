"""The ``dpp`` command line: solver commands here, checker commands from ``dppverify.cli``.

Every command reports bad input as one line on stderr (``error: ...``) and exits 2; an
unexpected internal failure prints one line and exits 3 (set ``DPP_DEBUG=1`` for the
traceback). ``dppverify`` never imports this module: the dependency points one way only.
"""

from __future__ import annotations

import os
from typing import Any

import click

from dppverify import cli as checker_cli
from dppverify.errors import CheckerError
from solver.equilibrium import solve
from solver.errors import DPPError, InvalidInstanceError
from solver.instance import Instance
from solver.instance_json import load_instance
from solver.io_utils import dumps, write_atomic
from solver.movingai import read_map

__all__ = ["main"]


class _DppGroup(click.Group):
    """A click group that turns package errors into one-line messages."""

    def invoke(self, ctx: click.Context) -> Any:
        try:
            return super().invoke(ctx)
        except (DPPError, CheckerError) as exc:
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


@click.group(cls=_DppGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="dppverify")
def main() -> None:
    """Deceptive path planning games: solve, certify, audit, experiment."""


def _cell(text: str, what: str) -> tuple[int, int]:
    try:
        r, c = (int(x) for x in text.split(","))
    except ValueError:
        raise InvalidInstanceError(f"{what} must be 'ROW,COL', got {text!r}") from None
    return (r, c)


def _prior(text: str) -> tuple[str, str]:
    parts = [x.strip() for x in text.split(",")]
    if len(parts) != 2:
        raise InvalidInstanceError(f"--prior must be two numbers 'P,Q', got {text!r}")
    return (parts[0], parts[1])


@main.command("solve")
@click.argument("instance", required=False, type=click.Path(dir_okay=False))
@click.option("--map", "map_file", type=click.Path(dir_okay=False),
              help="A MovingAI .map grid instead of an instance JSON file.")
@click.option("--start", help="Start cell ROW,COL (with --map).")
@click.option("--goals", nargs=2, help="The two goal cells ROW,COL ROW,COL (with --map).")
@click.option("--prior", "prior_text", help="Priors of the two goals, e.g. 0.6,0.4 or 3/5,2/5.")
@click.option("--connectivity", type=click.Choice(["4", "8"]), default="4", show_default=True,
              help="Grid moves (with --map): 4-connected unit, or 8-connected octile.")
@click.option("--json", "as_json", is_flag=True, help="Print the dpp-profile/1 JSON.")
@click.option("-o", "--output", type=click.Path(dir_okay=False),
              help="Write the dpp-profile/1 JSON to this file (atomically).")
def solve_command(instance: str | None, map_file: str | None, start: str | None,
                  goals: tuple[str, str] | None, prior_text: str | None, connectivity: str,
                  as_json: bool, output: str | None) -> None:
    """Solve INSTANCE (a dpp instance JSON file) for the paper's PBNE.

    \b
    Examples:
      dpp solve examples/triangle.json
      dpp solve examples/triangle.json --json -o profile.json
      dpp solve --map examples/paper10.map --start 9,0 --goals 0,9 0,0 --prior 0.6,0.4
    """
    inst = _load(instance, map_file, start, goals, prior_text, int(connectivity))
    eq = solve(inst)
    doc = eq.to_json()
    if output:
        write_atomic(output, dumps(doc))
    if as_json:
        click.echo(dumps(doc), nl=False)
    elif not output:
        click.echo(eq.summary())
    else:
        click.echo(f"wrote {output}: U* = {doc['value']['U']}, VoI* = {doc['value']['VoI']}")


def _load(instance: str | None, map_file: str | None, start: str | None,
          goals: tuple[str, str] | None, prior_text: str | None, connectivity: int) -> Instance:
    if (instance is None) == (map_file is None):
        raise InvalidInstanceError("give exactly one of INSTANCE or --map FILE")
    if instance is not None:
        if start or goals or prior_text:
            raise InvalidInstanceError("--start/--goals/--prior go with --map, not INSTANCE")
        return load_instance(instance)
    if not (start and goals and prior_text):
        raise InvalidInstanceError("--map needs --start ROW,COL --goals R,C R,C --prior P,Q")
    blocked = read_map(str(map_file))
    return Instance.from_grid(blocked, _cell(start, "--start"),
                              (_cell(goals[0], "--goals"), _cell(goals[1], "--goals")),
                              _prior(prior_text), connectivity=connectivity)


for _command in checker_cli.COMMANDS:
    main.add_command(_command)
