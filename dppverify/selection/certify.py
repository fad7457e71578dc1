"""``certify_selection``: the certificate of a goal-selection profile on the untruncated game
(proofs/SELECT.md SELECT.6; ``docs/formats.md`` §2d).

The records are :func:`dppverify.selection.checks.selection_checks`'s; the certificate is a
``dpp-certificate/1`` of the structured route at ``H = inf`` whose ``info`` says
``"game": "goal selection"`` and gives the choice. Its ``exploitability`` record is that of the
game with the prior ``q`` (the types' regrets weighted by ``q`` and the Defender's); what
choosing another goal would gain the Attacker is ``selection.goal_indifference``'s ``gain``.
"""

from __future__ import annotations

from collections.abc import Mapping
from fractions import Fraction
from pathlib import Path
from typing import Any

from dppverify.certificate import Certificate
from dppverify.errors import ProfileError
from dppverify.exploitability import exploitability_of
from dppverify.formats.json_reading import JsonReadError, read_json_file
from dppverify.selection.checks import selection_checks
from dppverify.selection.instance import SelectionInstance, load_selection, selection_from_json
from dppverify.selection.profile import selection_profile_from_json

__all__ = ["certify_selection"]


def _profile_document(profile: Any) -> Any:
    if isinstance(profile, Mapping):
        return profile
    to_json = getattr(profile, "to_json", None)
    if callable(to_json):
        return to_json()
    try:
        return read_json_file(profile if isinstance(profile, bytes) else Path(profile),
                              kind="profile")
    except JsonReadError as exc:
        raise ProfileError(f"{profile}: {exc}") from None


def certify_selection(instance: SelectionInstance | Mapping[str, Any] | str | Path,
                      profile: Any) -> Certificate:
    """Certify a goal-selection profile (a document, a path, JSON bytes or an object with
    ``to_json()``) against a goal-selection game (itself, a document or a path).

    Raises
    ------
    InvalidInstanceError, ProfileError
        An invalid instance, or a profile that is not a profile document at all; whatever a
        profile document says that is wrong is refuted by a check instead.

    Examples
    --------
    >>> from dppverify.game.examples import triangle_document
    >>> inst = {**triangle_document(), "goal_selection": True}
    >>> del inst["prior"]
    >>> doc = {"format": "dpp-selection-profile/1", "choice": ["1/4", "3/4"],
    ...        "attacker": [[{"path": ["s", "g2"], "probability": 1}],
    ...                     [{"path": ["s", "g2"], "probability": 1}]],
    ...        "defender": {"rule": "guarantee", "h": [2, 2]}, "value": {"V": 2}}
    >>> cert = certify_selection(inst, doc)
    >>> cert.verdict, cert.info["game"], cert.exploitability.nash_conv
    ('pass', 'goal selection', 0)
    """
    sel = (instance if isinstance(instance, SelectionInstance) else
           selection_from_json(instance) if isinstance(instance, Mapping) else
           load_selection(instance))
    prof = selection_profile_from_json(_profile_document(profile), sel)
    checks = tuple(selection_checks(sel, prof))
    game = sel.game
    q = prof.choice or tuple(Fraction(1, sel.n_goals) for _ in range(sel.n_goals))
    goals = [game.nodes[g] for g in game.goals]
    info = {"game": "goal selection", "goals": sel.n_goals,
            "choice": [str(x) for x in q] if prof.choice is not None else None,
            "goal_values": [str(r) for r in sel.values]}
    return Certificate(checks=checks, horizon=None, exact=True, route="structured",
                       info=info, exploitability=exploitability_of(
                           checks, goals=goals, priors=q, horizon=None, exact=True))
