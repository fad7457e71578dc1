"""Checker commands of the ``dpp`` CLI (certify, value, export-efg).

``COMMANDS`` is the list the ``dpp`` group registers. Commands report
:class:`dppverify.errors.CheckerError` subclasses (bad input) as one line on stderr and exit
2 themselves, so they behave the same inside the solver's ``dpp`` group and in
``python -m dppverify``. ``dpp certify`` exits 0 only when every check passes and 1 when the
profile is refuted (or a check could not be completed).
"""

from __future__ import annotations

import json
import os
from typing import Any

import click

from dppverify.audit_cli import audit_command
from dppverify.certificate import Certificate, CheckRecord
from dppverify.certify import DEFAULT_TRIALS, certify
from dppverify.cli_conventions import output_file_option, progress_option, status, want_progress
from dppverify.efg import DEFAULT_MAX_EFG_NODES, GameInstance, write_efg
from dppverify.errors import CheckerError, LPError, OptionError
from dppverify.exact import format_number
from dppverify.files import refuse_input_as_output
from dppverify.instance import Instance, load_instance
from dppverify.interrupts import Terminated, as_signal, exit_code, signals_as_exceptions
from dppverify.interrupts import message as interrupt_message
from dppverify.limits import MAX_HORIZON, MAX_PREFIXES_LIMIT, MAX_TRIALS
from dppverify.lp import LP_SOLVER, LP_TOLERANCE
from dppverify.map_options import MAP_USAGE, MapRequest, instance_or_map, map_options
from dppverify.ngoal.certify import certify_ngoal
from dppverify.ngoal.instance import load_ninstance
from dppverify.ngoal.routes import is_ngoal_file, nrouted_document, nrouted_lines, nrouted_value
from dppverify.routes import ROUTES, Route, RoutedValue, routed_value
from dppverify.text import show
from dppverify.tree import DEFAULT_MAX_PREFIXES
from dppverify.value_dp import StructuredValue
from dppverify.value_lp import GameValue

__all__ = ["COMMANDS", "CONSISTENCY_HEADING", "HORIZON", "CertifyHorizonParam",
           "ErrorReportingGroup", "HorizonParam", "certify_command", "export_efg_command",
           "format_table", "load_game", "value_command"]

NUMBERS_WIDTH = 44

CONSISTENCY_HEADING = ("consistency checks (the checker's own computations compared; a failure "
                       "is the checker's fault, not counted above):")



class ErrorReportingGroup(click.Group):
    """A click group for the ``dpp`` commands: bad input is one line and exit 2.

    Errors of the classes in :attr:`user_errors` are the user's (bad input): one line on
    stderr, ``error: ...``, exit code 2. Anything else is an internal failure: one line, exit
    code 3, no traceback (set ``DPP_DEBUG=1`` to see it). Subclasses add their package's error
    classes (``dpp``'s group adds the solver's).
    """

    user_errors: tuple[type[Exception], ...] = (CheckerError,)

    def main(self, *args: Any, **kwargs: Any) -> Any:
        """Run the command with SIGINT/SIGTERM/SIGHUP as exceptions (dppverify.interrupts):
        a signal ends it after cleaning up, with one line and exit code 128 + n."""
        with signals_as_exceptions():
            try:
                return super().main(*args, **kwargs)
            except Terminated as exc:  # a signal outside invoke (e.g. while parsing)
                click.echo(interrupt_message(exc), err=True)
                raise SystemExit(exit_code(exc)) from None

    def parse_args(self, ctx: click.Context, args: list[str]) -> list[str]:
        try:
            return super().parse_args(ctx, args)
        except click.UsageError as exc:
            _usage_error(exc)
            ctx.exit(2)
            raise  # pragma: no cover - ctx.exit raises

    def invoke(self, ctx: click.Context) -> Any:
        try:
            return super().invoke(ctx)
        except self.user_errors as exc:
            if (sig := as_signal(exc)) is not None:  # interrupted: a signal, not bad input
                click.echo(interrupt_message(sig), err=True)
                ctx.exit(exit_code(sig))
            click.echo(error_line(exc), err=True)
            ctx.exit(error_code(exc))
        except click.UsageError as exc:  # click's three-line usage message, as one line
            _usage_error(exc)
            ctx.exit(2)
        except (KeyboardInterrupt, Terminated) as exc:  # one line, 130 / 143, cleaned up
            click.echo(interrupt_message(exc), err=True)
            ctx.exit(exit_code(exc))
        except (click.exceptions.Exit, click.ClickException, click.Abort):
            raise
        except Exception as exc:
            if (sig := as_signal(exc)) is not None:  # a library turned the signal into this
                click.echo(interrupt_message(sig), err=True)
                ctx.exit(exit_code(sig))
            if os.environ.get("DPP_DEBUG"):
                raise
            click.echo(f"internal error: {type(exc).__name__}: {' '.join(str(exc).split())} "
                       "(set DPP_DEBUG=1 for details)", err=True)
            ctx.exit(3)


def _usage_error(exc: click.UsageError) -> None:
    """One line for a click usage error: the message and where to find help."""
    where = exc.ctx.command_path if exc.ctx is not None else "dpp"
    if isinstance(exc, click.exceptions.NoArgsIsHelpError):  # `dpp plot`: no help dump
        click.echo(f"error: missing command (see '{where} --help')", err=True)
        return
    message = " ".join(exc.format_message().split())
    click.echo(f"error: {message} (see '{where} --help')", err=True)


def error_code(exc: Exception) -> int:
    """The exit code of an error: 3 ("could not decide") when a numerical solver failed on
    input that passed every check (:class:`~dppverify.errors.LPError`), else 2 (bad input).

    Examples
    --------
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
        return (f"error: could not decide: {text} (a numerical failure of the checker on a "
                "valid input, not an error in it)")
    return f"error: {text}"


def _fail(exc: CheckerError) -> None:
    if (sig := as_signal(exc)) is not None:  # interrupted: the signal's line and code
        click.echo(interrupt_message(sig), err=True)
        raise click.exceptions.Exit(exit_code(sig))
    click.echo(error_line(exc), err=True)
    raise click.exceptions.Exit(error_code(exc))


def _numbers(rec: CheckRecord) -> str:
    text = " ".join(f"{k}={show(v)}" for k, v in rec.numbers.items() if v is not None)
    return text if len(text) <= NUMBERS_WIDTH else text[:NUMBERS_WIDTH - 3] + "..."


def format_table(cert: Certificate) -> str:
    """The human-readable certificate: a header line and one row per check.

    Parameters
    ----------
    cert : Certificate
        The result of :func:`~dppverify.certify.certify`.

    Returns
    -------
    str
        What ``dpp certify`` prints without ``--json``.

    Examples
    --------
    >>> from dppverify.examples import triangle_document
    >>> profile = {"format": "dpp-profile/1", "goals": {"primary": "g1", "secondary": "g2"},
    ...     "defender": {"rule": "progress", "goal": "g1"},
    ...     "attacker": {"primary": [{"path": ["s", "g1"], "probability": "4/7"},
    ...                              {"path": ["s", "g2"], "probability": "3/7"}],
    ...                  "secondary": [{"path": ["s", "g2"], "probability": 1}]}}
    >>> lines = format_table(certify(triangle_document(), profile)).splitlines()
    >>> len(lines), lines.index(CONSISTENCY_HEADING)
    (22, 19)
    >>> for line in lines[:2] + lines[5:7]:  # doctest: +NORMALIZE_WHITESPACE
    ...     print(line)
    verdict: PASS (17/17 checks passed; 2/2 consistency checks agree; H = 1, 3 prefixes,
      exact; LP CLARABEL agreement within 1e-07 relative)
    check      status  numbers                      message
    value.U    pass    U=12/5 U_lp=2.4 U_tree=12/5  U = 12/5, LP evaluation 2.4
    value.VoI  pass    U_bar=27/10 VoI=1/9          U_bar = 27/10, VoI = 1/9
    """
    counts = cert.counts()
    passed, total = counts["check"]
    tally = f"{passed}/{total} checks passed"
    if counts["consistency"][1]:
        tally += "; {}/{} consistency checks agree".format(*counts["consistency"])
    mode = "exact" if cert.exact else f"float mode, relative tolerance {cert.tolerance:g}"
    if cert.route == "structured":
        h = "inf" if cert.horizon is None else str(cert.horizon)
        skipped = f"; not run: {', '.join(cert.not_run)}" if cert.not_run else ""
        head = (f"verdict: {cert.verdict.upper()} ({tally}; "
                f"H = {h}, structured route (no walk tree), {mode}{skipped})")
    else:
        both = ", both routes" if cert.route == "both" else ""
        head = (f"verdict: {cert.verdict.upper()} ({tally}; "
                f"H = {cert.horizon}, {cert.prefixes} prefixes{both}, {mode}; LP "
                f"{cert.lp_solver} agreement within {cert.lp_tolerance:g} relative)")
    evidence = [(c.id, c.status, _numbers(c), c.message) for c in cert.of_kind("check")]
    own = [(c.id, c.status, _numbers(c), c.message) for c in cert.of_kind("consistency")]
    rows = [("check", "status", "numbers", "message"), *evidence, *own]
    w0 = max(len(r[0]) for r in rows)
    w1 = max(len(r[1]) for r in rows)
    w2 = max(len(r[2]) for r in rows)
    lines = [head] + [f"{a:<{w0}}  {b:<{w1}}  {c:<{w2}}  {d}".rstrip()
                      for a, b, c, d in rows[:1 + len(evidence)]]
    if own:
        lines.append(CONSISTENCY_HEADING)
        lines += [f"{a:<{w0}}  {b:<{w1}}  {c:<{w2}}  {d}".rstrip() for a, b, c, d in own]
    return "\n".join(lines)


class HorizonParam(click.ParamType):
    """A horizon: a non-negative integer, or ``inf`` for the untruncated game (None)."""

    name = "H|inf"
    infinite: Any = None
    """What ``inf`` converts to."""

    def convert(self, value: Any, param: click.Parameter | None,
                ctx: click.Context | None) -> Any:
        if value is None or isinstance(value, int):
            return value
        text = str(value).strip().lower()
        if text in ("inf", "infinity"):
            return self.infinite
        try:
            h = int(text)
        except ValueError:
            self.fail(f"{value!r} is not a non-negative integer or 'inf'", param, ctx)
        if h < 0:
            self.fail(f"{value!r} is negative", param, ctx)
        if h > MAX_HORIZON:
            self.fail(f"{value!r} is beyond the limit of {MAX_HORIZON}", param, ctx)
        return h


HORIZON = HorizonParam()


class CertifyHorizonParam(HorizonParam):
    """``certify``'s horizon: ``inf`` is the string ``"inf"`` (None means the default)."""

    infinite = "inf"


def load_game(instance: str | None, grid: MapRequest | None) -> Instance:
    """The instance of a command: the INSTANCE file or the ``--map`` option group's grid.

    Examples
    --------
    >>> import json, os, tempfile
    >>> from dppverify.examples import triangle_document
    >>> with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
    ...     json.dump(triangle_document(), f)
    >>> load_game(f.name, None).nodes
    ('s', 'g1', 'g2')
    >>> os.unlink(f.name)
    """
    instance_or_map(instance, grid)
    if grid is not None:
        return grid.instance()
    assert instance is not None
    return load_instance(instance)


@click.command("certify")
@click.argument("instance", required=False, type=click.Path(dir_okay=False))
@click.argument("profile", required=False, type=click.Path(dir_okay=False), metavar="PROFILE")
@map_options
@click.option("-H", "--horizon", type=CertifyHorizonParam(),
              help="Horizon H of the truncated game (default: the longest profile path, or "
                   "'inf' when that tree does not fit and --route is auto), or 'inf' for the "
                   "untruncated game (structured route).")
@click.option("--route", type=click.Choice(ROUTES), default="auto", show_default=True,
              help="tree: the walk tree; structured: shortest paths and the value DP, no tree "
                   "(docs/checker.md); auto: the tree when it fits --max-prefixes, else "
                   "structured; both: run both, a disagreement is an error record.")
@click.option("--json", "as_json", is_flag=True, help="Print the dpp-certificate/1 JSON.")
@click.option("--max-prefixes", type=click.IntRange(min=1, max=MAX_PREFIXES_LIMIT),
              default=DEFAULT_MAX_PREFIXES,
              show_default=True, help="Refuse walk trees larger than this.")
@click.option("--float", "float_mode", is_flag=True,
              help="Accept float-mode instances (\"numbers\": \"float\") and compare within a "
                   "relative tolerance of 1e-9 instead of refusing them.")
@click.option("--seed", type=int, default=0, show_default=True,
              help="Seed of the random attackers of the L3/L4 checks.")
@click.option("--trials", type=click.IntRange(min=0, max=MAX_TRIALS), default=DEFAULT_TRIALS,
              show_default=True,
              help="Number of random attackers in the L3/L4 checks.")
@progress_option
def certify_command(instance: str | None, profile: str | None, grid: MapRequest | None,
                    horizon: int | str | None, route: Route, as_json: bool, max_prefixes: int,
                    float_mode: bool, seed: int, trials: int, progress: bool | None) -> None:
    """Certify (exit 0) or refute (exit 1) PROFILE as a weak PBNE of INSTANCE.

    PROFILE is a dpp-profile/1 JSON file (from `dpp solve -o` or any other solver); for an
    instance with more than two goals, a dpp-ngoal-profile/1 file (docs/formats.md). With
    --map, the game is the grid and the only argument is PROFILE. Bad input exits 2 with a
    one-line message.

    \b
    Examples:
      dpp solve examples/triangle.json -o profile.json
      dpp certify examples/triangle.json profile.json
      dpp certify examples/triangle.json profile.json --horizon 4 --json
      dpp certify examples/triangle.json profile.json --horizon inf
      dpp certify --map m.map --start 2,0 --goals 0,3 0,0 --prior 0.6,0.4 profile.json
    """
    try:
        if grid is not None and profile is not None:
            raise OptionError(f"with --map, certify takes only PROFILE (got {instance!r} and "
                              f"{profile!r})")
        if grid is not None:
            instance, profile = None, instance
        if profile is None:
            raise OptionError("missing PROFILE: dpp certify INSTANCE PROFILE, or "
                              f"dpp certify {MAP_USAGE} PROFILE")
        if instance is not None and is_ngoal_file(instance):  # N > 2 goals: dppverify.ngoal
            cert = certify_ngoal(instance, profile, horizon=horizon,  # type: ignore[arg-type]
                                 max_prefixes=max_prefixes, route=route)
        else:
            cert = certify(load_game(instance, grid), profile,
                           horizon=horizon,  # type: ignore[arg-type]
                           exact=not float_mode, max_prefixes=max_prefixes, seed=seed,
                           trials=trials, progress=want_progress(progress), route=route)
    except CheckerError as exc:
        _fail(exc)
        return
    if as_json:
        click.echo(json.dumps(cert.to_json(), indent=2, ensure_ascii=False))
    else:
        click.echo(format_table(cert))
    raise click.exceptions.Exit(0 if cert.passed else 1)




def _show_horizon(h: int | None) -> str:
    return "inf" if h is None else str(h)


def value_document(v: GameValue) -> dict[str, Any]:
    """The JSON that ``dpp value --json`` prints for the tree route."""
    b = v.bracket
    return {
        "horizon": v.horizon,
        "route": "tree",
        "value_lp": v.lp.value,
        "value": format_number(b.exact),
        "lower": format_number(b.lower),
        "upper": format_number(b.upper),
        "lower_source": b.lower_source,
        "upper_source": b.upper_source,
        "exact": v.exact and b.closed,
        "lp": {"solver": LP_SOLVER, "status": v.lp.status, "tolerance": LP_TOLERANCE,
               "seconds": round(v.lp.seconds, 3), "variables": v.lp.variables,
               "constraints": v.lp.constraints},
        "tree": {"prefixes": v.prefixes, "leaves": v.leaves},
    }


def structured_document(v: StructuredValue) -> dict[str, Any]:
    """The JSON that ``dpp value --json`` prints for the structured route."""
    return {
        "horizon": "inf" if v.horizon is None else v.horizon,
        "route": "structured",
        "value": format_number(v.value),
        "lower": format_number(v.value),
        "upper": format_number(v.value),
        "exact": v.exact,
        "dp": {"D1": format_number(v.d1), "D2": format_number(v.d2), "m": format_number(v.m),
               "steps": v.steps, "fixpoint": v.fixpoint, "arithmetic": v.arithmetic,
               "seconds": round(v.seconds, 3)},
    }


def routed_document(r: RoutedValue) -> dict[str, Any]:
    """The JSON of ``dpp value --json``: one route's document, or both with ``agree``."""
    if r.route == "tree":
        assert r.tree is not None
        return value_document(r.tree)
    assert r.structured is not None
    if r.route == "structured":
        return structured_document(r.structured)
    assert r.tree is not None
    doc = value_document(r.tree)
    doc.update(route="both", structured=structured_document(r.structured),
               agree=r.disagreement is None)
    if r.disagreement is not None:
        doc["disagreement"] = r.disagreement
    return doc


def _tree_line(v: GameValue) -> str:
    b = v.bracket
    exact = (f"{show(b.exact)} exactly" if b.closed and v.exact else
             f"in [{show(b.lower)}, {show(b.upper)}]")
    return (f"V_H (H = {v.horizon}) = {exact}; LP value {show(v.lp.value)} "
            f"({LP_SOLVER}, agreement tolerance {LP_TOLERANCE:g} relative, "
            f"{v.prefixes} prefixes, {v.lp.seconds:.2f} s)")


def _structured_line(v: StructuredValue) -> str:
    how = "exactly" if v.exact else f"(float mode, {v.arithmetic})"
    fix = ", fixpoint reached" if v.fixpoint else ""
    return (f"V_H (H = {_show_horizon(v.horizon)}) = {show(v.value)} {how}; structured route "
            f"({v.steps} DP steps{fix}, {v.arithmetic}, {v.seconds:.2f} s)")


def _ngoal_value(instance: str, horizon: int | None, as_json: bool, route: Route,
                 max_prefixes: int) -> None:
    """``dpp value`` for an instance with more than two goals (dppverify.ngoal.routes)."""
    try:
        r = nrouted_value(load_ninstance(instance), horizon, route=route,
                          max_prefixes=max_prefixes)
    except CheckerError as exc:
        _fail(exc)
        return
    if as_json:
        click.echo(json.dumps(nrouted_document(r), indent=2))
    else:
        for line in nrouted_lines(r):
            click.echo(line)
    if r.disagreement is not None:
        click.echo(f"error: {r.disagreement}", err=True)
        raise click.exceptions.Exit(1)


@click.command("value")
@click.argument("instance", required=False, type=click.Path(dir_okay=False))
@map_options
@click.option("-H", "--horizon", type=HORIZON, required=True,
              help="Horizon H of the truncated game, or 'inf' for the untruncated game "
                   "(structured route).")
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON.")
@click.option("--route", type=click.Choice(ROUTES), default="auto", show_default=True,
              help="tree: the walk tree's LP; structured: the tree-free DP (docs/checker.md); "
                   "auto: the tree when it fits --max-prefixes, else structured; both: run "
                   "both, a disagreement is an error (exit 1).")
@click.option("--max-prefixes", type=click.IntRange(min=1, max=MAX_PREFIXES_LIMIT),
              default=DEFAULT_MAX_PREFIXES,
              show_default=True, help="Refuse walk trees larger than this.")
@progress_option
def value_command(instance: str | None, grid: MapRequest | None, horizon: int | None,
                  as_json: bool, route: Route, max_prefixes: int,
                  progress: bool | None) -> None:
    """Print V_H, the value of INSTANCE's game truncated at H steps.

    Tree route: the compact LP (cvxpy + Clarabel) on the walk tree gives a float; rounding
    its primal and dual solutions to rationals gives exact bounds, which usually meet.
    Structured route: three hop-bounded Bellman-Ford fields (proofs/DP.md), exact on
    rational instances, polynomial in the graph; `--horizon inf` is the untruncated game.
    Instances with more than two goals: the tree LP with N types, and as structured route
    the coalition DP over goal subsets (exact; conjectured equal to V_H, proofs/NGOAL.md).

    \b
    Examples:
      dpp value examples/triangle.json --horizon 4
      dpp value examples/triangle.json -H 4 --json --route both
      dpp value examples/triangle.json --horizon inf
      dpp value --map m.map --start 2,0 --goals 0,3 0,0 --prior 0.6,0.4 -H 6
    """
    if instance is not None and grid is None and is_ngoal_file(instance):
        _ngoal_value(instance, horizon, as_json, route, max_prefixes)
        return
    try:
        r = routed_value(load_game(instance, grid), horizon, route=route,
                         max_prefixes=max_prefixes, progress=want_progress(progress))
    except CheckerError as exc:
        _fail(exc)
        return
    if as_json:
        click.echo(json.dumps(routed_document(r), indent=2))
    else:
        if r.tree is not None:
            click.echo(_tree_line(r.tree))
        if r.structured is not None:
            click.echo(_structured_line(r.structured))
    if r.disagreement is not None:
        click.echo(f"error: {r.disagreement}", err=True)
        raise click.exceptions.Exit(1)


@click.command("export-efg")
@click.argument("instance", required=False, type=click.Path(dir_okay=False))
@map_options
@click.option("-H", "--horizon", type=click.IntRange(min=0, max=MAX_HORIZON), required=True,
              help="Horizon H of the truncated game.")
@output_file_option("The .efg file to write (atomically).", required=True)
@click.option("--attacker-observes/--attacker-blind", default=True, show_default=True,
              help="Whether the Attacker's information sets include the Defender's past "
                   "allocations (the value is the same either way).")
@click.option("--forced-moves", is_flag=True,
              help="Also write the Attacker's one-action decision nodes (skipped by default: "
                   "Gambit 17.0.0b2's lp_solve mis-solves one-action information sets).")
@click.option("--max-prefixes", type=click.IntRange(min=1, max=MAX_PREFIXES_LIMIT),
              default=DEFAULT_MAX_PREFIXES,
              show_default=True, help="Refuse walk trees larger than this.")
@click.option("--max-nodes", type=click.IntRange(min=1), default=DEFAULT_MAX_EFG_NODES,
              show_default=True, help="Refuse games with more nodes than this.")
@progress_option
def export_efg_command(instance: str | None, grid: MapRequest | None, horizon: int,
                       output: str, attacker_observes: bool, forced_moves: bool,
                       max_prefixes: int, max_nodes: int, progress: bool | None) -> None:
    """Write INSTANCE's game truncated at H steps as a Gambit .efg file.

    Chance draws the Attacker's goal, the Attacker picks each next node, the Defender
    allocates each step to a goal (information set: the walk plus its own past allocations,
    so the game has perfect recall); payoffs sit on the leaves only. Gambit and OpenSpiel
    read the file; every copy of a t-step walk prefix appears 2^t times (N^t with N goals:
    an instance may list N > 2 goals, docs/formats.md), so keep H small.

    \b
    Examples:
      dpp export-efg examples/triangle.json --horizon 2 -o triangle.efg
      dpp export-efg examples/triangle.json -H 3 -o game.efg --attacker-blind
      dpp export-efg --map m.map --start 2,0 --goals 0,3 0,0 --prior 0.6,0.4 -H 2 -o g.efg
    """
    goals = ""
    try:
        refuse_input_as_output(output, [instance, grid.path if grid is not None else None])
        game: GameInstance
        if instance is not None and grid is None and is_ngoal_file(instance):  # N > 2 goals
            game = load_ninstance(instance)
            goals = f"N = {game.n_goals} goals, "
        else:
            game = load_game(instance, grid)
        size = write_efg(output, game, horizon,
                         attacker_observes=attacker_observes, forced_moves=forced_moves,
                         max_prefixes=max_prefixes, max_nodes=max_nodes,
                         progress=want_progress(progress))
    except CheckerError as exc:
        _fail(exc)
        return
    status(f"wrote {output}: {goals}H = {horizon}, {size.nodes} game nodes ({size.terminals} "
           f"terminals), {size.attacker_infosets} Attacker and {size.defender_infosets} "
           f"Defender information sets")


COMMANDS: list[click.Command] = [certify_command, value_command, export_efg_command, audit_command]
