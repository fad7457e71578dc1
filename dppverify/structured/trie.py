"""The trie of a finite set of walks: every prefix once, in memory linear in the walks' length.

A *walk* is a sequence of node indices the Attacker takes; a *prefix* is a node of the walk
tree. The trie of some walks is their prefix closure: each prefix is stored as its last node
and its parent prefix, numbered in insertion order (the root, the one-node walk of the start,
is ``0``). Optionally it carries each type's realization mass ``x_θ(p)``: the probability that
type ``θ``'s mixed strategy plays a walk through ``p``. Used by the structured route for the
table Defender's trie (:mod:`dppverify.structured.table_br`) and for the prefixes of a profile's
walks (:mod:`dppverify.checks.structured`), for any number of goals.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Mapping, Sequence
from fractions import Fraction
from typing import Protocol


class MixedWalk(Protocol):
    """A walk with a probability (:class:`~dppverify.game.profile.StrategyWalk` and its N-goal
    counterpart)."""

    @property
    def walk(self) -> tuple[int, ...]: ...

    @property
    def probability(self) -> Fraction: ...


class _MassView(Mapping[tuple[int, ...], tuple[Fraction, ...]]):
    """``trie.mass``: prefix (a node-index tuple) -> each type's mass, computed on demand from
    the trie's arrays (no tuple per prefix is stored)."""

    def __init__(self, trie: WalkTrie) -> None:
        self._trie = trie

    def __getitem__(self, prefix: tuple[int, ...]) -> tuple[Fraction, ...]:
        i = self._trie.find(prefix)
        if i is None:
            raise KeyError(prefix)
        return tuple(self._trie.masses[i])

    def __iter__(self) -> Iterator[tuple[int, ...]]:
        return (self._trie.walk(i) for i in range(self._trie.size))

    def __len__(self) -> int:
        return self._trie.size


class WalkTrie:
    """Prefixes of a finite set of walks, numbered in insertion order.

    Attributes
    ----------
    node, parent, depth : list of int
        Last node, parent prefix (``-1`` at the root) and steps of each prefix.
    masses : list of list of Fraction
        ``masses[p][θ]``: type ``θ``'s realization mass at ``p`` (empty lists when the trie
        carries no masses).
    ids : list of tuple of int
        The prefixes along each walk inserted with a mass (:func:`mass_trie`), in order.

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> t = build_walk_trie(star3(), [(0, 1, 2), (0, 1, 3)])
    >>> len(t), t.find((0, 1, 3)), t.walk(3), t.find((0, 2)), t.child(1, 2)
    (4, 3, (0, 1, 3), None, 2)
    """

    __slots__ = ("_children", "_types", "depth", "ids", "masses", "node", "parent")

    def __init__(self, types: int = 0) -> None:
        self.node: list[int] = []
        self.parent: list[int] = []
        self.depth: list[int] = []
        self.masses: list[list[Fraction]] = []
        self.ids: list[tuple[int, ...]] = []
        self._types = types
        self._children: dict[tuple[int, int], int] = {}

    def __len__(self) -> int:
        return len(self.node)

    @property
    def size(self) -> int:
        """Number of prefixes (the root included)."""
        return len(self.node)

    @property
    def mass(self) -> Mapping[tuple[int, ...], tuple[Fraction, ...]]:
        """Prefix tuple -> ``(x_0, …, x_{N-1})`` (a view; each key built only when asked for)."""
        return _MassView(self)

    def insert(self, walk: Sequence[int], theta: int | None = None,
               probability: Fraction = Fraction(0)) -> int:
        """Add ``walk`` and its prefixes; return its prefix id.

        With ``theta``, add ``probability`` to type ``theta``'s mass along the walk and record
        the walk's prefix ids in :attr:`ids`.
        """
        p = -1
        along = []
        children = self._children
        if theta is not None and type(probability) is not Fraction:
            probability = Fraction(probability)
        for v in walk:
            c = children.get((p, v))
            if c is None:
                c = children[(p, v)] = len(self.node)
                self.node.append(v)
                self.parent.append(p)
                self.depth.append(self.depth[p] + 1 if p >= 0 else 0)
                self.masses.append([Fraction(0)] * self._types)
            if theta is not None:
                masses = self.masses[c]
                # a new prefix's mass is this walk's probability: no Fraction sum needed
                masses[theta] = masses[theta] + probability if masses[theta] else probability
                along.append(c)
            p = c
        if theta is not None:
            self.ids.append(tuple(along))
        return p

    def child(self, p: int, v: int) -> int | None:
        """The prefix ``p·v``, or None when it is not in the trie."""
        return self._children.get((p, v))

    def extend(self, p: int, v: int) -> int:
        """The prefix ``p·v``, which must be in the trie (KeyError otherwise)."""
        return self._children[(p, v)]

    def find(self, walk: Sequence[int]) -> int | None:
        """The prefix id of ``walk``, or None when it is not in the trie."""
        i = -1
        for v in walk:
            nxt = self._children.get((i, v))
            if nxt is None:
                return None
            i = nxt
        return i if walk else None

    def find_along(self, walk: Sequence[int]) -> list[int]:
        """The prefix ids along ``walk`` (one per node), which must be in the trie."""
        out, i = [], -1
        for v in walk:
            i = self._children[(i, v)]
            out.append(i)
        return out

    def walk(self, p: int) -> tuple[int, ...]:
        """The walk (node indices) of prefix ``p``."""
        out = []
        while p >= 0:
            out.append(self.node[p])
            p = self.parent[p]
        return tuple(reversed(out))


class _Start(Protocol):
    @property
    def start(self) -> int: ...


def build_walk_trie(instance: _Start, walks: Iterable[Sequence[int]]) -> WalkTrie:
    """The trie of ``walks`` (each starting at ``s0``); the root ``(s0,)`` is always present.

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> len(build_walk_trie(star3(), []))
    1
    """
    t = WalkTrie()
    t.insert((instance.start,))
    for w in walks:
        t.insert(w)
    return t


def mass_trie(mixes: Sequence[Iterable[MixedWalk]], start: int | None = None) -> WalkTrie:
    """Each type's realization masses on the prefixes of its walks (``mixes[θ]``: type ``θ``'s
    mixed strategy), in memory linear in the total walk length; ``start`` (``s0``) makes the
    root prefix ``0`` whatever the walks.

    Examples
    --------
    >>> from dppverify.game.profile import StrategyWalk
    >>> t = mass_trie([[StrategyWalk((0, 1), Fraction(4, 7)), StrategyWalk((0, 2), Fraction(3, 7))],
    ...                [StrategyWalk((0, 2), Fraction(1))]])
    >>> t.mass[(0,)], t.mass[(0, 2)]
    ((Fraction(1, 1), Fraction(1, 1)), (Fraction(3, 7), Fraction(1, 1)))
    >>> t.size, t.ids, t.walk(2)
    (3, [(0, 1), (0, 2), (0, 2)], (0, 2))
    """
    t = WalkTrie(len(mixes))
    if start is not None:
        t.insert((start,))
    for theta, mix in enumerate(mixes):
        for mw in mix:
            t.insert(mw.walk, theta, mw.probability)
    return t
