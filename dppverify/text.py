"""Small formatting helpers for check messages."""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction

from dppverify.exact import Number
from dppverify.instance import Instance, show_node

__all__ = ["show", "show_walk"]


def show(x: Number | None) -> str:
    """A number for a message: exact rationals as ``p/q``, floats with 12 significant digits.

    Examples
    --------
    >>> show(Fraction(12, 5)), show(3), show(2.4000000000001), show(None)
    ('12/5', '3', '2.4', '-')
    """
    if x is None:
        return "-"
    if isinstance(x, float):
        return f"{x:.12g}"
    return str(Fraction(x))


def show_walk(instance: Instance, walk: Sequence[int]) -> str:
    """A walk as node ids joined by ``->``.

    Examples
    --------
    >>> from dppverify.instance import instance_from_json
    >>> inst = instance_from_json({"graph": {"nodes": [{"id": "s"}, {"id": [0, 1]},
    ...     {"id": "g"}], "edges": [{"source": "s", "target": [0, 1]},
    ...     {"source": "s", "target": "g"}]}, "start": "s", "goals": [[0, 1], "g"],
    ...     "prior": ["1/2", "1/2"]})
    >>> show_walk(inst, [0, 1])
    '"s" -> [0, 1]'
    """
    return " -> ".join(show_node(instance.nodes[v]) for v in walk)
