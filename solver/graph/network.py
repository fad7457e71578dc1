"""Compressed sparse (CSR) form of the game graph: the solver's only hot-path data structure.

A :class:`Network` stores the directed edge set of the graph (an undirected edge is two arcs)
as scipy CSR arrays over node indices ``0..n-1``. Its :class:`~solver.numbers.NumberMode`,
decided once from the weights, says how they are stored: exactly as integer numerators over
one common denominator (exact mode) or as floats (float mode, e.g. octile grids). Grids are
built straight from a boolean obstacle array with numpy, with no
per-cell Python work; general graphs come through networkx.
"""

from __future__ import annotations

import math
from collections.abc import Hashable, Iterator, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from functools import cached_property
from typing import overload

import networkx as nx
import numpy as np
import scipy.sparse as sp

from dppio.limits import check_float_weights, common_denominator
from solver.errors import InvalidInstanceError
from solver.numbers import (
    DEFAULT_ABS_TOL,
    ExactNumbers,
    FloatNumbers,
    Number,
    NumberMode,
    parse_number,
)

SQRT2 = math.sqrt(2.0)


@dataclass(frozen=True)
class GridLabels(Sequence[tuple[int, int]]):
    """Node labels ``(row, col)`` of a grid's free cells, in row-major order, computed on
    demand: node ``i`` is the ``i``-th free cell (blocked cells are no nodes).

    Examples
    --------
    >>> labels = GridLabels(np.array([[False, True], [False, False]]))
    >>> len(labels), labels[1], labels.index_of((1, 1)), labels.index_of((0, 1))
    (3, (1, 0), 2, None)
    >>> labels.cells_of([2, 0])
    ((1, 1), (0, 0))
    """

    blocked: np.ndarray = field(repr=False)
    height: int = field(init=False)
    width: int = field(init=False)
    padded: np.ndarray = field(init=False, repr=False)
    """``padded[i]``: the index of node ``i``'s cell in the grid with a one-cell frame
    (``(row + 1) * (width + 2) + col + 1``), increasing."""
    node_at: np.ndarray = field(init=False, repr=False)
    """``node_at[p]``: the node at framed cell index ``p``, or -1 (blocked, or the frame)."""

    def __post_init__(self) -> None:
        h, w = (int(x) for x in self.blocked.shape)
        object.__setattr__(self, "height", h)
        object.__setattr__(self, "width", w)
        padded = np.flatnonzero(np.pad(~np.asarray(self.blocked, dtype=bool), 1))
        node_at = np.full((h + 2) * (w + 2), -1, dtype=np.int32)
        node_at[padded] = np.arange(padded.size, dtype=np.int32)
        object.__setattr__(self, "padded", padded)
        object.__setattr__(self, "node_at", node_at)

    def __len__(self) -> int:
        return int(self.padded.size)

    @overload
    def __getitem__(self, i: int) -> tuple[int, int]: ...

    @overload
    def __getitem__(self, i: slice) -> Sequence[tuple[int, int]]: ...

    def __getitem__(self, i: int | slice) -> tuple[int, int] | Sequence[tuple[int, int]]:
        if isinstance(i, slice):
            return list(self.cells_of(range(*i.indices(len(self)))))
        if not 0 <= i < len(self):
            raise IndexError(i)
        r, c = divmod(int(self.padded[i]), self.width + 2)
        return (r - 1, c - 1)

    def __iter__(self) -> Iterator[tuple[int, int]]:
        yield from self.cells_of(range(len(self)))

    def cells_of(self, nodes: Sequence[int]) -> tuple[tuple[int, int], ...]:
        """The cells of many nodes at once (one numpy pass)."""
        r, c = np.divmod(self.padded[np.asarray(nodes, dtype=np.int64)], self.width + 2)
        return tuple(zip((r - 1).tolist(), (c - 1).tolist(), strict=True))

    def index_of(self, label: Hashable) -> int | None:
        """Index of a free cell ``(row, col)``, or None if it is outside or blocked."""
        if not (isinstance(label, tuple) and len(label) == 2):
            return None
        r, c = label
        if not (isinstance(r, int) and isinstance(c, int)):
            return None
        if not (0 <= r < self.height and 0 <= c < self.width):
            return None
        i = int(self.node_at[(r + 1) * (self.width + 2) + c + 1])
        return None if i < 0 else i


@dataclass(frozen=True, eq=False)
class Network:
    """A directed weighted graph in CSR form.

    Attributes
    ----------
    labels : Sequence
        ``labels[i]`` is the node id of index ``i``.
    indptr, indices : numpy.ndarray
        CSR arrays of the out-arcs: the heads of node ``i``'s arcs are
        ``indices[indptr[i]:indptr[i+1]]``.
    weights : numpy.ndarray
        Arc weights aligned with ``indices``: integer numerators (exact mode; int64, or
        float64 holding small integers — every integer below 2**53 is exact in float64 —
        as for unit-weight grids, so the scipy matrix can share the buffer) or float64.
    numbers : NumberMode
        Exact (:class:`~solver.numbers.ExactNumbers`, with the common denominator of all
        weights) when every weight is rational; float
        (:class:`~solver.numbers.FloatNumbers`) otherwise.
    directed : bool
        Whether the source graph was directed (informative only: the arcs say it all).
    """

    labels: Sequence[Hashable]
    indptr: np.ndarray = field(repr=False)
    indices: np.ndarray = field(repr=False)
    weights: np.ndarray = field(repr=False)
    numbers: NumberMode
    directed: bool
    _index: dict[Hashable, int] | None = field(default=None, repr=False)

    # ------------------------------------------------------------------ construction
    @classmethod
    def from_networkx(cls, graph: nx.Graph, *, weight: str | None = "weight") -> Network:
        """Build from a networkx ``Graph``/``DiGraph``.

        ``weight`` names the edge attribute holding the weight, as in networkx. With the
        default ``"weight"`` an edge without it weighs 1 (as in the instance JSON); with any
        other name every edge must carry the attribute (a missing one is an error naming the
        edge, so a misspelt name cannot silently give unit weights); ``None`` gives every
        edge weight 1.

        Examples
        --------
        >>> g = nx.Graph([("s", "g1", {"weight": 3}), ("s", "g2", {"weight": "3/2"})])
        >>> net = Network.from_networkx(g)
        >>> net.n_nodes, net.n_arcs, net.numbers
        (3, 4, ExactNumbers(denominator=2))
        >>> Network.from_networkx(nx.Graph([("s", "g1", {"cost": 3})]), weight="cost").weights
        array([3, 3])
        >>> Network.from_networkx(nx.Graph([("s", "g1")]), weight="cost")  # doctest: +ELLIPSIS
        Traceback (most recent call last):
        ...
        solver.errors.InvalidInstanceError: edge ('s', 'g1') has no 'cost' attribute ...
        """
        if not isinstance(graph, nx.Graph):
            raise InvalidInstanceError(
                f"graph must be a networkx Graph or DiGraph, got {type(graph).__name__}"
            )
        if graph.is_multigraph():
            raise InvalidInstanceError("multigraphs are not supported: merge parallel edges")
        labels = list(graph.nodes)
        index = {v: i for i, v in enumerate(labels)}
        directed = graph.is_directed()
        heads: list[int] = []
        tails: list[int] = []
        values: list[Number] = []
        for u, v, data in graph.edges(data=True):
            if weight is not None and weight != "weight" and weight not in data:
                raise InvalidInstanceError(
                    f"edge ({u!r}, {v!r}) has no {weight!r} attribute (weight={weight!r})")
            raw = 1 if weight is None else data.get(weight, 1)
            w = parse_number(raw, where=f"weight of edge ({u!r}, {v!r})", allow_float=True)
            if not w > 0:
                raise InvalidInstanceError(
                    f"weight of edge ({u!r}, {v!r}) must be positive, got {w}"
                )
            tails.append(index[u])
            heads.append(index[v])
            values.append(w)
            if not directed and u != v:
                tails.append(index[v])
                heads.append(index[u])
                values.append(w)
        return cls._from_arcs(labels, index, tails, heads, values, directed=directed)

    @classmethod
    def _from_arcs(
        cls,
        labels: Sequence[Hashable],
        index: dict[Hashable, int] | None,
        tails: Sequence[int],
        heads: Sequence[int],
        values: Sequence[Number],
        *,
        directed: bool,
    ) -> Network:
        fractions = [w for w in values if isinstance(w, Fraction)]
        numbers: NumberMode
        if len(fractions) == len(values):
            den = common_denominator((w.denominator for w in fractions),
                                     where="edge weights", error=InvalidInstanceError)
            nums = [int(w * den) for w in fractions]
            big = max(nums, default=0) >= 2**62
            data = np.array(nums, dtype=object if big else np.int64)
            numbers = ExactNumbers(den)
        else:
            data = np.array([float(w) for w in values], dtype=np.float64)
            if data.size:
                check_float_weights([float(data.min()), float(data.max())],
                                    error=InvalidInstanceError)
            numbers = FloatNumbers(DEFAULT_ABS_TOL)
        indptr, indices, weights = _sorted_csr(len(labels), np.asarray(tails, dtype=np.int64),
                                               np.asarray(heads, dtype=np.int64), data)
        return cls(labels, indptr, indices, weights, numbers, directed, index)

    @classmethod
    def from_grid(cls, blocked: np.ndarray, *, connectivity: int = 4) -> Network:
        """Build the grid graph of the free cells of ``blocked`` (True = obstacle).

        The nodes are the free cells in row-major order (:class:`GridLabels`); blocked cells
        are no nodes, so no shortest-path run visits them. 4-connected grids have unit
        weights (exact). 8-connected grids use octile weights (diagonal ``sqrt(2)``, float
        mode) and forbid cutting corners: a diagonal move needs both orthogonal neighbours
        free (the MovingAI convention).

        Examples
        --------
        >>> net = Network.from_grid(np.array([[False, False], [True, False]]))
        >>> net.n_nodes, net.n_arcs, net.labels[2]
        (3, 4, (1, 1))
        """
        blocked = np.ascontiguousarray(np.asarray(blocked, dtype=bool))
        if blocked.ndim != 2 or blocked.size == 0:
            raise InvalidInstanceError(
                f"grid must be a non-empty 2-D array, got shape {blocked.shape}"
            )
        if connectivity not in (4, 8):
            raise InvalidInstanceError(f"connectivity must be 4 or 8, got {connectivity}")
        labels = GridLabels(blocked)
        stride = labels.width + 2  # a frame of blocked cells: no bounds checks needed
        # neighbour offsets in increasing index order, so each CSR row comes out sorted
        steps = [(-1, 0), (0, -1), (0, 1), (1, 0)]
        if connectivity == 8:
            steps = [(-1, -1), (-1, 0), (-1, 1), (0, -1), (0, 1), (1, -1), (1, 0), (1, 1)]
        n, k = len(labels), len(steps)
        cells, node_at = labels.padded, labels.node_at
        heads = np.empty((n, k), dtype=np.int32)  # heads[i, j]: node i + step j, or -1
        for j, (dr, dc) in enumerate(steps):
            heads[:, j] = node_at[cells + (dr * stride + dc)]
            if dr and dc:  # diagonal: both orthogonal neighbours must be free (no corner cutting)
                cut = (node_at[cells + dr * stride] < 0) | (node_at[cells + dc] < 0)
                heads[cut, j] = -1
        arc = heads >= 0
        indices = heads[arc]  # row by row, each row in increasing head order
        indptr = np.zeros(n + 1, dtype=np.int32 if n * k < 2**31 else np.int64)
        degree = np.zeros(n, dtype=indptr.dtype)
        for j in range(k):  # summing the k columns is far faster than count_nonzero(axis=1)
            degree += arc[:, j]
        np.cumsum(degree, out=indptr[1:])
        if connectivity == 4:  # unit weights: exact integers, stored as float64 for scipy
            data = np.ones(indices.size, dtype=np.float64)
            net = cls(labels, indptr, indices, data, ExactNumbers(), False, None)
            net.__dict__["weight_total"] = float(indices.size)  # the sum, without a pass
            return net
        step_weight = np.array([SQRT2 if dr and dc else 1.0 for dr, dc in steps])
        data = np.broadcast_to(step_weight, (n, k))[arc]
        return cls(labels, indptr, indices, data, FloatNumbers(DEFAULT_ABS_TOL), False, None)

    # ------------------------------------------------------------------ queries
    @property
    def n_nodes(self) -> int:
        return len(self.labels)

    @property
    def n_arcs(self) -> int:
        return int(self.indices.size)

    def labels_of(self, walk: Sequence[int]) -> tuple[Hashable, ...]:
        """The node ids of many node indices (a grid's cells in one numpy pass).

        Examples
        --------
        >>> Network.from_grid(np.zeros((2, 2), dtype=bool)).labels_of([3, 1])
        ((1, 1), (0, 1))
        """
        if isinstance(self.labels, GridLabels):
            return self.labels.cells_of(walk)
        labels = self.labels
        return tuple(labels[int(i)] for i in walk)

    def index_of(self, label: Hashable) -> int | None:
        """Index of node ``label``, or None if the graph has no such node."""
        if isinstance(self.labels, GridLabels):
            return self.labels.index_of(label)
        assert self._index is not None
        try:
            return self._index.get(label)
        except TypeError:  # unhashable label
            return None

    def out_arcs(self, i: int) -> tuple[np.ndarray, np.ndarray]:
        """Heads and weights of node ``i``'s out-arcs (heads in increasing index order)."""
        lo, hi = self.indptr[i], self.indptr[i + 1]
        return self.indices[lo:hi], self.weights[lo:hi]

    def arc_weight(self, i: int, j: int) -> int | float | None:
        """The stored weight of arc ``i -> j``, or None if there is no such arc."""
        heads, ws = self.out_arcs(i)
        k = int(np.searchsorted(heads, j))
        if k < heads.size and heads[k] == j:
            value = ws[k]
            return value.item() if isinstance(value, np.generic) else value
        return None

    def path_weights(self, path: Sequence[int]) -> np.ndarray:
        """Stored weights of the arcs ``path[t-1] -> path[t]``, vectorised.

        Raises
        ------
        ValueError
            If some consecutive pair is not an arc (the message names it).
        """
        p = np.asarray(path, dtype=np.int64)
        if p.size < 2:
            return self.weights[:0]
        tails, heads = p[:-1], p[1:]
        starts = self.indptr[tails]
        degree = self.indptr[tails + 1] - starts
        width = max(int(degree.max()), 1)
        offs = np.arange(width)
        slots = np.minimum(starts[:, None] + offs, max(self.n_arcs - 1, 0))
        hit = (offs < degree[:, None]) & (self.indices[slots] == heads[:, None])
        found = hit.any(axis=1)
        if not found.all():
            k = int(np.argmin(found))
            raise ValueError(f"{self.labels[int(tails[k])]!r} -> {self.labels[int(heads[k])]!r} "
                             "is not an edge")
        return self.weights[starts + hit.argmax(axis=1)]

    def matrix(self) -> sp.csr_matrix:
        """The arcs as a float64 scipy CSR matrix (for ``scipy.sparse.csgraph``)."""
        return self._matrix

    @cached_property
    def _matrix(self) -> sp.csr_matrix:
        n = self.n_nodes
        return sp.csr_matrix(
            (self.weights.astype(np.float64, copy=False), self.indices, self.indptr),
            shape=(n, n), copy=False,
        )

    @cached_property
    def reverse(self) -> Network:
        """The network with every arc reversed (itself when the graph is undirected)."""
        if not self.directed:
            return self
        tails = np.repeat(np.arange(self.n_nodes, dtype=np.int64), np.diff(self.indptr))
        indptr, indices, weights = _sorted_csr(self.n_nodes, self.indices.astype(np.int64),
                                               tails, self.weights)
        return Network(self.labels, indptr, indices, weights, self.numbers, True, self._index)

    @cached_property
    def weight_total(self) -> float:
        """Sum of all stored weights: an upper bound on every simple path's length (``inf``
        past the float range: exact numerators of weights with a large common denominator)."""
        try:
            return float(np.sum(self.weights, dtype=np.float64))
        except OverflowError:
            return math.inf


def _sorted_csr(n: int, tails: np.ndarray, heads: np.ndarray, weights: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """CSR arrays of the arcs ``tails[k] -> heads[k]``, heads sorted within each row.

    Pure index arithmetic: the weights are permuted, never converted, so exact integer
    numerators of any size (int64 or Python ints in an object array) stay exact.
    """
    order = np.lexsort((heads, tails))
    indptr = np.zeros(n + 1, dtype=np.int64)
    np.cumsum(np.bincount(tails, minlength=n), out=indptr[1:])
    return indptr, heads[order], weights[order]
