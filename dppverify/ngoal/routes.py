"""``dpp value`` for N-goal instances: the tree route, the coalition DP, or both.

Routes (the same names as for two goals): ``tree`` — the walk tree's compact LP closed by an
exact bracket (the literal definition; finite ``H`` only); ``structured`` — the guarantee sets
(:func:`dppverify.ngoal.proved_value.nvalue`; any ``H`` and ``H = inf``): the coalition DP over the
goal subsets, which is the value for N <= 3 (``proofs/NGOAL.md`` NG.3, NG.4) and for N = 4, 5
only where its certificate (NG.8) holds, refined with extra facet normals where it does not;
otherwise an exact bracket naming both bounds. ``auto`` — the tree when it fits the size
guard, else the structured route; ``both`` — run both, a disagreement is reported (and exits 1).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any, cast

from dppverify.errors import HorizonError, InvalidInstanceError, OptionError
from dppverify.exact import Number, format_number
from dppverify.ngoal.coalition import CoalitionValue, too_many_goals
from dppverify.ngoal.cover import MAX_BALANCED, members
from dppverify.ngoal.instance import NInstance, goal_count, read_instance_document
from dppverify.ngoal.proved_value import NValue, nvalue
from dppverify.routes import tree_fits
from dppverify.text import show, show_value
from dppverify.tree_route.lp import LP_SOLVER, LP_TOLERANCE, lp_agrees
from dppverify.tree_route.tree import DEFAULT_MAX_PREFIXES
from dppverify.tree_route.value_lp import GameValue, game_value

__all__ = ["CONJECTURE_NOTE", "NRoutedValue", "is_ngoal_file", "nrouted_document",
           "nrouted_lines", "nrouted_value", "ntree_fits"]

CONJECTURE_NOTE = ("the coalition DP is an upper bound on V_H (NG.2), the value for N <= 3 "
                   "(NG.3, NG.4) and for N >= 4 only where certified (NG.8; proofs/NGOAL.md)")


def is_ngoal_file(path: str | Path) -> bool:
    """True when the instance file lists more than two goals (False when unreadable).

    Examples
    --------
    >>> is_ngoal_file("/nonexistent.json")
    False
    """
    try:
        n = goal_count(read_instance_document(path))
    except InvalidInstanceError:
        return False
    return n is not None and n > 2


def ntree_fits(instance: NInstance, horizon: int, max_prefixes: int) -> bool:
    """True when the N-goal walk tree of ``horizon`` steps has at most ``max_prefixes`` prefixes.

    The two-goal count (:func:`dppverify.routes.tree_fits`: vectorised, saturated just above
    ``max_prefixes``, so huge trees are never counted in full); it reads only the graph, the
    start, the goals and the hop distances, which an N-goal instance has under the same names,
    and prunes by the same rule as :func:`~dppverify.tree_route.tree.count_prefixes`.

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> from dppverify.tree_route.tree import count_prefixes
    >>> [count_prefixes(star3(), h) for h in (2, 3)], ntree_fits(star3(), 3, 7)
    ([6, 8], False)
    """
    return tree_fits(cast(Any, instance), horizon, max_prefixes)


@dataclass(frozen=True)
class NRoutedValue:
    """``V_H`` of an N-goal instance by the chosen route(s).

    ``value`` is ``V_H`` when proved, else None; ``lower`` and ``upper`` are the exact
    bounds (equal when proved), whatever the route.

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> r = nrouted_value(star3(), None)
    >>> r.value, r.lower, r.upper
    (Fraction(3, 2), Fraction(3, 2), Fraction(3, 2))
    """

    route: str
    horizon: int | None
    goals: int
    tree: GameValue | None
    structured: NValue | None
    disagreement: str | None

    @property
    def lower(self) -> Number:
        """An exact lower bound on ``V_H``."""
        if self.structured is not None:
            return self.structured.lower
        assert self.tree is not None  # one route always ran
        return self.tree.bracket.lower

    @property
    def upper(self) -> Number:
        """An exact upper bound on ``V_H``."""
        if self.structured is not None:
            return self.structured.upper
        assert self.tree is not None
        return self.tree.bracket.upper

    @property
    def value(self) -> Number | None:
        """``V_H`` when proved, else None."""
        if self.structured is not None and self.structured.value is not None:
            return self.structured.value
        return self.tree.bracket.exact if self.tree is not None else None


def nrouted_value(instance: NInstance, horizon: int | None, *, route: str = "auto",
                  max_prefixes: int = DEFAULT_MAX_PREFIXES) -> NRoutedValue:
    """``V_H`` by the tree route, the coalition DP, or both (``horizon=None``: ``H = inf``).

    Raises
    ------
    HorizonError
        For ``--route tree`` (or ``both``) with ``H = inf``, or an unreachable horizon.
    OptionError
        For more than five goals where the coalition DP is needed (``H = inf``,
        ``--route structured`` or ``both``): the tree route needs a finite horizon.

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> r = nrouted_value(star3(), 3, route="both")
    >>> r.tree.bracket.exact, r.structured.value, r.disagreement
    (Fraction(3, 2), Fraction(3, 2), None)
    >>> nrouted_value(star3(), None).route
    'structured'
    """
    if route not in ("auto", "tree", "structured", "both"):
        raise ValueError(f"unknown route {route!r}")
    if horizon is None and route in ("tree", "both"):
        raise HorizonError("the tree route needs a finite horizon; use --route structured "
                           "(or auto) for H = inf")
    if instance.n_goals > MAX_BALANCED and (horizon is None or route in ("structured", "both")):
        raise OptionError(too_many_goals(instance.n_goals))
    if route == "auto":
        fits = horizon is not None and ntree_fits(instance, horizon, max_prefixes)
        route = "tree" if fits or instance.n_goals > MAX_BALANCED else "structured"
    tree = (game_value(instance, horizon, max_prefixes=max_prefixes)
            if route in ("tree", "both") and horizon is not None else None)
    dp = nvalue(instance, horizon) if route in ("structured", "both") else None
    disagreement = None
    if tree is not None and dp is not None:
        b = tree.bracket
        overlap = dp.lower <= b.upper and b.lower <= dp.upper
        exact_ok = dp.value is None or (b.lower <= dp.value <= b.upper
                                        and lp_agrees(tree.value, dp.value))
        if not (overlap and exact_ok):
            disagreement = (f"the routes disagree at H = {horizon}: structured route "
                            f"[{dp.lower}, {dp.upper}], tree route in [{b.lower}, {b.upper}] "
                            f"(LP {tree.value!r}) — a bug; please keep this instance")
    return NRoutedValue(route=route, horizon=horizon, goals=instance.n_goals, tree=tree,
                        structured=dp, disagreement=disagreement)


def _tree_doc(v: GameValue) -> dict[str, Any]:
    b = v.bracket
    return {"value": format_number(b.exact), "value_lp": v.lp.value,
            "lower": format_number(b.lower), "upper": format_number(b.upper),
            "lower_source": b.lower_source, "upper_source": b.upper_source,
            "exact": b.closed, "open_reason": b.reason,
            "lp": {"solver": LP_SOLVER, "status": v.lp.status, "tolerance": LP_TOLERANCE,
                   "seconds": round(v.lp.seconds, 3), "variables": v.lp.variables,
                   "constraints": v.lp.constraints},
            "tree": {"prefixes": v.prefixes, "leaves": v.leaves}}


def _subset(mask: int) -> list[int]:
    return [i + 1 for i in members(mask)]


def _coalition_doc(v: CoalitionValue) -> dict[str, Any]:
    return {"value": format_number(v.value), "layers": v.layers,
            "cover": [{"goals": _subset(m), "mass": format_number(c)}
                      for m, c in sorted(v.cover.items())],
            "coalition_costs": [{"goals": _subset(m), "cost": format_number(c)}
                                for m, c in sorted(v.coalition_costs.items())]}


def _dp_doc(v: NValue) -> dict[str, Any]:
    return {"value": format_number(v.value), "exact": v.exact,
            "lower": format_number(v.lower), "upper": format_number(v.upper),
            "lower_source": v.lower_source, "upper_source": v.upper_source,
            "reason": v.reason, "layers": v.layers,
            "extra_normals": [list(n) for n in v.normals], "note": CONJECTURE_NOTE,
            "coalition_dp": _coalition_doc(v.coalition)}


def nrouted_document(r: NRoutedValue) -> dict[str, Any]:
    """The JSON ``dpp value --json`` prints for an N-goal instance.

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> doc = nrouted_document(nrouted_value(star3(), 2, route="structured"))
    >>> doc["value"], doc["structured"]["coalition_dp"]["cover"]
    ('3/2', [{'goals': [1, 2], 'mass': '1/3'}, {'goals': [1, 3], 'mass': '1/6'}])
    >>> from dppverify.ngoal.examples import hub4
    >>> nrouted_document(nrouted_value(hub4(), None))["value"]
    '12/7'
    """
    value = None
    if r.structured is not None:
        value = r.structured.value
    if value is None and r.tree is not None:
        value = r.tree.bracket.exact
    doc: dict[str, Any] = {"goals": r.goals, "horizon": "inf" if r.horizon is None else r.horizon,
                           "route": r.route, "value": format_number(value),
                           "tree": None if r.tree is None else _tree_doc(r.tree),
                           "structured": None if r.structured is None else _dp_doc(r.structured)}
    if r.route == "both":
        doc["agree"] = r.disagreement is None
        if r.disagreement is not None:
            doc["disagreement"] = r.disagreement
    return doc


def nrouted_lines(r: NRoutedValue) -> list[str]:
    """The lines ``dpp value`` prints for an N-goal instance.

    Examples
    --------
    >>> from dppverify.ngoal.examples import star3
    >>> print(nrouted_lines(nrouted_value(star3(), None))[0])
    V_H (H = inf, N = 3 goals) = 3/2 (≈ 1.5) exactly; coalition DP (NG.4: the value for \
three goals) (3 layers)
    """
    h = "inf" if r.horizon is None else str(r.horizon)
    lines = []
    if r.tree is not None:
        b = r.tree.bracket
        exact = (f"{show_value(b.exact)} exactly" if b.closed else
                 f"in [{show_value(b.lower)}, {show_value(b.upper)}] (open: {b.reason})")
        lines.append(f"V_H (H = {h}, N = {r.goals} goals) = {exact}; LP value "
                     f"{show(r.tree.value)} ({LP_SOLVER}, agreement tolerance {LP_TOLERANCE:g} "
                     f"relative, {r.tree.prefixes} prefixes, {r.tree.lp.seconds:.2f} s)")
    v = r.structured
    if v is not None:
        head = f"V_H (H = {h}, N = {r.goals} goals)"
        if v.value is not None:
            lines.append(f"{head} = {show_value(v.value)} exactly; {v.upper_source} "
                         f"({v.layers} layers)")
        else:
            lines.append(f"{head} in [{show_value(v.lower)}, {show_value(v.upper)}]: lower "
                         f"bound from {v.lower_source}, upper bound from {v.upper_source}; "
                         f"not proved exact: {v.reason}")
    return lines
