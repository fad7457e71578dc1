"""The check registry: every check's id, certificate order, proof, routes and kind, once.

The certificate order, :data:`CHECK_IDS`, the routes each check runs on, what each relies on,
and the table in ``dppverify/checks.md`` (tested against this registry) all come from
:data:`CHECKS`, declared here once; this module imports nothing of the checker. The function
computing each tree check is declared beside the checks
(:data:`dppverify.checks.runners.TREE_RUNNERS`); ``certify`` runs them in registry order.

``kind``: ``check`` is evidence for the one question the verdict answers, "is the profile a
(weak) PBNE of the game?"; ``consistency`` compares two computations of the checker's own (a
failure is the checker's fault, never evidence for the profile); ``fact`` is a fact about the
profile or the instance reported beside the verdict: the paper's lemmas and whether the
profile is the paper's construction (Lemma 5's beliefs). ``profile.phases`` stays a ``check``:
it only tests phases the document claims (a claim must be true, like ``value.*``), and passes
when none are claimed, whatever the secondary plays. The verdict counts ``check``
and ``consistency`` records, never ``fact`` ones: an equilibrium that is not the paper's
construction still passes. The pass count ("9/9 checks passed") counts only kind ``check``;
the other kinds are reported apart (:func:`kind_of`,
:meth:`dppverify.certificate.Certificate.of_kind`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

__all__ = ["CHECKS", "CHECK_IDS", "FAMILIES", "KINDS", "CheckSpec", "Family", "check_ids",
           "checks_of", "kind_of", "not_run", "spec"]

RouteName = Literal["tree", "structured"]
Kind = Literal["check", "consistency", "fact"]
KINDS: tuple[Kind, ...] = ("check", "consistency", "fact")
"""The kinds, in the order reports show them."""
Family = Literal["two-goal", "per-goal"]
"""The check family of a certificate, chosen by the profile's format: ``two-goal`` for a
``dpp-profile/1`` profile (the paper's primary and secondary types, with the paper's lemmas and
facts), ``per-goal`` for a ``dpp-ngoal-profile/1`` profile (one type per goal index, any N)."""
FAMILIES: tuple[Family, ...] = ("two-goal", "per-goal")


@dataclass(frozen=True)
class CheckSpec:
    """One check of one family: id, proof file id, routes, kind, and what each route relies on.

    Attributes
    ----------
    id : str
        Stable check id (the same id in both families for the same question).
    proof : str or None
        The proof file id in ``proofs/`` the check tests.
    routes : tuple of str
        ``"tree"`` and/or ``"structured"``.
    kind : {"check", "consistency", "fact"}
        See the module docstring.
    tree, structured : str
        What the check relies on, per route (``"–"`` when it does not run there).
    family : {"two-goal", "per-goal"}
        The certificates that hold it (:data:`Family`).

    Examples
    --------
    >>> spec("game.value").routes, spec("game.value").structured
    (('tree', 'structured'), 'relies on proofs/DP.md')
    """

    id: str
    proof: str | None
    routes: tuple[RouteName, ...]
    kind: Kind
    tree: str
    structured: str
    family: Family = "two-goal"


_T = "the walk tree of H steps"
_BOTH: tuple[RouteName, ...] = ("tree", "structured")
_W = "relies on proofs/WALKBR.md"
_P = "the prefixes of the profile's walks (proofs/L3.md)"
_PROFILE = "the profile's walks, walk by walk"
_NW = "relies on proofs/NWALKBR.md (NW.1: the minimum over all walks of any length)"
_NP = ("the prefixes of the profile's walks (proofs/NWALKBR.md NW.3; off the path NW.4: any "
       "distribution is greedy for the belief uniform on its support)")


def _spec(check_id: str, proof: str | None, structured: str, *,
          routes: tuple[RouteName, ...] = _BOTH, kind: Kind = "check",
          family: Family = "two-goal") -> CheckSpec:
    """A registry row; on the tree route every check relies on the walk tree of H steps."""
    return CheckSpec(check_id, proof, routes, kind, _T, structured, family)


def _per_goal(check_id: str, structured: str, *, routes: tuple[RouteName, ...] = _BOTH,
              kind: Kind = "check") -> CheckSpec:
    """A row of the per-goal family (every one tests proofs/NGOAL.md)."""
    return _spec(check_id, "NGOAL", structured, routes=routes, kind=kind, family="per-goal")


CHECKS: tuple[CheckSpec, ...] = (
    _spec("profile.wellformed", None, "the profile document alone"),
    _spec("value.U1", "TEL", _PROFILE),
    _spec("value.U2", "TEL", _PROFILE),
    _spec("value.U", "TEL", _PROFILE),
    _spec("value.VoI", "THM", "the profile's walks"),
    _spec("profile.phases", "L5", "σ* along the profile's secondary walk"),
    _spec("pbne.attacker_br.primary", "L1", _W),
    _spec("pbne.attacker_br.secondary", "XI2", _W),
    _spec("pbne.defender_br", "L3", _P),
    _spec("pbne.sequential_rationality", "THM", _P),
    _spec("pbne.belief_consistency", "THM", _P, kind="consistency"),
    _spec("game.value", "HORIZON", "relies on proofs/DP.md"),
    _spec("lemma.TEL.telescoping", "TEL", "the profile's prefixes (a consistency check of σ*)",
          kind="consistency"),
    _spec("lemma.L1.lower_bound", "L1", _W, kind="fact"),
    _spec("lemma.L2.no_revisits", "L2", "the profile's secondary walks", kind="fact"),
    _spec("lemma.XI2.secondary_value", "XI2", _W, kind="fact"),
    _spec("lemma.L3.greedy", "L3", "–", routes=("tree",), kind="fact"),
    _spec("lemma.L4.monotonicity", "L4", "–", routes=("tree",), kind="fact"),
    _spec("lemma.L5.induced_beliefs", "L5", _P, kind="fact"),
    _per_goal("profile.wellformed", "the profile document alone"),
    _per_goal("value.U", _PROFILE),
    _per_goal("pbne.attacker_br", _NW),
    _per_goal("pbne.defender_br", _NP),
    _per_goal("pbne.sequential_rationality", _NP),
    _per_goal("game.value", "relies on proofs/NGOAL.md (the guarantee sets' value)"),
    _per_goal("game.value.structured", "–", routes=("tree",), kind="consistency"),
)
"""Every check of every family, each family in its certificate order.

The two-goal family (``dpp-profile/1``) asks the paper's questions of the primary and the
secondary type, with the lemmas and facts behind them. The per-goal family
(``dpp-ngoal-profile/1``, any N) uses the same id for the same question (well formed, ``U``,
the Defender's best response, sequential rationality, ``V_H = U``); ``pbne.attacker_br`` holds
every type's regret (two goals split it by type, with the lemmas behind each), and
``game.value.structured`` compares the structured value with the tree route's. The two-goal
facts (phases, lemmas) have no per-goal row."""


def checks_of(family: Family) -> tuple[CheckSpec, ...]:
    """The rows of ``family``, in certificate order.

    Examples
    --------
    >>> [c.id for c in checks_of("per-goal")][:3]
    ['profile.wellformed', 'value.U', 'pbne.attacker_br']
    """
    return tuple(c for c in CHECKS if c.family == family)


def check_ids(family: Family) -> tuple[str, ...]:
    """The check ids of ``family``'s certificates, in certificate order.

    Examples
    --------
    >>> len(check_ids("two-goal")), len(check_ids("per-goal"))
    (19, 7)
    """
    return tuple(c.id for c in checks_of(family))


CHECK_IDS: tuple[str, ...] = check_ids("two-goal")
"""Every check id of a two-goal certificate, in certificate order."""

_BY_ID = {(c.family, c.id): c for c in CHECKS}

NOT_RUN_REASONS = {
    "lemma.L3.greedy": "needs the walk tree (an LP per random attacker over all prefixes); "
                       "the Defender's greedy optimality is checked exactly by "
                       "pbne.defender_br on the profile's prefixes",
    "lemma.L4.monotonicity": "random primary strategies need the walk tree; the profile's own "
                             "beliefs along ξ² are checked by lemma.L5.induced_beliefs",
    "game.value.structured": "compares the structured value with the tree route's LP; the "
                             "structured route has no walk tree (its game.value is the "
                             "structured value itself)",
}


def spec(check_id: str, family: Family = "two-goal") -> CheckSpec:
    """The registry row of ``check_id`` in ``family`` (KeyError if unknown).

    Examples
    --------
    >>> spec("lemma.L3.greedy").routes, spec("value.U", "per-goal").proof
    (('tree',), 'NGOAL')
    """
    return _BY_ID[(family, check_id)]


def kind_of(check_id: str) -> Kind:
    """The kind of ``check_id`` (the same in every family that has it); an id the registry
    does not know (a certificate written by another version) counts as ``check``.

    Examples
    --------
    >>> kind_of("pbne.belief_consistency"), kind_of("value.U"), kind_of("no.such.check")
    ('consistency', 'check', 'check')
    """
    s = _BY_ID.get(("two-goal", check_id)) or _BY_ID.get(("per-goal", check_id))
    return "check" if s is None else s.kind


def not_run(route: RouteName, family: Family = "two-goal") -> dict[str, str]:
    """The checks of ``family`` that ``route`` does not run, each with the reason.

    Examples
    --------
    >>> sorted(not_run("structured"))
    ['lemma.L3.greedy', 'lemma.L4.monotonicity']
    >>> not_run("tree"), list(not_run("structured", "per-goal"))
    ({}, ['game.value.structured'])
    """
    return {c.id: NOT_RUN_REASONS.get(c.id, "not on this route")
            for c in checks_of(family) if route not in c.routes}
