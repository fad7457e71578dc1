"""Exact best responses, payoffs and Bayes beliefs in the truncated N-goal game.

A Defender strategy on the tree gives, at every prefix ``p``, a probability ``σ(g^θ | p)`` for
each goal; type ``θ`` then pays the stage cost ``a_θ(p) = w(p)·σ(g^θ | p)``. An Attacker type
is a realization plan ``x_θ`` (prefix -> reach probability).

- type θ's best response against a Defender: exact backward induction over ALL walks of the
  tree, ``J(p) = min_c [a_θ(c) + J(c)]``, ``J(leaf) = d(end, g^θ)``;
- the Defender's best response against plans: greedy per information set (the walk prefix),
  ``Σ_p w(p)·max_θ b_θ x_θ(p)`` plus the terminal costs — the N-type form of Lemma 3
  (``proofs/L3.md``'s argument does not use the number of types);
- the Bayes belief at a prefix reached with positive probability,
  ``μ(θ | p) = b_θ x_θ(p) / Σ_η b_η x_η(p)``.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction

from dppverify.exact import INF, Number, normalize
from dppverify.tree_route.tree import WalkTree

__all__ = ["NAttackerBR", "NDefenderBR", "NTreeDefender", "attacker_best_response",
           "beliefs", "defender_best_response", "defender_from_table", "payoff"]

Plan = Mapping[int, Fraction]


@dataclass(frozen=True)
class NTreeDefender:
    """A Defender strategy evaluated at every prefix of an N-goal walk tree.

    Attributes
    ----------
    sigma : tuple
        ``sigma[p][θ] = σ(g^θ | p)`` (the root's entry is all zeros: no action there).
    alloc : tuple
        ``alloc[θ][p] = w(p)·σ(g^θ | p)``: type θ's stage cost at prefix ``p``.

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> from dppverify.tree_route.tree import build_tree
    >>> t = build_tree(star3(), 1)
    >>> d = defender_from_table(t, {}, (Fraction(1), Fraction(0), Fraction(0)))
    >>> d.alloc[0]
    (0, 2)
    """

    sigma: tuple[tuple[Fraction, ...], ...]
    alloc: tuple[tuple[Number, ...], ...]


def defender_from_table(tree: WalkTree, entries: Mapping[int, Sequence[Fraction]],
                        default: Sequence[Fraction] | None) -> NTreeDefender:
    """Evaluate a table Defender (prefix -> goal distribution, with a default) on ``tree``.

    Raises
    ------
    KeyError
        If a prefix has no entry and there is no default.

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> from dppverify.tree_route.tree import build_tree
    >>> t = build_tree(star3(), 1)
    >>> half = (Fraction(1, 2), Fraction(1, 2), Fraction(0))
    >>> defender_from_table(t, {1: half}, None).alloc
    ((0, 1), (0, 1), (0, 0))
    """
    n_goals = tree.instance.n_goals
    zero = tuple(Fraction(0) for _ in range(n_goals))
    sigma: list[tuple[Fraction, ...]] = [zero]
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
    return NTreeDefender(sigma=tuple(sigma), alloc=tuple(tuple(a) for a in alloc))


@dataclass(frozen=True)
class NAttackerBR:
    """Type θ's best response in the tree: its cost and one minimising walk."""

    theta: int
    value: Number
    leaf: int
    walk: tuple[int, ...]


@dataclass(frozen=True)
class NDefenderBR:
    """The Defender's greedy best response: its value and a best goal per reached prefix."""

    value: Number
    choice: Mapping[int, int]


def attacker_best_response(tree: WalkTree, tdef: NTreeDefender, theta: int) -> NAttackerBR:
    """Exact best response of type ``θ`` (0-based) by backward induction over all walks.

    Examples
    --------
    Against a Defender that always guards goal ``a``, type ``b`` walks ``s m b`` for free
    and type ``a`` pays 2 whichever way it walks:

    >>> from dppverify.ngoal.examples import star3
    >>> from dppverify.tree_route.tree import build_tree
    >>> inst = star3()
    >>> t = build_tree(inst, 2)
    >>> d = defender_from_table(t, {}, (Fraction(1), Fraction(0), Fraction(0)))
    >>> [(br.value, inst.labels(br.walk)) for br in (attacker_best_response(t, d, 0),
    ...                                               attacker_best_response(t, d, 1))]
    [(2, ('s', 'm', 'a')), (0, ('s', 'm', 'b'))]
    """
    inst = tree.instance
    a = tdef.alloc[theta]
    d = inst.dist_to[theta]
    start = tree.child_start.tolist()
    stop = tree.child_stop.tolist()
    node = tree.node.tolist()
    n = tree.n_prefixes
    J: list[Number] = [INF] * n
    best = [-1] * n
    for p in range(n - 1, -1, -1):
        lo, hi = start[p], stop[p]
        if lo == hi:
            J[p] = d[node[p]]
            continue
        bj: Number = INF
        for c in range(lo, hi):
            v = a[c] + J[c]
            if v < bj:
                bj, best[p] = v, c
        J[p] = bj
    p = 0
    while best[p] >= 0:
        p = best[p]
    return NAttackerBR(theta=theta, value=normalize(J[0]), leaf=p, walk=tree.walk(p))


def _terminal(tree: WalkTree, plans: Sequence[Plan]) -> Number:
    inst = tree.instance
    leaf = tree.is_leaf_mask()
    total: Number = 0
    for theta, x in enumerate(plans):
        d = inst.dist_to[theta]
        for p, prob in x.items():
            if leaf[p]:
                total += inst.prior[theta] * prob * d[int(tree.node[p])]
    return total


def payoff(tree: WalkTree, tdef: NTreeDefender, plans: Sequence[Plan]) -> Number:
    """``U = Σ_θ b_θ [Σ_p x_θ(p) a_θ(p) + terminal]``: the Attacker's expected cost, exactly.

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> from dppverify.tree_route.tree import build_tree
    >>> t = build_tree(star3(), 1)
    >>> d = defender_from_table(t, {}, (Fraction(1), Fraction(0), Fraction(0)))
    >>> payoff(t, d, [{0: Fraction(1), 1: Fraction(1)}] * 3)   # all walk s a
    2
    """
    inst = tree.instance
    total = _terminal(tree, plans)
    for theta, x in enumerate(plans):
        a = tdef.alloc[theta]
        for p, prob in x.items():
            if p:
                total += inst.prior[theta] * prob * a[p]
    return normalize(total)


def defender_best_response(tree: WalkTree, plans: Sequence[Plan]) -> NDefenderBR:
    """Exact greedy Defender best response against realization plans (one per type).

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> from dppverify.tree_route.tree import build_tree
    >>> t = build_tree(star3(), 1)
    >>> br = defender_best_response(t, [{0: Fraction(1), 1: Fraction(1)}] * 3)
    >>> br.value, dict(br.choice)
    (2, {1: 0})
    """
    inst = tree.instance
    total = _terminal(tree, plans)
    choice: dict[int, int] = {}
    reached = sorted({p for x in plans for p, prob in x.items() if prob and p})
    for p in reached:
        masses = [inst.prior[t] * x.get(p, Fraction(0)) for t, x in enumerate(plans)]
        top = max(masses)
        choice[p] = masses.index(top)
        total += tree.weight[p] * top
    return NDefenderBR(value=normalize(total), choice=choice)


def beliefs(tree: WalkTree, plans: Sequence[Plan]) -> dict[int, tuple[Fraction, ...]]:
    """Bayes beliefs ``μ(· | p)`` at every prefix reached with positive probability.

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> from dppverify.tree_route.tree import build_tree
    >>> t = build_tree(star3(), 1)
    >>> beliefs(t, [{0: Fraction(1), 1: Fraction(1)}] * 3)[1]
    (Fraction(1, 2), Fraction(1, 3), Fraction(1, 6))
    """
    inst = tree.instance
    out: dict[int, tuple[Fraction, ...]] = {}
    reached = sorted({p for x in plans for p, prob in x.items() if prob})
    for p in reached:
        masses = [inst.prior[t] * x.get(p, Fraction(0)) for t, x in enumerate(plans)]
        tot = sum(masses, Fraction(0))
        out[p] = tuple(m / tot for m in masses)
    return out
