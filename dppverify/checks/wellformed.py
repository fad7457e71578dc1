"""The profile document's checks: ``profile.wellformed`` and ``profile.phases``."""

from __future__ import annotations

from dppio.text import count
from dppverify.certificate import CheckRecord
from dppverify.checks.skipped import skipped
from dppverify.exact import Number
from dppverify.game.defender import sigma_along
from dppverify.game.profile import ProgressRule
from dppverify.text import show_walk
from dppverify.tree_route.context import Context
from dppverify.twogoal.phases import phases_of


def wellformed(ctx: Context) -> CheckRecord:
    """``profile.wellformed``: the document describes a profile of this game.

    Examples
    --------
    The triangle's equilibrium (see :mod:`dppverify.game.examples`), then a primary mixture whose
    probabilities do not sum to 1:

    >>> from dppverify.game.examples import triangle_attacker

    >>> from tests.dppverify.checks.doctest_inputs import triangle_context as context
    >>> eq = triangle_attacker()
    >>> wellformed(context(eq)).message
    "well-formed: 2 primary walks and 1 secondary walk, primary goal 'g1'"
    >>> bad = dict(eq, primary=[{"path": ["s", "g1"], "probability": "1/7"},
    ...                         {"path": ["s", "g2"], "probability": "3/7"}])
    >>> r = wellformed(context(bad))
    >>> r.status, r.message
    ('fail', 'attacker.primary: probabilities sum to 4/7, not 1')
    """
    defects = [str(d) for d in ctx.profile.defects]
    if ctx.undefined:
        walk = show_walk(ctx.instance, ctx.tree.walk(ctx.undefined[0]))
        defects.append(f"defender: the table has no default and no entry for "
                       f"{count(len(ctx.undefined), 'walk')} of the H = {ctx.tree.horizon} tree, "
                       f"e.g. {walk}")
    numbers: dict[str, Number | None] = {"defects": len(defects),
                                         "primary_walks": len(ctx.profile.primary),
                                         "secondary_walks": len(ctx.profile.secondary)}
    if defects:
        shown = "; ".join(defects[:5])
        more = f"; and {len(defects) - 5} more" if len(defects) > 5 else ""
        return CheckRecord("profile.wellformed", "fail", shown + more, numbers)
    g1 = ctx.instance.nodes[ctx.roles.g1]
    return CheckRecord("profile.wellformed", "pass",
                       f"well-formed: {count(len(ctx.profile.primary), 'primary walk')} and "
                       f"{count(len(ctx.profile.secondary), 'secondary walk')}, primary goal "
                       f"{g1!r}",
                       numbers)


def phases(ctx: Context) -> CheckRecord:
    """``profile.phases``: the claimed ``t_I``, ``t_II``, ``T`` of ξ² match σ* along it.

    Examples
    --------
    On the triangle ξ² = ``s -> g2`` is all phase II (σ* = 1/2 on its one step):

    >>> from dppverify.game.examples import triangle_attacker

    >>> from tests.dppverify.checks.doctest_inputs import triangle_context as context
    >>> eq = triangle_attacker()
    >>> dict(phases(context(eq)).numbers)
    {'t_I': 0, 't_II': 1, 'T': 1}
    >>> r = phases(context(eq, phases={"t_I": 1, "t_II": 1, "T": 1}))
    >>> r.status, r.message
    ('fail', 't_I, t_II, T = (0, 1, 1) from σ* along ξ²; the profile claims (1, 1, 1)')
    """
    claim = ctx.profile.claimed_phases
    sec = [w for w in ctx.profile.secondary if w.probability > 0]
    if not ctx.profile.wellformed:
        return skipped("profile.phases", "L5")
    if len(sec) != 1:
        if claim is None:
            return CheckRecord("profile.phases", "pass", "no phases claimed (the secondary "
                               "mixes several walks)", {}, "L5")
        return CheckRecord("profile.phases", "fail", "phases are claimed but the secondary "
                           "type mixes several walks (phases are defined on one walk ξ²)", {},
                           "L5")
    got = phases_of(sigma_along(ctx.instance, ctx.roles, ProgressRule(ctx.roles.g1), sec[0].walk),
                   ctx.numbers)
    numbers: dict[str, Number | None] = {"t_I": got.t_I, "t_II": got.t_II, "T": got.T}
    if claim is None:
        return CheckRecord("profile.phases", "pass", f"no phases claimed; recomputed "
                           f"t_I = {got.t_I}, t_II = {got.t_II}, T = {got.T}", numbers, "L5")
    ok = tuple(claim) == got.as_tuple()
    return CheckRecord("profile.phases", "pass" if ok else "fail",
                       f"t_I, t_II, T = {got.as_tuple()} from σ* along ξ²"
                       + ("" if ok else f"; the profile claims {tuple(claim)}"), numbers, "L5")
