"""Inputs the doctests of ``dppverify/checks/structured_twogoal.py`` share (kept out of the
package: no doctest fixture ships in package code)."""

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
