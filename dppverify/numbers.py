"""The checker's number mode: exact or float, decided once per instance.

An instance is checked in one :class:`NumberMode`
(:attr:`dppverify.game.instance.Instance.numbers`):
exact (:class:`ExactNumbers`: ``int`` / ``Fraction`` values, comparisons with ``==`` and
``<=``, no tolerance ever applied) or float (:class:`FloatNumbers`: instances with
``"numbers": "float"``; values are floats, compared within a *relative* tolerance ``rel_tol``:
``a`` and ``b`` are equal when ``|a - b| <= rel_tol * max(1, |a|, |b|)``).

Code that builds or compares numbers asks the mode (``zero``, ``one``, ``convert``,
``product``, ``difference``, ``ratio``, ``equal``, ``at_most``, ``less_than``) instead of testing
for exactness itself. The method names are those of the solver's number mode where the meaning
is the same; the solver's tolerance is absolute (``abs_tol``), the checker's relative
(``rel_tol``). JSON number parsing stays in :mod:`dppverify.exact`.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass
from fractions import Fraction
from typing import ClassVar

from dppverify.exact import Number, normalize

DEFAULT_REL_TOL = 1e-9
"""Relative tolerance of float mode: ``|a - b| <= 1e-9 * max(1, |a|, |b|)``."""


class NumberMode(ABC):
    """How one instance's numbers are built and compared (exact or float)."""

    exact: ClassVar[bool]
    """True for exact rational arithmetic."""

    @property
    @abstractmethod
    def rel_tol(self) -> float | None:
        """Relative tolerance of the comparisons: None in exact mode."""

    def zero(self) -> Number:
        """0 as a value of this mode: ``convert(0)``."""
        return self.convert(0)

    def one(self) -> Number:
        """1 as a value of this mode: ``convert(1)``."""
        return self.convert(1)

    @abstractmethod
    def convert(self, x: Number) -> Number:
        """``x`` as a value of this mode (``int`` when integral, or ``float``)."""

    @abstractmethod
    def product(self, a: Number, b: Number) -> Number:
        """``a * b`` as a value of this mode."""

    @abstractmethod
    def difference(self, a: Number, b: Number) -> Number:
        """``a - b`` as a value of this mode."""

    @abstractmethod
    def ratio(self, num: Number, den: Number) -> Number:
        """``num / den``, a probability: exact, or clamped to [0, 1] in float mode."""

    @abstractmethod
    def equal(self, a: Number, b: Number) -> bool:
        """``a == b`` (within ``rel_tol`` in float mode)."""

    @abstractmethod
    def at_most(self, a: Number, b: Number) -> bool:
        """``a <= b`` (within ``rel_tol`` in float mode)."""

    def less_than(self, a: Number, b: Number) -> bool:
        """``a < b`` (by more than ``rel_tol`` in float mode): ``not at_most(b, a)``."""
        return not self.at_most(b, a)

    @abstractmethod
    def describe(self) -> str:
        """How the mode reads in a summary."""


@dataclass(frozen=True)
class ExactNumbers(NumberMode):
    """Exact mode: ``int`` / ``Fraction`` values, exact comparisons.

    Examples
    --------
    >>> mode = ExactNumbers()
    >>> mode.convert(Fraction(6, 3)), mode.ratio(3, 6), mode.product(Fraction(1, 2), 4)
    (2, Fraction(1, 2), 2)
    >>> mode.equal(Fraction(1, 3), Fraction(2, 6)), mode.equal(0.1 + 0.2, 0.3)
    (True, False)
    >>> mode.less_than(1, Fraction(3, 2)), mode.rel_tol, mode.describe()
    (True, None, 'exact (rational)')
    """

    exact: ClassVar[bool] = True

    @property
    def rel_tol(self) -> None:
        return None

    def convert(self, x: Number) -> Number:
        return normalize(x)

    def product(self, a: Number, b: Number) -> Number:
        return normalize(a * b)

    def difference(self, a: Number, b: Number) -> Number:
        return normalize(a - b)

    def ratio(self, num: Number, den: Number) -> Number:
        if isinstance(num, float) or isinstance(den, float):
            return float(num) / float(den)
        return normalize(Fraction(num) / Fraction(den))

    def equal(self, a: Number, b: Number) -> bool:
        return bool(a == b)

    def at_most(self, a: Number, b: Number) -> bool:
        return bool(a <= b)

    def describe(self) -> str:
        return "exact (rational)"


@dataclass(frozen=True)
class FloatNumbers(NumberMode):
    """Float mode: float values, equal within the relative tolerance ``rel_tol``.

    Examples
    --------
    >>> mode = FloatNumbers()
    >>> mode.equal(0.1 + 0.2, 0.3), mode.less_than(1.0, 1.0 + 1e-12), mode.at_most(1.0, 0.5)
    (True, False, False)
    >>> mode.convert(Fraction(1, 4)), mode.ratio(3.0, 2.0), mode.difference(1, 0.25)
    (0.25, 1.0, 0.75)
    >>> mode.rel_tol, mode.describe()
    (1e-09, 'float, relative tolerance 1e-09')
    """

    exact: ClassVar[bool] = False
    rel_tol: float = DEFAULT_REL_TOL

    def convert(self, x: Number) -> float:
        return float(x)

    def product(self, a: Number, b: Number) -> float:
        return float(a) * float(b)

    def difference(self, a: Number, b: Number) -> float:
        return float(a) - float(b)

    def ratio(self, num: Number, den: Number) -> float:
        return min(1.0, max(0.0, float(num) / float(den)))

    def _slack(self, a: Number, b: Number) -> float:
        return self.rel_tol * max(1.0, abs(float(a)), abs(float(b)))

    def equal(self, a: Number, b: Number) -> bool:
        return abs(float(a) - float(b)) <= self._slack(a, b)

    def at_most(self, a: Number, b: Number) -> bool:
        return float(a) <= float(b) + self._slack(a, b)

    def describe(self) -> str:
        return f"float, relative tolerance {self.rel_tol:g}"


EXACT = ExactNumbers()
"""The exact mode (the default of every comparison that is not told otherwise)."""

_FLOAT = FloatNumbers()


def number_mode(exact: bool) -> NumberMode:
    """The checker's mode for an instance that is exact (or not): ``ExactNumbers()`` or
    ``FloatNumbers(rel_tol=DEFAULT_REL_TOL)``.

    Examples
    --------
    >>> number_mode(True) is EXACT, number_mode(False).rel_tol
    (True, 1e-09)
    """
    return EXACT if exact else _FLOAT
