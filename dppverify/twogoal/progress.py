"""The progress rule σ* on the walk tree (Sec. IV, eq. (7); proofs/TEL.md): the new progress at
every prefix of a :class:`~dppverify.tree_route.tree.WalkTree` at once.

σ* along one walk is :mod:`dppverify.game.progress_rule` (the rule is part of the profile
format); the tree form is two-goal mathematics used by the tree route where N = 2.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from dppverify.exact import Number
from dppverify.game.progress_rule import distances_to_goal

if TYPE_CHECKING:
    from dppverify.tree_route.tree import WalkTree



def progress_on_tree(tree: WalkTree, goal: int) -> list[Number]:
    """New progress towards ``goal`` at every prefix of ``tree`` (root: 0), eq. (7)'s numerator.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> from dppverify.tree_route.tree import build_tree
    >>> progress_on_tree(build_tree(triangle(), 1), 1)   # root, s -> g1, s -> g2
    [0, 3, 1]
    """
    d = distances_to_goal(tree.instance, goal)
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
