"""The ``dpp-value/1`` document: ``V_H`` of a game as JSON, one shape for every route and N.

What ``dpp value --json`` prints and ``-o`` writes (``docs/formats.md`` §4). The top level
says which game (``goals``, ``horizon``, ``truncated``), how it was computed (``route``,
``numbers``) and the answer (``value`` when it is known, else null; ``exact``; the bounds
``lower <= V_H <= upper`` with where each comes from). ``tree`` and ``structured`` hold one
record per route that ran (null for a route that did not), each with the same keys
(:data:`ROUTE_KEYS`) and a ``method`` naming what its ``details`` hold:

- ``"tree-lp"``: the compact LP on the walk tree and its exact bracket (any N);
- ``"three-field-dp"``: the two-goal structured route (``proofs/DP.md``);
- ``"guarantee-sets"``: the N-goal structured route (``proofs/NGOAL.md``).

:func:`value_document` is the one builder; each method's ``details`` come from one function
below, so a change in how a route computes fills fields without changing the shape.
"""

from __future__ import annotations

from typing import Any

from dppverify.exact import Bracket, format_number
from dppverify.routes import RoutedValue
from dppverify.structured.cover import members
from dppverify.structured.proved_value import NValue
from dppverify.structured.selection_value import SelectionValue
from dppverify.text import show_value
from dppverify.tree_route.lp import LP_SOLVER, LP_TOLERANCE
from dppverify.tree_route.value_lp import GameValue
from dppverify.twogoal.value_dp import StructuredValue

__all__ = ["GUARANTEE_NOTE", "ROUTE_KEYS", "SELECTION_VALUE_FORMAT", "TOP_KEYS", "VALUE_FORMAT",
           "selection_lines", "selection_value_document", "value_document"]

VALUE_FORMAT = "dpp-value/1"
"""The ``format`` tag of the document."""

TOP_KEYS = ("format", "goals", "horizon", "truncated", "route", "numbers", "value", "exact",
            "lower", "upper", "lower_source", "upper_source", "open_reason", "agree",
            "disagreement", "tree", "structured")
"""The document's keys, in order: always all of them (null where they do not apply)."""

ROUTE_KEYS = ("method", "value", "exact", "lower", "upper", "lower_source", "upper_source",
              "open_reason", "details")
"""The keys of a route's record, in order: the same for every route and every N."""

GUARANTEE_NOTE = ("the coalition DP is an upper bound on V_H (NG.2), the value for N <= 3 "
                  "(NG.3, NG.4) and for N >= 4 only where certified (NG.8; proofs/NGOAL.md)")
"""What the guarantee sets' number is, stated in their record."""

DP_SOURCE = "three-field DP (proofs/DP.md)"


def value_document(r: RoutedValue) -> dict[str, Any]:
    """The ``dpp-value/1`` document of a routed value.

    Parameters
    ----------
    r : RoutedValue
        What :func:`dppverify.routes.routed_value` (``dppverify.value``) returned.

    Returns
    -------
    dict
        JSON-ready: exact numbers as ``"p/q"`` strings, floats (float mode, LP values) as
        JSON numbers, ``horizon`` an integer or ``"inf"``.

    Examples
    --------
    >>> from dppverify.game.examples import star3, triangle
    >>> from dppverify.routes import routed_value
    >>> doc = value_document(routed_value(triangle(), None))
    >>> doc["format"], doc["goals"], doc["horizon"], doc["value"], doc["exact"]
    ('dpp-value/1', 2, 'inf', '12/5', True)
    >>> doc["structured"]["method"], doc["tree"]
    ('three-field-dp', None)
    >>> doc = value_document(routed_value(star3(), 2, route="both"))
    >>> doc["route"], doc["agree"], doc["tree"]["method"], doc["structured"]["method"]
    ('both', True, 'tree-lp', 'guarantee-sets')
    >>> list(doc["tree"]) == list(doc["structured"]) == list(ROUTE_KEYS)
    True
    """
    tree = None if r.tree is None else _route_record(r.tree)
    structured = None if r.structured is None else _route_record(r.structured)
    main = structured if structured is not None else tree
    assert main is not None  # one route always ran
    lower, upper = r.bounds()
    floats = any(isinstance(x, float) for x in (lower, upper))
    both = r.route == "both"
    doc = {
        "format": VALUE_FORMAT,
        "goals": r.goals,
        "horizon": "inf" if r.horizon is None else r.horizon,
        "truncated": r.horizon is not None,
        "route": r.route,
        "numbers": "float" if floats else "exact",
        "value": format_number(r.value),
        "exact": r.value is not None and not floats,
        "lower": format_number(lower),
        "upper": format_number(upper),
        "lower_source": main["lower_source"],
        "upper_source": main["upper_source"],
        "open_reason": None if r.value is not None else main["open_reason"],
        "agree": (r.disagreement is None) if both else None,
        "disagreement": r.disagreement,
        "tree": tree,
        "structured": structured,
    }
    assert tuple(doc) == TOP_KEYS
    return doc


def _route_record(v: GameValue | StructuredValue | NValue) -> dict[str, Any]:
    """One route's record: the same keys (:data:`ROUTE_KEYS`) whatever the route."""
    if isinstance(v, GameValue):
        method, bracket, details = "tree-lp", v.bracket, _tree_details(v)
    elif isinstance(v, StructuredValue):
        method, details = "three-field-dp", _dp_details(v)
        bracket = Bracket(v.value, v.value, DP_SOURCE, DP_SOURCE)
    else:
        method, bracket, details = "guarantee-sets", v, _guarantee_details(v)
    floats = isinstance(bracket.lower, float) or isinstance(bracket.upper, float)
    record = {
        "method": method,
        "value": format_number(bracket.exact),
        "exact": bracket.closed and not floats,
        "lower": format_number(bracket.lower),
        "upper": format_number(bracket.upper),
        "lower_source": bracket.lower_source,
        "upper_source": bracket.upper_source,
        "open_reason": bracket.reason,
        "details": details,
    }
    assert tuple(record) == ROUTE_KEYS
    return record


def _tree_details(v: GameValue) -> dict[str, Any]:
    """``tree-lp``: the LP's float value and statistics, the walk tree's size."""
    return {"horizon": v.horizon, "value_lp": v.lp.value,
            "lp": {"solver": LP_SOLVER, "status": v.lp.status, "tolerance": LP_TOLERANCE,
                   "seconds": round(v.lp.seconds, 3), "variables": v.lp.variables,
                   "constraints": v.lp.constraints},
            "tree": {"prefixes": v.prefixes, "leaves": v.leaves}}


def _dp_details(v: StructuredValue) -> dict[str, Any]:
    """``three-field-dp``: the three fields at the start, the steps, the arithmetic."""
    return {"D1": format_number(v.d1), "D2": format_number(v.d2), "m": format_number(v.m),
            "steps": v.steps, "fixpoint": v.fixpoint, "arithmetic": v.arithmetic,
            "seconds": round(v.seconds, 3)}


def _subset(mask: int) -> list[int]:
    """A goal subset as 1-based goal numbers."""
    return [i + 1 for i in members(mask)]


def _guarantee_details(v: NValue) -> dict[str, Any]:
    """``guarantee-sets``: the DP's layers and normals, the coalition DP's cover and costs."""
    c = v.coalition
    return {"layers": v.layers, "extra_normals": [list(n) for n in v.normals],
            "note": GUARANTEE_NOTE,
            "coalition_dp": {
                "value": format_number(c.value), "layers": c.layers,
                "cover": [{"goals": _subset(m), "mass": format_number(x)}
                          for m, x in sorted(c.cover.items())],
                "coalition_costs": [{"goals": _subset(m), "cost": format_number(x)}
                                    for m, x in sorted(c.coalition_costs.items())]}}


# ------------------------------------------------------------ the goal-selection game
SELECTION_VALUE_FORMAT = "dpp-selection-value/1"


def selection_value_document(v: SelectionValue, horizon: int | None) -> dict[str, Any]:
    """The ``dpp-selection-value/1`` document of a goal-selection value (every key always
    present, ``null`` where it does not apply).

    Examples
    --------
    >>> from dppverify.game.examples import triangle_document
    >>> from dppverify.game.instance import instance_from_json
    >>> from dppverify.structured.selection_value import selection_value
    >>> doc = {**triangle_document(), "goal_selection": True}
    >>> del doc["prior"]
    >>> out = selection_value_document(selection_value(instance_from_json(doc)), None)
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
    >>> from dppverify.game.instance import instance_from_json
    >>> from dppverify.structured.selection_value import selection_value
    >>> doc = {**star3_document(), "goal_selection": True}
    >>> del doc["prior"]
    >>> print("\\n".join(selection_lines(selection_value(instance_from_json(doc)), None)))
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
