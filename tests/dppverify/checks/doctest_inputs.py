"""Inputs the doctests of the checks share (kept out of the package: no doctest fixture ships
in package code)."""

from __future__ import annotations

from typing import Any


def triangle_inputs() -> tuple[Any, Any, Any, Any, Any]:
    """The triangle, its roles, its equilibrium profile, the profile's trie and the minima over
    all walks against σ* (what the two-goal structured checks take)."""
    from dppverify.game.examples import triangle, triangle_profile
    from dppverify.game.profile import profile_from_json
    from dppverify.structured.trie import mass_trie
    from dppverify.twogoal.progress_br import walk_minima

    inst = triangle()
    r, prof = inst.roles(), profile_from_json(triangle_profile(), inst)
    return inst, r, prof, mass_trie([prof.primary, prof.secondary]), walk_minima(inst, r.g1)


def triangle_context(attacker: dict[str, Any] | None = None, *, horizon: int = 1,
                     **claims: Any) -> Any:
    """The checks' shared inputs for a triangle profile (exact, seed 0, 2 random trials):
    ``attacker`` and ``claims`` as for ``dppverify.game.examples.triangle_profile``, the walk
    tree of ``horizon`` steps.

    Examples
    --------
    >>> ctx = triangle_context()
    >>> ctx.tree.n_prefixes, ctx.profile.primary[0].probability
    (3, Fraction(4, 7))
    """
    from dppverify.game.examples import triangle, triangle_profile
    from dppverify.game.profile import profile_from_json
    from dppverify.tree_route.context import make_context
    from dppverify.tree_route.tree import build_tree

    inst = triangle()
    prof = profile_from_json(triangle_profile(attacker, **claims), inst)
    return make_context(inst, build_tree(inst, horizon), prof, seed=0, trials=2)
