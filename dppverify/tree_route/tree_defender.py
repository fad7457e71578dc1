"""A two-goal Defender rule evaluated at every prefix of a walk tree (:class:`TreeDefender`).

The tree route's form of :mod:`dppverify.game.defender`: ``σ(g1 | prefix)`` and the two types'
stage costs at every prefix, for the progress rule (σ*, through :mod:`dppverify.twogoal.progress`)
and for tables with or without a default.
"""

from __future__ import annotations

from dataclasses import dataclass

from dppverify.exact import Number
from dppverify.game.instance import Roles
from dppverify.game.profile import DefenderRule
from dppverify.tree_route.tree import WalkTree


@dataclass(frozen=True)
class TreeDefender:
    """A Defender strategy evaluated at every prefix of a walk tree.

    Attributes
    ----------
    sigma1 : tuple
        ``σ(g1 | prefix)`` for every prefix (index 0, the root, holds 0: no action).
    alloc1, alloc2 : tuple
        ``w σ(g1)`` and ``w (1 - σ(g1))``: type 1's and type 2's stage cost at each prefix.
    undefined : tuple of int
        Prefixes where a table Defender without default has no entry (their values are 0).
    """

    sigma1: tuple[Number, ...]
    alloc1: tuple[Number, ...]
    alloc2: tuple[Number, ...]
    undefined: tuple[int, ...] = ()

    def alloc(self, role: int) -> tuple[Number, ...]:
        """Stage costs of type ``role`` (1 = primary, 2 = secondary)."""
        return self.alloc1 if role == 1 else self.alloc2


def tree_defender(tree: WalkTree, roles: Roles, rule: DefenderRule) -> TreeDefender:
    """Evaluate a Defender rule at every prefix of ``tree`` (labelling ``roles``).

    For the progress rule the stage costs are the telescoping increments of proofs/TEL.md:
    ``a1 = c_{t-1} - c_t`` exactly (no division needed).

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> from dppverify.game.profile import ProgressRule
    >>> from dppverify.tree_route.tree import build_tree
    >>> tree = build_tree(triangle(), 1)
    >>> inst, r = tree.instance, tree.instance.roles()
    >>> td = tree_defender(tree, r, ProgressRule(r.g1))
    >>> [inst.labels(w) for w in ([0, 1], [0, 2])], td.sigma1, td.alloc1, td.alloc2
    ([('s', 'g1'), ('s', 'g2')], (0, 1, Fraction(1, 2)), (0, 3, 1), (0, 0, 1))
    """
    inst = tree.instance
    mode = inst.numbers
    n = tree.n_prefixes
    weight = tree.weight
    sigma_goal: list[Number] = [0] * n
    amount: list[Number | None] = [None] * n  # w * sigma_goal when known without multiplying
    undefined: list[int] = []
    progress_goal = rule.progress_goal
    if progress_goal is not None:
        from dppverify.twogoal.progress import progress_on_tree  # N = 2: σ*

        prog = progress_on_tree(tree, progress_goal)
        for p in range(1, n):
            s = mode.ratio(prog[p], weight[p])
            sigma_goal[p] = s
            amount[p] = prog[p] if mode.exact else mode.product(weight[p], s)
    elif rule.constant is not None:
        fill: Number = rule.constant
        sigma_goal = [0] + [fill] * (n - 1)
    listed = set()
    for walk, prob in rule.entries.items():  # the progress rule lists none
        p_idx = tree.find(walk)
        if p_idx is not None:
            sigma_goal[p_idx] = prob
            amount[p_idx] = None
            listed.add(p_idx)
    if not rule.defined_everywhere:
        undefined = [p for p in range(1, n) if p not in listed]
    one = mode.one()
    to_g1 = rule.goal == roles.g1
    sigma1: list[Number] = [0] * n
    alloc1: list[Number] = [0] * n
    alloc2: list[Number] = [0] * n
    for p in range(1, n):
        w = weight[p]
        a = amount[p]
        if a is None:
            a = mode.product(w, sigma_goal[p])
        b = mode.difference(w, a)
        if to_g1:
            sigma1[p], alloc1[p], alloc2[p] = sigma_goal[p], a, b
        else:
            s = mode.difference(one, sigma_goal[p])
            sigma1[p], alloc1[p], alloc2[p] = s, b, a
    return TreeDefender(sigma1=tuple(sigma1), alloc1=tuple(alloc1), alloc2=tuple(alloc2),
                        undefined=tuple(undefined))
