"""The weights of a walk's steps (a step that is not an edge is a ProfileError naming it)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import cast

from dppverify.errors import ProfileError
from dppverify.exact import Number
from dppverify.game.instance_type import Instance


def step_weight(instance: Instance, walk: Sequence[int], t: int) -> Number:
    """The weight of step ``t`` (``walk[t-1] -> walk[t]``) of ``walk``.

    Raises
    ------
    ProfileError
        If that step is not an edge of the instance (the message names it).

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> inst = triangle()
    >>> s, g1, g2 = (inst.index[v] for v in ("s", "g1", "g2"))
    >>> step_weight(inst, [s, g2, g1], 2)
    2
    >>> step_weight(inst, [s, s], 1)
    Traceback (most recent call last):
    ...
    dppverify.errors.ProfileError: step 1 of the walk, 's' -> 's', is not an edge
    """
    w = instance.weight(walk[t - 1], walk[t])
    if w is None:
        u, v = instance.nodes[walk[t - 1]], instance.nodes[walk[t]]
        raise ProfileError(f"step {t} of the walk, {u!r} -> {v!r}, is not an edge")
    return w


def step_weights(instance: Instance, walk: Sequence[int]) -> list[Number]:
    """The weights of steps ``1 .. T`` of ``walk``: :func:`step_weight` for the whole walk.

    Raises
    ------
    ProfileError
        At the first step that is not an edge (the same message as :func:`step_weight`).

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> inst = triangle()
    >>> s, g1, g2 = (inst.index[v] for v in ("s", "g1", "g2"))
    >>> step_weights(inst, [s, g2, g1])
    [2, 2]
    """
    weights = instance.weights_along(walk)
    for t, w in enumerate(weights, start=1):
        if w is None:
            step_weight(instance, walk, t)  # raises the message naming the step
    return cast(list[Number], weights)
