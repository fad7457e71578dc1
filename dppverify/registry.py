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

__all__ = ["CHECKS", "CHECK_IDS", "KINDS", "NGOAL_CHECKS", "NGOAL_CHECK_IDS", "SELECTION_CHECKS",
           "SELECTION_CHECK_IDS", "CheckSpec", "kind_of", "not_run", "spec"]

RouteName = Literal["tree", "structured"]
Kind = Literal["check", "consistency", "fact"]
KINDS: tuple[Kind, ...] = ("check", "consistency", "fact")
"""The kinds, in the order reports show them."""


@dataclass(frozen=True)
class CheckSpec:
    """One check: id, proof file id, routes, kind, and what each route relies on.

    Attributes
    ----------
    id : str
        Stable check id.
    proof : str or None
        The proof file id in ``proofs/`` the check tests.
    routes : tuple of str
        ``"tree"`` and/or ``"structured"``.
    kind : {"check", "consistency", "fact"}
        See the module docstring.
    tree, structured : str
        What the check relies on, per route (``"–"`` when it does not run there).

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


_T = "the walk tree of H steps"
_BOTH: tuple[RouteName, ...] = ("tree", "structured")
_W = "relies on proofs/WALKBR.md"
_P = "the prefixes of the profile's walks (proofs/L3.md)"
_PROFILE = "the profile's walks, walk by walk"


def _spec(check_id: str, proof: str | None, structured: str, *,
          routes: tuple[RouteName, ...] = _BOTH, kind: Kind = "check") -> CheckSpec:
    """A registry row; on the tree route every check relies on the walk tree of H steps."""
    return CheckSpec(check_id, proof, routes, kind, _T, structured)


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
)
"""Every check of a two-goal certificate (``dpp-profile/1``), in certificate order."""

CHECK_IDS: tuple[str, ...] = tuple(c.id for c in CHECKS)
"""Every check id of a two-goal certificate, in certificate order."""

_NW = "relies on proofs/NWALKBR.md (NW.1: the minimum over all walks of any length)"
_NP = ("the prefixes of the profile's walks (proofs/NWALKBR.md NW.3; off the path NW.4: any "
       "distribution is greedy for the belief uniform on its support)")

NGOAL_CHECKS: tuple[CheckSpec, ...] = (
    _spec("profile.wellformed", "NGOAL", "the profile document alone"),
    _spec("value.U", "NGOAL", _PROFILE),
    _spec("pbne.attacker_br", "NGOAL", _NW),
    _spec("pbne.defender_br", "NGOAL", _NP),
    _spec("pbne.sequential_rationality", "NGOAL", _NP),
    _spec("game.value", "NGOAL", "relies on proofs/NGOAL.md (the guarantee sets' value)"),
    _spec("game.value.structured", "NGOAL", "–", routes=("tree",), kind="consistency"),
)
"""Every check of an N-goal certificate (``dpp-ngoal-profile/1``), in certificate order: the
same id as two goals for the same question (well formed, ``U``, the Defender's best response,
sequential rationality, ``V_H = U``); ``pbne.attacker_br`` holds every type's regret (two
goals split it by type, with the lemmas behind each), ``game.value.structured`` compares the
structured value with the tree route's. The two-goal facts (phases, lemmas) have no N-goal
entry."""

NGOAL_CHECK_IDS: tuple[str, ...] = tuple(c.id for c in NGOAL_CHECKS)
"""Every check id of an N-goal certificate, in certificate order."""

_SEL = "relies on proofs/SELECT.md (SELECT.6)"

SELECTION_CHECKS: tuple[CheckSpec, ...] = (
    *(c for c in NGOAL_CHECKS if "structured" in c.routes),
    _spec("selection.goal_indifference", "SELECT",
          f"{_SEL}: c_i, the exact best-response costs of pbne.attacker_br",
          routes=("structured",)),
    _spec("selection.value", "SELECT",
          "relies on proofs/SELECT.md (SELECT.1, SELECT.2: the guarantee sets' V_sel)",
          routes=("structured",)),
)
"""Every check of a goal-selection certificate (``dpp-selection-profile/1``), in certificate
order: the N-goal structured route's checks on the game with the choice ``q`` as prior, then
goal indifference and the value (``dppverify/checks.md``, "Goal selection")."""

SELECTION_CHECK_IDS: tuple[str, ...] = tuple(c.id for c in SELECTION_CHECKS)
"""Every check id of a goal-selection certificate, in certificate order."""

_BY_ID = ({c.id: c for c in SELECTION_CHECKS} | {c.id: c for c in NGOAL_CHECKS}
          | {c.id: c for c in CHECKS})
"""One entry per id (a shared id: the two-goal entry; both have the same kind and routes)."""

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


def spec(check_id: str) -> CheckSpec:
    """The registry entry of ``check_id``, for two or N goals (KeyError if unknown).

    Examples
    --------
    >>> spec("lemma.L3.greedy").routes
    ('tree',)
    """
    return _BY_ID[check_id]


def kind_of(check_id: str) -> Kind:
    """The kind of ``check_id``; an id the registry does not know (a certificate written by
    another version) counts as ``check``.

    Examples
    --------
    >>> kind_of("pbne.belief_consistency"), kind_of("value.U"), kind_of("no.such.check")
    ('consistency', 'check', 'check')
    """
    s = _BY_ID.get(check_id)
    return "check" if s is None else s.kind


def not_run(route: RouteName, *, n_goals: int = 2) -> dict[str, str]:
    """The checks ``route`` does not run on a game of ``n_goals`` goals, each with the reason.

    Examples
    --------
    >>> sorted(not_run("structured"))
    ['lemma.L3.greedy', 'lemma.L4.monotonicity']
    >>> not_run("tree"), list(not_run("structured", n_goals=3))
    ({}, ['game.value.structured'])
    """
    return {c.id: NOT_RUN_REASONS.get(c.id, "not on this route")
            for c in (CHECKS if n_goals == 2 else NGOAL_CHECKS) if route not in c.routes}
