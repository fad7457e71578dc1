"""What the checker's commands read: the horizon option, the walk-tree size limit
(``--max-prefixes``), the instance (a file or ``--map``), and read errors turned into hints.

``-H/--horizon`` is read by :data:`HORIZON` into the one horizon type of the package
(:mod:`dppverify.horizons`): a non-negative integer ``H``, or None for the untruncated game
(``inf``, the default).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar

import click

from dppio.cli.hints import Kind
from dppio.cli.hints import hinted as shared_hinted
from dppio.cli.map_options import instance_or_map
from dppio.limits import MAX_PREFIXES_LIMIT
from dppverify.cli.map_options import MapRequest
from dppverify.errors import CheckerError
from dppverify.game.inputs import Parsed, read_instance
from dppverify.game.instance import Instance, instance_from_json
from dppverify.horizons import INFINITE_WORDS
from dppverify.limits import MAX_HORIZON
from dppverify.provenance import map_identity
from dppverify.tree_route.tree import DEFAULT_MAX_PREFIXES

__all__ = ["HORIZON", "HorizonParam", "hinted", "load_game", "max_prefixes_option", "read_game"]

F = TypeVar("F", bound=Callable[..., Any])


class HorizonParam(click.ParamType):
    """A horizon: a non-negative integer, or ``inf`` for the untruncated game (None).

    Examples
    --------
    >>> [HORIZON.convert(v, None, None) for v in ("4", "inf", "Infinity", None, 3)]
    [4, None, None, None, 3]
    """

    name = "H|inf"

    def convert(self, value: Any, param: click.Parameter | None,
                ctx: click.Context | None) -> int | None:
        if value is None or isinstance(value, int):
            return value
        text = str(value).strip().lower()
        if text in INFINITE_WORDS:
            return None
        try:
            h = int(text)
        except ValueError:
            self.fail(f"{value!r} is not a non-negative integer or 'inf'", param, ctx)
        if h < 0:
            self.fail(f"{value!r} is negative", param, ctx)
        if h > MAX_HORIZON:
            self.fail(f"{value!r} is beyond the limit of {MAX_HORIZON}", param, ctx)
        return h


HORIZON = HorizonParam()


def max_prefixes_option(help: str = "Refuse walk trees larger than this.",
                        default: int = DEFAULT_MAX_PREFIXES) -> Callable[[F], F]:
    """``--max-prefixes N`` (parameter ``max_prefixes``): the largest walk tree a command
    builds, from 1 to the package's limit.

    Examples
    --------
    >>> from click.testing import CliRunner
    >>> @click.command()
    ... @max_prefixes_option()
    ... def cmd(max_prefixes: int) -> None:
    ...     click.echo(max_prefixes)
    >>> [CliRunner().invoke(cmd, args).output.strip() for args in ([], ["--max-prefixes", "9"])]
    ['1000000', '9']
    """
    return click.option("--max-prefixes", type=click.IntRange(min=1, max=MAX_PREFIXES_LIMIT),
                        default=default, show_default=True, help=help)


def load_game(instance: str | None, grid: MapRequest | None,
              command: str = "dpp certify") -> Instance:
    """The instance of a command, two or N goals (:func:`read_game`'s value).

    Examples
    --------
    >>> import json, os, tempfile
    >>> from dppverify.game.examples import triangle_document
    >>> with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
    ...     json.dump(triangle_document(), f)
    >>> load_game(f.name, None).nodes
    ('s', 'g1', 'g2')
    >>> os.unlink(f.name)
    """
    return read_game(instance, grid, command).value


def read_game(instance: str | None, grid: MapRequest | None,
              command: str = "dpp certify") -> Parsed[Instance]:
    """The instance of a command and what was parsed: the INSTANCE file (read once, through
    the door :func:`~dppverify.game.inputs.read_instance`; a read error becomes a hint when the
    file is of another kind), or the ``--map`` option group's grid (its compact map instance,
    ``map`` cut to the file's name, and the ``.map`` file's sha256:
    :func:`~dppverify.provenance.map_identity`); with ``--goal-selection`` the grid's
    goal-selection game.

    Examples
    --------
    >>> from dppio.examples import example_path
    >>> read_game(str(example_path("triangle")), None).value.nodes
    ('s', 'g1', 'g2')
    >>> from dppio.cli.map_options import map_request
    >>> from dppverify.cli.map_options import MapRequest
    >>> grid = map_request(str(example_path("paper10")), "9,0", ("0,9", "0,0"), None, None,
    ...                    request=MapRequest, goal_selection=True)
    >>> game = read_game(None, grid, "dpp value").value
    >>> game.goal_selection, game.n_goals
    (True, 2)
    """
    instance_or_map(instance, grid)
    if grid is not None and grid.goal_selection:  # the goal-selection game of the grid
        doc = grid.selection_document()
        return Parsed(instance_from_json(doc), map_identity(doc),
                      (str(grid.path), doc["map_sha256"]))
    if grid is not None:
        doc = grid.document()
        return Parsed(grid.game(), map_identity(doc), (str(grid.path), doc["map_sha256"]),
                      folder=grid.path.resolve().parent)
    assert instance is not None  # instance_or_map: one of the two
    with hinted(instance, "instance", command):
        return read_instance(instance)


def hinted(path: str, kind: Kind, command: str = "dpp certify") -> shared_hinted:
    """:class:`dppio.cli.hints.hinted` for the checker's errors: a read error of ``path``
    becomes the hint of :func:`~dppio.cli.hints.file_hint` when it has one.

    Examples
    --------
    >>> with hinted("/nowhere/x.map", "instance"):  # doctest: +ELLIPSIS
    ...     read_instance("/nowhere/x.map")
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: /nowhere/x.map is a MovingAI .map file: give it as ...
    """
    return shared_hinted(path, kind, command, errors=(CheckerError,))
