"""``certify(instance, profile)``: certify or refute a profile as a weak PBNE, for any N >= 2.

One flow for every profile: the inputs are converted once at the door
(:mod:`dppverify.game.inputs`), the horizon is checked against the profile, the route is chosen
(:func:`dppverify.routes.resolve_route`), the routes run the checks of the profile's family
(:mod:`dppverify.checks.suites`), and :func:`_certificate` forms the one certificate, whose
verdict answers "is the profile a weak PBNE of that game?" (``dppverify/checks.md``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any, Unpack

from dppio.inputs import reading_once
from dppio.text import count
from dppverify.certificate import Certificate, CheckRecord, merge_routes, verdict_of
from dppverify.checks.suites import Options, Run, suite_of
from dppverify.errors import HorizonError, InvalidInstanceError, UndecidedError
from dppverify.exploitability import exploitability_of
from dppverify.game.inputs import GraphKeys, Parsed, read_instance, read_profile
from dppverify.game.instance import Instance
from dppverify.game.profile import Profile
from dppverify.horizons import parse_horizon
from dppverify.kernel import check as kernel_check
from dppverify.kernel.guarantee import MAX_BASES
from dppverify.limits import DEFAULT_TRIALS
from dppverify.numbers import DEFAULT_REL_TOL
from dppverify.provenance import canonical_json, provenance_record
from dppverify.registry import not_run
from dppverify.routes import ROUTES, Chosen, Route, resolve_route
from dppverify.structured.witness import witness_document
from dppverify.tree_route.lp import LP_SOLVER, LP_TOLERANCE
from dppverify.tree_route.tree import DEFAULT_MAX_PREFIXES

FLOAT_MODE_REFUSED = (
    "the instance uses \"numbers\": \"float\" (binary float weights), so it cannot be "
    "certified exactly; certify in float mode with exact=False (CLI: --float), which compares "
    f"with relative tolerance {DEFAULT_REL_TOL:g}")

_PER_GOAL_FLOAT = ("a dpp-ngoal-profile/1 profile is certified exactly, and this instance uses "
                   "\"numbers\": \"float\"; give it exact numbers, or a dpp-profile/1 profile")


def certify(instance: Any, profile: Any, *, horizon: int | str | float | None = None,
            exact: bool = True, max_prefixes: int = DEFAULT_MAX_PREFIXES, seed: int = 0,
            trials: int = DEFAULT_TRIALS, progress: bool = False, route: Route = "auto",
            **graph: Unpack[GraphKeys]) -> Certificate:
    """Certify or refute ``profile`` as a weak PBNE of ``instance`` (truncated at ``H``).

    Parameters
    ----------
    instance : Instance, Mapping, bytes, str, Path, networkx graph, or an object with ``to_json()``
        The game, two or N goals, in any form :func:`~dppverify.game.inputs.as_instance` takes.
    profile : Profile, Mapping, bytes, str, Path, or an object with ``to_json()``
        A ``dpp-profile/1`` profile (two goals) or a ``dpp-ngoal-profile/1`` one (any N), in
        any form :func:`~dppverify.game.inputs.as_profile` takes.
    horizon : int, "inf" or None
        None (default) or ``"inf"``: the untruncated game, by the structured route. An integer
        ``H``: the game truncated at ``H`` (at least the profile's longest walk).
    exact : bool
        Require exact certification (default). ``exact=False`` accepts a float-mode instance
        and compares within :data:`~dppverify.numbers.DEFAULT_REL_TOL`.
    max_prefixes : int
        Size guard of the walk tree.
    seed, trials : int
        Seed and number of the random attackers of the L3 / L4 checks (two goals).
    progress : bool
        Progress bars on stderr.
    route : {"auto", "tree", "structured", "both"}
        ``auto``: the walk tree when it fits ``max_prefixes``, else the structured route;
        ``both``: both, a status disagreement is an ``error`` (docs/checker.md, "Routes").
    **graph : GraphKeys
        ``start``, ``goals``, ``prior``, ``weight``: with a networkx graph ``instance`` only.

    Returns
    -------
    Certificate
        ``verdict == "pass"`` exactly when every check passed. A defective profile is
        refuted (``profile.wellformed`` fails), never an exception.

    Raises
    ------
    InvalidInstanceError, ProfileError
        A bad instance (or a float-mode one with ``exact=True``), a bad profile document.
    HorizonError, TreeTooLargeError
        ``horizon`` shorter than a profile walk; tree larger than ``max_prefixes``.
    UndecidedError
        The untruncated game cannot be decided for this profile (a table Defender without
        ``default`` that leaves a walk unlisted); the message names what would decide it.

    Examples
    --------
    >>> from dppverify.game.examples import triangle_attacker, triangle_document, triangle_profile
    >>> cert = certify(triangle_document(), triangle_profile())
    >>> cert.verdict, str(cert.check("value.U").numbers["U"])
    ('pass', '12/5')
    >>> cert = certify(triangle_document(), triangle_profile(triangle_attacker("3/7", "4/7")))
    >>> cert.verdict, cert.check("pbne.defender_br").status
    ('fail', 'fail')

    Three goals and a ``dpp-ngoal-profile/1``; on the untruncated game (the default) type
    ``b`` may loop ``s m s m b`` where the profile's default guards ``a``:

    >>> from dppverify.game.examples import star3_document, star3_profile
    >>> cert = certify(star3_document(), star3_profile(), horizon=2)
    >>> cert.verdict, cert.route, [c.status for c in cert.checks]
    ('pass', 'tree', ['pass', 'pass', 'pass', 'pass', 'pass', 'pass', 'pass'])
    >>> certify(star3_document(), star3_profile()).check("pbne.attacker_br").status
    'fail'
    """
    with reading_once():  # each input file read once: what is hashed is what was parsed
        game = read_instance(instance, **graph)
        prof = read_profile(profile, game.value)
        options = Options(max_prefixes=max_prefixes, seed=seed, trials=trials, progress=progress)
        return _certified(game, prof, parse_horizon(horizon), route, exact, options)


def _certified(game: Parsed[Instance], prof: Parsed[Profile], horizon: int | None,
               route: Route, exact: bool, options: Options) -> Certificate:
    """The certificate of the read inputs: the horizon checked, the routes run and merged."""
    inst, profile = game.value, prof.value
    suite = suite_of(profile)
    if route not in ROUTES:
        raise ValueError(f"unknown route {route!r}")
    if not inst.exact and (exact or suite.exact_only):
        raise InvalidInstanceError(_PER_GOAL_FLOAT if suite.exact_only else FLOAT_MODE_REFUSED)
    longest, word = suite.longest(inst, profile)
    if horizon is not None and horizon < longest:
        raise HorizonError(f"the horizon H = {horizon} is shorter than the profile's longest "
                           f"{word} ({count(longest, 'step')}): give a horizon of at least "
                           f"{longest}, or none for the untruncated game")
    chosen: Chosen = resolve_route(route, inst, horizon, options.max_prefixes, certifying=True,
                                   table=suite.tree_only(profile))
    tree = structured = None
    if chosen in ("tree", "both"):
        assert horizon is not None  # resolve_route: the tree route needs a finite horizon
        tree = suite.on_tree(inst, profile, horizon, options)
    if chosen in ("structured", "both"):
        structured = suite.structured(inst, profile, horizon)
    return _certificate(game, prof, chosen, tree, structured, options)


def _certificate(game: Parsed[Instance], prof: Parsed[Profile], chosen: Chosen,
                 tree: Run | None, structured: Run | None, options: Options) -> Certificate:
    """The one place a certificate is formed: the records of the routes that ran, merged,
    the game described, every player's regret, the provenance of what was parsed; the
    verdict is the certificate's (:func:`~dppverify.certificate.verdict_of` of its records)."""
    inst, profile = game.value, prof.value
    suite = suite_of(profile)
    runs = [r for r in (tree, structured) if r is not None]  # one route ran at least
    checks: list[CheckRecord] = (runs[0].records if len(runs) == 1 else
                                 merge_routes(runs[0].records, runs[1].records))
    horizon = runs[0].horizon
    who = suite.players(inst, profile, None if structured is None else structured.trie_prefixes)
    exploit = exploitability_of(checks, goals=who.goals, priors=who.priors, horizon=horizon,
                                exact=inst.exact)
    provenance = provenance_record(game, prof, route=chosen, exact=inst.exact)
    kernel = _kernel(game, prof, horizon, tuple(checks), provenance)
    return Certificate(
        checks=tuple(checks), horizon=horizon, exact=inst.exact,
        tolerance=inst.numbers.rel_tol, lp_solver=LP_SOLVER, lp_tolerance=LP_TOLERANCE,
        prefixes=tree.prefixes if tree else 0, leaves=tree.leaves if tree else 0,
        seed=options.seed if who.seeded else None, info={**who.info, "kernel": kernel},
        route=chosen,
        not_run=not_run("structured", suite.family) if chosen == "structured" else {},
        provenance=provenance, exploitability=exploit)


def _kernel(game: Parsed[Instance], prof: Parsed[Profile], horizon: int | None,
            checks: tuple[CheckRecord, ...], provenance: Mapping[str, Any]) -> dict[str, str]:
    """One verdict: the trusted kernel (:mod:`dppverify.kernel`, proofs/KERNEL.md) on the
    engine's witness (:mod:`dppverify.structured.witness`) of a profile the engine certifies,
    recorded in ``info.kernel``; a PASS the kernel does not accept is a bug of the checker
    (:class:`~dppverify.errors.UndecidedError`, exit 3, naming both). Not applicable (and why):
    a finite horizon, a float-mode game, inputs without bytes (objects given in Python), the
    goal-selection game (its documents are not the kernel's formats), a guarantee rule the
    engine decided by its exact search (NRULE NR.4: the kernel has NR.2 only) or whose packing
    polytope is beyond the kernel's bound."""
    verdict = verdict_of(checks)
    searched = any(c.id == "pbne.attacker_br" and (c.numbers or {}).get("states") for c in checks)
    data = [p.data if isinstance(p.data, bytes) or p.data is None else canonical_json(p.data)
            for p in (game, prof)]
    rule = getattr(prof.value.defender, "normals", None)  # the guarantee rule's extras
    n_goals = game.value.n_goals
    bases = 0 if rule is None else sum(math.comb(2**n_goals - 1 + len(rule) + n_goals, k)
                                       for k in range(1, n_goals + 1))
    why = ("the engine refutes the profile or could not decide it" if verdict != "pass" else
           "the goal-selection game (proofs/SELECT.md): the kernel reads games with a prior "
           "only" if game.value.goal_selection else
           "the engine decided the Attacker by its exact search over the rule's states (NRULE "
           "NR.4); the kernel decides the guarantee rule by NR.2 only" if searched else
           f"the guarantee rule's packing polytope needs {bases} candidate bases, beyond the "
           f"kernel's bound of {MAX_BASES}" if bases > MAX_BASES else
           f"the game truncated at H = {horizon}; the kernel decides the untruncated game"
           if horizon is not None else "a float-mode game; the kernel decides exact games only"
           if not game.value.exact else "objects given in Python have no bytes to tie a "
           "witness to" if None in data else None)
    if why is not None:
        return {"status": "not applicable", "message": why}
    witness = witness_document(game.value, prof.value,
                               instance_sha256=str(provenance["instance"]["sha256"]),
                               profile_sha256=str(provenance["profile"]["sha256"]))
    v = kernel_check(data[0], data[1], witness, base_dir=game.folder)  # type: ignore[arg-type]
    if not v.applicable:  # a size bound of the kernel, not a doubt about the witness
        return {"status": "not applicable", "message": v.message}
    if not v.accepted:
        raise UndecidedError(f"the engine certifies this profile but the trusted kernel does not "
                             f"accept the engine's witness ({v.status}: {v.message}): a bug in "
                             "dppverify; please report it")
    return {"status": v.status, "message": v.message}
