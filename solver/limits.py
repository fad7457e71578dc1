"""The solver's own limits (its options); the limits both packages share are in
:mod:`dppio.limits` (listed in the README, "Limits").

Beyond each limit the solver refuses with one line (exit code 2) instead of hanging or
exhausting memory. The shared checks raise the solver's
:class:`~solver.errors.InvalidInstanceError` when given ``error=InvalidInstanceError``.

Examples
--------
>>> MAX_DENSITY_SIZE, MAX_DENSITY_GRIDS
(200, 100000)
"""

from __future__ import annotations

MAX_DENSITY_SIZE = 200
"""Largest grid side of ``dpp experiment density --size``."""

MAX_DENSITY_GRIDS = 100_000
"""Most grids of one density sweep (samples x densities)."""

MAP_BYTES_PER_CELL = 512
"""Memory of the solver's two-goal game per free cell of a ``--map`` (measured: about 460 MB
for ``dpp solve`` on a 2000 x 2000 empty map, with room for the commands that evaluate
baselines on it). An N-goal solve, certified by the checker before it is written, takes
about 3 KiB per cell for three goals (measured: 2.4 GB on 1000 x 1000) and doubles with
each further goal. A map whose estimate is beyond the memory the process may use is refused
before the game is built (:func:`map_memory`)."""


def map_memory(free_cells: int, n_goals: int) -> int:
    """The estimated memory (bytes) of the solver's command on a grid of ``free_cells`` free
    cells with ``n_goals`` goals.

    Examples
    --------
    >>> map_memory(4_000_000, 2) // 2**20, map_memory(1_000_000, 3) // 2**20
    (1953, 2929)
    """
    if n_goals <= 2:
        return free_cells * MAP_BYTES_PER_CELL
    return free_cells * 3 * 1024 * 2 ** (n_goals - 3)
