"""The Defender's strategies: explicit tables (with a default) and the progress rule σ*.

A table gives ``σ(goal | walk)`` for the walks it lists and its default for the others: a
probability, the progress rule, or none (unlisted walks are undefined). The progress rule
σ* (eq. (7)) along a walk is :mod:`dppverify.game.progress_rule`'s.

Everything is expressed as ``σ(g1 | walk)``, the probability of allocating to the primary
goal ``g1`` of the labelling in use, and as the allocated amounts
``a1 = w(e_t) σ(g1)`` and ``a2 = w(e_t) (1 - σ(g1))`` — the stage costs of the two types.
"""

from __future__ import annotations

from collections.abc import Sequence

from dppverify.exact import Number
from dppverify.game.instance import Instance, Roles
from dppverify.game.profile import DefenderRule, ProgressRule
from dppverify.game.progress_rule import progress_sigma


class UndefinedStrategyError(LookupError):
    """A table Defender without default has no entry for a walk the game reaches."""


def _rule_sigma_to_goal(instance: Instance, rule: DefenderRule, walk: Sequence[int]
                        ) -> list[Number]:
    """σ(rule.goal | walk[:t+1]) for t = 1..T: the rule's listed walks, else σ* towards its
    progress goal, else its constant default; linear in the walk's length (the listed prefixes
    are found in one pass, :meth:`~dppverify.game.profile_types.ProfileDefender.listed_along`)."""
    listed = rule.listed_along(walk)
    progress: list[Number] | None = None
    if len(listed) < len(walk) - 1 and rule.progress_goal is not None:
        progress = progress_sigma(instance, ProgressRule(rule.progress_goal), walk)
    result: list[Number] = []
    for t in range(1, len(walk)):
        listed_t = listed.get(t)
        if listed_t is not None:
            result.append(listed_t)
        elif progress is not None:
            result.append(progress[t - 1])
        elif rule.constant is not None:
            result.append(rule.constant)
        else:
            raise UndefinedStrategyError(f"the Defender's table has no entry for walk "
                                         f"{instance.labels(tuple(walk[:t + 1]))} and no "
                                         f"default")
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
