"""Reading a goal-selection profile (``dpp-selection-profile/1``, ``docs/formats.md`` §2d)
against a goal-selection game (an :class:`~dppverify.game.instance_type.Instance` with
``goal_values``).

The document carries the Attacker's choice ``q`` (``"choice"``: one probability per goal), one
mixed strategy per goal index (as ``dpp-ngoal-profile/1``) and the Defender's rule: the
guarantee rule or a table (read by the per-goal reader against the game at ``q``), or for two
goals ``{"rule": "progress-mixture", "goal": g, "alpha": α}`` or ``{"rule": "progress",
"goal": g}`` (:class:`~dppverify.game.mixture_rule.ProgressMixture`). A ``dpp-profile/1``
document (the paper's two-goal profile) is read too: its ``prior`` block is the choice, its
Defender the progress rule; so the paper's σ* is certified, and refuted, as a profile of the
goal-selection game. Either way the result is a
:class:`~dppverify.game.profile_types.Profile` of format ``dpp-selection-profile/1`` with its
``choice``.

What the document says that is wrong is a defect (``profile.wellformed`` fails); only a
document that is not a profile of the game at all is bad input (:class:`ProfileError`).
"""

from __future__ import annotations

import dataclasses
import json
from collections.abc import Mapping
from fractions import Fraction
from types import MappingProxyType
from typing import Any

from dppverify.errors import ProfileError
from dppverify.exact import Number
from dppverify.formats.json_reading import lookup_node, show_node
from dppverify.game.goal_selection import with_choice
from dppverify.game.instance_type import Instance
from dppverify.game.mixture_rule import ProgressMixture
from dppverify.game.profile import _per_goal_profile, _two_goal_profile
from dppverify.game.profile_types import (
    PER_GOAL_PROFILE_FORMAT,
    PROFILE_FORMAT,
    SELECTION_PROFILE_FORMAT,
    Defect,
    DefectCollector,
    Profile,
    stated_of,
)
from dppverify.game.rules import ProgressRule

_PLACEHOLDER = {"rule": "table", "entries": []}
"""The Defender the per-goal reader is given when the rule is a progress mixture (it reads only
the walks then; the mixture is read here)."""


def selection_profile_from_json(doc: Any, instance: Instance, *, name: str = "profile"
                                ) -> Profile:
    """Resolve a ``dpp-selection-profile/1`` (or ``dpp-profile/1``) document against a
    goal-selection game.

    Raises
    ------
    ProfileError
        When ``doc`` is not an object tagged with one of the two formats.

    Examples
    --------
    >>> from dppverify.game.examples import triangle_document
    >>> from dppverify.game.instance import instance_from_json
    >>> inst = {**triangle_document(), "goal_selection": True}
    >>> del inst["prior"]
    >>> game = instance_from_json(inst)
    >>> doc = {"format": "dpp-selection-profile/1", "choice": ["1/4", "3/4"],
    ...        "attacker": [[{"path": ["s", "g2"], "probability": 1}],
    ...                     [{"path": ["s", "g2"], "probability": 1}]],
    ...        "defender": {"rule": "guarantee", "h": [2, 2]}, "value": {"V": 2}}
    >>> p = selection_profile_from_json(doc, game)
    >>> p.wellformed, p.choice, p.defender.h, p.claimed_values["V"]
    (True, (Fraction(1, 4), Fraction(3, 4)), (Fraction(2, 1), Fraction(2, 1)), 2)
    >>> bad = {**doc, "choice": ["1/2", "1/3"]}
    >>> [str(d) for d in selection_profile_from_json(bad, game).defects]
    ['choice: probabilities sum to 5/6, not 1']
    """
    if not isinstance(doc, Mapping):
        raise ProfileError(f"{name}: a profile must be a JSON object, got {type(doc).__name__}")
    tag = doc.get("format")
    if tag == PROFILE_FORMAT:
        return _paper_profile(doc, instance)
    if tag != SELECTION_PROFILE_FORMAT:
        raise ProfileError(f"{name}: \"format\" must be \"{SELECTION_PROFILE_FORMAT}\" for a "
                           f"goal-selection instance (or \"{PROFILE_FORMAT}\", whose prior is "
                           f"read as the choice), got {json.dumps(tag, default=str)[:60]}",
                           stated_of(doc))
    c = DefectCollector()
    n = instance.n_goals
    choice = _choice(doc.get("choice"), n, c)
    game = with_choice(instance, choice if choice is not None else [Fraction(1, n)] * n)
    raw_def = doc.get("defender")
    mixture = None
    defender: Any = raw_def
    if isinstance(raw_def, Mapping) and raw_def.get("rule") in ("progress", "progress-mixture"):
        mixture = _mixture(raw_def, instance, c)
        defender = _PLACEHOLDER
    per_goal = _per_goal_profile({"format": PER_GOAL_PROFILE_FORMAT, "goals": doc.get("goals"),
                                  "attacker": doc.get("attacker"), "defender": defender},
                                 game, stated_of(doc))
    claimed = _claimed_value(doc.get("value"), c)
    return dataclasses.replace(
        per_goal, format=SELECTION_PROFILE_FORMAT, choice=choice,
        defender=mixture if mixture is not None else per_goal.defender,
        claimed_values=MappingProxyType({} if claimed is None else {"V": claimed}),
        defects=tuple(c.defects) + per_goal.defects)


def _choice(raw: Any, n: int, c: DefectCollector) -> tuple[Fraction, ...] | None:
    if not isinstance(raw, list) or len(raw) != n:
        c.add("choice", f"must be a list of {n} probabilities (one per goal): the Attacker's "
                        f"choice of its goal")
        return None
    qs = [c.probability(x, f"choice[{i}]") for i, x in enumerate(raw)]
    out = tuple(q for q in qs if q is not None)
    if len(out) < n:
        return None
    if not c.sums_to_one(out, "choice"):
        return None
    return out


def _mixture(raw: Mapping[str, Any], instance: Instance, c: DefectCollector
             ) -> ProgressMixture | None:
    rule = raw["rule"]
    if instance.n_goals != 2:
        c.add("defender.rule", f"{rule!r} is a two-goal Defender; this game has "
                               f"{instance.n_goals} goals")
        return None
    allowed = {"rule", "goal"} | ({"alpha"} if rule == "progress-mixture" else set())
    extra = sorted(set(raw) - allowed)
    if extra:
        c.add("defender", f"keys not in the format: {', '.join(extra)} for the rule {rule!r}")
        return None
    node = lookup_node(instance.index, raw.get("goal"))
    theta = None if node is None else instance.goal_index(node)
    if theta is None:
        c.add("defender.goal", f"must be one of the instance's goals, got "
                               f"{show_node(raw.get('goal'))}")
        return None
    alpha: Fraction | None = Fraction(1)
    if rule == "progress-mixture":
        alpha = c.probability(raw.get("alpha"), "defender.alpha")
    return None if alpha is None else ProgressMixture(theta, alpha)


def _claimed_value(raw: Any, c: DefectCollector) -> Number | None:
    if not isinstance(raw, Mapping) or raw.get("V") is None:
        return None
    return c.number(raw["V"], "value.V")


def _paper_profile(doc: Mapping[str, Any], instance: Instance) -> Profile:
    """A ``dpp-profile/1`` on a goal-selection game: its prior block is the choice."""
    c = DefectCollector()
    prior, goals = doc.get("prior"), doc.get("goals")
    choice = None
    if instance.n_goals != 2:
        c.add("format", f"a {PROFILE_FORMAT} profile has two goals; this game has "
                        f"{instance.n_goals}")
    elif not (isinstance(prior, Mapping) and isinstance(goals, Mapping)):
        c.add("prior", f"a {PROFILE_FORMAT} profile of a goal-selection game needs its "
                       "\"goals\" and \"prior\" blocks: the prior is read as the Attacker's "
                       "choice")
    else:
        choice = _paper_choice(prior, goals, instance, c)
    stated = stated_of(doc)
    if choice is None or not 0 < choice[0] < 1:
        defects = tuple(c.defects) or (Defect("prior", "must lie strictly between 0 and 1"),)
        return Profile(attacker=((), ()), format=SELECTION_PROFILE_FORMAT, defects=defects,
                       stated=stated)
    paper = _two_goal_profile(doc, with_choice(instance, choice), stated)
    mixture = None
    if isinstance(paper.defender, ProgressRule):
        theta = instance.goal_index(paper.defender.goal)
        assert theta is not None
        mixture = ProgressMixture(theta, Fraction(1))
    elif paper.defender is not None:
        c.add("defender", f"a {PROFILE_FORMAT} table Defender is not read on a goal-selection "
                          f"game: write a {SELECTION_PROFILE_FORMAT} document")
    return Profile(attacker=paper.attacker, defender=mixture, format=SELECTION_PROFILE_FORMAT,
                   longest=paper.longest, defects=tuple(c.defects) + paper.defects,
                   stated=stated, choice=choice)


def _paper_choice(prior: Mapping[str, Any], goals: Mapping[str, Any], instance: Instance,
                  c: DefectCollector) -> tuple[Fraction, ...] | None:
    """The choice a ``dpp-profile/1``'s prior block states, by goal index."""
    q = [Fraction(0), Fraction(0)]
    for role in ("primary", "secondary"):
        node = lookup_node(instance.index, goals.get(role))
        theta = None if node is None else instance.goal_index(node)
        p = c.probability(prior.get(role), f"prior.{role}")
        if theta is None:
            c.add(f"goals.{role}", f"must be one of the instance's goals, got "
                                   f"{show_node(goals.get(role))}")
        elif p is not None:
            q[theta] = p
    if c.defects:
        return None
    if sum(q) != 1:
        c.add("prior", f"must sum to 1 over the two goals, got {q[0] + q[1]}")
        return None
    return (q[0], q[1])
