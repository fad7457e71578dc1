"""``certify(instance, profile)``: certify or refute a profile as a weak PBNE.

Without a horizon the profile is checked on the untruncated game (``H = inf``) by the
structured route; a finite ``horizon`` is an explicit request for the game truncated at
``H`` (the walk tree when it fits). The verdict answers one question, "is the profile a weak
PBNE of that game?": payoffs, both players' exact regrets, sequential rationality and Bayes
consistency, the value. The paper's lemmas and "is this the paper's construction" are
reported beside it as facts (kind ``fact``) and never decide it. See ``dppverify/checks.md``
for every check id.

Numbers: rational instances are certified exactly (``Fraction``); LP values are reported
beside the exact ones. Instances in float mode (``"numbers": "float"``) cannot be certified
exactly: ``certify`` refuses them unless ``exact=False``, which compares with the relative
tolerance :data:`~dppverify.numbers.DEFAULT_REL_TOL` and says so in the certificate.
"""

from __future__ import annotations

import dataclasses
import json
import sys
from collections.abc import Mapping
from pathlib import Path
from typing import Any, Literal

from tqdm import tqdm

from dppverify.certificate import Certificate, CheckRecord, merge_routes
from dppverify.checks.runners import TREE_RUNNERS
from dppverify.checks.structured import structured_checks
from dppverify.errors import (
    HorizonError,
    InvalidInstanceError,
    LPError,
    ProfileError,
    TreeTooLargeError,
)
from dppverify.game.instance import Instance, arc_arrays, as_instance, node_to_json
from dppverify.game.profile import (
    Profile,
    ProgressRule,
    check_format,
    load_profile_document,
    profile_from_json,
)
from dppverify.horizons import parse_horizon
from dppverify.numbers import DEFAULT_REL_TOL
from dppverify.provenance import provenance_record
from dppverify.registry import CHECK_IDS, CHECKS, RouteName, not_run
from dppverify.routes import Route, tree_fits
from dppverify.tree_route.context import Context, make_context
from dppverify.tree_route.lp import LP_SOLVER, LP_TOLERANCE
from dppverify.tree_route.tree import DEFAULT_MAX_PREFIXES, build_tree

__all__ = [
    "CHECK_IDS",
    "DEFAULT_TRIALS",
    "FLOAT_MODE_REFUSED",
    "certify",
    "in_registry_order",
    "resolve_instance",
    "shortest_horizon",
]

DEFAULT_TRIALS = 5
"""Random non-reacting attackers tried by the L3 and L4 checks."""

FLOAT_MODE_REFUSED = (
    "the instance uses \"numbers\": \"float\" (binary float weights), so it cannot be "
    "certified exactly; certify in float mode with exact=False (CLI: --float), which compares "
    f"with relative tolerance {DEFAULT_REL_TOL:g}")



def resolve_instance(instance: Instance | Mapping[str, Any] | str | Path | Any) -> Instance:
    """An :class:`Instance` from an instance, a document (dict), a file path or any object
    with ``to_json()`` (:func:`~dppverify.game.instance.as_instance`).

    Parameters
    ----------
    instance : Instance, Mapping, str, Path or an object with ``to_json()``
        Returned as is, parsed (:func:`~dppverify.game.instance.instance_from_json`), loaded
        (:func:`~dppverify.game.instance.load_instance`) or parsed from ``to_json()``.

    Returns
    -------
    Instance

    Raises
    ------
    InvalidInstanceError
        The document or file is not a valid instance.

    Examples
    --------
    >>> from dppverify.game.examples import triangle, triangle_document
    >>> inst = triangle()
    >>> resolve_instance(inst) is inst
    True
    >>> resolve_instance(triangle_document(("1/4", "3/4"))).prior
    (Fraction(1, 4), Fraction(3, 4))
    """
    return as_instance(instance, two_goals=True)


def _profile_document(profile: Any) -> Mapping[str, Any]:
    """A profile document from a dict, a path, JSON bytes or any object with ``to_json()``."""
    to_json = getattr(profile, "to_json", None)
    if not isinstance(profile, Mapping | str | Path | bytes) and callable(to_json):
        profile = to_json()
    if isinstance(profile, Mapping):
        check_format(profile)
        return profile
    if isinstance(profile, str | Path | bytes):
        return load_profile_document(profile if isinstance(profile, bytes) else Path(profile))
    raise ProfileError("a profile must be a JSON document (dict), a file path, JSON bytes or "
                       f"an object with to_json(); got {type(profile).__name__} (for the "
                       "solver's Equilibrium pass solver.equilibrium_to_json(eq))")


def _nprofile_input(profile: Any) -> Mapping[str, Any] | str | Path:
    """An N-goal profile as ``certify_ngoal`` takes it (paths stay paths: provenance)."""
    to_json = getattr(profile, "to_json", None)
    if not isinstance(profile, Mapping | str | Path | bytes) and callable(to_json):
        profile = to_json()
    if isinstance(profile, bytes):
        try:
            profile = json.loads(profile)
        except (ValueError, RecursionError) as exc:
            raise ProfileError(f"the profile is not JSON ({exc})") from None
    if isinstance(profile, Mapping | str | Path):
        return profile
    raise ProfileError("a profile must be a JSON document (dict), a file path, JSON bytes or "
                       f"an object with to_json(); got {type(profile).__name__}")


def shortest_horizon(instance: Instance, profile: Profile) -> int:
    """The shortest horizon a truncated game needs for the profile: its longest walk (at least
    the steps to the nearest goal).

    This is never a default: a profile under test is not known to be an equilibrium, and
    truncating at its own length hides the longer deviations that would refute it
    (proofs/HORIZON.md, H.5). Without a horizon :func:`certify` certifies the untruncated game.

    Parameters
    ----------
    instance : Instance
        The game.
    profile : Profile
        The resolved profile (:func:`~dppverify.game.profile.profile_from_json`).

    Returns
    -------
    int
        The least ``H`` that :func:`certify` accepts as an explicit horizon.

    Examples
    --------
    On ``s – a – g1``, ``a – g2``, a secondary walk that goes back and forth takes 4 steps:

    >>> from dppverify.game.instance import instance_from_json
    >>> inst = instance_from_json({"graph": {"nodes": [{"id": v} for v in ("s", "a", "g1", "g2")],
    ...     "edges": [{"source": "s", "target": "a"}, {"source": "a", "target": "g1"},
    ...               {"source": "a", "target": "g2"}]},
    ...     "start": "s", "goals": ["g1", "g2"], "prior": ["1/2", "1/2"]})
    >>> doc = {"format": "dpp-profile/1", "goals": {"primary": "g1", "secondary": "g2"},
    ...     "defender": {"rule": "progress", "goal": "g1"},
    ...     "attacker": {"primary": [{"path": ["s", "a", "g1"], "probability": 1}],
    ...                  "secondary": [{"path": ["s", "a", "s", "a", "g2"], "probability": 1}]}}
    >>> shortest_horizon(inst, profile_from_json(doc, inst))
    4
    >>> shortest_horizon(inst, profile_from_json({"format": "dpp-profile/1"}, inst))
    2
    """
    lengths = [len(w.walk) - 1 for w in (*profile.primary, *profile.secondary)]
    return max([*lengths, instance.hops[instance.start]])


def certify(instance: Instance | Mapping[str, Any] | str | Path | Any,
            profile: Mapping[str, Any] | str | Path | bytes | Any, *,
            horizon: int | Literal["inf"] | None = None, exact: bool = True,
            max_prefixes: int = DEFAULT_MAX_PREFIXES, seed: int = 0,
            trials: int = DEFAULT_TRIALS, progress: bool = False,
            route: Route = "auto") -> Certificate:
    """Certify or refute ``profile`` as a weak PBNE of ``instance`` (truncated at ``H``).

    Parameters
    ----------
    instance : Instance, Mapping, str, Path, or any object with ``to_json()``
        The game (object, instance document, path to an instance JSON file, or any object
        whose ``to_json()`` returns the instance document).
    profile : Mapping, str, Path, bytes, or any object with ``to_json()``
        A ``dpp-profile/1`` document, a path to one, its JSON text as bytes, or any object
        whose ``to_json()`` returns it.
    horizon : int, "inf" or None
        None (default) or ``"inf"``: the untruncated game, by the structured route. An
        integer ``H``: the game truncated at ``H`` (at least the profile's longest walk);
        the certificate then says it is not one for the full game.
    exact : bool
        Require exact certification (default). With ``exact=False`` float-mode instances
        are accepted and compared within the float tolerance; rational instances are
        always checked exactly.
    max_prefixes : int
        Size guard of the walk tree.
    seed, trials : int
        Seed and number of the random attackers of the L3 / L4 checks.
    progress : bool
        Show tqdm progress bars on stderr.
    route : {"auto", "tree", "structured", "both"}
        ``auto``: the walk tree when it fits ``max_prefixes``, else the structured route
        (docs/checker.md, "Routes"); ``both``: both, a status disagreement is an ``error``.

    Returns
    -------
    Certificate
        ``verdict == "pass"`` exactly when every check passed. A defective profile is
        refuted (``profile.wellformed`` fails), never an exception.

    Raises
    ------
    InvalidInstanceError
        Bad instance, or a float-mode instance with ``exact=True``.
    ProfileError
        The profile is not JSON or not a ``dpp-profile/1`` document.
    HorizonError, TreeTooLargeError
        ``horizon`` shorter than a profile path; tree larger than ``max_prefixes``.
    UndecidedError
        The untruncated game cannot be decided for this profile: a table Defender without
        ``default`` that leaves a walk of the game unlisted (a walk the profile itself plays
        unlisted is a refutation, ``profile.wellformed``); the message names the walk and
        what would decide it.

    Examples
    --------
    >>> doc = {"graph": {"nodes": [{"id": "s"}, {"id": "g1"}, {"id": "g2"}],
    ...        "edges": [{"source": "s", "target": "g2", "weight": 2},
    ...                  {"source": "g2", "target": "g1", "weight": 2},
    ...                  {"source": "s", "target": "g1", "weight": 3}]},
    ...        "start": "s", "goals": ["g1", "g2"], "prior": ["7/10", "3/10"]}
    >>> profile = {"format": "dpp-profile/1", "goals": {"primary": "g1", "secondary": "g2"},
    ...     "defender": {"rule": "progress", "goal": "g1"},
    ...     "attacker": {"primary": [{"path": ["s", "g1"], "probability": "4/7"},
    ...                              {"path": ["s", "g2"], "probability": "3/7"}],
    ...                  "secondary": [{"path": ["s", "g2"], "probability": "1"}]}}
    >>> cert = certify(doc, profile)
    >>> cert.verdict, str(cert.check("value.U").numbers["U"])
    ('pass', '12/5')
    >>> swapped = dict(profile, attacker={"primary": [
    ...     {"path": ["s", "g1"], "probability": "3/7"},
    ...     {"path": ["s", "g2"], "probability": "4/7"}],
    ...     "secondary": [{"path": ["s", "g2"], "probability": "1"}]})
    >>> cert = certify(doc, swapped)
    >>> cert.verdict, cert.check("pbne.defender_br").status
    ('fail', 'fail')

    An instance with more than two goals (and its ``dpp-ngoal-profile/1``) is certified by
    :func:`dppverify.ngoal.certify.certify_ngoal`, as ``dpp certify`` does:

    >>> from dppverify.game.examples import star3_document, star3_profile
    >>> cert = certify(star3_document(), star3_profile(), horizon=2)
    >>> cert.verdict, cert.check("ngoal.value.U").status
    ('pass', 'pass')
    """
    from dppverify.game.instance import Instance
    from dppverify.valuation import game_of

    game = game_of(instance)
    if game.n_goals > 2:  # N > 2 goals
        from dppverify.ngoal.certify import certify_ngoal

        given = instance if isinstance(instance, str | Path | Mapping) else game  # provenance
        nprofile = _nprofile_input(profile)
        cert = certify_ngoal(given, nprofile, horizon=horizon, max_prefixes=max_prefixes,
                             route=route)
        if cert.provenance is not None or isinstance(given, Instance):
            return cert
        return dataclasses.replace(cert, provenance=provenance_record(
            given, nprofile, route=cert.route, exact=cert.exact))
    inst = resolve_instance(game)
    if not inst.exact and exact:
        raise InvalidInstanceError(FLOAT_MODE_REFUSED)
    doc = _profile_document(profile)
    prof = profile_from_json(doc, inst, inst.numbers)
    asked = parse_horizon(horizon)
    longest = shortest_horizon(inst, prof)
    if asked is not None and asked < longest:
        raise HorizonError(f"the horizon H = {asked} is shorter than the profile's longest "
                           f"path ({longest} steps): give a horizon of at least "
                           f"{longest}, or none for the untruncated game")
    chosen, h = _choose_route(inst, prof, asked, route, max_prefixes)
    tree_checks: list[CheckRecord] = []
    prefixes = leaves = 0
    if chosen in ("tree", "both"):
        assert h is not None
        tree = build_tree(inst, h, max_prefixes=max_prefixes, progress=progress)
        prefixes, leaves = tree.n_prefixes, tree.n_leaves
        with tqdm(total=len(CHECK_IDS) + 1, desc="certify: strategies on the tree",
                  unit="check", disable=not progress, leave=False, file=sys.stderr) as bar:
            ctx = make_context(inst, tree, prof, seed=seed, trials=trials)
            bar.update(1)
            tree_checks = _run_checks(ctx, bar)
    checks = tree_checks
    if chosen in ("structured", "both"):
        structured = in_registry_order(structured_checks(inst, prof, h), "structured")
        checks = structured if chosen == "structured" else merge_routes(tree_checks, structured)
    roles = inst.roles(prof.primary_slot)
    defender = doc.get("defender")
    info = {
        "nodes": inst.n_nodes,
        "arcs": int(arc_arrays(inst).heads.size),
        "start": node_to_json(inst.nodes[inst.start]),
        "primary": node_to_json(inst.nodes[roles.g1]),
        "secondary": node_to_json(inst.nodes[roles.g2]),
        "prior": [str(roles.b1), str(roles.b2)],
        "defender_rule": defender.get("rule") if isinstance(defender, Mapping) else None,
    }
    return Certificate(checks=tuple(checks), horizon=h, exact=inst.exact,
                       tolerance=inst.numbers.rel_tol, lp_solver=LP_SOLVER,
                       lp_tolerance=LP_TOLERANCE,
                       prefixes=prefixes, leaves=leaves, seed=seed, info=info, route=chosen,
                       not_run=not_run("structured") if chosen == "structured" else {},
                       provenance=provenance_record(instance, profile, route=chosen,
                                                    exact=inst.exact))


def _choose_route(inst: Instance, prof: Profile, horizon: int | None,
                  route: Route, max_prefixes: int
                  ) -> tuple[Literal["tree", "structured", "both"], int | None]:
    """The route(s) to run and the horizon (None: the untruncated game).

    No horizon means the untruncated game (H = inf), which only the structured route
    evaluates; a finite horizon is an explicit request for the truncated game.
    """
    table = prof.defender is not None and not isinstance(prof.defender, ProgressRule)
    if horizon is None:
        if route in ("tree", "both"):
            raise HorizonError(f"--route {route} needs a finite horizon: the walk tree is the "
                               f"truncated game's (give --horizon H; without a horizon the "
                               f"untruncated game is certified by the structured route)")
        return "structured", None  # a table without default: decided there if it can be
    h = horizon
    if route == "auto":
        if tree_fits(inst, h, max_prefixes):
            return "tree", h
        if table:
            raise TreeTooLargeError(_TABLE_REFUSED.format(
                why=f"the H = {h} walk tree has more than {max_prefixes} prefixes"))
        return "structured", h
    if route in ("structured", "both") and table:
        raise TreeTooLargeError(_TABLE_REFUSED.format(why=f"--route {route} was asked for"))
    return route, h


_TABLE_REFUSED = ("a table Defender on a truncated game can only be certified on the walk "
                  "tree, and {why}; use --route tree with a horizon whose tree fits "
                  "--max-prefixes, or omit --horizon to certify the untruncated game")


def _run_checks(ctx: Context, bar: tqdm | None = None) -> list[CheckRecord]:
    """Every tree check in registry order; ``bar`` names each check as it starts."""
    out: list[CheckRecord] = []
    for s in CHECKS:
        if s.id not in TREE_RUNNERS:
            continue
        ids, fn = TREE_RUNNERS[s.id].ids, TREE_RUNNERS[s.id].run
        if bar is not None:
            bar.set_description(f"certify: {', '.join(ids)}")
        try:
            records = fn(ctx)
        except LPError as exc:
            records = [CheckRecord(i, "error", f"LP failure: {exc}") for i in ids]
        out += records
        if bar is not None:
            bar.update(len(ids))
    return in_registry_order(out, "tree")


def in_registry_order(records: list[CheckRecord], route: RouteName) -> list[CheckRecord]:
    """The records in registry order, each tagged with its route and what it relies on; a
    check of the route without a record becomes an ``error`` record (never a silent gap).

    Examples
    --------
    >>> recs = in_registry_order([CheckRecord("value.U", "pass", "")], "tree")
    >>> len(recs), recs[0].status, recs[3].route, recs[3].relies_on
    (19, 'error', 'tree', 'the walk tree of H steps')
    """
    by_id = {r.id: r for r in records}
    out = []
    for s in CHECKS:
        if route not in s.routes:
            continue
        r = by_id.get(s.id)
        if r is None:
            r = CheckRecord(s.id, "error", "internal: the check produced no record", {}, s.proof)
        relies = s.tree if route == "tree" else s.structured
        out.append(dataclasses.replace(r, route=route, relies_on=r.relies_on or relies))
    return out
