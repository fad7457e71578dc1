"""Hypothesis strategies for grid worlds with obstacles (the paper's Sec. VII)."""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Sequence
from numbers import Real
from typing import Any

from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument

from dppverify.strategies.graphs import Doc, check_bool, check_int, weight_strategy
from dppverify.strategies.instances import priors as _prior_pairs


# ----------------------------------------------------------------------------- grid worlds
def grid_worlds(
    *,
    min_size: int = 2,
    max_size: int = 6,
    max_cells: int | None = None,
    max_density: float = 0.3,
    avoid_other_goal: bool = True,
    weights: str | st.SearchStrategy[Any] = "units",
    priors: st.SearchStrategy[Sequence[Any]] | None = None,
) -> st.SearchStrategy[Doc]:
    """Grid-world instance documents: 4-connected cells ``[row, col]`` with obstacles.

    Obstacles cover at most ``floor(max_density * rows * cols)`` cells, never the start or a
    goal. With ``avoid_other_goal`` (the paper's Sec. VII-D condition) the start differs from
    both goals and each goal is reachable from the start along a path that does not pass
    through the other goal; without it, the start and both goals are merely connected (the
    start may then be a goal). When the drawn obstacles violate the condition, the fewest
    obstacles on a repair path are removed (0-1 BFS), so every example is valid by
    construction and the realised density may be lower than drawn.

    Parameters
    ----------
    min_size, max_size : int
        Bounds on the number of rows and of columns (``min_size >= 2`` with
        ``avoid_other_goal``, else ``>= 1``).
    max_cells : int or None
        Bound on ``rows * cols`` (default ``max_size ** 2``).
    max_density : float
        Largest obstacle fraction, in ``[0, 1)``.
    avoid_other_goal : bool
        Enforce the condition above.
    weights : str or SearchStrategy
        Edge weights, as in :func:`weighted_graphs` (default ``"units"``: the paper's grids;
        named kinds draw from ``[1, 9]``).
    priors : SearchStrategy, optional
        Prior pairs (default :func:`priors`).

    Returns
    -------
    SearchStrategy of dict
        Grid instance documents (``docs/formats.md`` §1), node ids ``[row, col]``.

    Raises
    ------
    hypothesis.errors.InvalidArgument
        Bounds out of range or inconsistent (checked when the strategy is built).

    Examples
    --------
    >>> from hypothesis import find, settings
    >>> doc = find(grid_worlds(), lambda d: True, settings=settings(database=None))
    >>> [n["id"] for n in doc["graph"]["nodes"]], doc["start"], doc["goals"]
    ([[0, 0], [0, 1], [1, 0], [1, 1]], [1, 0], [[0, 0], [0, 1]])
    """
    check_bool(avoid_other_goal, "avoid_other_goal")
    lo = check_int(min_size, "min_size", 2 if avoid_other_goal else 1)
    hi = check_int(max_size, "max_size", lo)
    cells = hi * hi if max_cells is None else check_int(max_cells, "max_cells", 1)
    density: object = max_density  # checked as given, whatever its type
    if (isinstance(density, bool) or not isinstance(density, Real)
            or not 0 <= float(density) < 1):
        raise InvalidArgument(f"max_density={max_density!r} must lie in [0, 1)")
    need = 3 if avoid_other_goal else 2
    shapes = {r: (max(lo, -(-need // r)), min(hi, cells // r)) for r in range(lo, hi + 1)}
    shapes = {r: c for r, c in shapes.items() if c[0] <= c[1]}
    if not shapes:
        raise InvalidArgument(f"no grid with sides in [{min_size}, {max_size}] has at least "
                              f"{need} and at most {cells} cells")
    weight = weight_strategy(weights, 1, 9, 6)
    prior_strategy = _prior_pairs() if priors is None else priors
    if not isinstance(prior_strategy, st.SearchStrategy):
        raise InvalidArgument(f"priors={priors!r} must be a SearchStrategy")
    return _grids(shapes, float(max_density), avoid_other_goal, weight, prior_strategy)


@st.composite
def _grids(draw: st.DrawFn, shapes: dict[int, tuple[int, int]], density: float, avoid: bool,
           weight: st.SearchStrategy[Any], prior_strategy: st.SearchStrategy[Sequence[Any]]
           ) -> Doc:
    rows = draw(st.sampled_from(sorted(shapes)))
    cols = draw(st.integers(*shapes[rows]))
    n = rows * cols
    first = draw(st.integers(0, n - 1))
    second = _skip(draw(st.integers(0, n - 2)), [first])
    start = (_skip(draw(st.integers(0, n - 3)), [first, second]) if avoid
             else draw(st.integers(0, n - 1)))
    special = {start, first, second}
    budget = min(math.floor(density * n), n - len(special))
    blocked = set(draw(st.lists(st.integers(0, n - 1), max_size=budget, unique=True))) - special
    neighbours = [_grid_neighbours(i, rows, cols) for i in range(n)]
    for goal, other in ((first, second), (second, first)):
        banned = {other} if avoid else set()
        blocked -= set(_cheapest_path(start, goal, neighbours, blocked, banned))
    free = [i for i in range(n) if i not in blocked]
    cell = [[i // cols, i % cols] for i in range(n)]
    edges = [{"source": cell[i], "target": cell[j], "weight": draw(weight)}
             for i in free for j in neighbours[i] if j > i and j not in blocked]
    doc: Doc = {"graph": {"directed": False, "multigraph": False, "graph": {},
                          "nodes": [{"id": cell[i]} for i in free], "edges": edges},
                "start": cell[start], "goals": [cell[first], cell[second]],
                "prior": list(draw(prior_strategy))}
    if any(isinstance(e["weight"], float) for e in edges):
        doc["numbers"] = "float"
    return doc


def _skip(i: int, taken: Sequence[int]) -> int:
    """The ``i``-th integer not in ``taken`` (choose among the rest without filtering)."""
    for t in sorted(taken):
        if i >= t:
            i += 1
    return i


def _grid_neighbours(i: int, rows: int, cols: int) -> list[int]:
    r, c = divmod(i, cols)
    out = []
    for dr, dc in ((-1, 0), (0, -1), (0, 1), (1, 0)):
        if 0 <= r + dr < rows and 0 <= c + dc < cols:
            out.append((r + dr) * cols + c + dc)
    return out


def _cheapest_path(source: int, target: int, neighbours: Sequence[Sequence[int]],
                   blocked: set[int], banned: set[int]) -> list[int]:
    """A path ``source -> target`` avoiding ``banned`` that crosses the fewest ``blocked``
    cells (0-1 BFS; deterministic). The grids here always have one (2-connected grids)."""
    cost = {source: 0}
    parent: dict[int, int] = {}
    todo = deque([source])
    while todo:
        u = todo.popleft()
        for v in neighbours[u]:
            if v in banned:
                continue
            step = 1 if v in blocked else 0
            if v not in cost or cost[u] + step < cost[v]:
                cost[v] = cost[u] + step
                parent[v] = u
                if step:
                    todo.append(v)
                else:
                    todo.appendleft(v)
    if target not in cost:  # unreachable only for impossible shapes, excluded by validation
        raise InvalidArgument("grid too small for the requested goal condition")
    path = [target]
    while path[-1] != source:
        path.append(parent[path[-1]])
    return path
