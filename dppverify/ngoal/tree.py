"""The truncated N-goal game's tree of walks, stored compactly as arrays.

The same construction as the two-goal tree (:mod:`dppverify.tree_route.tree`): a *prefix* is a walk
``s0 … s_t`` with ``t <= H`` steps that has not reached a goal before its last node; it is a
*leaf* when ``s_t`` is a goal (the game ends at the FIRST of the N goals reached). Prefixes
from which no goal is reachable within the steps left are pruned. Prefixes are numbered
breadth-first (``parent[p] < p``; children contiguous), so iterating downwards is backward
induction. A size guard counts the tree first, in ``O(H·|E|)``. The construction is the
two-goal one (:func:`dppverify.tree_route.tree.build_prefix_tree`); this module names the N-goal
tree.

Examples
--------
>>> from dppverify.game.examples import star3
>>> tree = build_ntree(star3(), 1)
>>> tree.n_prefixes, [tree.instance.labels(tree.walk(p)) for p in tree.leaves().tolist()]
(2, [('s', 'a')])
"""

from __future__ import annotations

from dataclasses import dataclass

from dppverify.game.instance import Instance
from dppverify.tree_route.tree import (
    DEFAULT_MAX_PREFIXES,
    PrefixTree,
    build_prefix_tree,
    count_prefixes,
    flow_matrix,
)

__all__ = ["NWalkTree", "build_ntree", "count_nprefixes", "nflow_matrix"]


@dataclass(frozen=True, eq=False)
class NWalkTree(PrefixTree):
    """The walks of the truncated N-goal game with at most ``horizon`` steps.

    A :class:`~dppverify.tree_route.tree.PrefixTree` whose ``instance`` is an :class:`Instance`
    (every other attribute as documented there).

    Attributes
    ----------
    instance : Instance
        The game.

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> t = build_ntree(star3(), 2)
    >>> t.n_leaves, t.find((0, 1, 3)), t.weight
    (4, 4, (0, 1, 2, 1, 1, 1))
    """

    instance: Instance


def count_nprefixes(instance: Instance, horizon: int) -> int:
    """Number of prefixes of the pruned walk tree, without building it (``O(H·|E|)``).

    :func:`dppverify.tree_route.tree.count_prefixes` without a limit.

    Raises
    ------
    HorizonError
        If ``horizon`` is negative.

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> [count_nprefixes(star3(), h) for h in range(4)]
    [0, 2, 6, 8]
    """
    return count_prefixes(instance, horizon)


def build_ntree(instance: Instance, horizon: int, *,
                max_prefixes: int = DEFAULT_MAX_PREFIXES, progress: bool = False) -> NWalkTree:
    """Build the pruned tree of walks from ``s0`` with at most ``horizon`` steps.

    :func:`dppverify.tree_route.tree.build_prefix_tree` for an N-goal instance.

    Raises
    ------
    HorizonError
        If ``horizon`` is negative or no walk reaches a goal within ``horizon`` steps.
    TreeTooLargeError
        If the tree has more than ``max_prefixes`` prefixes (checked before building).

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> build_ntree(star3(), 3, max_prefixes=7)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.TreeTooLargeError: the walk tree for horizon H = 3 has at least 8 prefixes, ...
    """
    return build_prefix_tree(instance, horizon, NWalkTree, max_prefixes=max_prefixes,
                             progress=progress)


nflow_matrix = flow_matrix
"""The flow constraints of an N-goal tree: :func:`dppverify.tree_route.tree.flow_matrix` (one
function
serves both trees)."""
