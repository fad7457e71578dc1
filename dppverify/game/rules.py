"""The Defender rules a profile states, typed by their interface, not told apart by their type.

Every rule answers what the checks ask of it (:class:`ProfileDefender`; the two-goal rules
also :class:`DefenderRule`): its ``kind`` (the document's ``rule``), whether it lists walks
and is defined after every walk, the goal σ* measures progress towards where it follows σ*,
and the listed prefixes of one walk, found in one pass over a trie of its entries
(:class:`PrefixIndex`: the cost of a walk is linear in its length, whatever the rule). The
two-goal rules (``dpp-profile/1``) are :class:`ProgressRule` and :class:`TableRule`; the
per-goal ones (``dpp-ngoal-profile/1``) :class:`GoalTable` and :class:`GuaranteeRule`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from functools import cached_property
from types import MappingProxyType
from typing import Any, Generic, Protocol, TypeVar

GUARANTEE_RULE = "guarantee"
"""The ``rule`` of the N-goal guarantee Defender (:class:`GuaranteeRule`)."""


class ProfileDefender(Protocol):
    """What the checks ask of the Defender of a profile of either format, answered by the rule
    itself: a new rule answers these instead of being told apart by its type.

    ``kind``: the document's ``rule`` (``"progress"``, ``"table"``, ``"guarantee"``);
    ``table``: the rule lists walks (its missing walks are its ``default``'s);
    ``defined_everywhere``: the rule gives a distribution after every walk of the game (a
    table only with a ``default``); ``progress_goal``: the node index σ* of eq. (7) measures
    progress towards where the rule follows it (the progress rule, or a table's
    ``"progress"`` default), else None; ``entries``: the walks the rule lists (none but a
    table's); :meth:`listed_along`: the listed prefixes of one walk, in one pass over it.
    """

    @property
    def kind(self) -> str: ...

    @property
    def table(self) -> bool: ...

    @property
    def defined_everywhere(self) -> bool: ...

    @property
    def progress_goal(self) -> int | None: ...

    @property
    def entries(self) -> Mapping[tuple[int, ...], Any]: ...

    def listed_along(self, walk: Sequence[int]) -> Mapping[int, Any]:
        """``{t: the rule's entry for walk[:t+1]}`` for the listed prefixes (``t >= 1``)."""
        ...


class DefenderRule(ProfileDefender, Protocol):
    """A two-goal Defender rule (``dpp-profile/1``): after each walk it allocates to ``goal``
    (a node index) with a probability σ, the rest to the other goal; ``constant``: the
    probability of a table's numeric ``default`` (else None)."""

    @property
    def goal(self) -> int: ...

    @property
    def constant(self) -> Fraction | None: ...


_NO_ENTRIES: Mapping[tuple[int, ...], Fraction] = MappingProxyType({})
_NO_STEPS: Mapping[int, Any] = MappingProxyType({})

V = TypeVar("V")


class PrefixIndex(Generic[V]):
    """The walks a Defender table lists, as a trie: the listed prefixes of a walk are found in
    one pass over the walk, whatever its length (never a tuple per step).

    Examples
    --------
    >>> index = PrefixIndex({(0, 1): "a", (0, 1, 2, 3): "b"})
    >>> index.along((0, 1, 2, 3, 4)), index.along((0, 2, 1))
    ({1: 'a', 3: 'b'}, {})
    """

    def __init__(self, entries: Mapping[tuple[int, ...], V]) -> None:
        self._child: dict[tuple[int, int], int] = {}
        self._value: dict[int, V] = {}
        for walk, value in entries.items():
            p = 0
            for v in walk:
                q = self._child.get((p, v))
                if q is None:
                    q = self._child[(p, v)] = len(self._child) + 1
                p = q
            self._value[p] = value

    def along(self, walk: Sequence[int]) -> dict[int, V]:
        """``{t: value of walk[:t+1]}`` for every listed prefix of ``walk`` with ``t >= 1``."""
        out: dict[int, V] = {}
        p = 0
        for t, v in enumerate(walk):
            q = self._child.get((p, v))
            if q is None:
                break
            p = q
            if t and p in self._value:
                out[t] = self._value[p]
        return out


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
    kind = "progress"
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

    def listed_along(self, walk: Sequence[int]) -> Mapping[int, Fraction]:
        """No prefix is listed."""
        return _NO_STEPS


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
    kind = "table"
    table = True

    @cached_property
    def _index(self) -> PrefixIndex[Fraction]:
        return PrefixIndex(self.entries)

    def listed_along(self, walk: Sequence[int]) -> Mapping[int, Fraction]:
        """The listed prefixes of ``walk`` (:meth:`PrefixIndex.along`)."""
        return self._index.along(walk)

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


@dataclass(frozen=True)
class GoalTable:
    """An N-goal Defender table: after observing a walk, a distribution over the goals.

    ``entries`` maps walks (node-index tuples with at least one step) to distributions
    ``(q_0, …, q_{N-1})`` over the goal indices; ``default`` is used for unlisted walks (None:
    unlisted walks are undefined).
    """

    entries: Mapping[tuple[int, ...], tuple[Fraction, ...]]
    default: tuple[Fraction, ...] | None
    kind = "table"
    table = True
    progress_goal = None

    @cached_property
    def _index(self) -> PrefixIndex[tuple[Fraction, ...]]:
        return PrefixIndex(self.entries)

    def listed_along(self, walk: Sequence[int]) -> Mapping[int, tuple[Fraction, ...]]:
        """The listed prefixes of ``walk`` (:meth:`PrefixIndex.along`)."""
        return self._index.along(walk)

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
    kind = "guarantee"
    table = False
    defined_everywhere = True
    progress_goal = None

    @property
    def entries(self) -> Mapping[tuple[int, ...], tuple[Fraction, ...]]:
        """No walk is listed: the rule is defined everywhere."""
        return MappingProxyType({})

    def listed_along(self, walk: Sequence[int]) -> Mapping[int, tuple[Fraction, ...]]:
        """No prefix is listed."""
        return _NO_STEPS
