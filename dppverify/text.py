"""Small formatting helpers for check messages (numbers: :func:`dppio.text.show`, the one
rule of both packages)."""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction
from typing import TYPE_CHECKING

from dppio.text import decimal, show
from dppverify.exact import Number
from dppverify.formats.json_reading import show_node

if TYPE_CHECKING:
    from dppverify.game.instance import Instance



def show_value(x: Number | None, digits: int = 40) -> str:
    """A value for a report line: the exact rational with a decimal approximation beside it.

    A rational longer than ``digits`` characters is shown by its decimal approximation only,
    with a pointer to the exact form (``--json`` carries it).

    Examples
    --------
    >>> show_value(Fraction(12, 7)), show_value(3), show_value(Fraction(10**50 + 1, 10**50))
    ('12/7 (≈ 1.714)', '3', '≈ 1 (exact: a 102-digit fraction, see --json)')
    """
    if x is None or isinstance(x, float):
        return show(x)
    q = Fraction(x)
    if q.denominator == 1:
        return str(q)
    text = str(q)
    if len(text) <= digits:
        return f"{text} (≈ {decimal(q)})"
    return f"≈ {decimal(q)} (exact: a {len(text) - 1}-digit fraction, see --json)"


def show_walk(instance: Instance, walk: Sequence[int]) -> str:
    """A walk as node ids joined by ``->``.

    Examples
    --------
    >>> from dppverify.game.instance import instance_from_json
    >>> inst = instance_from_json({"graph": {"nodes": [{"id": "s"}, {"id": [0, 1]},
    ...     {"id": "g"}], "edges": [{"source": "s", "target": [0, 1]},
    ...     {"source": "s", "target": "g"}]}, "start": "s", "goals": [[0, 1], "g"],
    ...     "prior": ["1/2", "1/2"]})
    >>> show_walk(inst, [0, 1])
    '"s" -> [0, 1]'
    """
    return " -> ".join(show_node(instance.nodes[v]) for v in walk)
