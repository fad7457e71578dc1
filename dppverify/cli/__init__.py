"""Checker commands of the ``dpp`` CLI (certify, value, export-efg).

``COMMANDS`` is the list the ``dpp`` group registers. Commands report
:class:`dppverify.errors.CheckerError` subclasses (bad input) as one line on stderr and exit
2 themselves, so they behave the same inside the solver's ``dpp`` group and in
``python -m dppverify``. ``dpp certify`` exits 0 only when every check passes and 1 when the
profile is refuted (or a check could not be completed).
"""

from __future__ import annotations

import dataclasses
import json
import os
import sys
from typing import Any

import click

from dppverify.certificate import Certificate, CheckRecord
from dppverify.certify import DEFAULT_TRIALS, certify
from dppverify.cli.audit import audit_command
from dppverify.cli.belongs import profile_mismatch
from dppverify.cli.conventions import (
    PhaseBar,
    output_file_option,
    progress_option,
    status,
    want_progress,
)
from dppverify.cli.hints import file_hint, what_is
from dppverify.cli.interrupts import Terminated, as_signal, exit_code, signals_as_exceptions
from dppverify.cli.interrupts import message as interrupt_message
from dppverify.cli.map_options import MAP_USAGE, MapRequest, instance_or_map, map_options
from dppverify.errors import (
    CertificateError,
    CheckerError,
    LPError,
    OptionError,
    ProfileError,
    UndecidedError,
)
from dppverify.exact import format_number
from dppverify.formats.files import read_input, refuse_input_as_output, write_files
from dppverify.game.instance import GameInstance as AnyGame
from dppverify.game.instance import Instance, load_instance
from dppverify.game.profile import load_profile_document
from dppverify.limits import MAX_HORIZON, MAX_PREFIXES_LIMIT, MAX_TRIALS
from dppverify.ngoal.certify import certify_ngoal
from dppverify.ngoal.instance import NInstance, load_ninstance
from dppverify.ngoal.routes import is_ngoal_file, nrouted_document, nrouted_lines, nrouted_value
from dppverify.provenance import (
    command_line,
    grid_document_of,
    grid_record,
    input_record,
    provenance_record,
    verify_provenance,
)
from dppverify.routes import ROUTES, Route, RoutedValue, routed_value
from dppverify.text import show, show_value
from dppverify.tree_route.efg import DEFAULT_MAX_EFG_NODES, write_efg
from dppverify.tree_route.lp import LP_SOLVER, LP_TOLERANCE
from dppverify.tree_route.tree import DEFAULT_MAX_PREFIXES
from dppverify.tree_route.value_lp import GameValue
from dppverify.twogoal.value_dp import StructuredValue

__all__ = ["COMMANDS", "CONSISTENCY_HEADING", "FACTS_HEADING", "HORIZON", "CertifyHorizonParam",
           "ErrorReportingGroup", "HorizonParam", "certify_command", "export_efg_command",
           "format_table", "load_game", "value_command"]

NUMBERS_WIDTH = 44

CONSISTENCY_HEADING = ("consistency checks (the checker's own computations compared; a failure "
                       "is the checker's fault, not counted above):")

FACTS_HEADING = ("facts about the profile and the instance (the paper's lemmas, whether this is "
                 "the paper's construction; reported beside the verdict, never deciding it):")



class ErrorReportingGroup(click.Group):
    """A click group for the ``dpp`` commands: bad input is one line and exit 2.

    Errors of the classes in :attr:`user_errors` are the user's (bad input): one line on
    stderr, ``error: ...``, exit code 2. Anything else is an internal failure: one line, exit
    code 3, no traceback (set ``DPP_DEBUG=1`` to see it). Subclasses add their package's error
    classes (``dpp``'s group adds the solver's).
    """

    user_errors: tuple[type[Exception], ...] = (CheckerError,)

    def main(self, *args: Any, **kwargs: Any) -> Any:
        """Run the command with SIGINT/SIGTERM/SIGHUP as exceptions (dppverify.cli.interrupts):
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
        except UndecidedError as exc:  # "could not decide": exit 3
            click.echo(f"undecided: {' '.join(str(exc).split())}", err=True)
            ctx.exit(3)
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
    if isinstance(exc, UndecidedError):  # "could not decide": exit 3, never a verdict
        click.echo(f"undecided: {' '.join(str(exc).split())}", err=True)
        raise click.exceptions.Exit(3)
    if (sig := as_signal(exc)) is not None:  # interrupted: the signal's line and code
        click.echo(interrupt_message(sig), err=True)
        raise click.exceptions.Exit(exit_code(sig))
    click.echo(error_line(exc), err=True)
    raise click.exceptions.Exit(error_code(exc))


def _short(x: Any) -> str:
    """A number for the table: floats (LP values) with 6 significant digits, else ``show``."""
    return f"{x:.6g}" if isinstance(x, float) else show(x)


def _numbers(rec: CheckRecord) -> list[str]:
    """The record's numbers as ``key=value`` items, wrapped into lines of NUMBERS_WIDTH.

    Nothing is cut: a number too long for a line is shown as a decimal (``text.show``); its
    exact form is in the ``--json`` certificate.
    """
    lines: list[str] = []
    for item in (f"{k}={_short(v)}" for k, v in rec.numbers.items() if v is not None):
        if lines and len(lines[-1]) + 1 + len(item) <= NUMBERS_WIDTH:
            lines[-1] += " " + item
        else:
            lines.append(item)
    return lines or [""]


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
    >>> from dppverify.game.examples import triangle_document
    >>> profile = {"format": "dpp-profile/1", "goals": {"primary": "g1", "secondary": "g2"},
    ...     "defender": {"rule": "progress", "goal": "g1"},
    ...     "attacker": {"primary": [{"path": ["s", "g1"], "probability": "4/7"},
    ...                              {"path": ["s", "g2"], "probability": "3/7"}],
    ...                  "secondary": [{"path": ["s", "g2"], "probability": 1}]}}
    >>> lines = format_table(certify(triangle_document(), profile, horizon=1)).splitlines()
    >>> lines.index(CONSISTENCY_HEADING) < lines.index(FACTS_HEADING), "..." in "".join(lines)
    (True, False)
    >>> for line in lines[:2] + lines[6:8]:  # doctest: +NORMALIZE_WHITESPACE
    ...     print(line)
    verdict: PASS for the game truncated at H = 1 (11/11 checks passed; 2/2 consistency checks
      agree; 6/6 facts hold; 3 prefixes, exact; LP CLARABEL agreement within 1e-07 relative)
    note: this certifies the game truncated at H = 1 only, not the full (untruncated) game;
      omit the horizon to certify the untruncated game
    value.U    pass    U=12/5 U_lp=2.4 U_tree=12/5  U = 12/5, LP evaluation 2.4
    value.VoI  pass    U_bar=27/10 VoI=1/9          U_bar = 27/10, VoI = 1/9
    >>> format_table(certify(triangle_document(), profile)).splitlines()[0][:50]
    'verdict: PASS for the untruncated game (H = inf) ('
    """
    counts = cert.counts()
    passed, total = counts["check"]
    tally = f"{passed}/{total} checks passed"
    if counts["consistency"][1]:
        tally += "; {}/{} consistency checks agree".format(*counts["consistency"])
    if counts["fact"][1]:
        tally += "; {}/{} facts hold".format(*counts["fact"])
    mode = "exact" if cert.exact else f"float mode, relative tolerance {cert.tolerance:g}"
    game = cert.game_line()
    if cert.route == "structured":
        skipped = f"; not run: {', '.join(cert.not_run)}" if cert.not_run else ""
        head = (f"verdict: {cert.verdict.upper()} for {game} ({tally}; structured route (no "
                f"walk tree), {mode}{skipped})")
    else:
        both = ", both routes" if cert.route == "both" else ""
        head = (f"verdict: {cert.verdict.upper()} for {game} ({tally}; "
                f"{cert.prefixes} prefixes{both}, {mode}; LP "
                f"{cert.lp_solver} agreement within {cert.lp_tolerance:g} relative)")
    evidence = [(c.id, c.status, _numbers(c), c.message) for c in cert.of_kind("check")]
    own = [(c.id, c.status, _numbers(c), c.message) for c in cert.of_kind("consistency")]
    facts = [(c.id, c.status, _numbers(c), c.message) for c in cert.of_kind("fact")]
    rows = [("check", "status", ["numbers"], "message"), *evidence, *own, *facts]
    w0 = max(len(r[0]) for r in rows)
    w1 = max(len(r[1]) for r in rows)
    w2 = max(len(x) for r in rows for x in r[2])

    def row(a: str, b: str, c: list[str], d: str) -> list[str]:
        first = f"{a:<{w0}}  {b:<{w1}}  {c[0]:<{w2}}  {d}".rstrip()
        return [first, *(f"{'':<{w0}}  {'':<{w1}}  {x}".rstrip() for x in c[1:])]

    note = cert.truncation_note()
    lines = [head] + ([f"note: {note}"] if note else [])
    for r in rows[:1 + len(evidence)]:
        lines += row(*r)
    for heading, group in ((CONSISTENCY_HEADING, own), (FACTS_HEADING, facts)):
        if group:
            lines.append(heading)
            for r in group:
                lines += row(*r)
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


def load_game(instance: str | None, grid: MapRequest | None,
              command: str = "dpp certify") -> Instance:
    """The instance of a command: the INSTANCE file or the ``--map`` option group's grid.

    Examples
    --------
    >>> import json, os, tempfile
    >>> from dppverify.game.examples import triangle_document
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
    with hinted(instance, "instance", command):
        return load_instance(instance)


def load_ngame(instance: str, command: str) -> NInstance:
    """The N-goal instance at ``instance``, a read error hinted as :func:`load_game`'s."""
    with hinted(instance, "instance", command):
        return load_ninstance(instance)


class hinted:
    """Context manager: a read error of ``path`` becomes :func:`~dppverify.cli.hints.file_hint`'s
    hint (the file is of another kind: swapped arguments, a ``.map`` file, ...) when it has one.

    Examples
    --------
    >>> import os, tempfile
    >>> d = tempfile.mkdtemp()
    >>> m = os.path.join(d, "x.map")
    >>> _ = open(m, "w").write("type octile\\n")
    >>> with hinted(m, "instance"):  # doctest: +ELLIPSIS
    ...     load_instance(m)
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: .../x.map is a MovingAI .map file: give it as ...
    """

    def __init__(self, path: str, kind: Any, command: str = "dpp certify",
                 errors: tuple[type[Exception], ...] = (CheckerError,)) -> None:
        self.path, self.kind, self.command, self.errors = path, kind, command, errors

    def __enter__(self) -> None:
        return None

    def __exit__(self, kind: Any, exc: Any, tb: Any) -> None:
        if isinstance(exc, self.errors):
            hint = file_hint(self.path, self.kind, self.command)
            if hint is not None:
                raise type(exc)(hint) from None


@click.command("certify", short_help="Certify or refute a profile as a PBNE of an instance.")
@click.argument("instance", required=False, type=click.Path(dir_okay=False))
@click.argument("profile", required=False, type=click.Path(dir_okay=False), metavar="PROFILE")
@map_options
@click.option("-H", "--horizon", type=CertifyHorizonParam(),
              help="Certify the game truncated at H steps instead (an explicit request; the "
                   "verdict then names that game). Default, or 'inf': the untruncated game, "
                   "by the structured route.")
@click.option("--route", type=click.Choice(ROUTES), default="auto", show_default=True,
              help="tree: the walk tree; structured: shortest paths and the value DP, no tree "
                   "(docs/checker.md); auto: the tree when it fits --max-prefixes, else "
                   "structured; both: run both, a disagreement is an error record.")
@click.option("--json", "as_json", is_flag=True,
              help="Print the dpp-certificate/1 JSON instead of the table.")
@output_file_option("Write the dpp-certificate/1 JSON to this file (atomically); stdout stays "
                    "empty, the verdict is one line on stderr.")
@click.option("--max-prefixes", type=click.IntRange(min=1, max=MAX_PREFIXES_LIMIT),
              default=DEFAULT_MAX_PREFIXES,
              show_default=True, help="Refuse walk trees larger than this.")
@click.option("--float", "float_mode", is_flag=True,
              help="Float mode is detected from the instance (\"numbers\": \"float\", e.g. "
                   "--connectivity 8): it is compared within a relative tolerance of 1e-9. "
                   "This flag is accepted for old scripts and changes nothing.")
@click.option("--seed", type=int, default=0, show_default=True,
              help="Seed of the random attackers of the L3/L4 checks.")
@click.option("--trials", type=click.IntRange(min=0, max=MAX_TRIALS), default=DEFAULT_TRIALS,
              show_default=True,
              help="Number of random attackers in the L3/L4 checks.")
@click.option("--verify-provenance", "provenance_of", metavar="CERT",
              type=click.Path(dir_okay=False),
              help="Do not certify: check that CERT (a certificate JSON) records the sha256 of "
                   "INSTANCE and PROFILE (exit 0), or say in one line what differs (exit 1).")
@progress_option
def certify_command(instance: str | None, profile: str | None, grid: MapRequest | None,
                    horizon: int | str | None, route: Route, as_json: bool,
                    output: str | None, max_prefixes: int, float_mode: bool, seed: int,
                    trials: int, provenance_of: str | None, progress: bool | None) -> None:
    """Certify (exit 0) or refute (exit 1) PROFILE as a weak PBNE of INSTANCE's game (exit 3:
    could not decide).

    Without --horizon the game is the untruncated one (H = inf); --horizon H certifies the
    game truncated at H, and the verdict says so. The paper's lemmas are reported beside the
    verdict as facts and never decide it. PROFILE is a dpp-profile/1 JSON file (from `dpp
    solve -o` or any other solver); for an instance with more than two goals, a
    dpp-ngoal-profile/1 file (docs/formats.md). With --map, the game is the grid and the only
    argument is PROFILE. Bad input exits 2 with a one-line message, a profile made for another
    instance (other goals, prior, start or map) too; a profile the untruncated game cannot be
    decided for (a table Defender without "default") exits 3. Float-mode instances
    (8-connected maps) are detected and compared within a relative tolerance of 1e-9.

    \b
    Examples:
      dpp solve examples/triangle.json -o profile.json
      dpp certify examples/triangle.json profile.json
      dpp certify examples/triangle.json profile.json --json
      dpp certify examples/triangle.json profile.json -o certificate.json
      dpp certify examples/triangle.json profile.json --horizon 4
      dpp certify --map m.map --start 2,0 --goals 0,3 0,0 --prior 0.6,0.4 profile.json
      dpp certify --verify-provenance cert.json examples/triangle.json profile.json
    """
    bar = PhaseBar(want_progress(progress), "certify", "reading the instance")
    try:
        if grid is not None and profile is not None:
            raise OptionError(f"with --map, certify takes only PROFILE (got {instance!r} and "
                              f"{profile!r})")
        if grid is not None:
            instance, profile = None, instance
        if profile is None and provenance_of is not None:
            raise OptionError("missing INSTANCE or PROFILE: dpp certify --verify-provenance "
                              "CERT INSTANCE PROFILE (with --map: CERT PROFILE)")
        if profile is None:
            raise OptionError("missing PROFILE: dpp certify INSTANCE PROFILE, or "
                              f"dpp certify {MAP_USAGE} PROFILE")
        refuse_input_as_output(output, [instance, profile, grid.path if grid else None])
        if provenance_of is not None:
            bar.close()
            _verify_provenance(provenance_of, instance, profile, grid)
            return
        if instance is not None and is_ngoal_file(instance):  # N > 2 goals: dppverify.ngoal
            game: AnyGame = load_ngame(instance, "dpp certify")
            bar.phase("reading the profile")
            doc = _profile_document(profile, game, instance)
            bar.phase(f"certifying (route {route})")
            del doc  # read again by certify_ngoal, which checks its format tag
            cert = certify_ngoal(game, profile,  # type: ignore[arg-type]
                                 horizon=horizon,  # type: ignore[arg-type]
                                 max_prefixes=max_prefixes, route=route)
        elif grid is not None and grid.n_goals > 2:  # an N-goal grid
            cert = certify_ngoal(grid.ninstance(), profile,
                                 horizon=horizon,  # type: ignore[arg-type]
                                 max_prefixes=max_prefixes, route=route)
        else:
            inst = load_game(instance, grid)
            bar.phase("reading the profile")
            doc = _profile_document(profile, inst, instance)
            bar.phase(f"certifying (route {route}; the checks' bars follow)")
            cert = certify(inst, doc, horizon=horizon,  # type: ignore[arg-type]
                           exact=inst.exact and not float_mode, max_prefixes=max_prefixes,
                           seed=seed, trials=trials, progress=want_progress(progress),
                           route=route)
    except CheckerError as exc:
        bar.close()
        _fail(exc)
        return
    bar.close()
    cert = _with_command(cert, instance, profile, grid)
    summary = format_table(cert).split("\n", 1)[0].removeprefix("verdict: ")
    emit(cert.to_json(), format_table(cert), as_json=as_json, output=output, summary=summary)
    raise click.exceptions.Exit(VERDICT_EXIT[cert.verdict])


VERDICT_EXIT = {"pass": 0, "fail": 1, "error": 3, "incomplete": 3}
"""``dpp certify``'s exit code per verdict: an ``error`` (the checker's own computations
disagree, e.g. an LP solver failing on a badly scaled valid input) or an ``incomplete``
verdict (a check could not run) decides nothing, so it is "could not decide" (3), never a
refutation (1)."""


def _profile_document(path: str, game: AnyGame, instance: str | None) -> dict[str, Any]:
    """The profile document at ``path``, refused in one line when it belongs to another game."""
    ngoal = len(game.goals) > 2
    with hinted(path, "profile"):
        if ngoal or what_is(path) == "dpp-ngoal-profile/1":  # (for two goals: not its game)
            from dppverify.formats.json_reading import JsonReadError, read_json_file

            try:
                doc = read_json_file(path, kind="profile")
            except JsonReadError as exc:
                raise ProfileError(f"{path}: {exc}") from None
        else:
            doc = load_profile_document(path)
    reason = profile_mismatch(game, doc)
    if reason is not None:
        solve = f"dpp solve {instance}" if instance is not None else "dpp solve --map ..."
        raise ProfileError(f"{path} does not belong to this instance: {reason}; make a "
                           f"profile for it with {solve} -o PROFILE")
    return dict(doc)


def emit(doc: Any, text: str, *, as_json: bool, output: str | None, summary: str) -> None:
    """The one output convention of the checker's commands.

    ``-o FILE``: the JSON document is written to FILE (atomically) and ``wrote FILE: SUMMARY``
    is the only line, on stderr (stdout stays empty, with or without ``--json``). Otherwise
    stdout gets the JSON (``--json``) or the text.

    Examples
    --------
    >>> emit({"a": 1}, "a = 1", as_json=False, output=None, summary="")
    a = 1
    >>> emit({"a": 1}, "a = 1", as_json=True, output=None, summary="")
    {
      "a": 1
    }
    """
    if output is not None:
        write_files({output: json.dumps(doc, indent=2, ensure_ascii=False) + "\n"})
        status(f"wrote {output}: {summary}")
    elif as_json:
        click.echo(json.dumps(doc, indent=2, ensure_ascii=False))
    else:
        click.echo(text)


def _with_command(cert: Certificate, instance: str | None, profile: str,
                  grid: MapRequest | None) -> Certificate:
    """The certificate with its provenance's command (and, for --map, the grid's hashes)."""
    prov = dict(cert.provenance or provenance_record(instance, profile, route=cert.route,
                                                     exact=cert.exact))
    prov["command"] = _command()
    prov["profile"] = input_record(profile)  # the file's bytes (certify was given its document)
    if grid is not None:
        prov["instance"] = grid_record(grid.path, _grid_document(grid))
    elif instance is not None:
        prov["instance"] = input_record(instance)
    return dataclasses.replace(cert, provenance=prov)


def _command() -> list[str]:
    """The command line of this run: ``sys.argv`` when the process is this command, else
    (e.g. invoked from Python) the command path and its parameters as ``name=value``."""
    ctx = click.get_current_context()
    root = ctx.find_root().info_name or ""
    if sys.argv and root == os.path.basename(sys.argv[0]):
        return command_line(sys.argv)
    if sys.argv and sys.argv[0].endswith("__main__.py") and root.startswith("python -m "):
        return [*root.split(), *sys.argv[1:]]  # python -m dppverify ...
    return [*ctx.command_path.split(), *(f"{k}={v}" for k, v in ctx.params.items()
                                         if v is not None)]


def _grid_document(grid: MapRequest) -> dict[str, Any]:
    return grid_document_of(grid.path, grid.start, grid.goals, grid.prior, grid.connectivity)


def _verify_provenance(cert_path: str, instance: str | None, profile: str,
                       grid: MapRequest | None) -> None:
    """``dpp certify --verify-provenance``: one line; exit 0 (match), 1 (mismatch), 2."""
    try:
        raw = read_input(cert_path)
    except (OSError, ValueError) as exc:
        raise CertificateError(f"{cert_path}: cannot read the certificate ({exc})") from None
    try:
        doc = json.loads(raw)
    except (json.JSONDecodeError, UnicodeDecodeError, RecursionError) as exc:
        raise CertificateError(f"{cert_path}: the certificate is not JSON ({exc})") from None
    if not isinstance(doc, dict) or doc.get("format") != "dpp-certificate/1":
        raise CertificateError(f"{cert_path}: not a dpp-certificate/1 document")
    try:
        Certificate.from_json(doc)  # well-formed, and its verdict agrees with its checks
    except CertificateError as exc:
        raise CertificateError(f"{cert_path}: {exc}") from None
    if grid is not None:
        result = verify_provenance(doc, _grid_document(grid), profile, map_file=grid.path)
    else:
        instance_or_map(instance, grid)
        result = verify_provenance(doc, instance, profile)
    click.echo(result.line)
    raise click.exceptions.Exit(0 if result.ok else 1)


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
        "open_reason": b.reason,
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
    exact = (f"{show_value(b.exact)} exactly" if b.closed and v.exact else
             f"in [{show_value(b.lower)}, {show_value(b.upper)}]"
             + (f" (open: {b.reason})" if b.reason else ""))
    return (f"V_H (H = {v.horizon}) = {exact}; LP value {show(v.lp.value)} "
            f"({LP_SOLVER}, agreement tolerance {LP_TOLERANCE:g} relative, "
            f"{v.prefixes} prefixes, {v.lp.seconds:.2f} s)")


def _structured_line(v: StructuredValue) -> str:
    how = "exactly" if v.exact else f"(float mode, {v.arithmetic})"
    fix = ", fixpoint reached" if v.fixpoint else ""
    return (f"V_H (H = {_show_horizon(v.horizon)}) = {show_value(v.value)} {how}; structured "
            f"route ({v.steps} DP steps{fix}, {v.arithmetic}, {v.seconds:.2f} s)")


def _ngoal_value(instance: str | MapRequest, horizon: int | None, as_json: bool, route: Route,
                 max_prefixes: int, output: str | None = None) -> None:
    """``dpp value`` for an instance with more than two goals (dppverify.ngoal.routes)."""
    try:
        game = (instance.ninstance() if isinstance(instance, MapRequest)
                else load_ngame(instance, "dpp value"))
        r = nrouted_value(game, horizon, route=route,
                          max_prefixes=max_prefixes)
    except CheckerError as exc:
        _fail(exc)
        return
    lines = list(nrouted_lines(r))
    emit(nrouted_document(r), "\n".join(lines), as_json=as_json, output=output,
         summary=lines[0] if lines else "")
    if r.disagreement is not None:
        click.echo(f"error: {r.disagreement}", err=True)
        raise click.exceptions.Exit(1)


@click.command("value", short_help="The value V_H of the game truncated at H steps.")
@click.argument("instance", required=False, type=click.Path(dir_okay=False))
@map_options
@click.option("-H", "--horizon", type=HORIZON, default=None,
              help="Horizon H of the truncated game (an explicit request), or 'inf' for the "
                   "untruncated game (structured route; the default).")
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON.")
@output_file_option("Write the result's JSON to this file (atomically); stdout stays empty, "
                    "the value is one line on stderr.")
@click.option("--route", type=click.Choice(ROUTES), default="auto", show_default=True,
              help="tree: the walk tree's LP; structured: the tree-free DP (docs/checker.md); "
                   "auto: the tree when it fits --max-prefixes, else structured; both: run "
                   "both, a disagreement is an error (exit 1).")
@click.option("--max-prefixes", type=click.IntRange(min=1, max=MAX_PREFIXES_LIMIT),
              default=DEFAULT_MAX_PREFIXES,
              show_default=True, help="Refuse walk trees larger than this.")
@progress_option
def value_command(instance: str | None, grid: MapRequest | None, horizon: int | None,
                  as_json: bool, output: str | None, route: Route, max_prefixes: int,
                  progress: bool | None) -> None:
    """Print the value of INSTANCE's game: untruncated (H = inf) unless --horizon H is given.

    Tree route: the compact LP (cvxpy + Clarabel) on the walk tree gives a float; rounding
    its primal and dual solutions to rationals gives exact bounds, which usually meet.
    Structured route: three hop-bounded Bellman-Ford fields (proofs/DP.md), exact on
    rational instances, polynomial in the graph; `--horizon inf` is the untruncated game.
    Instances with more than two goals: the tree LP with N types, and as structured route
    the guarantee sets: the coalition DP over goal subsets, the value for N <= 3 and, for
    N = 4, 5, where certified (else an exact bracket naming both bounds; proofs/NGOAL.md).

    \b
    Examples:
      dpp value examples/triangle.json
      dpp value examples/triangle.json --horizon 4
      dpp value examples/triangle.json -H 4 --json --route both
      dpp value examples/triangle.json -H 4 -o value.json
      dpp value --map m.map --start 2,0 --goals 0,3 0,0 --prior 0.6,0.4 -H 6
    """
    try:
        refuse_input_as_output(output, [instance, grid.path if grid else None])
    except CheckerError as exc:
        _fail(exc)
    if instance is not None and grid is None and is_ngoal_file(instance):
        _ngoal_value(instance, horizon, as_json, route, max_prefixes, output)
        return
    if grid is not None and grid.n_goals > 2 and instance is None:  # an N-goal grid
        _ngoal_value(grid, horizon, as_json, route, max_prefixes, output)
        return
    try:
        r = routed_value(load_game(instance, grid, "dpp value"), horizon, route=route,
                         max_prefixes=max_prefixes, progress=want_progress(progress))
    except CheckerError as exc:
        _fail(exc)
        return
    lines = ([_tree_line(r.tree)] if r.tree is not None else []) + \
        ([_structured_line(r.structured)] if r.structured is not None else [])
    emit(routed_document(r), "\n".join(lines), as_json=as_json, output=output,
         summary=lines[0])
    if r.disagreement is not None:
        click.echo(f"error: {r.disagreement}", err=True)
        raise click.exceptions.Exit(1)


@click.command("export-efg", short_help="Write the truncated game as a Gambit .efg file.")
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
        game: AnyGame
        if instance is not None and grid is None and is_ngoal_file(instance):  # N > 2 goals
            game = load_ngame(instance, "dpp export-efg")
            goals = f"N = {game.n_goals} goals, "
        elif grid is not None and grid.n_goals > 2 and instance is None:  # an N-goal grid
            game = grid.ninstance()
            goals = f"N = {game.n_goals} goals, "
        else:
            game = load_game(instance, grid, "dpp export-efg")
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
