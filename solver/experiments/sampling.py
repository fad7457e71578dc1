"""Random obstacle grids for the density sweep (paper Sec. VII-D), reproducible per sample.

Sample ``k`` at density ``p`` (percent) with seed ``s`` draws from
``numpy.random.default_rng([s, p, k])``: the same grid whatever the worker or the order.
Exactly ``round(p/100 · H·W)`` obstacles are placed uniformly among the cells other than
the start and the goals; a draw is rejected and redrawn until each goal can be reached from
the start by a 4-connected path avoiding the other goal.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import ndimage

from solver.errors import InvalidInstanceError

Cell = tuple[int, int]
MAX_ATTEMPTS = 100_000
"""Give up (an error) after this many rejected draws of one sample."""


@dataclass(frozen=True, eq=False)
class GridSample:
    """One accepted grid: obstacles (True = blocked) and the number of draws it took."""

    blocked: np.ndarray
    attempts: int


def goals_separately_reachable(blocked: np.ndarray, start: Cell, goals: tuple[Cell, Cell]) -> bool:
    """Whether each goal has a 4-connected path from ``start`` that avoids the other goal.

    Examples
    --------
    >>> b = np.zeros((1, 3), dtype=bool)
    >>> goals_separately_reachable(b, (0, 1), ((0, 0), (0, 2)))
    True
    >>> goals_separately_reachable(b, (0, 0), ((0, 1), (0, 2)))   # g2 only through g1
    False
    """
    for goal, other in ((goals[0], goals[1]), (goals[1], goals[0])):
        free = ~blocked
        free[other] = False
        labels, _ = ndimage.label(free)
        if labels[start] == 0 or labels[start] != labels[goal]:
            return False
    return True


def sample_grid(size: int, density: int, sample: int, seed: int, start: Cell,
                goals: tuple[Cell, Cell]) -> GridSample:
    """Draw sample ``sample`` of the ``size × size`` grids at ``density`` percent.

    Examples
    --------
    >>> g = sample_grid(20, 30, 0, 0, (19, 0), ((0, 19), (0, 0)))
    >>> int(g.blocked.sum()), bool(g.blocked[19, 0])
    (120, False)
    >>> bool((sample_grid(20, 30, 0, 0, (19, 0), ((0, 19), (0, 0))).blocked == g.blocked).all())
    True
    """
    if not 0 <= density < 100:
        raise InvalidInstanceError(f"density must be a percentage in [0, 100), got {density}")
    special = {start, *goals}
    n = size * size
    keep = np.array([r * size + c for r, c in special], dtype=np.int64)
    candidates = np.setdiff1d(np.arange(n), keep)
    count = round(density / 100 * n)
    if count > candidates.size:
        raise InvalidInstanceError(f"density {density}% leaves no room for start and goals")
    rng = np.random.default_rng([seed, density, sample])
    for attempt in range(1, MAX_ATTEMPTS + 1):
        blocked = np.zeros(n, dtype=bool)
        blocked[rng.choice(candidates, size=count, replace=False)] = True
        grid = blocked.reshape(size, size)
        if goals_separately_reachable(grid, start, goals):
            return GridSample(grid, attempt)
    raise InvalidInstanceError(f"no valid grid at density {density}% after {MAX_ATTEMPTS} "
                               f"draws (sample {sample})")
