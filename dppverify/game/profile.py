"""Read a ``dpp-profile/1`` strategy profile leniently (``docs/formats.md`` §2).

Only a document that is not JSON, not a JSON object, or not tagged ``dpp-profile/1`` raises
:class:`ProfileError`. Everything else wrong with a profile — probabilities that are negative
or do not sum to 1, a step that is not an edge, a path that does not start at ``s0``, does not
end at a goal or continues past its first goal, unknown nodes, duplicate walks, goals that do
not match the instance — is recorded as a :class:`Defect`: the checker then *refutes* the
profile (check ``profile.wellformed``) instead of crashing.

Defender rules (``defender``):

- ``{"rule": "progress", "goal": g}``: the paper's σ* (eq. (7)) measuring progress towards
  goal ``g`` and allocating to ``g`` with probability new-progress / step weight.
- ``{"rule": "table", "goal": g, "entries": [{"walk": [s0, …, s_t], "probability": p}, …],
  "default": q}``: after observing the walk ``s0 … s_t`` (``t >= 1``) allocate to ``g`` with
  probability ``p``. Unlisted walks use ``default``: a probability, or ``"progress"`` meaning
  the progress rule towards the same goal ``g``. Without ``default`` every walk the game
  can reach must be listed.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from types import MappingProxyType
from typing import Any

from dppverify.errors import ProfileError
from dppverify.exact import Number
from dppverify.formats.json_reading import (
    JsonReadError,
    lookup_node,
    parse_number,
    parse_probability,
    read_json_file,
    resolve_walk,
    show_node,
)
from dppverify.game.instance import Instance
from dppverify.numbers import EXACT, NumberMode

__all__ = ["PROFILE_FORMAT", "Defect", "DefenderRule", "Profile", "ProgressRule", "StrategyPath",
           "TableRule", "load_profile_document", "profile_from_json", "validate_walk"]

PROFILE_FORMAT = "dpp-profile/1"
VALUE_KEYS = ("U1", "U2", "U", "U_bar", "VoI")


@dataclass(frozen=True)
class Defect:
    """One thing wrong with a profile: where (a JSON path) and what."""

    where: str
    message: str

    def __str__(self) -> str:
        return f"{self.where}: {self.message}"


@dataclass(frozen=True)
class ProgressRule:
    """σ* of eq. (7) measuring progress towards ``goal`` (a node index); allocates to ``goal``."""

    goal: int


@dataclass(frozen=True)
class TableRule:
    """An explicit behavioural Defender strategy: ``P(allocate to goal | walk)``.

    ``entries`` maps walks (node-index tuples with at least one step) to probabilities;
    ``default`` is used for unlisted walks: a probability, a :class:`ProgressRule`, or None
    (unlisted walks are then undefined).
    """

    goal: int
    entries: Mapping[tuple[int, ...], Fraction]
    default: Fraction | ProgressRule | None


DefenderRule = ProgressRule | TableRule


@dataclass(frozen=True)
class StrategyPath:
    """One walk of a type's mixed strategy (Γ_mix) with its probability."""

    walk: tuple[int, ...]
    probability: Fraction
    label: str | None = None


@dataclass(frozen=True)
class Profile:
    """A strategy profile resolved against an instance (node indices), with its defects.

    Attributes
    ----------
    primary_slot : int
        Document position (in the instance's ``goals``) of the goal the profile calls
        primary. Falls back to the instance's primary goal when the profile's is unusable.
    defender : DefenderRule or None
        None when the ``defender`` section is unusable (then a defect says why).
    primary, secondary : tuple of StrategyPath
        The valid walks of each type's mixed strategy (invalid entries are dropped and
        recorded as defects).
    claimed_prior : tuple or None
        ``prior`` (primary, secondary) as the profile states it.
    claimed_values : Mapping
        The profile's ``value`` numbers (``U1``, ``U2``, ``U``, ``U_bar``, ``VoI``).
    claimed_phases : tuple or None
        ``(t_I, t_II, T)`` as the profile states them.
    declared_exact, declared_tolerance
        The profile's ``exact`` / ``tolerance`` (informative only, never trusted).
    longest : int
        Steps of the longest listed attacker path (valid or not).
    defects : tuple of Defect
        Everything that makes the profile ill-formed.
    """

    primary_slot: int
    defender: DefenderRule | None
    primary: tuple[StrategyPath, ...]
    secondary: tuple[StrategyPath, ...]
    claimed_prior: tuple[Fraction, Fraction] | None = None
    claimed_values: Mapping[str, Number] = field(default_factory=dict)
    claimed_phases: tuple[int, int, int] | None = None
    declared_exact: bool | None = None
    declared_tolerance: float | None = None
    longest: int = 0
    defects: tuple[Defect, ...] = ()

    @property
    def wellformed(self) -> bool:
        """True when the profile has no defect."""
        return not self.defects

    def walks(self, theta: int) -> tuple[StrategyPath, ...]:
        """Mixed strategy of type ``theta`` (1 = primary, 2 = secondary)."""
        return self.primary if theta == 1 else self.secondary


def load_profile_document(source: str | Path | bytes) -> dict[str, Any]:
    """Read a profile file (path) or JSON text (bytes) and check its format tag.

    Raises
    ------
    ProfileError
        One line when the file cannot be read, is not JSON, is not an object, or is not
        tagged ``"format": "dpp-profile/1"``.

    Examples
    --------
    >>> load_profile_document(b'{"format": "dpp-profile/2"}')
    Traceback (most recent call last):
    dppverify.errors.ProfileError: profile: "format" must be "dpp-profile/1", got "dpp-profile/2"
    """
    name = "profile" if isinstance(source, bytes) else str(source)
    try:
        doc = read_json_file(source, kind="profile")
    except JsonReadError as exc:
        raise ProfileError(f"{name}: {exc}") from None
    check_format(doc, name)
    return dict(doc)


def check_format(doc: Any, name: str = "profile") -> None:
    """Raise :class:`ProfileError` unless ``doc`` is an object tagged ``dpp-profile/1``."""
    if not isinstance(doc, Mapping):
        raise ProfileError(f"{name}: a dpp-profile/1 document must be a JSON object, "
                           f"got {type(doc).__name__}")
    tag = doc.get("format")
    if tag != PROFILE_FORMAT:
        raise ProfileError(f"{name}: \"format\" must be \"{PROFILE_FORMAT}\", got "
                           f"{json.dumps(tag, default=str)}")


def validate_walk(instance: Instance, raw: Any, *, complete: bool) -> tuple[int, ...] | str:
    """Resolve a JSON walk to node indices, or say what is wrong with it.

    A walk starts at ``s0``, follows arcs of the graph, and stops at the FIRST goal it
    reaches (paper Sec. III-A). ``complete`` walks (attacker paths) must end at a goal;
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


class _Collector:
    """Accumulates defects while a profile is resolved."""

    def __init__(self) -> None:
        self.defects: list[Defect] = []

    def add(self, where: str, message: str) -> None:
        self.defects.append(Defect(where, message))

    def number(self, raw: Any, where: str) -> Number | None:
        try:
            return parse_number(raw, where=where)
        except ValueError as exc:
            self.add(where, str(exc).split(": ", 1)[-1])
            return None

    def probability(self, raw: Any, where: str) -> Fraction | None:
        try:
            return parse_probability(raw, where=where)
        except ValueError as exc:
            self.add(where, str(exc).split(": ", 1)[-1])
            return None


def profile_from_json(doc: Mapping[str, Any], instance: Instance,
                      tolerance: NumberMode | None = None) -> Profile:
    """Resolve a ``dpp-profile/1`` document against ``instance``, recording defects.

    Parameters
    ----------
    doc : Mapping
        The document (numbers as ``int``, ``Fraction``, ``"p/q"`` strings or floats).
    instance : Instance
        The game the profile claims to solve.
    tolerance : NumberMode, optional
        How the sum of a mixed strategy's probabilities is compared with 1: exactly (the
        default and always for exact instances) or within the float-mode tolerance.

    Raises
    ------
    ProfileError
        Only when ``doc`` is not an object tagged ``dpp-profile/1``.

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
    """
    check_format(doc)
    tol = tolerance or EXACT
    c = _Collector()
    primary_slot = _goals(doc, instance, c)
    defender = _defender(doc, instance, c, tol)
    walks: dict[int, tuple[StrategyPath, ...]] = {}
    longest = 0
    attacker = doc.get("attacker")
    if not isinstance(attacker, Mapping):
        c.add("attacker", "missing, or not an object with \"primary\" and \"secondary\"")
        attacker = {}
    for theta, key in ((1, "primary"), (2, "secondary")):
        walks[theta], steps = _mixed(attacker.get(key), f"attacker.{key}", instance, c, tol)
        longest = max(longest, steps)
    return Profile(
        primary_slot=primary_slot, defender=defender,
        primary=walks[1], secondary=walks[2],
        claimed_prior=_claimed_prior(doc, c),
        claimed_values=MappingProxyType(_claimed_values(doc, c)),
        claimed_phases=_claimed_phases(doc, c),
        declared_exact=doc.get("exact") if isinstance(doc.get("exact"), bool) else None,
        declared_tolerance=_declared_tolerance(doc),
        longest=longest, defects=tuple(c.defects))


def _goal_node(raw: Any, instance: Instance) -> int | None:
    idx = lookup_node(instance.index, raw)
    return idx if idx is not None and instance.is_goal(idx) else None


def _goals(doc: Mapping[str, Any], instance: Instance, c: _Collector) -> int:
    default = instance.primary_slot
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
    slot = instance.slot(p)
    assert slot is not None
    if slot != default and not instance.tied:
        g1 = instance.nodes[instance.goals[default]]
        c.add("goals.primary", f"is {show_node(instance.nodes[p])}, but the instance's primary "
                               f"goal (prior {instance.prior[default]}) is {show_node(g1)}")
        return default
    return slot


def _defender(doc: Mapping[str, Any], instance: Instance, c: _Collector,
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


def _mixed(raw: Any, where: str, instance: Instance, c: _Collector,
           tol: NumberMode) -> tuple[tuple[StrategyPath, ...], int]:
    if not isinstance(raw, list) or not raw:
        c.add(where, "missing, or not a non-empty list of {\"path\": [...], \"probability\": p}")
        return (), 0
    out: list[StrategyPath] = []
    seen: dict[tuple[int, ...], int] = {}
    total: Fraction = Fraction(0)
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
            total += Fraction(prob)
        walk = validate_walk(instance, e.get("path"), complete=True)
        if isinstance(walk, str):
            c.add(w, walk)
            continue
        if walk in seen:
            c.add(w, f"duplicate walk: the same path as {where}[{seen[walk]}]")
            continue
        seen[walk] = k
        label = e.get("label")
        if prob is not None and prob >= 0:
            out.append(StrategyPath(walk, Fraction(prob),
                                    label if isinstance(label, str) else None))
    if ok_sum and not tol.equal(total, 1):
        c.add(where, f"probabilities sum to {total}, not 1")
    return tuple(out), longest


def _claimed_prior(doc: Mapping[str, Any], c: _Collector) -> tuple[Fraction, Fraction] | None:
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


def _claimed_values(doc: Mapping[str, Any], c: _Collector) -> dict[str, Number]:
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


def _value_number(raw: Any, where: str, c: _Collector) -> Number | None:
    if isinstance(raw, float):  # a float-mode document written from Python
        return raw
    return c.number(raw, where)


def _claimed_phases(doc: Mapping[str, Any], c: _Collector) -> tuple[int, int, int] | None:
    raw = doc.get("phases")
    if raw is None:
        return None
    keys = ("t_I", "t_II", "T")
    if not isinstance(raw, Mapping) or not all(
            isinstance(raw.get(k), int) and not isinstance(raw.get(k), bool) for k in keys):
        c.add("phases", "must be an object of integers {\"t_I\", \"t_II\", \"T\"}")
        return None
    return (raw["t_I"], raw["t_II"], raw["T"])


def _declared_tolerance(doc: Mapping[str, Any]) -> float | None:
    raw = doc.get("tolerance")
    if isinstance(raw, int | float | Fraction) and not isinstance(raw, bool):
        return float(raw)
    return None
