"""The strategy profile's types, its two JSON formats' tags and what their readers share.

Two documents describe a strategy profile (``docs/formats.md`` §2, §2b): ``dpp-profile/1``
(two goals: the paper's primary and secondary types, a Defender allocating to one goal) and
``dpp-ngoal-profile/1`` (``N >= 2`` goals: one mixed strategy per goal index, a Defender table
of goal distributions or the guarantee rule). Both are read into the one :class:`Profile`
(its ``format`` says which document it came from), with what the document says about its
game (:class:`Stated`). Both list each type's mixed strategy as :class:`StrategyWalk` s and
record everything wrong as :class:`Defect` s (:class:`DefectCollector`); the Defender rules
are :mod:`dppverify.game.rules`'. The readers are in :mod:`dppverify.game.profile`.
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any, TypeVar

from dppio.limits import MAX_DISTRIBUTION_DENOMINATOR_DIGITS, common_denominator
from dppio.text import plural, show
from dppverify.errors import ProfileError
from dppverify.exact import Number
from dppverify.formats.json_reading import parse_number, parse_probability
from dppverify.game.rules import GuaranteeRule, ProfileDefender

__all__ = ["MAX_NORMALS", "MAX_NORMAL_ENTRY", "PER_GOAL_PROFILE_FORMAT", "PROFILE_FORMAT",
           "SELECTION_PROFILE_FORMAT", "VALUE_KEYS", "Defect", "DefectCollector", "Profile",
           "Stated", "StrategyWalk", "parse_guarantee", "parse_normals", "stated_of"]

PROFILE_FORMAT = "dpp-profile/1"
"""The two-goal profile's ``format`` tag."""
PER_GOAL_PROFILE_FORMAT = "dpp-ngoal-profile/1"

SELECTION_PROFILE_FORMAT = "dpp-selection-profile/1"
"""The goal-selection profile format (``docs/formats.md`` §2d)."""
"""The per-goal profile's ``format`` tag (one mixed strategy per goal index, any N)."""
VALUE_KEYS = ("U1", "U2", "U", "U_bar", "VoI")
"""The ``value`` numbers a two-goal profile may claim."""

T = TypeVar("T")


@dataclass(frozen=True)
class Defect:
    """One thing wrong with a profile: where (a JSON path) and what.

    ``sep`` joins them in the one-line text (``": "``; the N-goal reader writes a walk's
    defect as ``attacker[0][1].path [2]: ...``, with a space).
    """

    where: str
    message: str
    sep: str = ": "

    def __str__(self) -> str:
        return f"{self.where}{self.sep}{self.message}"


@dataclass(frozen=True)
class StrategyWalk:
    """One walk of a type's mixed strategy (Γ_mix) with its probability (JSON: ``"path"``)."""

    walk: tuple[int, ...]
    probability: Fraction
    label: str | None = None


@dataclass(frozen=True)
class Stated:
    """What a profile document says about the game it was made for, read once with the
    document and without the instance: the JSON values as the document gives them.

    ``goals`` and ``prior`` as listed (a two-goal profile's ``primary`` then ``secondary``;
    None when absent or not a list or object); ``nodes``: every node id its walks visit, each
    once, first seen first; ``starts``: the first node of each walk, each once; ``u_bar``: its
    ``value.U_bar`` (None when not stated); ``rule``: its Defender's ``rule``.

    Examples
    --------
    >>> s = stated_of({"goals": ["a", "b"], "attacker": [[{"path": ["s", "m", "a"]}],
    ...                                                [{"path": ["s", [1, 2]]}]]})
    >>> s.goals, s.nodes, s.starts
    (('a', 'b'), ('s', 'm', 'a', [1, 2]), ('s',))
    """

    goals: tuple[Any, ...] | None = None
    prior: tuple[Any, ...] | None = None
    nodes: tuple[Any, ...] = ()
    starts: tuple[Any, ...] = ()
    u_bar: Any = None
    rule: Any = None


def stated_of(doc: Mapping[str, Any]) -> Stated:
    """What a profile document (either format) says about the game it was made for.

    Examples
    --------
    >>> from dppverify.game.examples import triangle_profile
    >>> s = stated_of(triangle_profile(value={"U_bar": "27/10"}))
    >>> s.goals, s.starts, s.u_bar, s.rule
    (('g1', 'g2'), ('s',), '27/10', 'progress')
    """
    goals, prior = doc.get("goals"), doc.get("prior")
    if isinstance(goals, Mapping):
        goals = [goals.get("primary"), goals.get("secondary")]
    if isinstance(prior, Mapping):
        prior = [prior.get("primary"), prior.get("secondary")]
    nodes: dict[Any, Any] = {}
    starts: dict[Any, Any] = {}
    for walk in _listed_walks(doc):
        for k, raw in enumerate(walk):
            key = _key(raw)
            nodes.setdefault(key, raw)
            if k == 0:
                starts.setdefault(key, raw)
    value, defender = doc.get("value"), doc.get("defender")
    return Stated(goals=tuple(goals) if isinstance(goals, list) and goals else None,
                  prior=tuple(prior) if isinstance(prior, list) else None,
                  nodes=tuple(nodes.values()), starts=tuple(starts.values()),
                  u_bar=value.get("U_bar") if isinstance(value, Mapping) else None,
                  rule=defender.get("rule") if isinstance(defender, Mapping) else None)


def _listed_walks(doc: Mapping[str, Any]) -> Iterator[list[Any]]:
    """Every walk (a ``path`` list) under ``attacker``, either format; malformed ones skipped."""
    attacker = doc.get("attacker")
    groups: list[Any] = []
    if isinstance(attacker, Mapping):
        groups = [attacker.get("primary"), attacker.get("secondary")]
    elif isinstance(attacker, list):
        groups = attacker
    for group in groups:
        if isinstance(group, list):
            for entry in group:
                if isinstance(entry, Mapping) and isinstance(entry.get("path"), list):
                    yield entry["path"]


def _key(raw: Any) -> Any:
    """A hashable key of a JSON node id (equal ids, equal keys)."""
    kind = type(raw)
    if kind is str or kind is int:
        return (kind, raw)
    if kind is list:  # a grid cell [r, c]
        return (list, tuple(_key(x) for x in raw))
    return json.dumps(raw, sort_keys=True, default=str)


@dataclass(frozen=True)
class Profile:
    """A strategy profile of either format resolved against an instance, with its defects.

    One type for both documents (``format`` says which it came from): ``attacker`` holds the
    mixed strategies by goal index for any N and ``defender`` the Defender. The two-goal
    views (:attr:`primary`, :attr:`secondary`, :meth:`walks`, ``primary_goal_index``,
    ``claimed_prior``, ``claimed_phases``) are meaningful for ``dpp-profile/1`` only.

    Attributes
    ----------
    attacker : tuple
        ``attacker[θ]``: the valid walks of the mixed strategy of goal index θ (walking to the
        instance's ``goals[θ]``; invalid entries are dropped and recorded as defects).
    defender : ProfileDefender or None
        ``dpp-profile/1``: a :class:`ProgressRule` or :class:`TableRule`;
        ``dpp-ngoal-profile/1``: a :class:`GoalTable` or the :class:`GuaranteeRule`. None when
        the ``defender`` section is unusable (then a defect says why).
    format : str
        The document's format tag (:data:`PROFILE_FORMAT` or :data:`PER_GOAL_PROFILE_FORMAT`).
    primary_goal_index : int
        ``dpp-profile/1``: goal index of the goal the profile calls primary. Falls back to the
        instance's primary goal when the profile's is unusable.
    claimed_values : Mapping
        The profile's ``value`` numbers (``U1``, ``U2``, ``U``, ``U_bar``, ``VoI``; only ``U``
        for ``dpp-ngoal-profile/1``).
    claimed_prior : tuple or None
        ``prior`` (primary, secondary) as the profile states it.
    claimed_phases : tuple or None
        ``(t_I, t_II, T)`` as the profile states them.
    longest : int
        Steps of the longest listed attacker walk (valid or not).
    defects : tuple of Defect
        Everything that makes the profile ill-formed.
    stated : Stated
        What the document says about the game it was made for (its goals, prior, start and
        node ids), for a note when a profile looks made for another instance.
    choice : tuple of Fraction or None
        A goal-selection profile (``dpp-selection-profile/1``): the Attacker's choice ``q`` of
        its goal (None elsewhere, or when the document's is unusable: a defect says why).

    Examples
    --------
    >>> w = StrategyWalk((0, 1), Fraction(1))
    >>> p = Profile(attacker=((), (w,)), primary_goal_index=1)
    >>> p.primary == (w,), p.secondary, p.walks(2), p.wellformed
    (True, (), (), True)
    """

    attacker: tuple[tuple[StrategyWalk, ...], ...]
    defender: ProfileDefender | None = None
    format: str = PROFILE_FORMAT
    primary_goal_index: int = 0
    claimed_values: Mapping[str, Number] = field(default_factory=dict)
    claimed_prior: tuple[Fraction, Fraction] | None = None
    claimed_phases: tuple[int, int, int] | None = None
    longest: int = 0
    defects: tuple[Defect, ...] = ()
    stated: Stated = field(default_factory=Stated)
    choice: tuple[Fraction, ...] | None = None

    @property
    def wellformed(self) -> bool:
        """True when the profile has no defect."""
        return not self.defects

    @property
    def claimed_u(self) -> Number | None:
        """The profile's ``value.U`` (informative), or None."""
        return self.claimed_values.get("U")

    @property
    def primary(self) -> tuple[StrategyWalk, ...]:
        """Two goals: the primary type's mixed strategy."""
        return self.attacker[self.primary_goal_index]

    @property
    def secondary(self) -> tuple[StrategyWalk, ...]:
        """Two goals: the secondary type's mixed strategy."""
        return self.attacker[1 - self.primary_goal_index]

    def walks(self, role: int) -> tuple[StrategyWalk, ...]:
        """Two goals: the mixed strategy of the type of ``role`` (1 = primary, 2 = secondary)."""
        return self.primary if role == 1 else self.secondary


MAX_NORMALS = 64
"""At most this many extra facet normals in a guarantee rule (``defender.normals``)."""
MAX_NORMAL_ENTRY = 16
"""The largest entry of an extra facet normal."""


def parse_normals(raw: Any, n: int) -> tuple[tuple[int, ...], ...]:
    """Read ``defender.normals``: extra facet normals of the guarantee rule (``docs/formats.md``
    §2b), each N non-negative integers (at most :data:`MAX_NORMAL_ENTRY`), not a 0/1 vector,
    gcd 1, no duplicates; at most :data:`MAX_NORMALS` of them.

    Raises
    ------
    ProfileError
        One line naming the first malformed entry (``dpp certify`` exits 2).

    Examples
    --------
    >>> parse_normals([[2, 2, 2, 1], [1, 2, 2, 2]], 4)
    ((2, 2, 2, 1), (1, 2, 2, 2))
    >>> parse_normals([[2, 2, 2, 2]], 4)
    Traceback (most recent call last):
    dppverify.errors.ProfileError: defender.normals[0]: the entries' gcd must be 1, got 2
    """
    where = "defender.normals"
    if not isinstance(raw, list):
        raise ProfileError(f"{where}: must be a list of facet normals (lists of {n} integers)")
    if len(raw) > MAX_NORMALS:
        raise ProfileError(f"{where}: at most {MAX_NORMALS} extra normals, got {len(raw)}")
    out: list[tuple[int, ...]] = []
    for i, a in enumerate(raw):
        at = f"{where}[{i}]"
        if not isinstance(a, list) or len(a) != n:
            raise ProfileError(f"{at}: must be a list of {n} integers (one per goal)")
        if not all(isinstance(x, int) and not isinstance(x, bool) for x in a):
            raise ProfileError(f"{at}: entries must be JSON integers")
        if any(x < 0 or x > MAX_NORMAL_ENTRY for x in a):
            raise ProfileError(f"{at}: entries must lie in 0..{MAX_NORMAL_ENTRY}")
        if all(x in (0, 1) for x in a):
            raise ProfileError(f"{at}: a 0/1 vector (the 0/1 normals are always included; "
                               f"list only the others)")
        g = math.gcd(*a)
        if g != 1:
            raise ProfileError(f"{at}: the entries' gcd must be 1, got {g}")
        t = tuple(a)
        if t in out:
            raise ProfileError(f"{at}: duplicates {where}[{out.index(t)}]")
        out.append(t)
    return tuple(out)


def parse_guarantee(raw: Mapping[str, Any], n: int, c: DefectCollector
                    ) -> GuaranteeRule | None:
    """Read ``{"rule": "guarantee", "h": [...], "normals": [...]}``, recording defects (None
    when ill-formed); malformed ``normals`` raise (:func:`parse_normals`).

    Examples
    --------
    >>> parse_guarantee({"rule": "guarantee", "h": ["1/2", 1, "3"]}, 3, DefectCollector()).h
    (Fraction(1, 2), Fraction(1, 1), Fraction(3, 1))
    >>> c = DefectCollector(); parse_guarantee({"rule": "guarantee", "h": [1]}, 3, c)
    >>> [str(d) for d in c.defects]
    ['defender.h: must be a list of 3 numbers (one per goal)']
    """
    h = raw.get("h")
    normals = parse_normals(raw.get("normals", []), n)
    extra = sorted(set(raw) - {"rule", "h", "normals"})
    if extra:
        c.add("defender", f"unknown {plural(len(extra), 'key')} {', '.join(extra)} for the "
                          "guarantee rule")
        return None
    if not isinstance(h, list) or len(h) != n:
        c.add("defender.h", f"must be a list of {n} numbers (one per goal)")
        return None
    out = []
    for i, x in enumerate(h):
        y = c.number(x, f"defender.h[{i}]")
        if y is None:
            return None
        out.append(Fraction(y))
    return GuaranteeRule(tuple(out), normals)


class DefectCollector:
    """Accumulates the defects of a profile while it is resolved (both formats).

    Examples
    --------
    >>> c = DefectCollector()
    >>> c.probability("3/2", "attacker[0][0].probability"), c.number("1/4", "value.U")
    (None, Fraction(1, 4))
    >>> [str(d) for d in c.defects]
    ['attacker[0][0].probability: probability 3/2 is outside [0, 1]']
    """

    def __init__(self) -> None:
        self.defects: list[Defect] = []

    def add(self, where: str, message: str, sep: str = ": ") -> None:
        """Record that ``where`` has the defect ``message``."""
        self.defects.append(Defect(where, message, sep))

    def number(self, raw: Any, where: str) -> Number | None:
        """``raw`` as an exact number, or None with a defect."""
        return self._parsed(parse_number, raw, where)

    def probability(self, raw: Any, where: str) -> Fraction | None:
        """``raw`` as a probability in [0, 1], or None with a defect."""
        return self._parsed(parse_probability, raw, where)

    def bounded(self, values: Sequence[Fraction], where: str) -> bool:
        """Whether the common denominator of ``values`` is within the distribution limit
        (``dppio.limits``), else False with a defect."""
        try:
            common_denominator((Fraction(x).denominator for x in values), where=where,
                               digits=MAX_DISTRIBUTION_DENOMINATOR_DIGITS, error=ValueError)
        except ValueError as exc:
            self.add(where, str(exc).split(": ", 1)[-1])
            return False
        return True

    def sums_to_one(self, values: Sequence[Fraction], where: str) -> bool:
        """Whether the probabilities ``values`` sum to exactly 1, else False with a defect;
        their common denominator is bounded first (``dppio.limits``), so the sum of many
        entries is never a number of millions of digits.

        Examples
        --------
        >>> c = DefectCollector()
        >>> c.sums_to_one([Fraction(1, 2)] * 2, "a"), c.sums_to_one([Fraction(1, 3)], "b")
        (True, False)
        >>> [str(d) for d in c.defects]
        ['b: probabilities sum to 1/3, not 1']
        """
        if not self.bounded(values, where):
            return False
        total = sum(values, Fraction(0))
        if total != 1:
            self.add(where, f"probabilities sum to {show(total)}, not 1")
        return total == 1

    def _parsed(self, parse: Callable[..., T], raw: Any, where: str) -> T | None:
        try:
            return parse(raw, where=where)
        except ValueError as exc:  # "where: what" -> Defect(where, what)
            self.add(where, str(exc).split(": ", 1)[-1])
            return None

