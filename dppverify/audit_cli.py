"""``dpp audit``: audit any solver on random instances (the click command).

:data:`audit_command` is registered in ``dppverify.cli.COMMANDS`` (the ``dpp`` group).
Exit codes: 0 every example was certified; 1 a failing example was found (shrunk, written to
``--output-dir``); 2 bad input (one line on stderr).
"""

from __future__ import annotations

import json
import os
import sys

import click

from dppverify.audit import (
    AUDIT_MAX_PREFIXES,
    AuditReport,
    Solver,
    command_solver,
    load_solver,
    run_audit,
)
from dppverify.cli_conventions import output_dir_option, progress_option, status, want_progress
from dppverify.errors import CheckerError

__all__ = ["audit_command", "format_report"]


def format_report(report: AuditReport) -> str:
    """What ``dpp audit`` prints for a report.

    Parameters
    ----------
    report : AuditReport
        The result of :func:`~dppverify.audit.run_audit`.

    Returns
    -------
    str
        The summary line; for a failure also the failing check and the minimal instance
        (one line of JSON). The command prints the files written on stderr.

    Examples
    --------
    >>> from hypothesis import strategies as st
    >>> from dppverify.examples import triangle_document
    >>> report = run_audit(lambda doc: 1 / 0, examples=5, shrink=False,
    ...                    strategy=st.just(triangle_document()))
    >>> print(format_report(report))  # doctest: +ELLIPSIS
    audit FAIL after 1 examples (seed 0; ...): the solver raised ZeroDivisionError: division by zero
    failing check: solver.error
    minimal failing instance: {"graph": {"nodes": [{"id": "s"}, ...], "prior": ["7/10", "3/10"]}
    """
    lines = [report.summary()]
    fail = report.failure
    if fail is not None:
        lines.append(f"failing check: {fail.check}")
        lines.append("minimal failing instance: " + json.dumps(fail.instance))
    return "\n".join(lines)


@click.command("audit")
@click.option("--solver", "solver_spec", metavar="MODULE:FUNCTION",
              help="A Python callable mapping an instance JSON dict to a profile JSON dict.")
@click.option("--solver-cmd", "solver_cmd", metavar="CMD",
              help="A command line run per example, e.g. 'prog {instance} {profile}': it reads "
                   "the instance file and writes the profile file.")
@click.option("--examples", type=click.IntRange(min=1), default=100, show_default=True,
              help="Example budget.")
@click.option("--seed", type=int, default=0, show_default=True,
              help="Seed of the instance generation (same seed, same campaign).")
@click.option("--max-nodes", type=click.IntRange(min=2), default=8, show_default=True,
              help="Largest generated instance, in nodes.")
@output_dir_option("Directory for the minimal failing instance, profile and certificate "
                   "(written only on failure).", default="audit-failure")
@click.option("--shrink/--no-shrink", default=True, show_default=True,
              help="Shrink the first failing instance to a minimal one.")
@click.option("--timeout", type=click.FloatRange(min=0, min_open=True), default=60.0,
              show_default=True, help="Seconds per run of a --solver-cmd command.")
@click.option("--max-prefixes", type=click.IntRange(min=1), default=AUDIT_MAX_PREFIXES,
              show_default=True, help="Skip examples whose walk tree is larger than this.")
@progress_option
def audit_command(solver_spec: str | None, solver_cmd: str | None, examples: int, seed: int,
                  max_nodes: int, output_dir: str, shrink: bool, timeout: float, max_prefixes: int,
                  progress: bool | None) -> None:
    """Audit a solver: certify its profiles on random instances; shrink the first failure.

    Exactly one of --solver and --solver-cmd. Exit 0 when every example is certified, 1 when
    a failing example is found (written to --output-dir), 2 on bad input.

    \b
    Examples:
      dpp audit --solver solver.adapter:solve_json --examples 500
      dpp audit --solver-cmd 'python examples/solver_cmd.py {instance} {profile}'
    """
    try:
        solver = _make_solver(solver_spec, solver_cmd, timeout)
        report = run_audit(solver, examples=examples, seed=seed, max_nodes=max_nodes,
                           out=output_dir, shrink=shrink, max_prefixes=max_prefixes,
                           progress=want_progress(progress))
    except CheckerError as exc:
        click.echo(f"error: {exc}", err=True)
        raise click.exceptions.Exit(2) from None
    click.echo(format_report(report))
    if report.files:
        status("wrote " + ", ".join(str(p) for p in report.files))
    raise click.exceptions.Exit(0 if report.passed else 1)


def _make_solver(spec: str | None, cmd: str | None, timeout: float) -> Solver:
    from dppverify.audit import AuditError

    if cmd is not None and spec is None:
        return command_solver(cmd, timeout=timeout)
    if spec is None or cmd is not None:
        raise AuditError("give exactly one of --solver MODULE:FUNCTION and --solver-cmd CMD")
    if os.getcwd() not in sys.path:  # like `python -m`: the user's modules in the cwd
        sys.path.insert(0, os.getcwd())
    return load_solver(spec)
