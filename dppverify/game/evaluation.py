"""Exact payoffs of a profile: U¹, U², U (eqs. (3)-(4)), Ū and VoI (Definition 6).

Walk by walk, independently of the tree: a walk ``s0 … s_T`` costs type θ
``Σ_t w(e_t) σ(g^θ | s0 … s_t) + d(s_T, g^θ)`` (stage costs plus the terminal cost, with
full-graph distances), and ``U^θ`` is the expectation over type θ's mixed strategy.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from fractions import Fraction
from typing import TYPE_CHECKING

from dppverify.exact import Number, normalize
from dppverify.game.defender import sigma_along
from dppverify.game.instance import Instance, Roles
from dppverify.game.profile import DefenderRule, StrategyWalk
from dppverify.game.step_weights import step_weights

if TYPE_CHECKING:  # the game model does not import the tree route
    from dppverify.tree_route.tree import WalkTree



@dataclass(frozen=True)
class Values:
    """Payoffs of a profile (paper eqs. (3)-(4) and Definition 6)."""

    U1: Number
    U2: Number
    U: Number
    U_bar: Number
    VoI: Number


def walk_cost(instance: Instance, roles: Roles, rule: DefenderRule, walk: tuple[int, ...],
              role: int) -> Number:
    """Type ``role``'s cost of ``walk`` against ``rule``: stage costs + terminal cost.

    Examples
    --------
    The walk ``s -> g2`` of the triangle against σ* costs the primary type 3, the secondary 1:

    >>> from dppverify.game import examples, profile
    >>> inst = examples.triangle(); roles = inst.roles()
    >>> [walk_cost(inst, roles, profile.ProgressRule(roles.g1), (0, 2), th) for th in (1, 2)]
    [3, 1]
    """
    sigma = sigma_along(instance, roles, rule, walk)
    total: Number = 0
    for w, s in zip(step_weights(instance, walk), sigma, strict=True):
        total += w * (s if role == 1 else 1 - s)
    total += roles.dist(role)[walk[-1]]
    return instance.numbers.convert(total)


def complete_information_value(instance: Instance, roles: Roles) -> Number:
    """``Ū = b1 d(s0, g1) + b2 d(s0, g2)`` (eq. (1) and Definition 6).

    The Attacker's expected cost when the Defender knows its goal: each type walks a
    shortest path and the Defender allocates every step to the true goal. ``roles`` says
    which goal is ``g1``; ``Ū`` is exact for rational instances.

    Examples
    --------
    On the triangle ``d(s, g1) = 3`` and ``d(s, g2) = 2``:

    >>> from dppverify.game.examples import triangle
    >>> inst = triangle()
    >>> complete_information_value(inst, inst.roles())     # 7/10 * 3 + 3/10 * 2
    Fraction(27, 10)
    >>> inst = triangle(("1/2", "1/2"))
    >>> complete_information_value(inst, inst.roles())
    Fraction(5, 2)
    """
    s0 = instance.start
    return normalize(roles.b1 * roles.d1[s0] + roles.b2 * roles.d2[s0])


def evaluate(instance: Instance, roles: Roles, rule: DefenderRule,
             primary: Iterable[StrategyWalk], secondary: Iterable[StrategyWalk]) -> Values:
    """Exact payoffs of the profile ``(rule, primary, secondary)``.

    Examples
    --------
    The triangle's equilibrium (``s -> g1`` 4/7, ``s -> g2`` 3/7 against σ*):

    >>> from dppverify.game import examples, profile
    >>> inst = examples.triangle(); roles = inst.roles(); W = StrategyWalk
    >>> v = evaluate(inst, roles, profile.ProgressRule(roles.g1),
    ...              [W((0, 1), Fraction(4, 7)), W((0, 2), Fraction(3, 7))],
    ...              [W((0, 2), Fraction(1))])
    >>> [str(x) for x in (v.U1, v.U2, v.U, v.U_bar, v.VoI)]
    ['3', '1', '12/5', '27/10', '1/9']
    """
    mode = instance.numbers
    u: dict[int, Number] = {}
    for role, walks in ((1, primary), (2, secondary)):
        acc: Number = 0
        for mw in walks:
            acc += mw.probability * walk_cost(instance, roles, rule, mw.walk, role)
        u[role] = mode.convert(acc)
    U = mode.convert(roles.b1 * u[1] + roles.b2 * u[2])
    U_bar = complete_information_value(instance, roles)
    if mode.exact:
        voi: Number = normalize(Fraction(U_bar - U) / Fraction(U_bar))
    else:
        voi = (float(U_bar) - float(U)) / float(U_bar)
    return Values(U1=u[1], U2=u[2], U=U, U_bar=U_bar, VoI=voi)


def realization(tree: WalkTree, walks: Iterable[StrategyWalk]) -> dict[int, Fraction]:
    """Realization plan of a mixed strategy over walks: prefix index -> reach probability.

    Only prefixes with positive probability are listed. Every walk must be in ``tree``.

    Parameters
    ----------
    tree : WalkTree
        The walk tree; every walk must end at one of its leaves.
    walks : iterable of StrategyWalk
        The mixed strategy (walks as node indices, with probabilities).

    Returns
    -------
    dict
        Prefix index -> exact reach probability (the root has probability 1).

    Raises
    ------
    KeyError
        If a walk is not a leaf of ``tree`` (longer than the horizon).

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> from dppverify.tree_route.tree import build_tree
    >>> tree = build_tree(triangle(), 1)   # prefixes: 0 = s, 1 = s g1, 2 = s g2
    >>> realization(tree, [StrategyWalk((0, 1), Fraction(4, 7)),
    ...                    StrategyWalk((0, 2), Fraction(3, 7))])
    {0: Fraction(1, 1), 1: Fraction(4, 7), 2: Fraction(3, 7)}
    >>> realization(tree, [StrategyWalk((0, 2, 1), Fraction(1))])
    Traceback (most recent call last):
    KeyError: 'walk (0, 2, 1) is not in the walk tree (horizon 1)'
    """
    x: dict[int, Fraction] = {}
    for mw in walks:
        if mw.probability == 0:
            continue
        leaf = tree.find(mw.walk)
        if leaf is None:
            raise KeyError(f"walk {mw.walk} is not in the walk tree (horizon {tree.horizon})")
        for p in tree.prefixes(leaf):
            x[p] = x.get(p, Fraction(0)) + mw.probability
    return x
