"""The example files shipped with the package, named ``examples:NAME`` from any folder.

Three files are package data (``dppio/data/``): ``examples:triangle`` (``triangle.json``, the
smallest two-goal instance with every phase of the game, U* = 12/5), ``examples:paper10``
(``paper10.map``, the paper's 10×10 MovingAI map) and ``examples:paper10-selection``
(``paper10-selection.json``, the goal-selection game on that map, V_sel = 25/2). Every command
that reads an instance file or a ``--map`` accepts the name (``dpp solve examples:triangle``,
``dpp certify --map examples:paper10 ...``), and so does the ``map`` of a
``dpp-map-instance/1`` document; the ``--help`` examples and the notebook therefore run outside
a clone of the repository, whose ``examples/`` folder links to the same files. In Python,
:func:`example_path` gives the file.

This is the one place that locates a bundled example, shared by both packages (each passes its
own error class as ``error=``, like every check of :mod:`dppio`); :data:`INSTANCE_FILE` is the
click type of every command's instance argument, which resolves the name at the door.
"""

from __future__ import annotations

import importlib.resources
from pathlib import Path
from typing import Any

import click

from dppio.errors import ErrorClass, InputError

__all__ = ["EXAMPLES", "INSTANCE_FILE", "PREFIX", "InstanceFile", "display_name",
           "example_names", "example_path", "resolve_input"]

PREFIX = "examples:"
"""Values starting with this name a bundled example."""

EXAMPLES = {"triangle": "triangle.json", "paper10": "paper10.map",
            "paper10-selection": "paper10-selection.json"}
"""Each bundled example's name and its file in ``dppio/data/``."""


def example_names() -> tuple[str, ...]:
    """The names of the bundled examples, sorted.

    Returns
    -------
    tuple of str
        The names ``NAME`` of ``examples:NAME``.

    Examples
    --------
    >>> example_names()
    ('paper10', 'paper10-selection', 'triangle')
    """
    return tuple(sorted(EXAMPLES))


def example_path(name: str, *, error: ErrorClass = InputError) -> Path:
    """The file of the bundled example ``name`` (with or without the ``examples:`` prefix or
    the file's suffix).

    Parameters
    ----------
    name : str
        ``NAME``, ``examples:NAME`` or the file's name (``triangle.json``).
    error : callable, default InputError
        The error class to raise, called with the one-line message.

    Returns
    -------
    pathlib.Path
        The file inside the installed package (``dppio/data/``).

    Raises
    ------
    InputError
        (or ``error``) An unknown name: the message lists the bundled ones.

    Examples
    --------
    >>> example_path("paper10").read_text().splitlines()[:3]
    ['type octile', 'height 10', 'width 10']
    >>> example_path("examples:triangle.json").name
    'triangle.json'
    >>> example_path("square")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppio.errors.InputError: unknown example 'square'; bundled: examples:paper10 (paper10.map), ...
    """
    stem = name.removeprefix(PREFIX)
    stem = next((n for n, file in EXAMPLES.items() if stem in (n, file)), stem)
    if stem not in EXAMPLES:
        raise error(f"unknown example {stem!r}; bundled: "
                    + ", ".join(f"{PREFIX}{n} ({EXAMPLES[n]})" for n in example_names()))
    path = importlib.resources.files("dppio") / "data" / EXAMPLES[stem]
    if not isinstance(path, Path) or not path.is_file():  # an installation without its data
        raise error(f"the installed dppverify has no {EXAMPLES[stem]} ({path})")
    return path


def resolve_input(value: str, *, error: ErrorClass = InputError) -> str:
    """The file an input argument names: ``examples:NAME`` or a path (returned as is).

    Parameters
    ----------
    value : str
        An instance argument or a ``--map`` value.
    error : callable, default InputError
        The error class to raise for an unknown example, called with the one-line message.

    Returns
    -------
    str
        The path of the file.

    Raises
    ------
    InputError
        (or ``error``) An unknown example name.

    Examples
    --------
    >>> resolve_input("my/instance.json")
    'my/instance.json'
    >>> Path(resolve_input("examples:triangle")).name
    'triangle.json'
    """
    return str(example_path(value, error=error)) if value.startswith(PREFIX) else value


def display_name(path: str | Path) -> str:
    """How messages name a file: ``examples:NAME`` for a bundled example's file, else the path.

    Parameters
    ----------
    path : str or pathlib.Path
        A file a command read.

    Returns
    -------
    str
        ``examples:NAME``, or the path as given.

    Examples
    --------
    >>> display_name(example_path("paper10")), display_name("my/instance.json")
    ('examples:paper10', 'my/instance.json')
    """
    try:  # the package's own file, not a link to it (the repository's examples/ links)
        given = Path(path).absolute()
        for name in EXAMPLES:
            if given == example_path(name).absolute():
                return PREFIX + name
    except (OSError, InputError):  # an odd path, or an installation without its data
        pass
    return str(path)


class InstanceFile(click.Path):
    """An instance file argument: a path, or ``examples:NAME`` for a bundled example, resolved
    to its file here (an unknown name is a usage error: one line, exit 2).

    Examples
    --------
    >>> Path(INSTANCE_FILE.convert("examples:triangle", None, None)).name
    'triangle.json'
    >>> INSTANCE_FILE.convert("mine.json", None, None)
    'mine.json'
    """

    def __init__(self) -> None:
        super().__init__(dir_okay=False)

    def convert(self, value: Any, param: click.Parameter | None,
                ctx: click.Context | None) -> Any:
        if isinstance(value, str) and value.startswith(PREFIX):
            try:
                value = resolve_input(value)
            except InputError as exc:
                self.fail(str(exc), param, ctx)
        return super().convert(value, param, ctx)


INSTANCE_FILE = InstanceFile()
"""The click type of an instance argument (``dpp solve``, ``certify``, ``value``, ...)."""
