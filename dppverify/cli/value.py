"""``dpp value``: the value ``V_H`` of an instance's game, as text or JSON, for any N >= 2.

The value comes from :func:`dppverify.routes.routed_value` (the route is chosen there); this
module only prints it, :func:`routed_lines` as text and :func:`routed_document` as JSON. Two
goals: the tree route's LP and exact bracket (:func:`value_document`), the structured route's
three-field DP (:func:`structured_document`). More goals: the tree LP with N types and the
guarantee sets. With ``--route both`` a disagreement of the routes is one line on stderr and
exit 1.
"""

from __future__ import annotations

from typing import Any

import click

from dppio.limits import MAX_PREFIXES_LIMIT
from dppverify.cli.conventions import emit, output_file_option, progress_option, want_progress
from dppverify.cli.errors import fail
from dppverify.cli.inputs import HORIZON, load_game
from dppverify.cli.map_options import MapRequest, map_options
from dppverify.errors import CheckerError
from dppverify.exact import format_number
from dppverify.formats.files import refuse_input_as_output
from dppverify.routes import ROUTES, Route, RoutedValue, routed_value
from dppverify.structured.coalition import CoalitionValue
from dppverify.structured.cover import members
from dppverify.structured.proved_value import NValue
from dppverify.text import show, show_value
from dppverify.tree_route.lp import LP_SOLVER, LP_TOLERANCE
from dppverify.tree_route.tree import DEFAULT_MAX_PREFIXES
from dppverify.tree_route.value_lp import GameValue
from dppverify.twogoal.value_dp import StructuredValue

__all__ = ["CONJECTURE_NOTE", "routed_document", "routed_lines", "structured_document",
           "value_command", "value_document"]

CONJECTURE_NOTE = ("the coalition DP is an upper bound on V_H (NG.2), the value for N <= 3 "
                   "(NG.3, NG.4) and for N >= 4 only where certified (NG.8; proofs/NGOAL.md)")


@click.command("value", short_help="The value V_H of the game truncated at H steps.")
@click.argument("instance", required=False, type=click.Path(dir_okay=False))
@map_options
@click.option("-H", "--horizon", type=HORIZON, default=None,
              help="Horizon H of the truncated game (an explicit request), or 'inf' for the "
                   "untruncated game (structured route; the default).")
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON.")
@output_file_option("Write the result's JSON to this file (atomically); stdout stays empty, "
                    "the value is one line on stderr.")
@click.option("--route", type=click.Choice(ROUTES), default="auto", show_default=True,
              help="tree: the walk tree's LP; structured: the tree-free DP (docs/checker.md); "
                   "auto: the tree when it fits --max-prefixes, else structured; both: run "
                   "both, a disagreement is an error (exit 1).")
@click.option("--max-prefixes", type=click.IntRange(min=1, max=MAX_PREFIXES_LIMIT),
              default=DEFAULT_MAX_PREFIXES,
              show_default=True, help="Refuse walk trees larger than this.")
@progress_option
def value_command(instance: str | None, grid: MapRequest | None, horizon: int | None,
                  as_json: bool, output: str | None, route: Route, max_prefixes: int,
                  progress: bool | None) -> None:
    """Print the value of INSTANCE's game: untruncated (H = inf) unless --horizon H is given.

    Tree route: the compact LP (cvxpy + Clarabel) on the walk tree gives a float; rounding
    its primal and dual solutions to rationals gives exact bounds, which usually meet.
    Structured route: three hop-bounded Bellman-Ford fields (proofs/DP.md), exact on
    rational instances, polynomial in the graph; `--horizon inf` is the untruncated game.
    Instances with more than two goals: the tree LP with N types, and as structured route
    the guarantee sets: the coalition DP over goal subsets, the value for N <= 3 and, for
    N = 4, 5, where certified (else an exact bracket naming both bounds; proofs/NGOAL.md).

    \b
    Examples:
      dpp value examples/triangle.json
      dpp value examples/triangle.json --horizon 4
      dpp value examples/triangle.json -H 4 --json --route both
      dpp value examples/triangle.json -H 4 -o value.json
      dpp value --map m.map --start 2,0 --goals 0,3 0,0 --prior 0.6,0.4 -H 6
    """
    try:
        refuse_input_as_output(output, [instance, grid.path if grid else None])
        r = routed_value(load_game(instance, grid, "dpp value"), horizon, route=route,
                         max_prefixes=max_prefixes, progress=want_progress(progress))
    except CheckerError as exc:
        fail(exc)
    lines = routed_lines(r)
    emit(routed_document(r), "\n".join(lines), as_json=as_json, output=output,
         summary=lines[0] if lines else "")
    if r.disagreement is not None:
        click.echo(f"error: {r.disagreement}", err=True)
        raise click.exceptions.Exit(1)


def routed_lines(r: RoutedValue) -> list[str]:
    """The lines ``dpp value`` prints: one per route that ran.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> print(routed_lines(routed_value(triangle(), None))[0])  # doctest: +ELLIPSIS
    V_H (H = inf) = 12/5 (≈ 2.4) exactly; structured route (... DP steps, fixpoint reached, ...)
    """
    if r.goals > 2:
        return _ngoal_lines(r)
    tree = r.tree if isinstance(r.tree, GameValue) else None
    sv = r.structured if isinstance(r.structured, StructuredValue) else None
    return ([_tree_line(tree)] if tree is not None else []) + \
        ([_structured_line(sv)] if sv is not None else [])


def _show_horizon(h: int | None) -> str:
    return "inf" if h is None else str(h)


def value_document(v: GameValue) -> dict[str, Any]:
    """The JSON that ``dpp value --json`` prints for the tree route.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> from dppverify.tree_route.value_lp import game_value
    >>> doc = value_document(game_value(triangle(), 2))
    >>> doc["route"], doc["value"], doc["exact"], doc["tree"]
    ('tree', '12/5', True, {'prefixes': 3, 'leaves': 2})
    """
    b = v.bracket
    return {
        "horizon": v.horizon,
        "route": "tree",
        "value_lp": v.lp.value,
        "value": format_number(b.exact),
        "lower": format_number(b.lower),
        "upper": format_number(b.upper),
        "lower_source": b.lower_source,
        "upper_source": b.upper_source,
        "open_reason": b.reason,
        "exact": v.exact and b.closed,
        "lp": {"solver": LP_SOLVER, "status": v.lp.status, "tolerance": LP_TOLERANCE,
               "seconds": round(v.lp.seconds, 3), "variables": v.lp.variables,
               "constraints": v.lp.constraints},
        "tree": {"prefixes": v.prefixes, "leaves": v.leaves},
    }


def structured_document(v: StructuredValue) -> dict[str, Any]:
    """The JSON that ``dpp value --json`` prints for the structured route.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> from dppverify.twogoal.value_dp import structured_value
    >>> doc = structured_document(structured_value(triangle(), None))
    >>> doc["horizon"], doc["value"], doc["dp"]["fixpoint"]
    ('inf', '12/5', True)
    """
    return {
        "horizon": "inf" if v.horizon is None else v.horizon,
        "route": "structured",
        "value": format_number(v.value),
        "lower": format_number(v.value),
        "upper": format_number(v.value),
        "exact": v.exact,
        "dp": {"D1": format_number(v.d1), "D2": format_number(v.d2), "m": format_number(v.m),
               "steps": v.steps, "fixpoint": v.fixpoint, "arithmetic": v.arithmetic,
               "seconds": round(v.seconds, 3)},
    }


def routed_document(r: RoutedValue) -> dict[str, Any]:
    """The JSON of ``dpp value --json``: one route's document, or both with ``agree``
    (:func:`_ngoal_document` for more than two goals).

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> doc = routed_document(routed_value(triangle(), 3, route="both"))
    >>> doc["route"], doc["agree"], doc["value"], doc["structured"]["value"]
    ('both', True, '12/5', '12/5')
    """
    if r.goals > 2:
        return _ngoal_document(r)
    assert isinstance(r.tree, GameValue | None) and isinstance(r.structured, StructuredValue | None)
    if r.route == "tree":
        assert r.tree is not None
        return value_document(r.tree)
    assert r.structured is not None
    if r.route == "structured":
        return structured_document(r.structured)
    assert r.tree is not None
    doc = value_document(r.tree)
    doc.update(route="both", structured=structured_document(r.structured),
               agree=r.disagreement is None)
    if r.disagreement is not None:
        doc["disagreement"] = r.disagreement
    return doc


def _tree_line(v: GameValue) -> str:
    b = v.bracket
    exact = (f"{show_value(b.exact)} exactly" if b.closed and v.exact else
             f"in [{show_value(b.lower)}, {show_value(b.upper)}]"
             + (f" (open: {b.reason})" if b.reason else ""))
    return (f"V_H (H = {v.horizon}) = {exact}; LP value {show(v.lp.value)} "
            f"({LP_SOLVER}, agreement tolerance {LP_TOLERANCE:g} relative, "
            f"{v.prefixes} prefixes, {v.lp.seconds:.2f} s)")


def _structured_line(v: StructuredValue) -> str:
    how = "exactly" if v.exact else f"(float mode, {v.arithmetic})"
    fix = ", fixpoint reached" if v.fixpoint else ""
    return (f"V_H (H = {_show_horizon(v.horizon)}) = {show_value(v.value)} {how}; structured "
            f"route ({v.steps} DP steps{fix}, {v.arithmetic}, {v.seconds:.2f} s)")



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
    return {"value": format_number(v.value), "exact": v.closed,
            "lower": format_number(v.lower), "upper": format_number(v.upper),
            "lower_source": v.lower_source, "upper_source": v.upper_source,
            "reason": v.reason, "layers": v.layers,
            "extra_normals": [list(n) for n in v.normals], "note": CONJECTURE_NOTE,
            "coalition_dp": _coalition_doc(v.coalition)}


def _ngoal_document(r: RoutedValue) -> dict[str, Any]:
    """The JSON ``dpp value --json`` prints for an N-goal instance.

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> doc = _ngoal_document(routed_value(star3(), 2, route="structured"))
    >>> doc["value"], doc["structured"]["coalition_dp"]["cover"]
    ('3/2', [{'goals': [1, 2], 'mass': '1/3'}, {'goals': [1, 3], 'mass': '1/6'}])
    >>> from dppverify.game.examples import hub4
    >>> _ngoal_document(routed_value(hub4(), None))["value"]
    '12/7'
    """
    assert isinstance(r.tree, GameValue | None) and isinstance(r.structured, NValue | None)
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


def _ngoal_lines(r: RoutedValue) -> list[str]:
    """The lines ``dpp value`` prints for an N-goal instance.

    Examples
    --------
    >>> from dppverify.game.examples import star3
    >>> print(_ngoal_lines(routed_value(star3(), None))[0])
    V_H (H = inf, N = 3 goals) = 3/2 (≈ 1.5) exactly; coalition DP (NG.4: the value for \
three goals) (3 layers)
    """
    assert isinstance(r.tree, GameValue | None) and isinstance(r.structured, NValue | None)
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
