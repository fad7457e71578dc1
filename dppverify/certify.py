"""``certify(instance, profile)``: certify or refute a profile as a weak PBNE.

The profile is checked on the truncated game of horizon ``H`` (default: the longest path in
the profile): payoffs, both players' exact regrets, sequential rationality and Bayes
consistency, the value ``V_H``, and the paper's lemmas on the instance. See
``dppverify/checks.md`` for every check id.

Numbers: rational instances are certified exactly (``Fraction``); LP values are reported
beside the exact ones. Instances in float mode (``"numbers": "float"``) cannot be certified
exactly: ``certify`` refuses them unless ``exact=False``, which compares with the relative
tolerance :data:`~dppverify.exact.FLOAT_TOLERANCE` and says so in the certificate.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

from tqdm import tqdm

from dppverify.certificate import Certificate, CheckRecord
from dppverify.context import Context, make_context
from dppverify.errors import HorizonError, InvalidInstanceError, LPError
from dppverify.exact import FLOAT_TOLERANCE, Tolerance
from dppverify.instance import Instance, instance_from_json, load_instance, node_to_json
from dppverify.lemmas import (
    l1_lower_bound,
    l2_no_revisits,
    l3_greedy,
    l4_monotonicity,
    l5_induced_beliefs,
    telescoping,
    xi2_secondary_value,
)
from dppverify.lp import LP_SOLVER, LP_TOLERANCE
from dppverify.pbne import (
    attacker_br,
    belief_consistency,
    defender_br,
    phases,
    sequential_rationality,
    value_check,
    values,
    wellformed,
)
from dppverify.profile import Profile, check_format, load_profile_document, profile_from_json
from dppverify.tree import DEFAULT_MAX_PREFIXES, build_tree

__all__ = ["CHECK_IDS", "DEFAULT_TRIALS", "FLOAT_MODE_REFUSED", "certify", "default_horizon",
           "resolve_instance"]

DEFAULT_TRIALS = 5
"""Random non-reacting attackers tried by the L3 and L4 checks."""

FLOAT_MODE_REFUSED = (
    "the instance uses \"numbers\": \"float\" (binary float weights), so it cannot be "
    "certified exactly; certify in float mode with exact=False (CLI: --float), which compares "
    f"with relative tolerance {FLOAT_TOLERANCE:g}")

CHECK_IDS = (
    "profile.wellformed", "value.U1", "value.U2", "value.U", "value.VoI", "profile.phases",
    "pbne.attacker_br.primary", "pbne.attacker_br.secondary", "pbne.defender_br",
    "pbne.sequential_rationality", "pbne.belief_consistency", "game.value",
    "lemma.TEL.telescoping", "lemma.L1.lower_bound", "lemma.L2.no_revisits",
    "lemma.XI2.secondary_value", "lemma.L3.greedy", "lemma.L4.monotonicity",
    "lemma.L5.induced_beliefs",
)
"""Every check id, in certificate order (documented in ``dppverify/checks.md``)."""


def resolve_instance(instance: Instance | Mapping[str, Any] | str | Path) -> Instance:
    """An :class:`Instance` from an instance, a document (dict) or a file path.

    Parameters
    ----------
    instance : Instance, Mapping, str or Path
        Returned as is, parsed (:func:`~dppverify.instance.instance_from_json`) or loaded
        (:func:`~dppverify.instance.load_instance`).

    Returns
    -------
    Instance

    Raises
    ------
    InvalidInstanceError
        The document or file is not a valid instance.

    Examples
    --------
    >>> from dppverify.examples import triangle, triangle_document
    >>> inst = triangle()
    >>> resolve_instance(inst) is inst
    True
    >>> resolve_instance(triangle_document(("1/4", "3/4"))).prior
    (Fraction(1, 4), Fraction(3, 4))
    """
    if isinstance(instance, Instance):
        return instance
    if isinstance(instance, Mapping):
        return instance_from_json(instance)
    return load_instance(instance)


def _profile_document(profile: Mapping[str, Any] | str | Path | bytes) -> Mapping[str, Any]:
    if isinstance(profile, Mapping):
        check_format(profile)
        return profile
    return load_profile_document(profile if isinstance(profile, bytes) else Path(profile))


def default_horizon(instance: Instance, profile: Profile) -> int:
    """The longest valid path in the profile (at least the steps to the nearest goal).

    Parameters
    ----------
    instance : Instance
        The game.
    profile : Profile
        The resolved profile (:func:`~dppverify.profile.profile_from_json`).

    Returns
    -------
    int
        The horizon ``H`` that :func:`certify` uses when none is given.

    Examples
    --------
    On ``s – a – g1``, ``a – g2``, a secondary walk that goes back and forth takes 4 steps:

    >>> from dppverify.instance import instance_from_json
    >>> inst = instance_from_json({"graph": {"nodes": [{"id": v} for v in ("s", "a", "g1", "g2")],
    ...     "edges": [{"source": "s", "target": "a"}, {"source": "a", "target": "g1"},
    ...               {"source": "a", "target": "g2"}]},
    ...     "start": "s", "goals": ["g1", "g2"], "prior": ["1/2", "1/2"]})
    >>> doc = {"format": "dpp-profile/1", "goals": {"primary": "g1", "secondary": "g2"},
    ...     "defender": {"rule": "progress", "goal": "g1"},
    ...     "attacker": {"primary": [{"path": ["s", "a", "g1"], "probability": 1}],
    ...                  "secondary": [{"path": ["s", "a", "s", "a", "g2"], "probability": 1}]}}
    >>> default_horizon(inst, profile_from_json(doc, inst))
    4
    >>> default_horizon(inst, profile_from_json({"format": "dpp-profile/1"}, inst))
    2
    """
    lengths = [len(w.walk) - 1 for w in (*profile.primary, *profile.secondary)]
    return max([*lengths, instance.hops[instance.start]])


def certify(instance: Instance | Mapping[str, Any] | str | Path,
            profile: Mapping[str, Any] | str | Path | bytes, *,
            horizon: int | None = None, exact: bool = True,
            max_prefixes: int = DEFAULT_MAX_PREFIXES, seed: int = 0,
            trials: int = DEFAULT_TRIALS, progress: bool = False) -> Certificate:
    """Certify or refute ``profile`` as a weak PBNE of ``instance`` (truncated at ``H``).

    Parameters
    ----------
    instance : Instance, Mapping, str or Path
        The game (object, instance document, or path to an instance JSON file).
    profile : Mapping, str, Path or bytes
        A ``dpp-profile/1`` document, a path to one, or its JSON text as bytes.
    horizon : int, optional
        ``H``; default the longest path in the profile. Must be at least that.
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
    """
    inst = resolve_instance(instance)
    if not inst.exact and exact:
        raise InvalidInstanceError(FLOAT_MODE_REFUSED)
    tol = Tolerance(exact=inst.exact)
    doc = _profile_document(profile)
    prof = profile_from_json(doc, inst, tol)
    longest = default_horizon(inst, prof)
    if horizon is None:
        horizon = longest
    elif horizon < longest:
        raise HorizonError(f"the horizon H = {horizon} is shorter than the profile's longest "
                           f"path ({longest} steps)")
    tree = build_tree(inst, horizon, max_prefixes=max_prefixes, progress=progress)
    with tqdm(total=len(CHECK_IDS) + 1, desc="certify: strategies on the tree", unit="check",
              disable=not progress, leave=False, file=sys.stderr) as bar:
        ctx = make_context(inst, tree, prof, tol, seed=seed, trials=trials)
        bar.update(1)
        checks = _run_checks(ctx, bar)
    roles = ctx.roles
    defender = doc.get("defender")
    info = {
        "nodes": inst.n_nodes,
        "arcs": sum(len(s) for s in inst.succ),
        "start": node_to_json(inst.nodes[inst.start]),
        "primary": node_to_json(inst.nodes[roles.g1]),
        "secondary": node_to_json(inst.nodes[roles.g2]),
        "prior": [str(roles.b1), str(roles.b2)],
        "defender_rule": defender.get("rule") if isinstance(defender, Mapping) else None,
    }
    return Certificate(checks=tuple(checks), horizon=horizon, exact=inst.exact,
                       tolerance=tol.tolerance, lp_solver=LP_SOLVER, lp_tolerance=LP_TOLERANCE,
                       prefixes=tree.n_prefixes, leaves=tree.n_leaves, seed=seed, info=info)


def _guard(check_id: str, fn: Callable[[], list[CheckRecord]]) -> list[CheckRecord]:
    """Run a check; an LP that does not solve makes it an ``error`` record, not a crash."""
    try:
        return fn()
    except LPError as exc:
        return [CheckRecord(check_id, "error", f"LP failure: {exc}")]


def _run_checks(ctx: Context, bar: tqdm | None = None) -> list[CheckRecord]:
    """Every check in :data:`CHECK_IDS` order; ``bar`` names each check as it starts."""
    def starting(check_id: str) -> None:
        if bar is not None:
            bar.set_description(f"certify: {check_id}")

    starting("profile.wellformed, value.*")
    out = [wellformed(ctx)]
    value_ids = ("value.U1", "value.U2", "value.U", "value.VoI")
    try:
        out += values(ctx)
    except LPError as exc:  # pragma: no cover - values() solves no LP
        out += [CheckRecord(i, "error", f"LP failure: {exc}") for i in value_ids]
    if bar is not None:
        bar.update(len(out))
    steps: list[tuple[str, Callable[[], list[CheckRecord]]]] = [
        ("profile.phases", lambda: [phases(ctx)]),
        ("pbne.attacker_br.primary", lambda: [attacker_br(ctx, 1)]),
        ("pbne.attacker_br.secondary", lambda: [attacker_br(ctx, 2)]),
        ("pbne.defender_br", lambda: [defender_br(ctx)]),
        ("pbne.sequential_rationality", lambda: [sequential_rationality(ctx)]),
        ("pbne.belief_consistency", lambda: [belief_consistency(ctx)]),
        ("game.value", lambda: [value_check(ctx)]),
        ("lemma.TEL.telescoping", lambda: [telescoping(ctx)]),
        ("lemma.L1.lower_bound", lambda: [l1_lower_bound(ctx)]),
        ("lemma.L2.no_revisits", lambda: [l2_no_revisits(ctx)]),
        ("lemma.XI2.secondary_value", lambda: [xi2_secondary_value(ctx)]),
        ("lemma.L3.greedy", lambda: [l3_greedy(ctx)]),
        ("lemma.L4.monotonicity", lambda: [l4_monotonicity(ctx)]),
        ("lemma.L5.induced_beliefs", lambda: [l5_induced_beliefs(ctx)]),
    ]
    for check_id, fn in steps:
        starting(check_id)
        out += _guard(check_id, fn)
        if bar is not None:
            bar.update(1)
    assert tuple(c.id for c in out) == CHECK_IDS, [c.id for c in out]
    return out
