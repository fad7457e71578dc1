"""The goal-selection value as ``dpp value`` prints it: one text line and the
``dpp-selection-value/1`` document (``docs/formats.md`` §4b)."""

from __future__ import annotations

from typing import Any

from dppverify.exact import format_number
from dppverify.selection.value import SelectionValue
from dppverify.text import show_value

__all__ = ["SELECTION_VALUE_FORMAT", "selection_lines", "selection_value_document"]

SELECTION_VALUE_FORMAT = "dpp-selection-value/1"


def selection_value_document(v: SelectionValue, horizon: int | None) -> dict[str, Any]:
    """The ``dpp-selection-value/1`` document of a goal-selection value (every key always
    present, ``null`` where it does not apply).

    Examples
    --------
    >>> from dppverify.game.examples import triangle_document
    >>> from dppverify.selection.instance import selection_from_json
    >>> from dppverify.selection.value import selection_value
    >>> doc = {**triangle_document(), "goal_selection": True}
    >>> del doc["prior"]
    >>> out = selection_value_document(selection_value(selection_from_json(doc)), None)
    >>> out["value"], out["choice"], out["uniform"]["value"], out["gain"]
    ('2', ['1/4', '3/4'], '2', '0')
    """
    u = v.uniform_payoff
    gain = (None if v.value is None or u.exact is None
            else format_number(u.exact - v.value))
    return {
        "format": SELECTION_VALUE_FORMAT,
        "goals": len(v.values),
        "horizon": "inf" if horizon is None else horizon,
        "truncated": horizon is not None,
        "numbers": "exact",
        "value": format_number(v.value),
        "exact": v.value is not None,
        "lower": format_number(v.lower),
        "upper": format_number(v.upper),
        "lower_source": v.lower_source,
        "upper_source": v.upper_source,
        "open_reason": v.reason,
        "choice": None if v.choice is None else [format_number(q) for q in v.choice],
        "binding": [list(a) for a in v.binding],
        "normals": [list(a) for a in v.normals],
        "goal_values": [format_number(r) for r in v.values],
        "uniform": {"value": format_number(u.exact), "lower": format_number(u.lower),
                    "upper": format_number(u.upper), "lower_source": u.lower_source,
                    "upper_source": u.upper_source},
        "gain": gain,
    }


def selection_lines(v: SelectionValue, horizon: int | None) -> list[str]:
    """The lines ``dpp value`` prints: ``V_sel`` (or its bracket) with the choice, and the
    value at the uniform prior beside it.

    Examples
    --------
    >>> from dppverify.game.examples import star3_document
    >>> from dppverify.selection.instance import selection_from_json
    >>> from dppverify.selection.value import selection_value
    >>> doc = {**star3_document(), "goal_selection": True}
    >>> del doc["prior"]
    >>> print("\\n".join(selection_lines(selection_value(selection_from_json(doc)), None)))
    ... # doctest: +ELLIPSIS
    V_sel (H = inf, N = 3 goals, the Attacker chooses its goal) = 4/3 (≈ 1.333) exactly at \
q* = (1/3, 1/3, 1/3); ...
    at the uniform prior: V = 4/3 (≈ 1.333) exactly; choosing gains the Attacker 0
    """
    h = "inf" if horizon is None else str(horizon)
    head = f"V_sel (H = {h}, N = {len(v.values)} goals, the Attacker chooses its goal)"
    if v.value is not None:
        assert v.choice is not None
        q = ", ".join(str(x) for x in v.choice)
        first = f"{head} = {show_value(v.value)} exactly at q* = ({q}); {v.upper_source}"
    else:
        first = (f"{head} in [{show_value(v.lower)}, {show_value(v.upper)}]: lower bound from "
                 f"{v.lower_source}, upper bound from {v.upper_source}; not proved exact: "
                 f"{v.reason}")
    u = v.uniform_payoff
    if u.exact is not None:
        second = f"at the uniform prior: V = {show_value(u.exact)} exactly"
        if v.value is not None:
            second += f"; choosing gains the Attacker {show_value(u.exact - v.value)}"
    else:
        second = f"at the uniform prior: V in [{show_value(u.lower)}, {show_value(u.upper)}]"
    return [first, second]
