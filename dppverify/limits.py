"""The checker's own limits (its options); the numeric and size limits both packages share
are in :mod:`dppio.limits` (listed in the README, "Limits").

Beyond each limit the checker refuses with one line (exit code 2) instead of hanging or
exhausting memory.

Examples
--------
>>> MAX_HORIZON, MAX_TRIALS, MAX_AUDIT_EXAMPLES, MAX_LP_CELLS
(10000, 10000, 1000000, 100000)
"""

from __future__ import annotations

MAX_HORIZON = 10_000
"""Largest horizon H of a truncated game (``--horizon``)."""

MAX_TRIALS = 10_000
"""Most random attackers per L3/L4 lemma check (``--trials``)."""

DEFAULT_TRIALS = 5
"""Random non-reacting attackers tried by the L3 and L4 checks (``--trials``' default)."""

MAX_AUDIT_EXAMPLES = 1_000_000
"""Largest example budget of ``dpp audit --examples``."""

MAX_LP_CELLS = 100_000
"""N goals: the most (goal, prefix) pairs of a walk tree's LP, which has one variable per goal
and prefix (the size rule of N goals; two goals have ``--max-prefixes`` alone). Measured: a
star of 300 goals at H = 2 (90,000 pairs) takes about 25 s, one of 500 goals (250,000) about
110 s, one of 1,000 goals did not finish in 5 minutes."""

MAX_GOALS = 1_000
"""Most goals of an instance: reading one computes the distances to every goal (one
shortest-path pass each), so the count is bounded before any of them (5,000 goals on a
5,000-node star took a minute to read)."""

MAP_BYTES_PER_CELL = 1024
"""Memory of the checker's grid game per free cell of a ``--map`` with two goals (measured:
about 980 MB for ``dpp value`` on a 1000 x 1000 empty map); each further goal doubles it
(the N-goal guarantee sets range over goal subsets). A map whose estimate is beyond the
memory the process may use is refused before the game is built (:func:`map_memory`)."""


def map_memory(free_cells: int, n_goals: int) -> int:
    """The estimated memory (bytes) of the checker's game on a grid of ``free_cells`` free
    cells with ``n_goals`` goals.

    Examples
    --------
    >>> map_memory(1_000_000, 2) // 2**20, map_memory(1_000_000, 3) // 2**20
    (976, 1953)
    """
    return free_cells * MAP_BYTES_PER_CELL * 2 ** max(0, n_goals - 2)
