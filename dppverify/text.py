"""Small formatting helpers for check messages."""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction
from typing import TYPE_CHECKING

from dppio.text import decimal
from dppverify.exact import Number
from dppverify.formats.json_reading import show_node

if TYPE_CHECKING:
    from dppverify.game.instance import Instance

__all__ = ["MAX_EXACT_CHARS", "approx", "show", "show_value", "show_walk"]


MAX_EXACT_CHARS = 24
"""An exact number longer than this is shown as a decimal (its exact form is in ``--json``)."""


def approx(x: Number) -> str:
    """``x`` as a decimal: :func:`dppio.text.decimal` (the one rule of both packages).

    Works for rationals of any size (no float overflow).

    Examples
    --------
    >>> approx(Fraction(10**80 * 109, 100)), approx(Fraction(1, 3)), approx(Fraction(-1, 10**9))
    ('1.09×10^80', '0.3333', '-1×10^-9')
    """
    return decimal(x)


def show(x: Number | None) -> str:
    """A number for a message: exact rationals as ``p/q``, floats with 12 significant digits.

    An exact number longer than :data:`MAX_EXACT_CHARS` characters is shown as ``≈`` and a
    decimal (powers of ten for large ones): the exact value is in the ``--json`` output.

    Examples
    --------
    >>> show(Fraction(12, 5)), show(3), show(2.4000000000001), show(None)
    ('12/5', '3', '2.4', '-')
    >>> show(Fraction(10**30 + 1, 3)), show(2**300)
    ('≈3.333×10^29', '≈2.037×10^90')
    >>> show(Fraction(2**100 + 1, 2**100))
    '≈1'
    """
    if x is None:
        return "-"
    if isinstance(x, float):
        if x != x or x in (float("inf"), float("-inf")):
            return str(x)
        return decimal(x)
    text = str(Fraction(x))
    if len(text) <= MAX_EXACT_CHARS:
        return text
    return "≈" + approx(x)


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
        return f"{text} (≈ {approx(q)})"
    return f"≈ {approx(q)} (exact: a {len(text) - 1}-digit fraction, see --json)"


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
