"""Small bundled instances for examples, doctests and quick experiments.

The triangle is proofs/ERRATA.md E1's smallest instance with all the structure of the game: the
secondary path ``s -> g2`` is all phase II, the primary mixes ``s -> g1`` (4/7) with
``s -> g2`` (3/7), and ``U* = 12/5``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from dppverify.game.instance import Instance, instance_from_json

if TYPE_CHECKING:
    from dppverify.tree_route.context import Context

__all__ = ["kite", "kite_document", "kite_naive_profile", "triangle", "triangle_attacker",
           "triangle_context", "triangle_document", "triangle_profile"]


def triangle_document(prior: tuple[str, str] = ("7/10", "3/10")) -> dict[str, Any]:
    """The triangle ``s–g2`` (2), ``g2–g1`` (2), ``s–g1`` (3) as an instance document.

    Examples
    --------
    >>> doc = triangle_document()
    >>> doc["start"], doc["goals"], doc["prior"]
    ('s', ['g1', 'g2'], ['7/10', '3/10'])
    """
    return {"graph": {"nodes": [{"id": "s"}, {"id": "g1"}, {"id": "g2"}],
                      "edges": [{"source": "s", "target": "g2", "weight": 2},
                                {"source": "g2", "target": "g1", "weight": 2},
                                {"source": "s", "target": "g1", "weight": 3}]},
            "start": "s", "goals": ["g1", "g2"], "prior": list(prior)}


def triangle(prior: tuple[str, str] = ("7/10", "3/10")) -> Instance:
    """The triangle as a parsed :class:`~dppverify.game.instance.Instance`.

    Examples
    --------
    >>> inst = triangle()
    >>> inst.nodes[inst.roles().g1], inst.prior
    ('g1', (Fraction(7, 10), Fraction(3, 10)))
    """
    return instance_from_json(triangle_document(prior))


def triangle_attacker(p_g1: str = "4/7", p_g2: str = "3/7") -> dict[str, Any]:
    """The ``attacker`` part of a triangle profile: the equilibrium mixture by default.

    The primary goes ``s -> g1`` with ``p_g1`` and ``s -> g2`` with ``p_g2`` (eq. (15): 4/7
    and 3/7 at the prior 7/10); the secondary goes ``s -> g2``.

    Examples
    --------
    >>> [w["probability"] for w in triangle_attacker("3/7", "4/7")["primary"]]
    ['3/7', '4/7']
    """
    return {"primary": [{"path": ["s", "g1"], "probability": p_g1},
                        {"path": ["s", "g2"], "probability": p_g2}],
            "secondary": [{"path": ["s", "g2"], "probability": 1}]}


def triangle_profile(attacker: dict[str, Any] | None = None, **claims: Any) -> dict[str, Any]:
    """A ``dpp-profile/1`` document for the triangle with the progress Defender.

    Parameters
    ----------
    attacker : dict, optional
        The ``attacker`` member (default: :func:`triangle_attacker`, the equilibrium).
    **claims
        Extra members, e.g. ``value={"U": "12/5"}`` or ``phases={...}``.

    Examples
    --------
    >>> from dppverify import certify
    >>> certify(triangle_document(), triangle_profile()).verdict
    'pass'
    >>> certify(triangle_document(), triangle_profile(triangle_attacker("3/7", "4/7"))).verdict
    'fail'
    """
    return {"format": "dpp-profile/1", "goals": {"primary": "g1", "secondary": "g2"},
            "defender": {"rule": "progress", "goal": "g1"},
            "attacker": triangle_attacker() if attacker is None else attacker, **claims}


def triangle_context(attacker: dict[str, Any] | None = None, *, horizon: int = 1,
                     **claims: Any) -> Context:
    """The checks' shared inputs for a triangle profile (exact, seed 0, 2 random trials).

    Parameters
    ----------
    attacker, **claims
        As for :func:`triangle_profile`.
    horizon : int
        The walk tree's horizon.

    Examples
    --------
    >>> ctx = triangle_context()
    >>> ctx.tree.n_prefixes, ctx.profile.primary[0].probability
    (3, Fraction(4, 7))
    """
    from dppverify.game.profile import profile_from_json
    from dppverify.tree_route.context import make_context
    from dppverify.tree_route.tree import build_tree

    inst = triangle()
    prof = profile_from_json(triangle_profile(attacker, **claims), inst)
    return make_context(inst, build_tree(inst, horizon), prof, seed=0, trials=2)


def kite_document(prior: tuple[str, str] = ("3/5", "2/5")) -> dict[str, Any]:
    """The kite of issue 18: ``s–g1``, ``s–g2`` of weight 2, ``s–a`` 1, ``a–g1``, ``a–g2`` 1.

    Walking straight to one's goal (one step of weight 2) is an equilibrium of the game
    truncated at ``H = 1`` but not of the untruncated game, where the secondary's detour
    ``s a g2`` (two steps) costs 1 against σ*; ``V = 8/5``.

    Examples
    --------
    >>> from dppverify import certify
    >>> certify(kite_document(), kite_naive_profile()).verdict
    'fail'
    >>> certify(kite_document(), kite_naive_profile(), horizon=1).verdict
    'pass'
    """
    edges = [("s", "g1", 2), ("s", "g2", 2), ("s", "a", 1), ("a", "g1", 1), ("a", "g2", 1)]
    return {"graph": {"directed": False,
                      "nodes": [{"id": v} for v in ("s", "a", "g1", "g2")],
                      "edges": [{"source": u, "target": v, "weight": w} for u, v, w in edges]},
            "start": "s", "goals": ["g1", "g2"], "prior": list(prior)}


def kite(prior: tuple[str, str] = ("3/5", "2/5")) -> Instance:
    """The kite (:func:`kite_document`) as a parsed :class:`~dppverify.game.instance.Instance`.

    Examples
    --------
    >>> kite().nodes
    ('s', 'a', 'g1', 'g2')
    """
    return instance_from_json(kite_document(prior))


def kite_naive_profile() -> dict[str, Any]:
    """Each type walks straight to its goal; the Defender is σ* (the progress rule to g1).

    Examples
    --------
    >>> kite_naive_profile()["attacker"]["secondary"]
    [{'path': ['s', 'g2'], 'probability': 1}]
    """
    return {"format": "dpp-profile/1", "goals": {"primary": "g1", "secondary": "g2"},
            "defender": {"rule": "progress", "goal": "g1"},
            "attacker": {"primary": [{"path": ["s", "g1"], "probability": 1}],
                         "secondary": [{"path": ["s", "g2"], "probability": 1}]}}
