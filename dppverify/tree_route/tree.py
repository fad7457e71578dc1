"""The truncated game's tree of walks (proofs/LP.md), stored compactly as arrays.

A *prefix* is a walk ``s0 s1 … s_t`` with ``t <= H`` steps that has not reached a goal before
its last node; it is a *leaf* when ``s_t`` is a goal (the game ends at the FIRST goal reached,
paper Sec. III-A). Prefixes from which no goal can be reached within the ``H - t`` steps
left are pruned, so every leaf of the tree ends at a goal and every other prefix has a child.
The Defender's information set after step ``t`` is the prefix itself (it observes the walk).

Prefixes are numbered in breadth-first order: the root (the empty walk at ``s0``) is 0,
``parent[p] < p``, and the children of ``p`` are the contiguous range
``child_start[p]:child_stop[p]``. Iterating ``p`` downwards is backward induction.

Examples
--------
>>> from dppverify.game.instance import instance_from_json
>>> doc = {"graph": {"nodes": [{"id": "s"}, {"id": "g1"}, {"id": "g2"}],
...        "edges": [{"source": "s", "target": "g2", "weight": 2},
...                  {"source": "g2", "target": "g1", "weight": 2},
...                  {"source": "s", "target": "g1", "weight": 3}]},
...        "start": "s", "goals": ["g1", "g2"], "prior": ["7/10", "3/10"]}
>>> tree = build_tree(instance_from_json(doc), 1)
>>> tree.n_prefixes, [tree.instance.labels(tree.walk(p)) for p in tree.leaves()]
(3, [('s', 'g1'), ('s', 'g2')])
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Generic, TypeVar

import numpy as np
from tqdm import tqdm

from dppverify.errors import HorizonError, TreeTooLargeError
from dppverify.exact import Number
from dppverify.game.instance import Instance
from dppverify.limits import MAX_LP_CELLS
from dppverify.structured.cover import MAX_BALANCED

if TYPE_CHECKING:  # scipy loads where a matrix is built (`dpp --help` stays fast)
    import scipy.sparse as sp


DEFAULT_MAX_PREFIXES = 1_000_000
"""Default size guard: trees with more prefixes raise :class:`TreeTooLargeError`."""


G = TypeVar("G", bound=Instance)


@dataclass(frozen=True, eq=False)
class WalkTree(Generic[G]):
    """The walks of a truncated game (``N >= 2`` goals) with at most ``horizon`` steps.

    Built by :func:`build_tree` (proofs/LP.md); generic in the instance type it was built from.

    Attributes
    ----------
    instance : Instance
        The game the tree belongs to.
    horizon : int
        ``H``: the maximum number of steps of a walk.
    node : numpy.ndarray of int32
        Last node of each prefix (``node[0] = s0``).
    parent : numpy.ndarray of int64
        Parent prefix (``-1`` for the root).
    depth : numpy.ndarray of int32
        Number of steps ``t`` of each prefix.
    child_start, child_stop : numpy.ndarray of int64
        Children of ``p``: ``range(child_start[p], child_stop[p])`` (empty for leaves).
    weight : tuple
        Exact weight ``w(e_t)`` of the last step of each prefix (0 for the root).
    """

    instance: G
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
        """Number of prefixes (tree nodes), the root included."""
        return int(self.node.shape[0])

    def is_leaf_mask(self) -> np.ndarray:
        """Boolean mask of the leaves (prefixes ending at a goal)."""
        return np.asarray(self.child_start == self.child_stop)

    def leaves(self) -> np.ndarray:
        """Indices of the leaves, in breadth-first order."""
        return np.flatnonzero(self.child_start == self.child_stop)

    @property
    def n_leaves(self) -> int:
        """Number of leaves (complete walks of the truncated game)."""
        return int(np.count_nonzero(self.child_start == self.child_stop))

    def children(self, p: int) -> range:
        """Child prefixes of ``p``."""
        return range(int(self.child_start[p]), int(self.child_stop[p]))

    def walk(self, p: int) -> tuple[int, ...]:
        """The walk (node indices ``s0 … s_t``) of prefix ``p``."""
        return tuple(int(self.node[q]) for q in self.prefixes(p))

    def prefixes(self, p: int) -> list[int]:
        """The prefixes of ``p``'s walk: prefix indices from the root down to ``p`` (inclusive)."""
        out = []
        parent = self.parent
        while p >= 0:
            out.append(p)
            p = int(parent[p])
        out.reverse()
        return out

    def find(self, walk: Sequence[int]) -> int | None:
        """Index of the prefix whose walk is ``walk`` (node indices), or None if not in the tree."""
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


def count_prefixes(instance: Instance, horizon: int, *, limit: int | None = None) -> int:
    """Number of prefixes of the pruned walk tree with ``horizon`` steps, without building it.

    Dynamic programming over (node, steps left), vectorised, touching at each layer only the
    nodes a prefix can be at (a goal within the steps left, reached within the steps taken):
    at most ``O(H·|E|)``, and ``O(total walk length)`` on a path. Bounded: the count is
    non-decreasing in the steps left, so with a ``limit`` it saturates just above it and
    stops as soon as the start's count exceeds it (returning ``limit + 1``).

    Parameters
    ----------
    instance : Instance
        The game (any number of goals).
    horizon : int
        ``H >= 0``.
    limit : int, optional
        Stop counting above this (the result is then ``limit + 1``).

    Returns
    -------
    int
        The number of prefixes (0 when no walk reaches a goal within ``horizon`` steps).

    Raises
    ------
    HorizonError
        A negative ``horizon``.

    Examples
    --------
    The path graph ``2 - 0 - 1 - 3`` from ``0`` with goals ``2`` and ``3``:

    >>> from dppverify.game.examples import fork
    >>> [count_prefixes(fork(), h) for h in range(5)]
    [0, 2, 4, 6, 8]
    """
    if horizon < 0:
        raise HorizonError(f"the horizon must be a non-negative integer, got {horizon}")
    inst = instance
    n = inst.n_nodes
    cap = limit + 1 if limit is not None and limit + 1 < 2**40 else None
    exact = cap is None  # no limit, or saturated int64 sums could overflow: Python ints
    goal = np.zeros(n, dtype=bool)
    goal[list(inst.goals)] = True
    hops = np.asarray(inst.hops, dtype=np.int64)
    reach = _hops_from(inst, goal)
    deg = np.asarray([0 if goal[v] else len(inst.succ[v]) for v in range(n)], dtype=np.int64)
    indptr = np.concatenate([[0], np.cumsum(deg)])
    heads = np.asarray([u for v in range(n) if not goal[v] for u, _ in inst.succ[v]],
                       dtype=np.int64)
    cnt = np.zeros(n, dtype=object if exact else np.int64)
    cnt[goal] = 1  # k = 0 steps left
    # a prefix at v with k steps left took horizon - k >= reach[v] steps and reaches a goal
    # within k: v is active for k in [hops[v], horizon - reach[v]]; only active nodes change
    # (the others keep a value that is never read again)
    last = horizon - reach
    cand = np.flatnonzero(~goal & (hops >= 0) & (hops <= last))
    cand = cand[np.argsort(hops[cand], kind="stable")]
    starts = hops[cand]
    active = np.zeros(0, dtype=np.int64)
    taken = 0
    for k in range(1, horizon + 1):
        upto = int(np.searchsorted(starts, k, side="right"))
        active = np.concatenate([active[last[active] >= k], cand[taken:upto]])
        taken = upto
        if active.size:
            lens = deg[active]
            first = np.repeat(indptr[active] - np.cumsum(lens) + lens, lens)
            arcs = first + np.arange(int(lens.sum()))
            owner = np.repeat(np.arange(active.size), lens)
            sums = np.zeros(active.size, dtype=cnt.dtype)
            if exact:
                for j, c in zip(owner.tolist(), cnt[heads[arcs]].tolist(), strict=True):
                    sums[j] += c
            else:
                np.add.at(sums, owner, cnt[heads[arcs]])
            cnt[active] = sums + 1 if cap is None else np.minimum(sums + 1, cap)
        if cap is not None and cnt[inst.start] >= cap:
            break  # the count never decreases with more steps left
    return int(cnt[inst.start])


def _hops_from(inst: Instance, goal: np.ndarray) -> np.ndarray:
    """Fewest steps from the start to each node along walks that stop at the first goal
    (a large number where there is none)."""
    n = inst.n_nodes
    far = np.iinfo(np.int64).max // 4
    dist = np.full(n, far, dtype=np.int64)
    dist[inst.start] = 0
    frontier = [inst.start]
    d = 0
    while frontier:
        d += 1
        nxt = []
        for v in frontier:
            if goal[v]:
                continue
            for u, _ in inst.succ[v]:
                if dist[u] == far:
                    dist[u] = d
                    nxt.append(u)
        frontier = nxt
    return dist


def build_tree(instance: G, horizon: int, *, max_prefixes: int = DEFAULT_MAX_PREFIXES,
               progress: bool = False) -> WalkTree[G]:
    """Build the pruned tree of walks from ``s0`` with at most ``horizon`` steps.

    Parameters
    ----------
    instance : Instance
        The game (any number of goals ``N >= 2``).
    horizon : int
        ``H >= 0``.
    max_prefixes : int
        Size guard: the tree is counted first (:func:`count_prefixes`) and
        :class:`TreeTooLargeError` is raised before any memory is spent when it is larger.
    progress : bool
        Show a tqdm progress bar on stderr.

    Returns
    -------
    WalkTree
        The prefixes breadth first: node, parent, depth, children and step weight of each.

    Raises
    ------
    HorizonError
        If ``horizon`` is negative or no walk reaches a goal within ``horizon`` steps.
    TreeTooLargeError
        If the tree has more than ``max_prefixes`` prefixes.

    Examples
    --------
    The path graph ``2 - 0 - 1 - 3`` from ``0`` with goals ``2`` and ``3``:

    >>> from dppverify.game.examples import fork
    >>> t = build_tree(fork(), 4)
    >>> [t.walk(int(p)) for p in t.leaves()]
    [(0, 2), (0, 1, 3), (0, 1, 0, 2), (0, 1, 0, 1, 3)]
    >>> build_tree(fork(), 4, max_prefixes=5)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.TreeTooLargeError: the walk tree for horizon H = 4 has at least 6 prefixes, ...

    With three goals (the game ends at the first of them reached):

    >>> from dppverify.game.examples import star3
    >>> t = build_tree(star3(), 2)
    >>> t.n_leaves, t.find((0, 1, 3)), t.weight
    (4, 4, (0, 1, 2, 1, 1, 1))
    >>> build_tree(star3(), 3, max_prefixes=7)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.TreeTooLargeError: the walk tree for horizon H = 3 has at least 8 prefixes, ...
    """
    size = _tree_size(instance, horizon, max_prefixes)
    node, parent, depth, weight, child_start, child_stop = _levels(instance, horizon, size,
                                                                   progress)
    return WalkTree(instance=instance, horizon=horizon,
                    node=np.asarray(node, dtype=np.int32),
                    parent=np.asarray(parent, dtype=np.int64),
                    depth=np.asarray(depth, dtype=np.int32),
                    child_start=np.asarray(child_start, dtype=np.int64),
                    child_stop=np.asarray(child_stop, dtype=np.int64),
                    weight=tuple(weight))


def _levels(inst: Instance, horizon: int, size: int, progress: bool) -> tuple[
        list[int], list[int], list[int], list[Number], list[int], list[int]]:
    """The walk tree level by level (breadth first): each prefix's node, parent, depth, last
    step's weight and children's range; ``size`` is its count (:func:`count_prefixes`)."""
    goal = [inst.is_goal(v) for v in range(inst.n_nodes)]
    hops = inst.hops
    node = [inst.start]
    parent = [-1]
    depth = [0]
    weight: list[Number] = [0]
    child_start = [0] * size
    child_stop = [0] * size
    bar = tqdm(total=size, desc=f"walk tree H={horizon}", unit="prefix", disable=not progress,
               leave=False)
    lo, hi = 0, 1  # the current level is node[lo:hi]
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
        bar.update(hi - lo)
        lo, hi = hi, len(node)
        if lo == hi:
            break
    for p in range(lo, hi):  # the deepest level: leaves
        child_start[p] = child_stop[p] = len(node)
    bar.update(hi - lo)
    bar.close()
    if len(node) != size:  # pragma: no cover - the count and the build share the pruning rule
        raise AssertionError(f"tree size {len(node)} differs from its count {size}")
    return node, parent, depth, weight, child_start, child_stop


def _tree_size(instance: Instance, horizon: int, max_prefixes: int) -> int:
    """The number of prefixes of the walk tree, refused (before any memory is spent) when no
    walk reaches a goal or the tree is larger than ``max_prefixes`` or its LP allows."""
    cap = lp_prefix_limit(instance, max_prefixes)
    size = count_prefixes(instance, horizon, limit=cap)
    if size == 0:
        raise HorizonError(f"no walk from the start reaches a goal within H = {horizon} steps "
                           f"(the nearest goal is {instance.hops[instance.start]} steps away)")
    if size > cap < max_prefixes:
        raise TreeTooLargeError(
            f"N = {instance.n_goals} goals: the walk tree's LP has one variable per goal and "
            f"prefix, at most {MAX_LP_CELLS:,} (so {cap:,} prefixes for "
            f"{instance.n_goals} goals), and the tree for horizon H = {horizon} has at least "
            f"{size:,} prefixes; lower the horizon" + (
                ", or use --route structured" if instance.n_goals <= MAX_BALANCED
                else ""))
    if size > max_prefixes:
        raise TreeTooLargeError(
            f"the walk tree for horizon H = {horizon} has at least {size} prefixes, more than "
            f"the limit of {max_prefixes} (--max-prefixes); use --route structured, or lower "
            "the horizon")
    return size


def lp_prefix_limit(instance: Instance, max_prefixes: int) -> int:
    """The most prefixes a walk tree of ``instance`` may have: ``max_prefixes``, and with more
    than two goals also ``MAX_LP_CELLS // N`` (the tree's LP has one variable per goal
    and prefix: the size rule of N goals, ``docs/limits.md``).

    Examples
    --------
    >>> from dppverify.game.examples import star3, triangle
    >>> lp_prefix_limit(triangle(), 10**6), lp_prefix_limit(star3(), 10**6)
    (1000000, 33333)
    """
    if instance.n_goals <= 2:
        return max_prefixes
    return min(max_prefixes, MAX_LP_CELLS // instance.n_goals)


def tree_fits(instance: Instance, horizon: int | None, max_prefixes: int) -> bool:
    """True when the pruned walk tree of ``horizon`` steps has at most ``max_prefixes`` prefixes.

    Counts with :func:`count_prefixes`, saturated just above ``max_prefixes`` and stopping as
    soon as the count exceeds it, so that huge trees are never counted in full. An untruncated
    game (``horizon=None``) never fits; a negative horizon raises :class:`HorizonError`.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> from dppverify.game.examples import star3
    >>> inst = triangle()
    >>> tree_fits(inst, 5, 3), tree_fits(inst, 5, 2), tree_fits(inst, None, 10**9)
    (True, False, False)
    >>> [count_prefixes(star3(), h) for h in (2, 3)], tree_fits(star3(), 3, 7)
    ([6, 8], False)
    """
    if horizon is None:
        return False
    if horizon < 0:
        raise HorizonError(f"the horizon must be a non-negative integer, got {horizon}")
    cap = lp_prefix_limit(instance, max_prefixes)
    return count_prefixes(instance, horizon, limit=cap) <= cap


def simple_mask(tree: WalkTree) -> np.ndarray:
    """Boolean mask: ``True`` for prefixes whose walk visits no node twice (paths).

    Examples
    --------
    The path graph ``2 - 0 - 1 - 3`` from ``0`` with goals ``2`` and ``3``:

    >>> from dppverify.game.examples import fork
    >>> t = build_tree(fork(), 4)
    >>> [t.walk(int(p)) for p in t.leaves()[simple_mask(t)[t.leaves()]]]
    [(0, 2), (0, 1, 3)]
    """
    n = tree.n_prefixes
    node = tree.node.tolist()
    parent = tree.parent.tolist()
    visited = [0] * n
    simple = [True] * n
    visited[0] = 1 << node[0]
    for p in range(1, n):
        q = parent[p]
        bit = 1 << node[p]
        simple[p] = simple[q] and not (visited[q] & bit)
        visited[p] = visited[q] | bit
    return np.asarray(simple, dtype=bool)


def flow_matrix(tree: WalkTree) -> sp.csr_matrix:
    """Sequence-form flow constraints ``x[p] - Σ_children x[c] = 0``, one row per inner prefix.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> flow_matrix(build_tree(triangle(), 1)).toarray()   # s -> s g1, s g2
    array([[ 1., -1., -1.]])
    """
    import scipy.sparse as sp

    n = tree.n_prefixes
    inner = np.flatnonzero(tree.child_start != tree.child_stop)
    row_of = np.full(n, -1, dtype=np.int64)
    row_of[inner] = np.arange(inner.size)
    children = np.arange(1, n)
    rows = np.concatenate([row_of[inner], row_of[tree.parent[children]]])
    cols = np.concatenate([inner, children])
    vals = np.concatenate([np.ones(inner.size), -np.ones(children.size)])
    return sp.csr_matrix((vals, (rows, cols)), shape=(inner.size, n))
