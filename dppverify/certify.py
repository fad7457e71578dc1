"""``certify(instance, profile)``: certify or refute a profile as a weak PBNE, for any N >= 2.

The one entry point for two and N goals: the instance is read once (:func:`game_of`) and its
number of goals decides which game it is. Without a horizon the profile is checked on the
untruncated game (``H = inf``) by the structured route; a finite ``horizon`` is an explicit
request for the game truncated at ``H`` (the walk tree when it fits; the route is chosen by
:func:`dppverify.routes.resolve_route`). The verdict answers one question, "is the profile a
weak PBNE of that game?": payoffs, both players' exact regrets, sequential rationality and Bayes
consistency, the value. The paper's lemmas and "is this the paper's construction" are
reported beside it as facts (kind ``fact``) and never decide it. See ``dppverify/checks.md``
for every check id.

Two goals: a ``dpp-profile/1`` profile and the checks of :data:`CHECK_IDS`. More goals: a
``dpp-ngoal-profile/1`` profile and the checks of :data:`NGOAL_CHECK_IDS`
(:mod:`dppverify.tree_route.per_goal_checks` on the walk tree,
:mod:`dppverify.checks.structured_per_goal` without it).

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
from typing import Any

from tqdm import tqdm

from dppio.inputs import reading_once
from dppio.text import count
from dppverify.certificate import Certificate, CheckRecord, merge_routes
from dppverify.checks.runners import TREE_RUNNERS
from dppverify.checks.structured import structured_checks
from dppverify.checks.structured_per_goal import NSTRUCTURED_NOT_RUN, nstructured_checks
from dppverify.errors import (
    HorizonError,
    InvalidInstanceError,
    LPError,
    ProfileError,
    UndecidedError,
)
from dppverify.exploitability import exploitability_of
from dppverify.formats.json_reading import JsonReadError, read_json_file
from dppverify.game.instance import Instance, arc_arrays, node_to_json
from dppverify.game.profile import (
    NGOAL_PROFILE_FORMAT,
    Profile,
    check_format,
    load_profile_document,
    profile_from_json,
)
from dppverify.horizons import parse_horizon
from dppverify.numbers import DEFAULT_REL_TOL
from dppverify.provenance import provenance_record
from dppverify.registry import CHECK_IDS, CHECKS, RouteName, not_run
from dppverify.routes import Chosen, Route, ngoal_game, resolve_route
from dppverify.tree_route.context import Context, make_context
from dppverify.tree_route.lp import LP_SOLVER, LP_TOLERANCE
from dppverify.tree_route.per_goal_checks import NGOAL_CHECK_IDS, ngoal_tree_checks
from dppverify.tree_route.tree import DEFAULT_MAX_PREFIXES, build_tree
from dppverify.valuation import game_of

__all__ = [
    "CHECK_IDS",
    "DEFAULT_TRIALS",
    "FLOAT_MODE_REFUSED",
    "NGOAL_CHECK_IDS",
    "NTABLE_UNDECIDED",
    "certify",
    "in_registry_order",
    "shortest_horizon",
]

DEFAULT_TRIALS = 5
"""Random non-reacting attackers tried by the L3 and L4 checks."""

FLOAT_MODE_REFUSED = (
    "the instance uses \"numbers\": \"float\" (binary float weights), so it cannot be "
    "certified exactly; certify in float mode with exact=False (CLI: --float), which compares "
    f"with relative tolerance {DEFAULT_REL_TOL:g}")

NTABLE_UNDECIDED = (
    "the untruncated game (H = inf) cannot be decided for this profile: its Defender table has "
    "no \"default\" and does not list every walk of the game, so it is undefined on some; a "
    "\"default\" distribution would decide it, or --horizon H certifies the game truncated "
    "at H")
"""Why an N-goal table without default (that leaves walks unlisted) cannot be certified on
the untruncated game."""


def _read_profile(profile: Any) -> tuple[Any, str]:
    """A profile document (not yet checked) and its name for messages, from a dict, a path,
    JSON bytes or any object with ``to_json()``; a file is read once."""
    to_json = getattr(profile, "to_json", None)
    if not isinstance(profile, Mapping | str | Path | bytes) and callable(to_json):
        profile = to_json()
    if isinstance(profile, Mapping):
        return profile, "profile"
    if isinstance(profile, str | Path | bytes):
        source = profile if isinstance(profile, bytes) else Path(profile)
        name = "profile" if isinstance(source, bytes) else str(source)
        try:
            return read_json_file(source, kind="profile"), name
        except JsonReadError as exc:
            raise ProfileError(f"{name}: {exc}") from None
    raise ProfileError("a profile must be a JSON document (dict), a file path, JSON bytes or "
                       f"an object with to_json(); got {type(profile).__name__} (the solver's "
                       "results have to_json())")


def _ngoal_profile_input(profile: Any) -> Mapping[str, Any] | str | Path:
    """An N-goal profile document, or its path (read by
    :func:`~dppverify.game.profile.load_profile_document`)."""
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
            horizon: int | str | float | None = None, exact: bool = True,
            max_prefixes: int = DEFAULT_MAX_PREFIXES, seed: int = 0,
            trials: int = DEFAULT_TRIALS, progress: bool = False,
            route: Route = "auto") -> Certificate:
    """Certify or refute ``profile`` as a weak PBNE of ``instance`` (truncated at ``H``).

    Parameters
    ----------
    instance : Instance, Instance, Mapping, str, Path, or any object with ``to_json()``
        The game, two or N goals (object, instance document, path to an instance JSON file,
        or any object whose ``to_json()`` returns the instance document).
    profile : Mapping, str, Path, bytes, or any object with ``to_json()``
        A ``dpp-profile/1`` document (``dpp-ngoal-profile/1`` for more than two goals), a
        path to one, its JSON text as bytes, or any object whose ``to_json()`` returns it.
    horizon : int, "inf" or None
        None (default) or ``"inf"``: the untruncated game, by the structured route
        (:func:`~dppverify.horizons.parse_horizon`). An integer ``H``: the game truncated at
        ``H`` (at least the profile's longest walk); the certificate then says it is not one
        for the full game.
    exact : bool
        Require exact certification (default). With ``exact=False`` float-mode instances
        are accepted and compared within the float tolerance; rational instances are
        always checked exactly.
    max_prefixes : int
        Size guard of the walk tree.
    seed, trials : int
        Seed and number of the random attackers of the L3 / L4 checks (two goals).
    progress : bool
        Show tqdm progress bars on stderr (two goals).
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
        The profile is not JSON or not a profile document of the instance's format.
    HorizonError, TreeTooLargeError
        ``horizon`` shorter than a profile walk; tree larger than ``max_prefixes``.
    UndecidedError
        The untruncated game cannot be decided for this profile: a table Defender without
        ``default`` that leaves a walk of the game unlisted (a walk the profile itself plays
        unlisted is a refutation, ``profile.wellformed``); the message names what would
        decide it.

    Examples
    --------
    >>> from dppverify.game.examples import triangle_attacker, triangle_document, triangle_profile
    >>> cert = certify(triangle_document(), triangle_profile())
    >>> cert.verdict, str(cert.check("value.U").numbers["U"])
    ('pass', '12/5')
    >>> cert = certify(triangle_document(), triangle_profile(triangle_attacker("3/7", "4/7")))
    >>> cert.verdict, cert.check("pbne.defender_br").status
    ('fail', 'fail')

    An instance with more than two goals and its ``dpp-ngoal-profile/1`` (a
    ``dpp-ngoal-profile/1`` for a two-goal instance document is checked the same way):

    >>> from dppverify.game.examples import star3_document, star3_profile
    >>> cert = certify(star3_document(), star3_profile(), horizon=2)
    >>> cert.verdict, cert.route, [c.status for c in cert.checks]
    ('pass', 'tree', ['pass', 'pass', 'pass', 'pass', 'pass', 'pass', 'pass'])
    >>> bad = star3_profile()
    >>> bad["defender"]["default"] = [0, 1, 0]   # guards b off the table: on s m and s m a
    >>> cert = certify(star3_document(), bad, horizon=2)
    >>> cert.verdict, cert.check("pbne.defender_br").message
    ('fail', 'Defender regret 2/3: greedy best response 3/2, profile 5/6')

    On the untruncated game (the default) type ``b`` may loop ``s m s m b`` where the default
    guards ``a``:

    >>> cert = certify(star3_document(), star3_profile())
    >>> cert.route, cert.horizon, cert.check("pbne.attacker_br").status
    ('structured', None, 'fail')
    """
    with reading_once():  # each input file read once: what is hashed is what was parsed
        return _certify(instance, profile, horizon=horizon, exact=exact,
                        max_prefixes=max_prefixes, seed=seed, trials=trials, progress=progress,
                        route=route)


def _certify(instance: Any, profile: Any, *, horizon: int | str | float | None, exact: bool,
             max_prefixes: int, seed: int, trials: int, progress: bool,
             route: Route) -> Certificate:
    """:func:`certify` inside its :func:`~dppio.inputs.reading_once` block."""
    game = game_of(instance)
    if ngoal_game(game):
        return _with_provenance(_certify_n(game, _ngoal_profile_input(profile), horizon,
                                           max_prefixes, route), instance, profile)
    if not game.exact and exact:
        raise InvalidInstanceError(FLOAT_MODE_REFUSED)
    doc, name = _read_profile(profile)
    if isinstance(doc, Mapping) and doc.get("format") == NGOAL_PROFILE_FORMAT:
        # two goals, as an N-goal game (an Instance object is one already: the same verdict
        # whether the game is given as a file, a document or an object)
        ngame = game if isinstance(instance, Instance) else game_of(instance, ngoal=True)
        return _with_provenance(_certify_n(ngame, doc, horizon, max_prefixes, route),
                                instance, profile)
    check_format(doc, name)
    prof = profile_from_json(doc, game, game.numbers)
    asked = parse_horizon(horizon)
    _check_horizon(asked, shortest_horizon(game, prof), "path")
    table = prof.defender is not None and prof.defender.table
    chosen = resolve_route(route, game, asked, max_prefixes, certifying=True, table=table)
    h = asked
    tree_checks: list[CheckRecord] = []
    prefixes = leaves = 0
    if chosen in ("tree", "both"):
        assert h is not None
        tree = build_tree(game, h, max_prefixes=max_prefixes, progress=progress)
        prefixes, leaves = tree.n_prefixes, tree.n_leaves
        with tqdm(total=len(CHECK_IDS) + 1, desc="certify: strategies on the tree",
                  unit="check", disable=not progress, leave=False, file=sys.stderr) as bar:
            ctx = make_context(game, tree, prof, seed=seed, trials=trials)
            bar.update(1)
            tree_checks = _run_checks(ctx, bar)
    checks = tree_checks
    if chosen in ("structured", "both"):
        structured = in_registry_order(structured_checks(game, prof, h), "structured")
        checks = structured if chosen == "structured" else merge_routes(tree_checks, structured)
    roles = game.roles(prof.primary_goal_index)
    defender = doc.get("defender")
    info = {
        "nodes": game.n_nodes,
        "arcs": int(arc_arrays(game).heads.size),
        "start": node_to_json(game.nodes[game.start]),
        "primary": node_to_json(game.nodes[roles.g1]),
        "secondary": node_to_json(game.nodes[roles.g2]),
        "prior": [str(roles.b1), str(roles.b2)],
        "defender_rule": defender.get("rule") if isinstance(defender, Mapping) else None,
    }
    exploit = exploitability_of(checks, goals=[info["primary"], info["secondary"]],
                                priors=[roles.b1, roles.b2], horizon=h, exact=game.exact)
    return Certificate(checks=tuple(checks), horizon=h, exact=game.exact,
                       tolerance=game.numbers.rel_tol, lp_solver=LP_SOLVER,
                       lp_tolerance=LP_TOLERANCE,
                       prefixes=prefixes, leaves=leaves, seed=seed, info=info, route=chosen,
                       not_run=not_run("structured") if chosen == "structured" else {},
                       provenance=provenance_record(instance, profile, route=chosen,
                                                    exact=game.exact),
                       exploitability=exploit)


def _with_provenance(cert: Certificate, instance: Any, profile: Any) -> Certificate:
    """An N-goal certificate with the provenance of its inputs (none for a game object)."""
    if not isinstance(instance, str | Path | Mapping):  # a game object: no provenance
        return cert
    return dataclasses.replace(cert, provenance=provenance_record(
        instance, _ngoal_profile_input(profile), route=cert.route, exact=cert.exact))


def _check_horizon(asked: int | None, longest: int, word: str) -> None:
    """Refuse a finite horizon shorter than the profile's longest walk (``word``: the two-goal
    message says "path", as it always has)."""
    if asked is not None and asked < longest:
        raise HorizonError(f"the horizon H = {asked} is shorter than the profile's longest "
                           f"{word} ({count(longest, 'step')}): give a horizon of at least "
                           f"{longest}, or none for the untruncated game")


def _certify_n(inst: Instance, profile: Mapping[str, Any] | str | Path, horizon: Any,
               max_prefixes: int, route: Route) -> Certificate:
    """:func:`certify` with more than two goals (a ``dpp-ngoal-profile/1`` profile)."""
    if isinstance(profile, str | Path):
        doc = load_profile_document(profile, NGOAL_PROFILE_FORMAT)
    else:  # a document is held to its format tag as a file is (one verdict)
        check_format(profile, "profile", NGOAL_PROFILE_FORMAT)
        doc = dict(profile)
    prof = profile_from_json(doc, inst, fmt=NGOAL_PROFILE_FORMAT)
    if route not in ("auto", "tree", "structured", "both"):
        raise ValueError(f"unknown route {route!r}")
    asked = parse_horizon(horizon)
    _check_horizon(asked, prof.longest, "walk")
    chosen: Chosen = resolve_route(route, inst, asked, max_prefixes, certifying=True)
    h = asked
    tree_checks: list[CheckRecord] = []
    tree = None
    if chosen in ("tree", "both"):
        assert h is not None
        tree_checks, tree = ngoal_tree_checks(inst, prof, h, max_prefixes)
    checks = tree_checks
    trie_size = 0
    if chosen in ("structured", "both"):
        structured, trie_size = nstructured_checks(inst, prof, h)
        if h is None and prof.defender is not None and not prof.defender.defined_everywhere:
            br = next((r for r in structured if r.id == "pbne.attacker_br"), None)
            if br is not None and br.status == "error":  # undefined off the table: undecided
                raise UndecidedError(NTABLE_UNDECIDED)
        checks = structured if chosen == "structured" else merge_routes(tree_checks, structured)
    info: dict[str, Any] = {"goals": inst.n_goals, "nodes": inst.n_nodes,
                            "game": "N goals"}
    if chosen != "tree":
        info["trie_prefixes"] = trie_size
    horizon_of = h if tree is None else tree.horizon
    exploit = exploitability_of(checks, goals=[node_to_json(inst.nodes[g]) for g in inst.goals],
                                priors=list(inst.prior), horizon=horizon_of, exact=True)
    return Certificate(checks=tuple(checks), horizon=horizon_of, exploitability=exploit,
                       exact=True, lp_solver=LP_SOLVER,
                       lp_tolerance=LP_TOLERANCE,
                       prefixes=0 if tree is None else tree.n_prefixes,
                       leaves=0 if tree is None else tree.n_leaves, info=info, route=chosen,
                       not_run=dict(NSTRUCTURED_NOT_RUN) if chosen == "structured" else {})


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
