"""Small bundled N-goal instances for examples, doctests and tests.

``star3`` is a hub graph with three goals: from ``s`` one step to the hub ``m``, from which
each goal is one step away, plus a direct edge ``s–a`` of weight 2. Walking through ``m``
keeps every goal possible for one more step.
"""

from __future__ import annotations

from typing import Any

from dppverify.ngoal.instance import NInstance, ninstance_from_json

__all__ = ["star3", "star3_document", "star3_profile"]


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
