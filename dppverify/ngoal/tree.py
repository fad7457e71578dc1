"""The truncated N-goal game's tree of walks, stored compactly as arrays.

The same construction as the two-goal tree (:mod:`dppverify.tree`): a *prefix* is a walk
``s0 … s_t`` with ``t <= H`` steps that has not reached a goal before its last node; it is a
*leaf* when ``s_t`` is a goal (the game ends at the FIRST of the N goals reached). Prefixes
from which no goal is reachable within the steps left are pruned. Prefixes are numbered
breadth-first (``parent[p] < p``; children contiguous), so iterating downwards is backward
induction. A size guard counts the tree first, in ``O(H·|E|)``.

Examples
--------
>>> from dppverify.ngoal.examples import star3
>>> tree = build_ntree(star3(), 1)
>>> tree.n_prefixes, [tree.instance.labels(tree.walk(p)) for p in tree.leaves().tolist()]
(2, [('s', 'a')])
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from dppverify.errors import HorizonError, TreeTooLargeError
from dppverify.exact import Number
from dppverify.ngoal.instance import NInstance
from dppverify.tree import DEFAULT_MAX_PREFIXES

__all__ = ["NWalkTree", "build_ntree", "count_nprefixes", "nflow_matrix"]


@dataclass(frozen=True, eq=False)
class NWalkTree:
    """The walks of the truncated N-goal game with at most ``horizon`` steps.

    Attributes
    ----------
    instance : NInstance
        The game.
    horizon : int
        ``H``.
    node, parent, depth, child_start, child_stop : numpy.ndarray
        Last node, parent prefix (``-1`` at the root), steps, children range of each prefix.
    weight : tuple
        Exact weight of the last step of each prefix (0 at the root).

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> t = build_ntree(star3(), 2)
    >>> t.n_leaves, t.find((0, 1, 3)), t.weight
    (4, 4, (0, 1, 2, 1, 1, 1))
    """

    instance: NInstance
    horizon: int
    node: np.ndarray
    parent: np.ndarray
    depth: np.ndarray
    child_start: np.ndarray
    child_stop: np.ndarray
    weight: tuple[Number, ...]
    weight_float: np.ndarray = field(init=False, repr=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "weight_float", np.array([float(w) for w in self.weight]))

    @property
    def n_prefixes(self) -> int:
        """Number of prefixes, the root included."""
        return int(self.node.shape[0])

    def is_leaf_mask(self) -> np.ndarray:
        """Boolean mask of the leaves (prefixes ending at a goal)."""
        return np.asarray(self.child_start == self.child_stop)

    def leaves(self) -> np.ndarray:
        """Indices of the leaves, breadth-first."""
        return np.flatnonzero(self.child_start == self.child_stop)

    @property
    def n_leaves(self) -> int:
        """Number of leaves (complete walks)."""
        return int(np.count_nonzero(self.child_start == self.child_stop))

    def children(self, p: int) -> range:
        """Child prefixes of ``p``."""
        return range(int(self.child_start[p]), int(self.child_stop[p]))

    def walk(self, p: int) -> tuple[int, ...]:
        """The walk (node indices) of prefix ``p``."""
        out = []
        while p >= 0:
            out.append(int(self.node[p]))
            p = int(self.parent[p])
        return tuple(reversed(out))

    def find(self, walk: tuple[int, ...] | list[int]) -> int | None:
        """Index of the prefix whose walk is ``walk``, or None if it is not in the tree."""
        if not walk or walk[0] != int(self.node[0]):
            return None
        p = 0
        for v in walk[1:]:
            lo, hi = int(self.child_start[p]), int(self.child_stop[p])
            hits = np.flatnonzero(self.node[lo:hi] == v)
            if hits.size == 0:
                return None
            p = lo + int(hits[0])
        return p


def count_nprefixes(instance: NInstance, horizon: int) -> int:
    """Number of prefixes of the pruned walk tree, without building it (``O(H·|E|)``).

    Raises
    ------
    HorizonError
        If ``horizon`` is negative.

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> [count_nprefixes(star3(), h) for h in range(4)]
    [0, 2, 6, 8]
    """
    if horizon < 0:
        raise HorizonError(f"the horizon must be a non-negative integer, got {horizon}")
    inst = instance
    goal = [inst.is_goal(v) for v in range(inst.n_nodes)]
    cnt = [1 if goal[v] else 0 for v in range(inst.n_nodes)]
    for k in range(1, horizon + 1):
        cnt = [1 if goal[v] else
               (1 + sum(cnt[u] for u, _ in inst.succ[v]) if 0 <= inst.hops[v] <= k else 0)
               for v in range(inst.n_nodes)]
    return cnt[inst.start]


def build_ntree(instance: NInstance, horizon: int, *,
                max_prefixes: int = DEFAULT_MAX_PREFIXES) -> NWalkTree:
    """Build the pruned tree of walks from ``s0`` with at most ``horizon`` steps.

    Raises
    ------
    HorizonError
        If ``horizon`` is negative or no walk reaches a goal within ``horizon`` steps.
    TreeTooLargeError
        If the tree has more than ``max_prefixes`` prefixes (checked before building).

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> build_ntree(star3(), 3, max_prefixes=7)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.TreeTooLargeError: the walk tree for horizon H = 3 has 8 prefixes, ...
    """
    size = count_nprefixes(instance, horizon)
    inst = instance
    if size == 0:
        raise HorizonError(f"no walk from the start reaches a goal within H = {horizon} steps "
                           f"(the nearest goal is {inst.hops[inst.start]} steps away)")
    if size > max_prefixes:
        raise TreeTooLargeError(
            f"the walk tree for horizon H = {horizon} has {size} prefixes, more than the limit "
            f"of {max_prefixes}; lower the horizon or raise the limit (--max-prefixes)")
    goal = [inst.is_goal(v) for v in range(inst.n_nodes)]
    hops = inst.hops
    node, parent, depth = [inst.start], [-1], [0]
    weight: list[Number] = [0]
    child_start = [0] * size
    child_stop = [0] * size
    lo, hi = 0, 1
    for t in range(1, horizon + 1):
        left = horizon - t
        for p in range(lo, hi):
            child_start[p] = len(node)
            v = node[p]
            if not goal[v]:
                for u, w in inst.succ[v]:
                    if goal[u] or 0 <= hops[u] <= left:
                        node.append(u)
                        parent.append(p)
                        depth.append(t)
                        weight.append(w)
            child_stop[p] = len(node)
        lo, hi = hi, len(node)
        if lo == hi:
            break
    for p in range(lo, hi):
        child_start[p] = child_stop[p] = len(node)
    if len(node) != size:  # pragma: no cover - the count and the build share the pruning rule
        raise AssertionError(f"tree size {len(node)} differs from its count {size}")
    return NWalkTree(instance=inst, horizon=horizon, node=np.asarray(node, dtype=np.int32),
                     parent=np.asarray(parent, dtype=np.int64),
                     depth=np.asarray(depth, dtype=np.int32),
                     child_start=np.asarray(child_start, dtype=np.int64),
                     child_stop=np.asarray(child_stop, dtype=np.int64), weight=tuple(weight))


def nflow_matrix(tree: NWalkTree) -> sp.csr_matrix:
    """Sequence-form flow constraints ``x[p] - Σ_children x[c] = 0``, one row per inner prefix.

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> nflow_matrix(build_ntree(star3(), 1)).toarray()
    array([[ 1., -1.]])
    """
    n = tree.n_prefixes
    inner = np.flatnonzero(tree.child_start != tree.child_stop)
    row_of = np.full(n, -1, dtype=np.int64)
    row_of[inner] = np.arange(inner.size)
    children = np.arange(1, n)
    rows = np.concatenate([row_of[inner], row_of[tree.parent[children]]])
    cols = np.concatenate([inner, children])
    vals = np.concatenate([np.ones(inner.size), -np.ones(children.size)])
    return sp.csr_matrix((vals, (rows, cols)), shape=(inner.size, n))
