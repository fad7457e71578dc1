"""The progress rule σ* (Sec. IV, Definition 3 and eq. (7); proofs/TEL.md).

Re-implemented from the paper's definition, independently of the solver: with
``c_0 = d(s0, g)`` and ``c_t = min(c_{t-1}, d(s_t, g))`` (full-graph distances), the Defender
allocates to ``g`` with probability ``(c_{t-1} - c_t) / w(e_t)`` and to the other goal with
the rest. A node that cannot reach ``g`` has ``d = inf`` and gives no progress. A rule that
gives "the rest" to "the other goal" is two-goal mathematics: the N-general Defender
(:mod:`dppverify.game.defender`) calls this module for a :class:`ProgressRule` only.
"""

from __future__ import annotations

import weakref
from collections.abc import Sequence
from fractions import Fraction
from typing import TYPE_CHECKING, cast

from dppverify.errors import InvalidInstanceError
from dppverify.exact import Number
from dppverify.game.defender import step_weights
from dppverify.game.instance import Instance
from dppverify.game.profile import ProgressRule

if TYPE_CHECKING:
    from dppverify.tree_route.tree import WalkTree

__all__ = ["progress_along", "progress_on_tree", "progress_sigma"]


def _distances_to(instance: Instance, goal: int) -> Sequence[Number]:
    """``d(., goal)`` over the whole graph (InvalidInstanceError if ``goal`` is no goal)."""
    theta = instance.goal_index(goal)
    if theta is None:
        raise InvalidInstanceError(f"node {instance.nodes[goal]!r} is not a goal of the instance")
    return instance.dist_to[theta]


def progress_along(instance: Instance, goal: int, walk: Sequence[int]) -> list[Number]:
    """The new progress ``c_{t-1} - c_t`` towards ``goal`` at each step of ``walk`` (eqs. (6)-(7)).

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> inst = triangle()
    >>> progress_along(inst, 1, [0, 2])   # s -> g2: d(., g1) drops from 3 to 2
    [1]
    """
    d = _distances_to(instance, goal)
    c = d[walk[0]]
    out: list[Number] = []
    for v in walk[1:]:
        new = min(c, d[v])
        out.append(c - new)
        c = new
    return out


_PROGRESS_SIGMA: weakref.WeakKeyDictionary[Instance, dict[tuple[int, tuple[int, ...]],
                                                          tuple[Number, ...]]] = \
    weakref.WeakKeyDictionary()


def progress_sigma(instance: Instance, rule: ProgressRule, walk: Sequence[int]
                   ) -> list[Number]:
    """``σ*(rule.goal | walk[:t+1])`` for ``t = 1..T`` (cached per instance and walk: the
    checks ask for σ* along the same profile walks repeatedly).

    Raises
    ------
    ProfileError
        If a step of ``walk`` is not an edge (:func:`~dppverify.game.defender.step_weights`).

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> progress_sigma(triangle(), ProgressRule(1), [0, 2])   # progress 1 on a step of 2
    [Fraction(1, 2)]
    """
    memo = _PROGRESS_SIGMA.get(instance)
    if memo is None:
        memo = _PROGRESS_SIGMA[instance] = {}
    key = (rule.goal, tuple(walk))
    if key not in memo:
        memo[key] = tuple(_progress_sigma(instance, rule, walk))
    return list(memo[key])


def _progress_sigma(instance: Instance, rule: ProgressRule, walk: Sequence[int]
                    ) -> list[Number]:
    """:func:`progress_sigma` without the cache."""
    prog = progress_along(instance, rule.goal, walk)
    weights = step_weights(instance, walk)
    if all(type(x) is int for x in prog) and all(type(w) is int for w in weights):
        # integers (unit grids): the exact ratio without a Fraction per step, decided
        # once per walk; the same numbers as NumberMode.ratio (an int when it divides)
        ints = cast(list[tuple[int, int]], list(zip(prog, weights, strict=True)))
        return [p // w if p % w == 0 else Fraction(p, w) for p, w in ints]
    ratio = instance.numbers.ratio
    return [ratio(pr, w) for pr, w in zip(prog, weights, strict=True)]


def progress_on_tree(tree: WalkTree, goal: int) -> list[Number]:
    """New progress towards ``goal`` at every prefix of ``tree`` (root: 0), eq. (7)'s numerator.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> from dppverify.tree_route.tree import build_tree
    >>> progress_on_tree(build_tree(triangle(), 1), 1)   # root, s -> g1, s -> g2
    [0, 3, 1]
    """
    d = _distances_to(tree.instance, goal)
    node = tree.node.tolist()
    parent = tree.parent.tolist()
    n = tree.n_prefixes
    c: list[Number] = [0] * n
    prog: list[Number] = [0] * n
    c[0] = d[node[0]]
    for p in range(1, n):
        cq = c[parent[p]]
        dv = d[node[p]]
        if dv < cq:
            c[p] = dv
            prog[p] = cq - dv
        else:
            c[p] = cq
    return prog
