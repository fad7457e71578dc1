"""The strategy profile's types, its two JSON formats' tags and what their readers share.

Two documents describe a strategy profile (``docs/formats.md`` §2, §2b): ``dpp-profile/1``
(two goals: the paper's primary and secondary types, a Defender allocating to one goal) and
``dpp-ngoal-profile/1`` (``N >= 2`` goals: one mixed strategy per goal index, a Defender table
of goal distributions or the guarantee rule). Both are read into the one :class:`Profile`
(its ``format`` says which document it came from). Both list each type's mixed strategy as
:class:`StrategyWalk` s, record everything wrong as :class:`Defect` s
(:class:`DefectCollector`) and are loaded by :func:`load_profile_document`. The readers are
in :mod:`dppverify.game.profile`.
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from types import MappingProxyType
from typing import Any, Protocol, TypeVar

from dppio.text import plural
from dppverify.errors import ProfileError
from dppverify.exact import Number
from dppverify.formats.json_reading import (
    JsonReadError,
    parse_number,
    parse_probability,
    read_json_file,
)

__all__ = [
    "GUARANTEE_RULE",
    "MAX_NORMALS",
    "MAX_NORMAL_ENTRY",
    "NGOAL_PROFILE_FORMAT",
    "PROFILE_FORMAT",
    "VALUE_KEYS",
    "Defect",
    "DefectCollector",
    "DefenderInterface",
    "DefenderRule",
    "GoalTable",
    "GuaranteeRule",
    "Profile",
    "ProfileDefender",
    "ProgressRule",
    "StrategyWalk",
    "TableRule",
    "check_format",
    "load_profile_document",
    "parse_guarantee",
    "parse_normals",
]

PROFILE_FORMAT = "dpp-profile/1"
"""The two-goal profile's ``format`` tag."""
NGOAL_PROFILE_FORMAT = "dpp-ngoal-profile/1"
"""The N-goal profile's ``format`` tag."""
VALUE_KEYS = ("U1", "U2", "U", "U_bar", "VoI")
"""The ``value`` numbers a two-goal profile may claim."""
GUARANTEE_RULE = "guarantee"
"""The ``rule`` of the N-goal guarantee Defender (:class:`GuaranteeRule`)."""

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


class DefenderInterface(Protocol):
    """What the checks ask of any Defender rule, answered by the rule itself (a new rule
    answers these, instead of being told apart by its type in every module).

    ``table``: the rule lists walks (a table; its missing walks are its ``default``'s);
    ``defined_everywhere``: the rule gives a σ after every walk of the game (a table only with a
    ``default``); ``progress_goal``: the goal index σ* of eq. (7) measures progress towards where
    the rule follows it (the progress rule, or a table's ``"progress"`` default), else None;
    ``entries``: the walks the rule lists (none but a table's).
    """

    @property
    def table(self) -> bool: ...

    @property
    def defined_everywhere(self) -> bool: ...

    @property
    def progress_goal(self) -> int | None: ...

    @property
    def entries(self) -> Mapping[tuple[int, ...], Any]: ...


_NO_ENTRIES: Mapping[tuple[int, ...], Fraction] = MappingProxyType({})


@dataclass(frozen=True)
class ProgressRule:
    """σ* of eq. (7) measuring progress towards ``goal`` (a node index); allocates to ``goal``.

    Examples
    --------
    >>> rule = ProgressRule(1)
    >>> rule.table, rule.defined_everywhere, rule.progress_goal, dict(rule.entries), rule.constant
    (False, True, 1, {}, None)
    """

    goal: int
    table = False
    defined_everywhere = True

    @property
    def progress_goal(self) -> int:
        """σ*'s goal: this rule's."""
        return self.goal

    @property
    def entries(self) -> Mapping[tuple[int, ...], Fraction]:
        """No walk is listed: σ* everywhere."""
        return _NO_ENTRIES

    @property
    def constant(self) -> Fraction | None:
        """No constant probability off a table."""
        return None


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
    table = True

    @property
    def defined_everywhere(self) -> bool:
        """A σ after every walk: with a ``default`` only.

        Examples
        --------
        >>> TableRule(0, {}, None).defined_everywhere, TableRule(0, {}, Fraction(1, 2)).constant
        (False, Fraction(1, 2))
        >>> TableRule(0, {}, ProgressRule(2)).progress_goal
        2
        """
        return self.default is not None

    @property
    def progress_goal(self) -> int | None:
        """σ*'s goal when the ``default`` is ``"progress"``."""
        return self.default.goal if isinstance(self.default, ProgressRule) else None

    @property
    def constant(self) -> Fraction | None:
        """The ``default`` when it is a probability."""
        return None if isinstance(self.default, ProgressRule) else self.default


DefenderRule = ProgressRule | TableRule
"""A two-goal Defender rule (``dpp-profile/1``); :data:`ProfileDefender` holds any format's."""


@dataclass(frozen=True)
class StrategyWalk:
    """One walk of a type's mixed strategy (Γ_mix) with its probability (JSON: ``"path"``)."""

    walk: tuple[int, ...]
    probability: Fraction
    label: str | None = None


@dataclass(frozen=True)
class GoalTable:
    """An N-goal Defender table: after observing a walk, a distribution over the goals.

    ``entries`` maps walks (node-index tuples with at least one step) to distributions
    ``(q_0, …, q_{N-1})`` over the goal indices; ``default`` is used for unlisted walks (None:
    unlisted walks are undefined).
    """

    entries: Mapping[tuple[int, ...], tuple[Fraction, ...]]
    default: tuple[Fraction, ...] | None
    table = True
    progress_goal = None

    @property
    def defined_everywhere(self) -> bool:
        """A distribution after every walk: with a ``default`` only."""
        return self.default is not None


@dataclass(frozen=True)
class GuaranteeRule:
    """The N-goal guarantee rule: its starting state ``h`` and its extra facet normals.

    The Defender of :mod:`dppverify.structured.guarantee` (``{"rule": "guarantee", "h": [...],
    "normals": [...]}``); ``normals`` are the normals beyond the 0/1 vectors (always included).
    """

    h: tuple[Fraction, ...]
    normals: tuple[tuple[int, ...], ...] = ()
    table = False
    defined_everywhere = True
    progress_goal = None

    @property
    def entries(self) -> Mapping[tuple[int, ...], tuple[Fraction, ...]]:
        """No walk is listed: the rule is defined everywhere."""
        return MappingProxyType({})


ProfileDefender = ProgressRule | TableRule | GoalTable | GuaranteeRule
"""The Defender a profile states: a two-goal rule (``dpp-profile/1``), or an N-goal table or the
guarantee rule (``dpp-ngoal-profile/1``)."""


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
        The document's format tag (:data:`PROFILE_FORMAT` or :data:`NGOAL_PROFILE_FORMAT`).
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
    declared_exact, declared_tolerance
        The profile's ``exact`` / ``tolerance`` (informative only, never trusted).
    longest : int
        Steps of the longest listed attacker walk (valid or not).
    defects : tuple of Defect
        Everything that makes the profile ill-formed.

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
    declared_exact: bool | None = None
    declared_tolerance: float | None = None
    longest: int = 0
    defects: tuple[Defect, ...] = ()

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

    def walks(self, theta: int) -> tuple[StrategyWalk, ...]:
        """Two goals: mixed strategy of type ``theta`` (1 = primary, 2 = secondary)."""
        return self.primary if theta == 1 else self.secondary


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


def load_profile_document(source: str | Path | bytes, fmt: str = PROFILE_FORMAT
                          ) -> dict[str, Any]:
    """Read a profile file (path) or JSON text (bytes) and check its format tag ``fmt``.

    Raises
    ------
    ProfileError
        One line when the file cannot be read, is not JSON, is not an object, or is not
        tagged ``fmt`` (``dpp-profile/1`` or ``dpp-ngoal-profile/1``).

    Examples
    --------
    >>> load_profile_document(b'{"format": "dpp-profile/2"}')
    Traceback (most recent call last):
    dppverify.errors.ProfileError: profile: "format" must be "dpp-profile/1", got "dpp-profile/2"
    >>> load_profile_document(b'{"format": "dpp-profile/1"}', NGOAL_PROFILE_FORMAT)
    Traceback (most recent call last):
    dppverify.errors.ProfileError: profile: "format" must be "dpp-ngoal-profile/1" for an \
instance with more than two goals, got "dpp-profile/1"
    """
    name = "profile" if isinstance(source, bytes) else str(source)
    try:
        doc = read_json_file(source, kind="profile")
    except JsonReadError as exc:
        raise ProfileError(f"{name}: {exc}") from None
    check_format(doc, name, fmt)
    return dict(doc)


def check_format(doc: Any, name: str = "profile", fmt: str = PROFILE_FORMAT) -> None:
    """Raise :class:`ProfileError` unless ``doc`` is an object tagged ``fmt``.

    Examples
    --------
    >>> check_format({"format": "dpp-ngoal-profile/1"}, "p.json", NGOAL_PROFILE_FORMAT)
    >>> check_format([], "p.json")
    Traceback (most recent call last):
    dppverify.errors.ProfileError: p.json: a dpp-profile/1 document must be a JSON object, got list
    """
    two = fmt == PROFILE_FORMAT
    if not isinstance(doc, Mapping):
        what = f"a {fmt} document" if two else "a profile"
        raise ProfileError(f"{name}: {what} must be a JSON object, got {type(doc).__name__}")
    tag = doc.get("format")
    if tag != fmt:
        why = "" if two else " for an instance with more than two goals"
        raise ProfileError(f"{name}: \"format\" must be \"{fmt}\"{why}, got "
                           f"{json.dumps(tag, default=str)}")


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

    def _parsed(self, parse: Callable[..., T], raw: Any, where: str) -> T | None:
        try:
            return parse(raw, where=where)
        except ValueError as exc:  # "where: what" -> Defect(where, what)
            self.add(where, str(exc).split(": ", 1)[-1])
            return None

