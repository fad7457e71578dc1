"""Read strategy profiles leniently: ``dpp-profile/1`` and ``dpp-ngoal-profile/1``.

``docs/formats.md`` §2 and §2b; the types are in :mod:`dppverify.game.profile_types`.
Only a document that is not a JSON object tagged with a format of its game raises
:class:`ProfileError`. Everything else wrong with a profile — probabilities that are negative
or do not sum to 1, a step that is not an edge, a walk that does not start at ``s0``, does not
end at a goal or continues past its first goal, unknown nodes, duplicate walks, goals that do
not match the instance — is recorded as a :class:`Defect`: the checker then *refutes* the
profile (check ``profile.wellformed``) instead of crashing.

The formats themselves (the two-goal Defender rules ``progress`` and ``table``, the
per-goal ``table`` of goal distributions and the ``guarantee`` rule) are ``docs/formats.md``'s;
``attacker[θ]`` of a per-goal profile is the mixed strategy of goal index θ.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from fractions import Fraction
from types import MappingProxyType
from typing import Any

from dppio.text import show
from dppverify.errors import ProfileError
from dppverify.exact import Number
from dppverify.formats.json_reading import lookup_node, resolve_walk, show_node
from dppverify.game.instance import Instance
from dppverify.game.profile_types import (
    PER_GOAL_PROFILE_FORMAT,
    PROFILE_FORMAT,
    VALUE_KEYS,
    Defect,
    DefectCollector,
    Profile,
    Stated,
    StrategyWalk,
    parse_guarantee,
    stated_of,
)
from dppverify.game.rules import (
    GUARANTEE_RULE,
    DefenderRule,
    GoalTable,
    GuaranteeRule,
    ProfileDefender,
    ProgressRule,
    TableRule,
)
from dppverify.numbers import NumberMode

__all__ = ["PER_GOAL_PROFILE_FORMAT", "PROFILE_FORMAT", "Defect", "DefenderRule", "GoalTable",
           "GuaranteeRule", "Profile", "ProfileDefender", "ProgressRule", "Stated",
           "StrategyWalk", "TableRule", "profile_from_json", "stated_of", "validate_walk"]


def validate_walk(instance: Instance, raw: Any, *, complete: bool) -> tuple[int, ...] | str:
    """Resolve a JSON walk to node indices, or say what is wrong with it.

    A walk starts at ``s0``, follows arcs of the graph, and stops at the FIRST goal it
    reaches (paper Sec. III-A). ``complete`` walks (the Attacker's) must end at a goal;
    otherwise (Defender table entries) the walk must have at least one step. The two-goal
    form of :func:`dppverify.formats.json_reading.resolve_walk`: messages name the ``path`` (the
    ``walk`` of a Defender entry when not ``complete``).

    Examples
    --------
    >>> from dppverify.game.instance import instance_from_json
    >>> inst = instance_from_json({"graph": {"nodes": [{"id": "s"}, {"id": "a"},
    ...     {"id": "g1"}, {"id": "g2"}], "edges": [{"source": "s", "target": "a"},
    ...     {"source": "a", "target": "g1"}, {"source": "s", "target": "g2"},
    ...     {"source": "g2", "target": "g1"}]}, "start": "s", "goals": ["g1", "g2"],
    ...     "prior": ["1/2", "1/2"]})
    >>> validate_walk(inst, ["s", "a", "g1"], complete=True)
    (0, 1, 2)
    >>> validate_walk(inst, ["s", "g1"], complete=True)
    'path[1]: no edge "s" -> "g1"'
    >>> validate_walk(inst, ["s", "g2", "g1"], complete=True)
    'path reaches goal "g2" at step 1 and continues (the game ends at the first goal)'
    >>> validate_walk(inst, ["s", "a"], complete=True)
    'path ends at "a", which is not a goal'
    """
    return resolve_walk(instance, raw, complete=complete,
                        subject="path" if complete else "walk")


def profile_from_json(doc: Any, instance: Instance, *, name: str = "profile") -> Profile:
    """Resolve a profile document against ``instance``, recording its defects.

    The document's ``format`` tag picks the reader: ``dpp-ngoal-profile/1`` (one mixed
    strategy per goal index) for any number of goals, ``dpp-profile/1`` (primary and
    secondary) for two. The sums of a two-goal profile's probabilities are compared in the
    instance's number mode (within the float tolerance in float mode), a per-goal profile's
    exactly.

    Parameters
    ----------
    doc : Any
        The parsed document (numbers as ``int``, ``Fraction``, ``"p/q"`` strings or floats).
    instance : Instance
        The game the profile claims to solve.
    name : str
        The document's name in messages (its file path, or ``"profile"``).

    Returns
    -------
    Profile
        With what the document says about its game (:class:`Stated`) and every defect.

    Raises
    ------
    ProfileError
        Only when ``doc`` is not a JSON object tagged with a format of the instance's game
        (``dpp-ngoal-profile/1``, or ``dpp-profile/1`` for two goals); the error holds the
        document's :class:`Stated` when it is an object.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> inst = triangle()
    >>> doc = {"format": "dpp-profile/1", "goals": {"primary": "g1", "secondary": "g2"},
    ...        "defender": {"rule": "progress", "goal": "g1"},
    ...        "attacker": {"primary": [{"path": ["s", "g1"], "probability": "4/7"},
    ...                                 {"path": ["s", "g2"], "probability": "3/7"}],
    ...                     "secondary": [{"path": ["s", "g2"], "probability": 1}]}}
    >>> p = profile_from_json(doc, inst)
    >>> p.wellformed, [str(w.probability) for w in p.primary], p.longest
    (True, ['4/7', '3/7'], 1)
    >>> bad = dict(doc, attacker={"primary": [{"path": ["s", "g1"], "probability": 0.5}],
    ...                           "secondary": [{"path": ["s", "g2"], "probability": 1}]})
    >>> [str(d) for d in profile_from_json(bad, inst).defects]
    ['attacker.primary: probabilities sum to 1/2, not 1']
    >>> from dppverify.game.examples import star3, star3_profile
    >>> p = profile_from_json(star3_profile(), star3())
    >>> p.format, p.wellformed, [w.walk for w in p.attacker[1]], p.defender.default
    ('dpp-ngoal-profile/1', True, [(0, 1, 3)], (Fraction(1, 1), Fraction(0, 1), Fraction(0, 1)))
    >>> bad = {**star3_profile(), "attacker": star3_profile()["attacker"][:2]}
    >>> [str(d) for d in profile_from_json(bad, star3()).defects]
    ['attacker: must be a list of 3 mixed strategies (one per goal), got 2']
    >>> profile_from_json(doc, star3(), name="p.json")
    Traceback (most recent call last):
    dppverify.errors.ProfileError: p.json: "format" must be "dpp-ngoal-profile/1" for an \
instance with more than two goals, got "dpp-profile/1"
    """
    fmt = _format_of(doc, instance, name)
    stated = stated_of(doc)
    if fmt == PER_GOAL_PROFILE_FORMAT:
        return _per_goal_profile(doc, instance, stated)
    return _two_goal_profile(doc, instance, stated)


def _format_of(doc: Any, instance: Instance, name: str) -> str:
    """The format to read ``doc`` as, or :class:`ProfileError` naming the one expected."""
    if isinstance(doc, Mapping) and doc.get("format") == PER_GOAL_PROFILE_FORMAT:
        return PER_GOAL_PROFILE_FORMAT
    fmt = PROFILE_FORMAT if instance.n_goals == 2 else PER_GOAL_PROFILE_FORMAT
    two = fmt == PROFILE_FORMAT
    if not isinstance(doc, Mapping):
        what = f"a {fmt} document" if two else "a profile"
        raise ProfileError(f"{name}: {what} must be a JSON object, got {type(doc).__name__}")
    tag = doc.get("format")
    if tag != fmt:
        why = "" if two else " for an instance with more than two goals"
        raise ProfileError(f"{name}: \"format\" must be \"{fmt}\"{why}, got "
                           f"{json.dumps(tag, default=str)}", stated_of(doc))
    return fmt


def _two_goal_profile(doc: Mapping[str, Any], instance: Instance, stated: Stated) -> Profile:
    """Resolve a ``dpp-profile/1`` document against the two-goal ``instance``."""
    tol = instance.numbers
    c = DefectCollector()
    primary_goal_index = _goals(doc, instance, c)
    defender = _defender(doc, instance, c, tol)
    walks: dict[int, tuple[StrategyWalk, ...]] = {}
    longest = 0
    attacker = doc.get("attacker")
    if not isinstance(attacker, Mapping):
        c.add("attacker", "missing, or not an object with \"primary\" and \"secondary\"")
        attacker = {}
    for role, key in ((1, "primary"), (2, "secondary")):
        walks[role], steps = _mixed(attacker.get(key), f"attacker.{key}", instance, c, tol)
        longest = max(longest, steps)
    pair = (walks[1], walks[2])
    return Profile(
        attacker=pair if primary_goal_index == 0 else pair[::-1],
        primary_goal_index=primary_goal_index, defender=defender,
        claimed_prior=_claimed_prior(doc, c),
        claimed_values=MappingProxyType(_claimed_values(doc, c)),
        claimed_phases=_claimed_phases(doc, c),
        longest=longest, defects=tuple(c.defects), stated=stated)


def _goal_node(raw: Any, instance: Instance) -> int | None:
    idx = lookup_node(instance.index, raw)
    return idx if idx is not None and instance.is_goal(idx) else None


def _goals(doc: Mapping[str, Any], instance: Instance, c: DefectCollector) -> int:
    default = instance.primary_goal_index
    goals = doc.get("goals")
    if not isinstance(goals, Mapping):
        c.add("goals", "missing, or not an object {\"primary\": g1, \"secondary\": g2}")
        return default
    p, s = _goal_node(goals.get("primary"), instance), _goal_node(goals.get("secondary"), instance)
    if p is None or s is None or p == s:
        c.add("goals", f"must name the instance's two goals, got primary "
                       f"{json.dumps(goals.get('primary'), default=str)}, secondary "
                       f"{json.dumps(goals.get('secondary'), default=str)}")
        return default
    slot = instance.goal_index(p)
    assert slot is not None
    if slot != default and not instance.tied:
        g1 = instance.nodes[instance.goals[default]]
        c.add("goals.primary", f"is {show_node(instance.nodes[p])}, but the instance's primary "
                               f"goal (prior {instance.prior[default]}) is {show_node(g1)}")
        return default
    return slot


def _defender(doc: Mapping[str, Any], instance: Instance, c: DefectCollector,
              tol: NumberMode) -> DefenderRule | None:
    d = doc.get("defender")
    if not isinstance(d, Mapping):
        c.add("defender", "missing, or not an object with a \"rule\"")
        return None
    goal = _goal_node(d.get("goal"), instance)
    if goal is None:
        c.add("defender.goal", f"must be one of the instance's goals, got "
                               f"{json.dumps(d.get('goal'), default=str)}")
        return None
    rule = d.get("rule")
    if rule == "progress":
        return ProgressRule(goal)
    if rule != "table":
        c.add("defender.rule", f"must be \"progress\" or \"table\", got "
                               f"{json.dumps(rule, default=str)}")
        return None
    n_before = len(c.defects)
    entries: dict[tuple[int, ...], Fraction] = {}
    raw_entries = d.get("entries", [])
    if not isinstance(raw_entries, list):
        c.add("defender.entries", "must be a list of {\"walk\": [...], \"probability\": p}")
        raw_entries = []
    for k, e in enumerate(raw_entries):
        where = f"defender.entries[{k}]"
        if not isinstance(e, Mapping):
            c.add(where, "must be an object {\"walk\": [...], \"probability\": p}")
            continue
        walk = validate_walk(instance, e.get("walk"), complete=False)
        if isinstance(walk, str):
            c.add(where, walk)
            continue
        prob = c.probability(e.get("probability"), f"{where}.probability")
        if prob is None:
            continue
        if walk in entries:
            c.add(where, "duplicate walk (listed twice)")
            continue
        entries[walk] = prob
    default: Fraction | ProgressRule | None = None
    if "default" in d:
        raw = d["default"]
        if raw == "progress":
            default = ProgressRule(goal)
        else:
            default = c.probability(raw, "defender.default")
    if len(c.defects) > n_before:
        return None
    return TableRule(goal=goal, entries=MappingProxyType(entries), default=default)


def _mixed(raw: Any, where: str, instance: Instance, c: DefectCollector,
           tol: NumberMode) -> tuple[tuple[StrategyWalk, ...], int]:
    if not isinstance(raw, list) or not raw:
        c.add(where, "missing, or not a non-empty list of {\"path\": [...], \"probability\": p}")
        return (), 0
    out: list[StrategyWalk] = []
    seen: dict[tuple[int, ...], int] = {}
    probs: list[Fraction] = []
    ok_sum = True
    longest = 0
    for k, e in enumerate(raw):
        w = f"{where}[{k}]"
        if not isinstance(e, Mapping):
            c.add(w, "must be an object {\"path\": [...], \"probability\": p}")
            ok_sum = False
            continue
        if isinstance(e.get("path"), list):
            longest = max(longest, len(e["path"]) - 1)
        prob = c.number(e.get("probability"), f"{w}.probability")
        if prob is None:
            ok_sum = False
        elif prob < 0:
            c.add(f"{w}.probability", f"is negative ({prob})")
            ok_sum = False
        else:
            probs.append(Fraction(prob))
        walk = validate_walk(instance, e.get("path"), complete=True)
        if isinstance(walk, str):
            c.add(w, walk)
            continue
        if walk in seen:
            c.add(w, f"duplicate walk: the same walk as {where}[{seen[walk]}]")
            continue
        seen[walk] = k
        label = e.get("label")
        if prob is not None and prob >= 0:
            out.append(StrategyWalk(walk, Fraction(prob),
                                    label if isinstance(label, str) else None))
    if ok_sum and c.bounded(probs, where) and not tol.equal(total := sum(probs, Fraction(0)), 1):
        c.add(where, f"probabilities sum to {show(total)}, not 1")
    return tuple(out), longest


def _claimed_prior(doc: Mapping[str, Any], c: DefectCollector) -> tuple[Fraction, Fraction] | None:
    raw = doc.get("prior")
    if raw is None:
        return None
    if not isinstance(raw, Mapping):
        c.add("prior", "must be an object {\"primary\": b1, \"secondary\": b2}")
        return None
    p = c.number(raw.get("primary"), "prior.primary")
    s = c.number(raw.get("secondary"), "prior.secondary")
    if p is None or s is None:
        return None
    return (Fraction(p), Fraction(s))


def _claimed_values(doc: Mapping[str, Any], c: DefectCollector) -> dict[str, Number]:
    raw = doc.get("value")
    if raw is None:
        return {}
    if not isinstance(raw, Mapping):
        c.add("value", "must be an object of numbers (U1, U2, U, U_bar, VoI)")
        return {}
    out: dict[str, Number] = {}
    for key in VALUE_KEYS:
        if key in raw and raw[key] is not None:
            x = _value_number(raw[key], f"value.{key}", c)
            if x is not None:
                out[key] = x
    return out


def _value_number(raw: Any, where: str, c: DefectCollector) -> Number | None:
    if isinstance(raw, float):  # a float-mode document written from Python
        return raw
    return c.number(raw, where)


def _claimed_phases(doc: Mapping[str, Any], c: DefectCollector) -> tuple[int, int, int] | None:
    raw = doc.get("phases")
    if raw is None:
        return None
    keys = ("t_I", "t_II", "T")
    if not isinstance(raw, Mapping) or not all(
            isinstance(raw.get(k), int) and not isinstance(raw.get(k), bool) for k in keys):
        c.add("phases", "must be an object of integers {\"t_I\", \"t_II\", \"T\"}")
        return None
    return (raw["t_I"], raw["t_II"], raw["T"])


def _per_goal_profile(doc: Mapping[str, Any], instance: Instance, stated: Stated) -> Profile:
    """Resolve a ``dpp-ngoal-profile/1`` document against ``instance``, recording defects."""
    n = instance.n_goals
    c = DefectCollector()
    goals = doc.get("goals")
    if goals is not None and not (isinstance(goals, list) and [
            lookup_node(instance.index, g) for g in goals] == list(instance.goals)):
        c.add("goals", "must list the instance's goals in the instance's order")
    raw_att = doc.get("attacker")
    types: list[tuple[StrategyWalk, ...]] = [() for _ in range(n)]
    longest = 0
    if not isinstance(raw_att, list) or len(raw_att) != n:
        got = len(raw_att) if isinstance(raw_att, list) else type(raw_att).__name__
        c.add("attacker", f"must be a list of {n} mixed strategies (one per goal), got {got}")
    else:
        for theta, mix in enumerate(raw_att):
            types[theta], steps = _nmixed(mix, f"attacker[{theta}]", instance, c)
            longest = max(longest, steps)
    raw_def = doc.get("defender")
    defender: ProfileDefender | None = None
    if isinstance(raw_def, Mapping) and raw_def.get("rule") == GUARANTEE_RULE:
        defender = parse_guarantee(raw_def, n, c)
    elif not isinstance(raw_def, Mapping) or raw_def.get("rule") != "table":
        c.add("defender", "must be {\"rule\": \"table\", \"entries\": [...], \"default\": [...]} "
                          "or {\"rule\": \"guarantee\", \"h\": [...]}")
    else:
        entries = _ntable(raw_def.get("entries", []), instance, c)
        default = (None if raw_def.get("default") is None
                   else _distribution(raw_def["default"], n, "defender.default", c))
        defender = GoalTable(MappingProxyType(entries), default)
    claimed: Number | None = None
    value = doc.get("value")
    if isinstance(value, Mapping) and value.get("U") is not None:
        claimed = c.number(value["U"], "value.U")
    return Profile(attacker=tuple(types), defender=defender, format=PER_GOAL_PROFILE_FORMAT,
                   claimed_values=MappingProxyType({} if claimed is None else {"U": claimed}),
                   longest=longest, defects=tuple(c.defects), stated=stated)


def _nmixed(mix: Any, where: str, instance: Instance, c: DefectCollector
            ) -> tuple[tuple[StrategyWalk, ...], int]:
    """One goal index's mixed strategy of an N-goal profile, and its longest listed walk."""
    if not isinstance(mix, list) or not mix:
        c.add(where, "must be a non-empty list of walks")
        return (), 0
    walks: list[StrategyWalk] = []
    listed: set[tuple[int, ...]] = set()
    longest = 0
    for j, entry in enumerate(mix):
        at = f"{where}[{j}]"
        if not isinstance(entry, Mapping) or "path" not in entry:
            c.add(at, "must be an object with \"path\" and \"probability\"")
            continue
        if isinstance(entry["path"], list):
            longest = max(longest, len(entry["path"]) - 1)
        walk = resolve_walk(instance, entry["path"], complete=True, subject="")
        prob = c.probability(entry.get("probability"), f"{at}.probability")
        if isinstance(walk, str):
            c.add(f"{at}.path", walk, sep=" ")
            continue
        if prob is None:
            continue
        if walk in listed:
            c.add(f"{at}.path", "the same walk is listed twice")
            continue
        listed.add(walk)
        label = entry.get("label")
        walks.append(StrategyWalk(walk, prob, None if label is None else str(label)))
    c.sums_to_one([w.probability for w in walks], where)
    return tuple(walks), longest


def _ntable(raw: Any, instance: Instance, c: DefectCollector
            ) -> dict[tuple[int, ...], tuple[Fraction, ...]]:
    """The N-goal Defender table's entries: walk -> goal distribution."""
    entries: dict[tuple[int, ...], tuple[Fraction, ...]] = {}
    for j, entry in enumerate(raw):
        at = f"defender.entries[{j}]"
        if not isinstance(entry, Mapping) or "walk" not in entry:
            c.add(at, "must be an object with \"walk\" and \"probabilities\"")
            continue
        walk = resolve_walk(instance, entry["walk"], complete=False, subject="")
        dist = _distribution(entry.get("probabilities"), instance.n_goals,
                             f"{at}.probabilities", c)
        if isinstance(walk, str):
            c.add(f"{at}.walk", walk, sep=" ")
        elif dist is not None:
            if walk in entries:
                c.add(f"{at}.walk", "the same walk is listed twice")
            entries[walk] = dist
    return entries


def _distribution(raw: Any, n: int, where: str, c: DefectCollector
                  ) -> tuple[Fraction, ...] | None:
    """A distribution over the ``n`` goals (probabilities summing to 1), or None."""
    if not isinstance(raw, list) or len(raw) != n:
        c.add(where, f"must be a list of {n} probabilities (one per goal)")
        return None
    qs = [c.probability(x, f"{where}[{i}]") for i, x in enumerate(raw)]
    out = tuple(q for q in qs if q is not None)
    if len(out) < len(qs):
        return None
    if not c.sums_to_one(out, where):
        return None
    return out
