"""``dpp solve`` for N > 2 goals: solve, certify with the independent checker, then write.

Only the command line composes the solver and the checker (``dppverify`` never imports
``solver``). The profile is written only when ``dpp certify --route structured --horizon inf``
would print PASS for it; otherwise one line says why (usually: the arc condition of
proofs/NSOLVE.md cannot be established, as on the N = 4 gadget of proofs/NSOLVE.md) and the
command exits 3 with nothing written.
"""

from __future__ import annotations

from typing import Any

import click

from dppverify.cli_conventions import status
from dppverify.map_options import MapRequest, instance_or_map
from solver.errors import InvalidInstanceError
from solver.instance_json import read_json
from solver.io_utils import dumps, write_atomic
from solver.movingai import read_map
from solver.ngoal_equilibrium import nequilibrium_to_json, solve_ngoal
from solver.ngoal_instance import NGame, ngame_from_grid, ngame_from_json

__all__ = ["ngoal_game", "solve_ngoal_command"]


def ngoal_game(instance: str | None, grid: MapRequest | None) -> NGame | None:
    """The N-goal game of a solver command, or None when it has two goals."""
    instance_or_map(instance, grid)
    if grid is not None:
        if grid.n_goals <= 2:
            return None
        try:
            return ngame_from_grid(read_map(grid.path), grid.start, grid.goals, grid.prior)
        except InvalidInstanceError as exc:
            raise InvalidInstanceError(f"{grid.map}: {exc}") from None
    assert instance is not None
    doc = read_json(instance)
    if not (isinstance(doc, dict) and isinstance(doc.get("goals"), list)
            and len(doc["goals"]) > 2):
        return None
    try:
        return ngame_from_json(doc)
    except InvalidInstanceError as exc:
        raise InvalidInstanceError(f"{instance}: {exc}") from None


def _instance_document(game: NGame) -> dict[str, Any]:
    """The instance JSON of an N-goal game (exact weights as strings)."""
    from fractions import Fraction

    from solver.instance_json import node_to_json

    net = game.network
    den = game.denominator
    nodes = [{"id": node_to_json(net.labels[i])} for i in range(net.n_nodes)
             if net.indptr[i + 1] > net.indptr[i] or i == game.start or i in game.goals]
    edges = []
    for i in range(net.n_nodes):
        heads, ws = net.out_arcs(i)
        for j, w in zip(heads.tolist(), ws.tolist(), strict=True):
            edges.append({"source": node_to_json(net.labels[i]),
                          "target": node_to_json(net.labels[j]),
                          "weight": str(Fraction(int(w), den))})
    return {"graph": {"directed": True, "multigraph": False, "graph": {}, "nodes": nodes,
                      "edges": edges},
            "start": node_to_json(net.labels[game.start]),
            "goals": [node_to_json(net.labels[g]) for g in game.goals],
            "prior": [str(b) for b in game.prior]}


def solve_ngoal_command(game: NGame, instance: str | None, grid: MapRequest | None,
                        as_json: bool, output: str | None, save_instance: str | None) -> None:
    """Solve, certify, and write (or refuse in one line, exit 3)."""
    from dppverify.ngoal.certify import certify_ngoal

    eq = solve_ngoal(game)
    doc = nequilibrium_to_json(eq)
    checked = grid.ninstance() if grid is not None else instance
    assert checked is not None
    cert = certify_ngoal(checked, doc, horizon="inf", route="structured")
    if cert.verdict != "pass":
        bad = next((c for c in cert.checks if c.status not in ("pass", "skipped")), None)
        why = "" if bad is None else f": {bad.id}: {' '.join(bad.message.split())}"
        click.echo(f"error: the coalition construction does not give a certified equilibrium "
                   f"on this instance{why}; nothing written", err=True)
        raise click.exceptions.Exit(3)
    text = dumps(doc)
    instance_text = dumps(_instance_document(game)) if save_instance is not None else None
    if output is not None:
        write_atomic(output, text)
    if save_instance is not None and instance_text is not None:
        write_atomic(save_instance, instance_text)
    if as_json:
        click.echo(text, nl=False)
    elif output is None:
        click.echo(f"N = {game.n_goals} goals: U = {eq.U} (certified: structured route, "
                   f"H = inf), VoI = {eq.VoI}, U_bar = {eq.U_bar}; type costs "
                   f"{[str(c) for c in eq.costs]}; Defender: guarantee rule h = "
                   f"{[str(x) for x in eq.h]}")
    else:
        status(f"wrote {output}: U = {doc['value']['U']}, VoI = {doc['value']['VoI']} "
               f"(N = {game.n_goals} goals, certified)")
    if save_instance is not None:
        status(f"wrote {save_instance}: the instance")
