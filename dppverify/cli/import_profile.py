"""``dpp import-profile``: a Gambit or OpenSpiel behaviour profile of the game ``dpp export-efg``
wrote, as a ``dpp-profile/1`` (two goals) or ``dpp-ngoal-profile/1`` of the truncated game,
for ``dpp certify --horizon H`` (its exact exploitability).

The game is rebuilt from the instance with the export's options (``-H``,
``--attacker-observes/--attacker-blind``, ``--forced-moves``), never read from the peer's
side; the profile's information sets must be exactly the export's
(:mod:`dppverify.formats.peer_profiles` reads the three forms,
:mod:`dppverify.tree_route.efg_profile` converts).
"""

from __future__ import annotations

import json

import click

from dppio.cli.conventions import (
    output_file_option,
    progress_option,
    status,
    want_progress,
)
from dppio.cli.map_options import MAP_USAGE
from dppio.examples import INSTANCE_FILE, display_name
from dppverify.cli.errors import fail
from dppverify.cli.export_efg import efg_game_options
from dppverify.cli.inputs import load_game
from dppverify.cli.map_options import MapRequest, map_options
from dppverify.errors import CheckerError, OptionError
from dppverify.formats.files import refuse_input_as_output, write_files
from dppverify.formats.peer_profiles import rationalise, read_peer_profile
from dppverify.limits import MAX_HORIZON
from dppverify.tree_route.efg_profile import (
    exported_action_names,
    exported_infosets,
    profile_from_behaviour,
)
from dppverify.tree_route.tree import build_tree

DEFAULT_TOLERANCE = 1e-9
"""How far a float probability may move to the simplest rational near it."""


@click.command("import-profile",
               short_help="Read a Gambit or OpenSpiel profile of the exported .efg game.")
@click.argument("instance", required=False, type=INSTANCE_FILE)
@click.argument("peer_profile", required=False, type=click.Path(dir_okay=False))
@map_options
@click.option("-H", "--horizon", type=click.IntRange(min=0, max=MAX_HORIZON), required=True,
              help="The horizon H the .efg game was exported with.")
@output_file_option("The dpp-profile/1 (two goals) or dpp-ngoal-profile/1 to write "
                    "(atomically).", required=True)
@efg_game_options  # as dpp export-efg: the same game
@click.option("--tolerance", type=click.FloatRange(min=0, max=1e-3), default=DEFAULT_TOLERANCE,
              show_default=True,
              help="A float probability becomes the simplest rational within this distance (0: "
                   "its exact binary value); each distribution is then scaled to sum to 1.")
@progress_option
def import_profile_command(instance: str | None, peer_profile: str | None,
                           grid: MapRequest | None, horizon: int, output: str,
                           attacker_observes: bool, forced_moves: bool, tolerance: float,
                           max_prefixes: int, max_nodes: int, progress: bool | None) -> None:
    """Write PEER_PROFILE, a behaviour profile of INSTANCE's game exported by dpp export-efg,
    as a profile of the game truncated at H, for dpp certify --horizon H.

    PEER_PROFILE is Gambit's profile line (NE,p1,p2,... as gambit-lp or gambit-lcp print
    it), a JSON object {infoset label: {action label: probability}} (e.g. from pygambit), or
    OpenSpiel's tabular policy saved with json.dump(policy.to_dict(), f). Exact probabilities
    (p/q) stay exact; floats become rationals within --tolerance, and the report says by how
    much they moved. dpp certify then states the profile's exact exploitability (NashConv).

    \b
    Examples:
      dpp export-efg examples:triangle -H 2 -o game.efg --attacker-blind
      dpp import-profile examples:triangle policy.json -H 2 --attacker-blind -o p.json
      dpp certify examples:triangle p.json -H 2
      dpp import-profile --map examples:paper10 --start 9,0 --goals 0,9 0,0 --prior 0.6,0.4 \\
          ne.csv -H 3 -o p.json
    """
    try:
        if grid is not None and peer_profile is not None:
            raise OptionError(f"with --map, import-profile takes only PEER_PROFILE (got "
                              f"{instance!r} and {peer_profile!r})")
        if grid is not None:
            instance, peer_profile = None, instance
        if peer_profile is None:
            raise OptionError("missing PEER_PROFILE: dpp import-profile INSTANCE PEER_PROFILE "
                              f"-H H -o OUT, or dpp import-profile {MAP_USAGE} PEER_PROFILE "
                              "-H H -o OUT")
        refuse_input_as_output(output, [instance, peer_profile,
                                        grid.path if grid is not None else None])
        peer = read_peer_profile(peer_profile)
        game = load_game(instance, grid, "dpp import-profile")
        tree = build_tree(game, horizon, max_prefixes=max_prefixes,
                          progress=want_progress(progress))
        infosets = exported_infosets(tree, attacker_observes=attacker_observes,
                                     forced_moves=forced_moves, max_nodes=max_nodes)
        names = exported_action_names(tree, attacker_observes=attacker_observes,
                                      forced_moves=forced_moves, max_nodes=max_nodes)
        behaviour = peer.behaviour(infosets, names)
        exact, report = rationalise(behaviour, tolerance)
        solver = {"name": peer.source, "imported_by": "dpp import-profile",
                  "from": peer.description,
                  "game": {"horizon": horizon, "attacker_observes": attacker_observes,
                           "forced_moves": forced_moves},
                  "rationalised": report.to_json()}
        imported = profile_from_behaviour(tree, exact, attacker_observes=attacker_observes,
                                          forced_moves=forced_moves, solver=solver)
        write_files({output: json.dumps(imported.document, indent=1) + "\n"})
    except CheckerError as exc:
        fail(exc)
    doc = imported.document
    target = "dpp certify " + (display_name(instance) if instance is not None else "--map ...")
    status(f"wrote {output}: {doc['format']} of the game truncated at H = {horizon}, from "
           f"{peer.description} ({report.summary()}); its exact exploitability: {target} "
           f"{output} --horizon {horizon}")
    if imported.history_dependent:
        status(f"note: at {imported.history_dependent} of the Attacker's decisions the peer's "
               "moves depend on the Defender's past allocations, which a walk mixture cannot "
               "express: the imported walks are those the profile realises against its own "
               "Defender (export with --attacker-blind for a profile that keeps its "
               "exploitability)")
