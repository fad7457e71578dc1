"""``dpp certify``: certify or refute a profile, print the certificate, record its provenance.

Exit codes: 0 (every check passes), 1 (refuted), 3 (could not decide: an ``error`` or
``incomplete`` verdict, or an undecidable untruncated game), 2 (bad input, one line). With
``--verify-provenance CERT`` it certifies nothing: it checks the hashes CERT recorded.
"""

from __future__ import annotations

import dataclasses
import json
import os
import sys
from dataclasses import dataclass
from typing import Any

import click

from dppio.cli.conventions import (
    PhaseBar,
    emit,
    output_file_option,
    progress_option,
    status,
    want_progress,
)
from dppio.cli.map_options import MAP_USAGE, instance_or_map
from dppio.examples import INSTANCE_FILE
from dppio.inputs import reading_once
from dppverify.certificate import Certificate
from dppverify.cli.belongs import profile_mismatch
from dppverify.cli.errors import fail
from dppverify.cli.inputs import HORIZON, hinted, max_prefixes_option, read_game
from dppverify.cli.map_options import MapRequest, map_options
from dppverify.cli.selection import selection_options
from dppverify.cli.table import format_table
from dppverify.errors import CertificateError, CheckerError, OptionError, ProfileError
from dppverify.formats.files import read_input, refuse_input_as_output
from dppverify.game.inputs import Parsed, read_profile
from dppverify.game.instance import Instance
from dppverify.game.profile import Profile, Stated
from dppverify.limits import DEFAULT_TRIALS, MAX_TRIALS
from dppverify.provenance import command_line, map_identity, verify_provenance
from dppverify.routes import ROUTES, Route

__all__ = ["VERDICT_EXIT", "certify_command"]


@click.command("certify", short_help="Certify or refute a profile as a PBNE of an instance.")
@click.argument("instance", required=False, type=INSTANCE_FILE)
@click.argument("profile", required=False, type=click.Path(dir_okay=False), metavar="PROFILE")
@selection_options
@map_options
@click.option("-H", "--horizon", type=HORIZON,
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
@max_prefixes_option()
@click.option("--float", "float_mode", is_flag=True,
              help="Float mode is detected from the instance (\"numbers\": \"float\", e.g. "
                   "--connectivity 8): it is compared within a relative tolerance of 1e-9. "
                   "This flag is accepted for old scripts and changes nothing.")
@click.option("--seed", type=int, default=0, show_default=True,
              help="Seed of the random attackers of the L3/L4 checks.")
@click.option("--trials", type=click.IntRange(min=0, max=MAX_TRIALS), default=DEFAULT_TRIALS,
              show_default=True,
              help="Number of random attackers in the L3/L4 checks.")
@click.option("--witness", type=click.Path(dir_okay=False),
              help="Also write the dpp-witness/1 of the untruncated game to this file "
                   "(atomically): the numbers `dpp check` verifies with the trusted kernel "
                   "(docs/formats.md §5).")
@click.option("--verify-provenance", "provenance_of", metavar="CERT",
              type=click.Path(dir_okay=False),
              help="Do not certify: check that CERT (a certificate JSON) records the sha256 of "
                   "INSTANCE and PROFILE (exit 0), or say in one line what differs (exit 1).")
@progress_option
def certify_command(**params: Any) -> None:
    """Certify (exit 0) or refute (exit 1) PROFILE as a weak PBNE of INSTANCE's game (exit 3:
    could not decide).

    Without --horizon the game is the untruncated one (H = inf); --horizon H certifies the
    game truncated at H, and the verdict says so. The paper's lemmas are reported beside the
    verdict as facts and never decide it. PROFILE is a dpp-profile/1 JSON file (from `dpp
    solve -o` or any other solver); for an instance with more than two goals, a
    dpp-ngoal-profile/1 file (docs/formats.md). With --map, the game is the grid and the only
    argument is PROFILE; either file may be - (standard input). Bad input (a file that is
    not JSON or not a profile document) exits 2 with a one-line message; a profile that
    names other goals or states a wrong prior or value is refuted (exit 1) by the check
    that names it, with a note when it looks made for another instance; a profile the
    untruncated game cannot be decided for (a table Defender without "default") exits 3.
    Float-mode instances (8-connected maps) are detected and compared within a relative
    tolerance of 1e-9.

    \b
    Examples:
      dpp solve examples:triangle -o profile.json
      dpp certify examples:triangle profile.json
      dpp certify examples:triangle profile.json --json
      dpp certify examples:triangle profile.json -o certificate.json
      dpp certify examples:triangle profile.json --horizon 4
      dpp certify examples:triangle profile.json --witness w.json
      dpp certify --map m.map --start 2,0 --goals 0,3 0,0 --prior 0.6,0.4 profile.json
      dpp certify --verify-provenance cert.json examples:triangle profile.json
      dpp certify examples:paper10-selection selection-profile.json

    Goal selection (a goal-selection INSTANCE, or --goal-selection with --map): PROFILE is a
    dpp-selection-profile/1 (or a dpp-profile/1, whose prior is read as the Attacker's
    choice); the untruncated game only; the checks of the game with prior q plus
    selection.goal_indifference and selection.value (dppverify/checks.md, "Goal selection").
    """
    with reading_once():  # each input read once: the certificate hashes the bytes parsed
        _certify_files(_Request(**params))


@dataclass(frozen=True)
class _Request:
    """The options of one ``dpp certify`` run, as click parsed them."""

    instance: str | None
    profile: str | None
    grid: MapRequest | None
    horizon: int | None
    route: Route
    as_json: bool
    output: str | None
    max_prefixes: int
    float_mode: bool
    seed: int
    trials: int
    witness: str | None
    provenance_of: str | None
    progress: bool | None
    goal_selection: bool = False  # read by the --map group (the grid carries them)
    goal_values: str | None = None


def _certify_files(req: _Request) -> None:
    """The body of :func:`certify_command` (inside its ``reading_once`` block)."""
    bar = PhaseBar(want_progress(req.progress), "certify", "reading the instance")
    instance, profile, grid, output = req.instance, req.profile, req.grid, req.output
    try:
        if grid is not None and profile is not None:
            raise OptionError(f"with --map, certify takes only PROFILE (got {instance!r} and "
                              f"{profile!r})")
        if grid is not None:
            instance, profile = None, instance
        if profile is None and req.provenance_of is not None:
            raise OptionError("missing INSTANCE or PROFILE: dpp certify --verify-provenance "
                              "CERT INSTANCE PROFILE (with --map: CERT PROFILE)")
        if profile is None:
            raise OptionError("missing PROFILE: dpp certify INSTANCE PROFILE, or "
                              f"dpp certify {MAP_USAGE} PROFILE")
        refuse_input_as_output(output, [instance, profile, grid.path if grid else None])
        refuse_input_as_output(req.witness, [instance, profile, output,
                                             grid.path if grid else None])
        if req.witness is not None and req.horizon is not None:
            raise OptionError("--witness is for the untruncated game (the kernel decides no "
                              "truncated game): drop --horizon")
        if req.provenance_of is not None:
            bar.close()
            _verify_provenance(req.provenance_of, instance, profile, grid)
            return
        game = read_game(instance, grid)
        if req.witness is not None and not game.value.exact:
            raise OptionError("--witness: the trusted kernel decides exact games only; this "
                              "instance is in float mode")
        if req.witness is not None and game.value.goal_selection:
            raise OptionError("--witness: the trusted kernel does not decide the goal-selection "
                              "game (proofs/SELECT.md); the certificate's checks do")
        bar.phase("reading the profile")
        prof = _read_profile(profile, game.value, instance)
        bar.phase(f"certifying (route {req.route}; the checks' bars follow)")
        from dppverify.certify import certify  # here: a refused input never loads the checks

        cert = certify(game, prof, horizon=req.horizon,
                       exact=game.value.exact and not req.float_mode,
                       max_prefixes=req.max_prefixes, seed=req.seed, trials=req.trials,
                       progress=want_progress(req.progress), route=req.route)
    except CheckerError as exc:
        bar.close()
        fail(exc)
    bar.close()
    reason = profile_mismatch(game.value, prof.value.stated)
    if reason is not None and cert.verdict != "pass":  # refuted; say why it looks foreign
        status(f"note: {profile} looks made for another instance: {reason} (make a profile "
               f"for this one with {_solve_hint(instance)} -o PROFILE)")
    assert cert.provenance is not None  # certify records what it parsed
    cert = dataclasses.replace(cert, provenance={**cert.provenance, "command": _command()})
    if req.witness is not None:
        from dppverify.cli.witness import engine_witness, write_witness

        write_witness(req.witness, engine_witness(game.value, prof.value, cert.provenance or {}))
    summary = format_table(cert).split("\n", 1)[0].removeprefix("verdict: ")
    emit(cert.to_json(), format_table(cert), as_json=req.as_json, output=output,
         summary=summary)
    raise click.exceptions.Exit(VERDICT_EXIT[cert.verdict])


VERDICT_EXIT = {"pass": 0, "fail": 1, "error": 3, "incomplete": 3}
"""``dpp certify``'s exit code per verdict: an ``error`` (the checker's own computations
disagree, e.g. an LP solver failing on a badly scaled valid input) or an ``incomplete``
verdict (a check could not run) decides nothing, so it is "could not decide" (3), never a
refutation (1)."""


def _read_profile(path: str, game: Instance, instance: str | None) -> Parsed[Profile]:
    """The profile file at ``path``, read once (not JSON, or not a profile document of the
    game's format: bad input, one line, naming the game it looks made for when it can be
    told). Whatever it says about the game is the certificate's business: a claim or a goal
    that disagrees with the instance is refuted by a named check (docs/formats.md, "One
    verdict")."""
    with hinted(path, "profile"):
        try:
            return read_profile(path, game)
        except ProfileError as exc:
            reason = (profile_mismatch(game, exc.stated) if isinstance(exc.stated, Stated)
                      else None)
            if reason is None:
                raise
            raise ProfileError(f"{exc}; it looks made for another instance: {reason} (make a "
                               f"profile for this one with {_solve_hint(instance)} -o "
                               f"PROFILE)") from None


def _solve_hint(instance: str | None) -> str:
    """The ``dpp solve`` command that makes a profile for this game."""
    return f"dpp solve {instance}" if instance is not None else "dpp solve --map ..."


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


def _verify_provenance(cert_path: str, instance: str | None, profile: str,
                       grid: MapRequest | None) -> None:
    """``dpp certify --verify-provenance``: one line; exit 0 (match), 1 (mismatch), 2."""
    try:
        raw = read_input(cert_path)
    except (OSError, ValueError) as exc:
        raise CertificateError(f"{cert_path}: cannot read the certificate ({exc})") from None
    try:
        doc = json.loads(raw)
    except (ValueError, RecursionError) as exc:  # not JSON, not UTF-8, an integer of 5000 digits
        raise CertificateError(f"{cert_path}: the certificate is not JSON ({exc})") from None
    if not isinstance(doc, dict) or doc.get("format") != "dpp-certificate/1":
        raise CertificateError(f"{cert_path}: not a dpp-certificate/1 document")
    try:
        Certificate.from_json(doc)  # well-formed, and its verdict agrees with its checks
    except CertificateError as exc:
        raise CertificateError(f"{cert_path}: {exc}") from None
    if grid is not None:
        result = verify_provenance(doc, map_identity(grid.document()), profile,
                                   map_file=grid.path)
    else:
        instance_or_map(instance, grid)
        result = verify_provenance(doc, instance, profile)
    click.echo(result.line)
    raise click.exceptions.Exit(0 if result.ok else 1)


