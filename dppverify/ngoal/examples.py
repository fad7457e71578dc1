"""Small bundled N-goal instances for examples, doctests and tests.

``star3`` is a hub graph with three goals: from ``s`` one step to the hub ``m``, from which
each goal is one step away, plus a direct edge ``s–a`` of weight 2. Walking through ``m``
keeps every goal possible for one more step.
"""

from __future__ import annotations

from typing import Any

from dppverify.ngoal.instance import NInstance, ninstance_from_json

__all__ = ["hub4", "hub4_document", "star3", "star3_document", "star3_profile"]


def star3_document(prior: tuple[str, ...] = ("1/2", "1/3", "1/6")) -> dict[str, Any]:
    """The hub instance ``s–m`` (1), ``m–a``, ``m–b``, ``m–c`` (1 each), ``s–a`` (2).

    Examples
    --------
    >>> doc = star3_document()
    >>> doc["goals"], doc["prior"]
    (['a', 'b', 'c'], ['1/2', '1/3', '1/6'])
    """
    return {"graph": {"directed": False,
                      "nodes": [{"id": v} for v in ("s", "m", "a", "b", "c")],
                      "edges": [{"source": "s", "target": "m", "weight": 1},
                                {"source": "m", "target": "a", "weight": 1},
                                {"source": "m", "target": "b", "weight": 1},
                                {"source": "m", "target": "c", "weight": 1},
                                {"source": "s", "target": "a", "weight": 2}]},
            "start": "s", "goals": ["a", "b", "c"], "prior": list(prior)}


def star3(prior: tuple[str, ...] = ("1/2", "1/3", "1/6")) -> NInstance:
    """The hub instance, parsed.

    Examples
    --------
    >>> inst = star3()
    >>> inst.n_goals, inst.labels(inst.goals)
    (3, ('a', 'b', 'c'))
    """
    return ninstance_from_json(star3_document(prior))


def star3_profile() -> dict[str, Any]:
    """An equilibrium profile of the hub instance at ``H = 2`` (``dpp-ngoal-profile/1``).

    Every type walks ``s m`` and then to its own goal; the Defender guards ``a`` (the
    largest prior) on ``s m`` and everywhere off the walks, and the true goal on ``s m b``
    and ``s m c``. ``U = 1/2 · 2 + 1/3 · 1 + 1/6 · 1 = 3/2 = V_2``.

    Examples
    --------
    >>> [mix[0]["path"] for mix in star3_profile()["attacker"]]
    [['s', 'm', 'a'], ['s', 'm', 'b'], ['s', 'm', 'c']]
    """
    return {"format": "dpp-ngoal-profile/1", "goals": ["a", "b", "c"],
            "attacker": [[{"path": ["s", "m", g], "probability": 1}] for g in ("a", "b", "c")],
            "defender": {"rule": "table",
                         "entries": [{"walk": ["s", "m", "b"], "probabilities": [0, 1, 0]},
                                     {"walk": ["s", "m", "c"], "probabilities": [0, 0, 1]}],
                         "default": [1, 0, 0]},
            "value": {"U": "3/2"}}


def hub4_document(prior: tuple[str, ...] = ("2/7", "2/7", "2/7", "1/7"), *,
                  directed: bool = True) -> dict[str, Any]:
    """The four-goal hub where the coalition DP is not the value (``proofs/NGOAL.md``).

    Unit arcs ``u→u1``; ``u1→A, B, C``; ``A→g1, g2``; ``B→g1, g3``; ``C→g2, g3, g4``; return
    arcs ``g_i→u`` of weight 10 (they keep the goals' distances finite). Start ``u``. With
    the default prior the coalition DP is 25/14 and the value 12/7 at every ``H >= 3``.
    ``directed=False`` gives the undirected version (same gap).

    Examples
    --------
    >>> doc = hub4_document()
    >>> len(doc["graph"]["edges"]), doc["prior"]
    (15, ['2/7', '2/7', '2/7', '1/7'])
    """
    arcs = [("u", "u1", 1), ("u1", "A", 1), ("u1", "B", 1), ("u1", "C", 1),
            ("A", "g1", 1), ("A", "g2", 1), ("B", "g1", 1), ("B", "g3", 1),
            ("C", "g2", 1), ("C", "g3", 1), ("C", "g4", 1)]
    arcs += [(g, "u", 10) for g in ("g1", "g2", "g3", "g4")]
    nodes = ("u", "u1", "A", "B", "C", "g1", "g2", "g3", "g4")
    return {"graph": {"directed": directed, "nodes": [{"id": v} for v in nodes],
                      "edges": [{"source": a, "target": b, "weight": w} for a, b, w in arcs]},
            "start": "u", "goals": ["g1", "g2", "g3", "g4"], "prior": list(prior)}


def hub4(prior: tuple[str, ...] = ("2/7", "2/7", "2/7", "1/7"), *,
         directed: bool = True) -> NInstance:
    """The four-goal hub, parsed (:func:`hub4_document`).

    Examples
    --------
    >>> hub4().n_goals
    4
    """
    return ninstance_from_json(hub4_document(prior, directed=directed))
