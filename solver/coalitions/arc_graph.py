"""The walkable part of an N-goal game as arrays (CSR by tail and by head), for the DPs."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


@dataclass(frozen=True, eq=False)
class ArcGraph:
    """The walkable part of an N-goal game as arrays.

    Attributes
    ----------
    indptr, heads, weights : numpy.ndarray
        The arcs out of non-goal nodes, by tail (CSR); weights are int64 numerators over
        ``denominator``.
    denominator : int
        The weights' common denominator.
    goals : tuple of int
        Goal nodes, ``goals[θ]`` is type θ's goal.
    terminal : numpy.ndarray
        ``terminal[i, θ]``: ``d(goals[i], g^θ)`` as a numerator over ``denominator``.
    start : int
        The start node.
    """

    indptr: np.ndarray
    heads: np.ndarray
    weights: np.ndarray
    denominator: int
    goals: tuple[int, ...]
    terminal: np.ndarray
    start: int
    tails: np.ndarray = field(init=False, repr=False)
    rev_indptr: np.ndarray = field(init=False, repr=False)
    rev_tails: np.ndarray = field(init=False, repr=False)
    is_goal: np.ndarray = field(init=False, repr=False)

    def __post_init__(self) -> None:
        n = self.n_nodes
        tails = np.repeat(np.arange(n, dtype=np.int64), np.diff(self.indptr))
        order = np.argsort(self.heads, kind="stable")
        rev = np.zeros(n + 1, dtype=np.int64)
        np.add.at(rev, self.heads + 1, 1)
        object.__setattr__(self, "tails", tails)
        object.__setattr__(self, "rev_indptr", np.cumsum(rev))
        object.__setattr__(self, "rev_tails", tails[order])
        goal = np.zeros(n, dtype=bool)
        goal[list(self.goals)] = True
        object.__setattr__(self, "is_goal", goal)

    @property
    def n_nodes(self) -> int:
        """Number of nodes."""
        return len(self.indptr) - 1

    @property
    def n_goals(self) -> int:
        """``N``."""
        return len(self.goals)

    def arcs_of(self, nodes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The arc indices out of ``nodes`` (concatenated) and each node's first position."""
        lo, hi = self.indptr[nodes], self.indptr[nodes + 1]
        counts = hi - lo
        seg = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(np.int64)
        idx = np.arange(int(counts.sum()), dtype=np.int64) - np.repeat(seg - lo, counts)
        return idx, seg

    def tails_into(self, nodes: np.ndarray) -> np.ndarray:
        """The distinct tails of arcs into ``nodes``."""
        lo, hi = self.rev_indptr[nodes], self.rev_indptr[nodes + 1]
        counts = hi - lo
        if not counts.sum():
            return np.zeros(0, dtype=np.int64)
        seg = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(np.int64)
        idx = np.arange(int(counts.sum()), dtype=np.int64) - np.repeat(seg - lo, counts)
        return np.unique(self.rev_tails[idx])
