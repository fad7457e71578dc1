"""Reading a goal-selection profile (``dpp-selection-profile/1``, ``docs/formats.md`` §2d).

The document carries the Attacker's choice ``q`` (``"choice"``: one probability per goal), one
mixed strategy per goal index (as ``dpp-ngoal-profile/1``) and the Defender's rule: the
guarantee rule or a table (read by the per-goal profile reader, against the game at ``q``), or
for two goals ``{"rule": "progress-mixture", "goal": g, "alpha": α}`` or ``{"rule":
"progress", "goal": g}`` (:class:`~dppverify.selection.mixture.ProgressMixture`).

A ``dpp-profile/1`` document (the paper's two-goal profile) is read too: its ``prior`` block is
the choice ``q``, its Defender the progress rule; so the paper's σ* can be certified, and
refuted, as a profile of the goal-selection game.

What the document says that is wrong is recorded as a defect (``profile.wellformed`` fails);
only a document that is not a profile at all is bad input (:class:`ProfileError`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from dppverify.errors import ProfileError
from dppverify.exact import Number
from dppverify.formats.json_reading import lookup_node, show_node
from dppverify.game.profile import profile_from_json
from dppverify.game.profile_types import (
    NGOAL_PROFILE_FORMAT,
    PROFILE_FORMAT,
    Defect,
    DefectCollector,
    Profile,
    ProgressRule,
)
from dppverify.selection.instance import SelectionInstance
from dppverify.selection.mixture import ProgressMixture

__all__ = ["SELECTION_PROFILE_FORMAT", "SelectionProfile", "selection_profile_from_json"]

SELECTION_PROFILE_FORMAT = "dpp-selection-profile/1"
"""The goal-selection profile format (``docs/formats.md`` §2d)."""

_PLACEHOLDER = {"rule": "table", "entries": []}
"""The Defender the per-goal reader is given when the rule is a progress mixture (it reads only
the walks then; the mixture is read here)."""


@dataclass(frozen=True, eq=False)
class SelectionProfile:
    """A goal-selection profile resolved against its game, with its defects.

    Attributes
    ----------
    choice : tuple of Fraction or None
        ``q`` (None when unusable: a defect says why).
    per_goal : Profile
        The walks (and, for the guarantee rule and tables, the Defender) as the per-goal
        reader resolved them against the game at ``q`` (at the uniform prior when ``q`` is
        unusable).
    mixture : ProgressMixture or None
        The Defender when it is a progress rule or a mixture of the two (two goals).
    claimed_value : Number or None
        ``value.V``.
    claimed_costs : tuple or None
        ``value.costs``.
    format : str
        The document's format tag.
    defects : tuple of Defect
        Everything that makes the profile ill-formed (the per-goal reader's included).
    """

    choice: tuple[Fraction, ...] | None
    per_goal: Profile
    mixture: ProgressMixture | None
    claimed_value: Number | None
    claimed_costs: tuple[Number | None, ...] | None
    format: str
    defects: tuple[Defect, ...]

    @property
    def wellformed(self) -> bool:
        """True when the profile has no defect."""
        return not self.defects


def selection_profile_from_json(doc: Any, selection: SelectionInstance) -> SelectionProfile:
    """Resolve a ``dpp-selection-profile/1`` (or ``dpp-profile/1``) document against a game.

    Raises
    ------
    ProfileError
        When ``doc`` is not an object tagged with one of the two formats.

    Examples
    --------
    >>> from dppverify.game.examples import triangle_document
    >>> from dppverify.selection.instance import selection_from_json
    >>> inst = {**triangle_document(), "goal_selection": True}
    >>> del inst["prior"]
    >>> sel = selection_from_json(inst)
    >>> doc = {"format": "dpp-selection-profile/1", "choice": ["1/4", "3/4"],
    ...        "attacker": [[{"path": ["s", "g2"], "probability": 1}],
    ...                     [{"path": ["s", "g2"], "probability": 1}]],
    ...        "defender": {"rule": "guarantee", "h": [2, 2]}, "value": {"V": 2}}
    >>> p = selection_profile_from_json(doc, sel)
    >>> p.wellformed, p.choice, p.per_goal.defender.h, p.claimed_value
    (True, (Fraction(1, 4), Fraction(3, 4)), (Fraction(2, 1), Fraction(2, 1)), 2)
    >>> bad = {**doc, "choice": ["1/2", "1/3"]}
    >>> [str(d) for d in selection_profile_from_json(bad, sel).defects]
    ['choice: probabilities sum to 5/6, not 1']
    """
    if not isinstance(doc, Mapping):
        raise ProfileError(f"profile: a profile must be a JSON object, got {type(doc).__name__}")
    tag = doc.get("format")
    if tag == PROFILE_FORMAT:
        return _paper_profile(doc, selection)
    if tag != SELECTION_PROFILE_FORMAT:
        raise ProfileError(f"profile: \"format\" must be \"{SELECTION_PROFILE_FORMAT}\" for a "
                           f"goal-selection instance (or \"{PROFILE_FORMAT}\", whose prior is "
                           f"read as the choice), got {str(tag)[:60]!r}")
    c = DefectCollector()
    n = selection.n_goals
    choice = _choice(doc.get("choice"), n, c)
    game = selection.at_choice(choice if choice is not None else [Fraction(1, n)] * n)
    raw_def = doc.get("defender")
    mixture = None
    defender: Any = raw_def
    if isinstance(raw_def, Mapping) and raw_def.get("rule") in ("progress", "progress-mixture"):
        mixture = _mixture(raw_def, selection, c)
        defender = _PLACEHOLDER
    per_goal = profile_from_json({"format": NGOAL_PROFILE_FORMAT, "goals": doc.get("goals"),
                                  "attacker": doc.get("attacker"), "defender": defender},
                                 game, fmt=NGOAL_PROFILE_FORMAT)
    value, costs = _claims(doc.get("value"), n, c)
    return SelectionProfile(choice, per_goal, mixture, value, costs, SELECTION_PROFILE_FORMAT,
                            tuple(c.defects) + per_goal.defects)


def _choice(raw: Any, n: int, c: DefectCollector) -> tuple[Fraction, ...] | None:
    if not isinstance(raw, list) or len(raw) != n:
        c.add("choice", f"must be a list of {n} probabilities (one per goal): the Attacker's "
                        f"choice of its goal")
        return None
    qs = [c.probability(x, f"choice[{i}]") for i, x in enumerate(raw)]
    out = tuple(q for q in qs if q is not None)
    if len(out) < n:
        return None
    if sum(out) != 1:
        c.add("choice", f"probabilities sum to {sum(out)}, not 1")
        return None
    return out


def _mixture(raw: Mapping[str, Any], selection: SelectionInstance, c: DefectCollector
             ) -> ProgressMixture | None:
    game = selection.game
    rule = raw["rule"]
    if selection.n_goals != 2:
        c.add("defender.rule", f"{rule!r} is a two-goal Defender; this game has "
                               f"{selection.n_goals} goals")
        return None
    allowed = {"rule", "goal"} | ({"alpha"} if rule == "progress-mixture" else set())
    extra = sorted(set(raw) - allowed)
    if extra:
        c.add("defender", f"unknown key(s) {', '.join(extra)} for the rule {rule!r}")
        return None
    node = lookup_node(game.index, raw.get("goal"))
    theta = None if node is None else game.goal_index(node)
    if theta is None:
        c.add("defender.goal", f"must be one of the instance's goals, got "
                               f"{show_node(raw.get('goal'))}")
        return None
    alpha: Fraction | None = Fraction(1)
    if rule == "progress-mixture":
        alpha = c.probability(raw.get("alpha"), "defender.alpha")
    return None if alpha is None else ProgressMixture(theta, alpha)


def _claims(raw: Any, n: int, c: DefectCollector
            ) -> tuple[Number | None, tuple[Number | None, ...] | None]:
    if not isinstance(raw, Mapping):
        return None, None
    value = None if raw.get("V") is None else c.number(raw["V"], "value.V")
    costs = raw.get("costs")
    if costs is None:
        return value, None
    if not isinstance(costs, list) or len(costs) != n:
        c.add("value.costs", f"must be a list of {n} numbers (one per goal)")
        return value, None
    return value, tuple(c.number(x, f"value.costs[{i}]") for i, x in enumerate(costs))


def _paper_profile(doc: Mapping[str, Any], selection: SelectionInstance) -> SelectionProfile:
    """A ``dpp-profile/1`` on a goal-selection game: its prior block is the choice."""
    c = DefectCollector()
    game = selection.game
    prior, goals = doc.get("prior"), doc.get("goals")
    choice = None
    if selection.n_goals != 2:
        c.add("format", f"a {PROFILE_FORMAT} profile has two goals; this game has "
                        f"{selection.n_goals}")
    elif not (isinstance(prior, Mapping) and isinstance(goals, Mapping)):
        c.add("prior", f"a {PROFILE_FORMAT} profile of a goal-selection game needs its "
                       "\"goals\" and \"prior\" blocks: the prior is read as the Attacker's "
                       "choice")
    else:
        q = [Fraction(0), Fraction(0)]
        for role in ("primary", "secondary"):
            node = lookup_node(game.index, goals.get(role))
            theta = None if node is None else game.goal_index(node)
            p = c.probability(prior.get(role), f"prior.{role}")
            if theta is None:
                c.add(f"goals.{role}", f"must be one of the instance's goals, got "
                                       f"{show_node(goals.get(role))}")
            elif p is not None:
                q[theta] = p
        choice = tuple(q) if len(c.defects) == 0 and sum(q) == 1 else None
        if choice is None and not c.defects:
            c.add("prior", f"must sum to 1 over the two goals, got {q[0] + q[1]}")
    if choice is None or not 0 < choice[0] < 1:
        return SelectionProfile(choice, Profile(attacker=((), ())), None, None, None,
                                PROFILE_FORMAT, tuple(c.defects) or (
                                    Defect("prior", "must lie strictly between 0 and 1"),))
    paper = profile_from_json(doc, selection.at_choice(choice))
    mixture = None
    if isinstance(paper.defender, ProgressRule):
        theta = game.goal_index(paper.defender.goal)
        assert theta is not None
        mixture = ProgressMixture(theta, Fraction(1))
    elif paper.defender is not None:
        c.add("defender", f"a {PROFILE_FORMAT} table Defender is not read on a goal-selection "
                          f"game: write a {SELECTION_PROFILE_FORMAT} document")
    per_goal = Profile(attacker=paper.attacker, defects=paper.defects)
    return SelectionProfile(choice, per_goal, mixture, None, None, PROFILE_FORMAT,
                            tuple(c.defects) + paper.defects)
