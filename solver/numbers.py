"""The solver's numbers: one number mode per instance, and exact parsing and writing.

An instance is solved in one :class:`NumberMode`, decided once from its weights: exact
(:class:`ExactNumbers`: weights and distances are stored as integer numerators over one common
denominator, values are ``Fraction``, comparisons are exact) or float
(:class:`FloatNumbers`: octile grids; values are floats compared within an absolute tolerance
``abs_tol``). Code that builds or compares numbers asks the mode (``zero``, ``convert``,
``equal``, ``at_most``, ``is_zero``, ``ratio``) instead of testing for exactness itself.

At the edges, floats enter only through ``str`` (``Fraction("0.6") == 3/5``), never through
their binary value, so ``0.6`` in a JSON file means exactly 3/5.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass
from fractions import Fraction
from numbers import Rational
from typing import Any, ClassVar

import numpy as np

from dppio.limits import check_numeral, check_rational
from dppio.text import decimal
from solver.errors import InvalidInstanceError

Number = Fraction | float
"""An exact rational, or a float in float mode (e.g. octile weights)."""

DEFAULT_ABS_TOL = 1e-9
"""Absolute tolerance on distances in float mode (octile weights)."""


class NumberMode(ABC):
    """How one instance's numbers are stored, built and compared (exact or float).

    *Stored* values are what the solver's arrays hold (CSR weights, distance fields):
    integer numerators over ``denominator`` in exact mode, floats in float mode.
    :meth:`convert` turns one into its value (``Fraction`` or ``float``).
    """

    exact: ClassVar[bool]
    """True for exact rational arithmetic."""

    @property
    @abstractmethod
    def denominator(self) -> int:
        """Common denominator of the stored values (1 in float mode)."""

    @property
    @abstractmethod
    def abs_tol(self) -> float | None:
        """Absolute tolerance of the comparisons: None in exact mode."""

    @abstractmethod
    def zero(self) -> Number:
        """0 as a value of this mode."""

    @abstractmethod
    def one(self) -> Number:
        """1 as a value of this mode."""

    @abstractmethod
    def convert(self, stored: Any) -> Number:
        """The value of a stored weight or distance."""

    @abstractmethod
    def equal(self, a: Any, b: Any) -> bool:
        """``a == b`` (within ``abs_tol`` in float mode)."""

    @abstractmethod
    def at_most(self, a: Any, b: Any) -> bool:
        """``a <= b`` (within ``abs_tol`` in float mode)."""

    @abstractmethod
    def is_zero(self, values: np.ndarray) -> np.ndarray:
        """Elementwise ``values == 0`` (within ``abs_tol`` in float mode), vectorised."""

    @abstractmethod
    def ratio(self, num: Any, den: Any) -> Number:
        """``num / den`` of two stored values, a probability in [0, 1]: exact, or snapped
        to exactly 0 or 1 within ``abs_tol`` in float mode."""

    @abstractmethod
    def describe(self) -> str:
        """How the mode reads in a summary."""

    @abstractmethod
    def with_abs_tol(self, abs_tol: float) -> NumberMode:
        """This mode with another float tolerance (exact mode has none: itself)."""


_ZERO, _ONE = Fraction(0), Fraction(1)


@dataclass(frozen=True)
class ExactNumbers(NumberMode):
    """Exact mode: stored values are integer numerators over ``denominator``.

    Examples
    --------
    >>> mode = ExactNumbers(denominator=2)
    >>> mode.convert(3), mode.ratio(1, 2), mode.zero()
    (Fraction(3, 2), Fraction(1, 2), Fraction(0, 1))
    >>> mode.equal(0.1 + 0.2, 0.3), mode.abs_tol, mode.describe()
    (False, None, 'exact (rational)')
    """

    exact: ClassVar[bool] = True
    denominator: int = 1

    @property
    def abs_tol(self) -> None:
        return None

    def zero(self) -> Fraction:
        return Fraction(0)

    def one(self) -> Fraction:
        return Fraction(1)

    def convert(self, stored: Any) -> Fraction:
        return Fraction(int(stored), self.denominator)

    def equal(self, a: Any, b: Any) -> bool:
        return bool(a == b)

    def at_most(self, a: Any, b: Any) -> bool:
        return bool(a <= b)

    def is_zero(self, values: np.ndarray) -> np.ndarray:
        return np.asarray(values == 0)

    def ratio(self, num: Any, den: Any) -> Fraction:
        n, d = int(num), int(den)
        if n == 0:  # σ* is 0 or 1 on most steps of a unit grid: no gcd for those
            return _ZERO
        return _ONE if n == d else Fraction(n, d)

    def describe(self) -> str:
        return "exact (rational)"

    def with_abs_tol(self, abs_tol: float) -> ExactNumbers:
        return self


@dataclass(frozen=True)
class FloatNumbers(NumberMode):
    """Float mode: stored values are floats; values within ``abs_tol`` count as equal.

    Examples
    --------
    >>> mode = FloatNumbers(abs_tol=1e-9)
    >>> mode.equal(0.1 + 0.2, 0.3), mode.at_most(0.3, 0.1 + 0.2), mode.ratio(1.0, 2.0)
    (True, True, 0.5)
    >>> mode.ratio(1e-12, 1.0), mode.ratio(1.0 - 1e-12, 1.0), mode.describe()
    (0.0, 1.0, 'float, absolute tolerance 1e-09')
    """

    exact: ClassVar[bool] = False
    abs_tol: float = DEFAULT_ABS_TOL

    @property
    def denominator(self) -> int:
        return 1

    def zero(self) -> float:
        return 0.0

    def one(self) -> float:
        return 1.0

    def convert(self, stored: Any) -> float:
        return float(stored)

    def equal(self, a: Any, b: Any) -> bool:
        return bool(abs(a - b) <= self.abs_tol)

    def at_most(self, a: Any, b: Any) -> bool:
        return bool(a <= b + self.abs_tol)

    def is_zero(self, values: np.ndarray) -> np.ndarray:
        return np.asarray(np.abs(values) <= self.abs_tol)

    def ratio(self, num: Any, den: Any) -> float:
        if self.at_most(num, 0.0):
            return 0.0
        if self.equal(num, den):
            return 1.0
        return float(num) / float(den)

    def describe(self) -> str:
        return f"float, absolute tolerance {self.abs_tol:g}"

    def with_abs_tol(self, abs_tol: float) -> FloatNumbers:
        return FloatNumbers(abs_tol)


def parse_number(value: object, *, where: str, allow_float: bool = False) -> Number:
    """Parse an exact number from JSON-like input.

    Parameters
    ----------
    value : int, Fraction, str, float
        ``3``, ``"3/5"``, ``"0.25"``; a ``float`` is read through ``str`` (exact decimal)
        unless ``allow_float`` is set, in which case it is kept as a float.
    where : str
        Names the value in error messages (e.g. ``"weight of edge ('a', 'b')"``).
    allow_float : bool
        Keep Python floats as floats (float mode) instead of converting them.

    Returns
    -------
    Fraction or float

    Raises
    ------
    InvalidInstanceError
        If ``value`` is not a finite number.

    Examples
    --------
    >>> parse_number("3/5", where="prior")
    Fraction(3, 5)
    >>> parse_number(0.6, where="prior")
    Fraction(3, 5)
    """
    if isinstance(value, bool):
        raise InvalidInstanceError(f"{where}: expected a number, got {value!r}")
    if isinstance(value, Rational):
        exact = Fraction(int(value.numerator), int(value.denominator))
        check_rational(exact, where=where, error=InvalidInstanceError)
        return exact
    if isinstance(value, float):
        if not math.isfinite(value):
            raise InvalidInstanceError(f"{where}: expected a finite number, got {value!r}")
        exact = Fraction(repr(value))
        # the checker reads the literal exactly: the same limit
        check_rational(exact, where=where, error=InvalidInstanceError)
        return value if allow_float else exact
    if isinstance(value, str):
        check_numeral(value, where=where, error=InvalidInstanceError)
        try:
            exact = Fraction(value.strip())
        except (ValueError, ZeroDivisionError):
            raise InvalidInstanceError(f"{where}: {value!r} is not a number") from None
        check_rational(exact, where=where, error=InvalidInstanceError)
        return exact
    raise InvalidInstanceError(f"{where}: expected a number, got {value!r}")


def format_number(value: Number) -> str | float:
    """Write a number for JSON: exact values as ``"p/q"`` strings, floats as floats.

    Examples
    --------
    >>> format_number(Fraction(12, 5)), format_number(Fraction(3)), format_number(0.5)
    ('12/5', '3', 0.5)
    """
    if isinstance(value, float):
        return value
    return str(Fraction(value))


def solve_exact(rows: list[list[Fraction]], rhs: list[Fraction]) -> list[Fraction] | None:
    """The unique solution of a square linear system in exact rationals (Gauss-Jordan), or
    None when the system is singular.

    Examples
    --------
    >>> from fractions import Fraction as F
    >>> solve_exact([[F(2), F(1)], [F(1), F(3)]], [F(3), F(5)])
    [Fraction(4, 5), Fraction(7, 5)]
    >>> solve_exact([[F(1), F(1)], [F(2), F(2)]], [F(1), F(2)]) is None
    True
    """
    n = len(rows)
    mat = [[*row, r] for row, r in zip(rows, rhs, strict=True)]
    for c in range(n):
        p = next((r for r in range(c, n) if mat[r][c] != 0), None)
        if p is None:
            return None
        mat[c], mat[p] = mat[p], mat[c]
        pivot(mat, c, c)
    return [mat[i][n] for i in range(n)]


def pivot(rows: list[list[Fraction]], i: int, j: int) -> None:
    """One exact pivot step in place: divide row ``i`` by ``rows[i][j]`` (non-zero), then
    clear column ``j`` from every other row (Gauss-Jordan elimination, simplex tableaus).

    Examples
    --------
    >>> rows = [[Fraction(2), Fraction(4)], [Fraction(1), Fraction(3)]]
    >>> pivot(rows, 0, 0)
    >>> [[str(x) for x in row] for row in rows]
    [['1', '2'], ['0', '1']]
    """
    piv = rows[i][j]
    rows[i] = [x / piv for x in rows[i]]
    for k, row in enumerate(rows):
        if k != i and row[j]:
            f = row[j]
            rows[k] = [x - f * y for x, y in zip(row, rows[i], strict=True)]


def format_value(x: Number) -> str:
    """A value as the text outputs write it: ``p/q (≈ decimal)``, an integer bare.

    The same style as the checker's reports (``dppverify.text.show_value``); a fraction longer
    than 40 characters is shown by its decimal only (``--json`` has the exact form).

    Parameters
    ----------
    x : Fraction, int or float
        The value (a float is float mode: dppio.text.decimal, no fraction).

    Returns
    -------
    str

    Examples
    --------
    >>> from fractions import Fraction
    >>> format_value(Fraction(12, 7)), format_value(Fraction(4)), format_value(2 ** 0.5)
    ('12/7 (≈ 1.714)', '4', '1.414')
    >>> format_value(Fraction(10**50 + 1, 10**50))
    '≈ 1 (exact: a 102-digit fraction, see --json)'
    """
    if isinstance(x, float):
        return decimal(x)
    if x.denominator == 1:
        return str(x)
    text = str(x)
    if len(text) > 40:
        return f"≈ {decimal(x)} (exact: a {len(text) - 1}-digit fraction, see --json)"
    return f"{text} (≈ {decimal(x)})"
