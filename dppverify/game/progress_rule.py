"""The progress rule σ* along a walk (Sec. IV, Definition 3 and eq. (7); proofs/TEL.md).

Re-implemented from the paper's definition, independently of the solver: with
``c_0 = d(s0, g)`` and ``c_t = min(c_{t-1}, d(s_t, g))`` (full-graph distances), the Defender
allocates to ``g`` with probability ``(c_{t-1} - c_t) / w(e_t)`` (the rest goes to the other
goal: two goals). The rule is part of the profile format (:class:`ProgressRule`), so its
σ along a walk sits here, beside the other Defender rules (:mod:`dppverify.game.defender`);
its form on the walk tree and the rest of the two-goal mathematics are in
:mod:`dppverify.twogoal`. A node that cannot reach ``g`` has ``d = inf`` and gives no progress.
"""

from __future__ import annotations

import weakref
from collections.abc import Sequence
from fractions import Fraction
from typing import cast

from dppverify.errors import InvalidInstanceError
from dppverify.exact import Number
from dppverify.game.instance_type import Instance
from dppverify.game.rules import ProgressRule
from dppverify.game.step_weights import step_weights


def distances_to_goal(instance: Instance, goal: int) -> Sequence[Number]:
    """``d(., goal)`` over the whole graph (InvalidInstanceError if ``goal`` is no goal).

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> distances_to_goal(triangle(), 1)   # d(s, g1), d(g1, g1), d(g2, g1)
    (3, 0, 2)
    """
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
    d = distances_to_goal(instance, goal)
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
        If a step of ``walk`` is not an edge (:func:`~dppverify.game.step_weights.step_weights`).

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
