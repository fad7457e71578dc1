"""The players on the walk tree (any ``N >= 2`` goals): the Attacker's types and a Defender.

The Attacker's *types* (:class:`Types`: a prior and the distances to the type's goal) are
keyed either by role, for the two-goal labelling (:class:`~dppverify.game.instance.Roles`:
1 primary, 2 secondary), or by goal index θ ``0 .. N-1``, for an instance's N goals in
document order; ``who`` names a type by its key. An Attacker type plays a realization plan
(:data:`Plan`). A Defender evaluated on the tree gives type ``who`` the stage cost
``a(p) = w(p)·σ(goal of who | p)`` at every prefix ``p``
(:class:`TreeStrategy`): the two-goal
:class:`~dppverify.tree_route.tree_defender.TreeDefender`, or a :class:`DefenderOnTree` for any
number of goals.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Protocol

from dppverify.exact import Number, normalize
from dppverify.game.instance import Instance, Roles
from dppverify.tree_route.tree import WalkTree

Plan = Mapping[int, Fraction]
"""A realization plan: prefix -> reach probability (reached prefixes)."""


@dataclass(frozen=True)
class Types:
    """The Attacker's types: for each its key, its prior and the distances to its goal.

    Attributes
    ----------
    keys : tuple of int
        The types' keys, in order: roles (1, 2) or goal indices θ (0 .. N-1).
    priors : tuple of Fraction
        ``priors[k]``: the prior of type ``keys[k]``.
    dists : tuple
        ``dists[k][v]``: full-graph ``d(v, goal of type keys[k])``.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> t = as_types(triangle().roles())
    >>> t.keys, t.prior(2), t.dist(1)
    ((1, 2), Fraction(3, 10), (3, 0, 2))
    """

    keys: tuple[int, ...]
    priors: tuple[Fraction, ...]
    dists: tuple[Sequence[Number], ...]

    def prior(self, who: int) -> Fraction:
        """The prior of type ``who``."""
        return self.priors[self.keys.index(who)]

    def dist(self, who: int) -> Sequence[Number]:
        """Distances from every node to the goal of type ``who``."""
        return self.dists[self.keys.index(who)]


AnyTypes = Types | Roles | Instance
"""What :func:`as_types` reads as the types."""


def as_types(types: AnyTypes) -> Types:
    """The types of a two-goal labelling (keys: the roles 1, 2) or of an instance's goals
    (keys: the goal indices θ = 0 .. N-1).

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> t = as_types(star3())
    >>> t.keys, t.priors
    ((0, 1, 2), (Fraction(1, 2), Fraction(1, 3), Fraction(1, 6)))
    """
    if isinstance(types, Types):
        return types
    if isinstance(types, Roles):
        return Types(keys=(1, 2), priors=(types.b1, types.b2), dists=(types.d1, types.d2))
    return Types(keys=tuple(range(len(types.goals))), priors=types.prior,
                 dists=types.dist_to)


class TreeStrategy(Protocol):
    """A Defender evaluated at every prefix of the tree: each type's stage costs."""

    def alloc(self, who: int) -> Sequence[Number]:
        """``w(p)·σ(goal of who | p)`` for every prefix ``p`` (0 at the root)."""
        ...


@dataclass(frozen=True)
class DefenderOnTree:
    """A Defender strategy on N goals evaluated at every prefix of a walk tree (θ = goal index).

    Attributes
    ----------
    sigma : tuple
        ``sigma[p][k] = σ(g^θ | p)`` for ``θ = keys[k]`` (the root's entry is all zeros: no
        action there).
    allocs : tuple
        ``allocs[k][p] = w(p)·σ(g^θ | p)``: type ``θ = keys[k]``'s stage cost at ``p``.
    keys : tuple of int
        The types (the goal indices ``0 .. N-1`` for :func:`defender_from_table`).

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> from dppverify.tree_route.tree import build_tree
    >>> t = build_tree(star3(), 1)
    >>> d = defender_from_table(t, {}, (Fraction(1), Fraction(0), Fraction(0)))
    >>> d.alloc(0)
    (0, 2)
    """

    sigma: tuple[tuple[Number, ...], ...]
    allocs: tuple[tuple[Number, ...], ...]
    keys: tuple[int, ...]

    def alloc(self, who: int) -> tuple[Number, ...]:
        """Type ``who``'s stage costs."""
        return self.allocs[self.keys.index(who)]


def defender_from_table(tree: WalkTree, entries: Mapping[int, Sequence[Fraction]],
                        default: Sequence[Fraction] | None) -> DefenderOnTree:
    """Evaluate a table Defender (prefix -> goal distribution, with a default) on ``tree``.

    Raises
    ------
    KeyError
        If a prefix has no entry and there is no default.

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> from dppverify.tree_route.tree import build_tree
    >>> t = build_tree(star3(), 1)
    >>> half = (Fraction(1, 2), Fraction(1, 2), Fraction(0))
    >>> defender_from_table(t, {1: half}, None).allocs
    ((0, 1), (0, 1), (0, 0))
    """
    n_goals = len(tree.instance.goals)
    zero = tuple(Fraction(0) for _ in range(n_goals))
    sigma: list[tuple[Number, ...]] = [zero]
    alloc: list[list[Number]] = [[0] * tree.n_prefixes for _ in range(n_goals)]
    for p in range(1, tree.n_prefixes):
        if p in entries:
            s = tuple(Fraction(x) for x in entries[p])
        elif default is not None:
            s = tuple(Fraction(x) for x in default)
        else:
            raise KeyError(p)
        sigma.append(s)
        for theta in range(n_goals):
            alloc[theta][p] = normalize(tree.weight[p] * s[theta])
    return DefenderOnTree(sigma=tuple(sigma), allocs=tuple(tuple(a) for a in alloc),
                          keys=tuple(range(n_goals)))


def defender_from_rows(tree: WalkTree, types: Types, rows: Sequence[Sequence[Number]]
                       ) -> DefenderOnTree:
    """The Defender with ``σ(g^θ | p) = rows[p][k]`` (``θ = keys[k]``; each row sums to 1).

    The last type's stage cost is the rest of the step's weight, ``w - Σ`` of the others'
    (so that in float mode the two stage costs of a step add up to its weight exactly).

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> from dppverify.tree_route.tree import build_tree
    >>> inst = triangle()
    >>> d = defender_from_rows(build_tree(inst, 1), as_types(inst.roles()),
    ...                        [(0, 0), (1, 0), (Fraction(1, 4), Fraction(3, 4))])
    >>> d.alloc(1), d.alloc(2)
    ((0, 3, Fraction(1, 2)), (0, 0, Fraction(3, 2)))
    """
    numbers = tree.instance.numbers
    w = tree.weight
    k = len(types.keys)
    allocs: list[list[Number]] = [[0] * tree.n_prefixes for _ in range(k)]
    for p in range(1, tree.n_prefixes):
        rest = w[p]
        for j in range(k - 1):
            allocs[j][p] = numbers.product(w[p], rows[p][j])
            rest = numbers.difference(rest, allocs[j][p])
        allocs[k - 1][p] = rest
    return DefenderOnTree(sigma=tuple(tuple(r) for r in rows),
                          allocs=tuple(tuple(a) for a in allocs), keys=types.keys)
