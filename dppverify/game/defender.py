"""The Defender's strategies: explicit tables (with a default) and the progress rule σ*.

A table gives ``σ(goal | walk)`` for the walks it lists and its default for the others: a
probability, the progress rule, or none (unlisted walks are undefined). The progress rule
σ* (eq. (7)) is two-goal mathematics: :mod:`dppverify.twogoal.progress` computes it, and this
module calls it (imported where a :class:`ProgressRule` is met) only.

Everything is expressed as ``σ(g1 | walk)``, the probability of allocating to the primary
goal ``g1`` of the labelling in use, and as the allocated amounts
``a1 = w(e_t) σ(g1)`` and ``a2 = w(e_t) (1 - σ(g1))`` — the stage costs of the two types.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import cast

from dppverify.errors import ProfileError
from dppverify.exact import Number
from dppverify.game.instance import Instance, Roles
from dppverify.game.profile import DefenderRule, ProgressRule, TableRule

__all__ = ["UndefinedStrategyError", "sigma_along", "step_weight", "step_weights"]


class UndefinedStrategyError(LookupError):
    """A table Defender without default has no entry for a walk the game reaches."""


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


def _rule_sigma_to_goal(instance: Instance, rule: DefenderRule, walk: Sequence[int]
                        ) -> list[Number]:
    """σ(rule.goal | walk[:t+1]) for t = 1..T."""
    if isinstance(rule, ProgressRule):
        from dppverify.twogoal.progress import progress_sigma  # N = 2: σ*

        return progress_sigma(instance, rule, walk)
    return _table_sigma(instance, rule, walk)


def _table_sigma(instance: Instance, rule: TableRule, walk: Sequence[int]) -> list[Number]:
    """σ(rule.goal | walk[:t+1]) for t = 1..T under a table (its default for unlisted)."""
    result: list[Number] = []
    progress: list[Number] | None = None
    for t in range(1, len(walk)):
        key = tuple(walk[:t + 1])
        if key in rule.entries:
            result.append(rule.entries[key])
        elif isinstance(rule.default, ProgressRule):
            if progress is None:
                progress = _rule_sigma_to_goal(instance, rule.default, walk)
            result.append(progress[t - 1])
        elif rule.default is not None:
            result.append(rule.default)
        else:
            raise UndefinedStrategyError(f"the Defender's table has no entry for walk "
                                         f"{instance.labels(key)} and no default")
    return result


def sigma_along(instance: Instance, roles: Roles, rule: DefenderRule,
                walk: Sequence[int]) -> list[Number]:
    """``σ(g1 | s0 … s_t)`` at each step ``t = 1..T`` of ``walk``.

    Raises
    ------
    UndefinedStrategyError
        For a table without default that does not list one of the walk's prefixes.

    Examples
    --------
    >>> from dppverify.game.instance import instance_from_json
    >>> inst = instance_from_json({"graph": {"nodes": [{"id": "s"}, {"id": "a"},
    ...     {"id": "g1"}, {"id": "g2"}], "edges": [{"source": "s", "target": "a", "weight": 2},
    ...     {"source": "a", "target": "g1", "weight": 2}, {"source": "s", "target": "g2",
    ...     "weight": 3}]}, "start": "s", "goals": ["g1", "g2"], "prior": ["3/5", "2/5"]})
    >>> r = inst.roles()
    >>> sigma_along(inst, r, ProgressRule(r.g1), [0, 1, 2])
    [1, 1]
    >>> sigma_along(inst, r, ProgressRule(r.g1), [0, 1, 0, 3])   # back to s, then g2
    [1, 0, 0]
    """
    sigma = _rule_sigma_to_goal(instance, rule, walk)
    if rule.goal == roles.g1:
        return sigma
    mode = instance.numbers
    return [mode.difference(mode.one(), s) for s in sigma]
