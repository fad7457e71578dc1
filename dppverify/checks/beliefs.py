"""Bayes beliefs of the profile: ``pbne.belief_consistency``."""

from __future__ import annotations

from fractions import Fraction

from dppverify.certificate import CheckRecord
from dppverify.exact import Number
from dppverify.text import show
from dppverify.tree_route.context import EvaluatedContext


def belief_consistency(ctx: EvaluatedContext) -> CheckRecord:
    """``pbne.belief_consistency``: beliefs follow Bayes' rule (eq. (2)) from the prior.

    The belief is propagated step by step with the behavioural probabilities
    ``γ_t(e_t | h_t, g^i) = x_i(child) / x_i(parent)`` and must equal the closed form
    ``b1 x1 / (b1 x1 + b2 x2)`` at every reached information set; the profile's stated prior
    (if any) must be the instance's. Off-path beliefs are unspecified (weak PBNE).

    Examples
    --------
    >>> from dppverify.game.examples import triangle_attacker
    >>> from tests.dppverify.checks.doctest_inputs import triangle_context as context
    >>> eq = triangle_attacker()
    >>> dict(belief_consistency(context(eq)).numbers)
    {'b1': Fraction(7, 10), 'b2': Fraction(3, 10), 'infosets': 2, 'mismatches': 0}
    >>> r = belief_consistency(context(eq, prior={"primary": "1/2", "secondary": "1/2"}))
    >>> r.status, r.message
    ('fail', "the profile states the prior (1/2, 1/2) but the instance's is (7/10, 3/10)")
    """
    cid = "pbne.belief_consistency"
    roles, tree = ctx.roles, ctx.tree
    claim = ctx.profile.claimed_prior
    numbers: dict[str, Number | None] = {"b1": roles.b1, "b2": roles.b2}
    if claim is not None and claim != (roles.b1, roles.b2):
        return CheckRecord(cid, "fail", f"the profile states the prior ({show(claim[0])}, "
                           f"{show(claim[1])}) but the instance's is ({show(roles.b1)}, "
                           f"{show(roles.b2)})", numbers, "THM")
    ev = ctx.evaluated
    closed = ev.beliefs
    recursive: dict[int, Fraction] = {0: roles.b1}
    parent = tree.parent
    mismatches = 0
    for p in sorted(closed):
        if p == 0:
            continue
        q = int(parent[p])
        b = recursive[q]
        g1 = ev.x1.get(p, Fraction(0)) / ev.x1[q] if ev.x1.get(q) else Fraction(0)
        g2 = ev.x2.get(p, Fraction(0)) / ev.x2[q] if ev.x2.get(q) else Fraction(0)
        num = b * g1
        den = num + (1 - b) * g2
        recursive[p] = num / den
        if recursive[p] != closed[p]:
            mismatches += 1
    numbers["infosets"] = len(closed) - 1
    numbers["mismatches"] = mismatches
    if mismatches:
        return CheckRecord(cid, "error", f"Bayes' rule step by step and the closed form "
                           f"disagree at {mismatches} information sets", numbers, "THM")
    return CheckRecord(cid, "pass", f"Bayes beliefs from the prior ({show(roles.b1)}, "
                       f"{show(roles.b2)}) at all {len(closed) - 1} reached information sets "
                       f"(step by step = closed form); off-path beliefs unspecified", numbers,
                       "THM")
