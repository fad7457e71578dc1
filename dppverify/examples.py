"""Small bundled instances for examples, doctests and quick experiments.

The triangle is NOTES §3's smallest instance with all the structure of the game: the
secondary path ``s -> g2`` is all phase II, the primary mixes ``s -> g1`` (4/7) with
``s -> g2`` (3/7), and ``U* = 12/5``.
"""

from __future__ import annotations

from typing import Any

from dppverify.instance import Instance, instance_from_json

__all__ = ["triangle", "triangle_document"]


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
    """The triangle as a parsed :class:`~dppverify.instance.Instance`.

    Examples
    --------
    >>> inst = triangle()
    >>> inst.nodes[inst.roles().g1], inst.prior
    ('g1', (Fraction(7, 10), Fraction(3, 10)))
    """
    return instance_from_json(triangle_document(prior))
