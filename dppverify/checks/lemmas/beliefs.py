"""Lemma 5 on the profile's attacker: ``lemma.L5.induced_beliefs`` (proofs/L5.md).

Lemma 5's belief 1 off ξ² is not checked: with one secondary walk the secondary puts no
mass off ξ², so that belief is 1 by Bayes' rule whatever the profile (a check that cannot
fail is no evidence); the message says so (:data:`OFF_XI2`).
"""

from __future__ import annotations

from fractions import Fraction

from dppverify.certificate import CheckRecord
from dppverify.exact import Number
from dppverify.game.defender import sigma_along
from dppverify.game.profile import ProgressRule
from dppverify.text import show
from dppverify.tree_route.context import EvaluatedContext
from dppverify.twogoal.phases import phases_of

HALF = Fraction(1, 2)

OFF_XI2 = ("off ξ² the belief is 1 by construction (the single secondary walk puts no mass "
           "there; not checked)")
"""L5's note on the primary prefixes off ξ² (see the module docstring)."""


def l5_induced_beliefs(ctx: EvaluatedContext) -> CheckRecord:
    """``lemma.L5.induced_beliefs``: Lemma 5 for the profile's attacker.

    Examples
    --------
    ξ² = ``s -> g2`` is all phase II: the equilibrium mixture makes the belief 1/2 after its
    step; with the primary's probabilities swapped it is 4/7.

    >>> from dppverify.game.examples import triangle_attacker

    >>> from tests.dppverify.checks.doctest_inputs import triangle_context as context
    >>> l5_induced_beliefs(context()).status
    'pass'
    >>> r = l5_induced_beliefs(context(triangle_attacker("3/7", "4/7")))
    >>> r.status, r.message
    ('fail', 'at step 1 of ξ² (phase II) the belief is 4/7, not 1/2')
    """
    cid = "lemma.L5.induced_beliefs"
    sec = [w for w in ctx.profile.secondary if w.probability > 0]
    if len(sec) != 1:
        return CheckRecord(cid, "skipped", "not applicable: the secondary type mixes several "
                           "walks, Lemma 5 is about the paper's deterministic ξ²", {}, "L5")
    inst, tree, roles = ctx.instance, ctx.tree, ctx.roles
    xi2 = sec[0].walk
    t1, t2, T = phases_of(sigma_along(inst, roles, ProgressRule(roles.g1), xi2),
                          ctx.numbers).as_tuple()
    leaf = tree.find(xi2)
    assert leaf is not None
    along = tree.prefixes(leaf)

    problems = []
    for t, p in enumerate(along):
        want = roles.b1 if t <= t1 else (HALF if t <= t2 else Fraction(0))
        got = ctx.evaluated.beliefs[p]
        if got != want:
            phase = "I" if t <= t1 else ("II" if t <= t2 else "III")
            problems.append(f"at step {t} of ξ² (phase {phase}) the belief is {show(got)}, "
                            f"not {show(want)}")
    on_xi2 = set(along)
    off = [p for p in ctx.evaluated.x1 if p not in on_xi2]
    numbers: dict[str, Number | None] = {"t_I": t1, "t_II": t2, "T": T, "b1": roles.b1,
                                         "off_path_prefixes": len(off)}
    if problems:
        return CheckRecord(cid, "fail", "; ".join(problems[:3]), numbers, "L5")
    return CheckRecord(cid, "pass", f"beliefs along ξ² are {show(roles.b1)} on phase I "
                       f"(t <= {t1}), 1/2 on phase II (t <= {t2}), 0 on phase III (t <= {T}); "
                       f"{OFF_XI2}", numbers, "L5")
