"""How numbers are compared: exactly for rational instances, with a stated tolerance for floats."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

__all__ = ["DEFAULT_TOLERANCE", "Comparator"]

DEFAULT_TOLERANCE = 1e-9
"""Absolute tolerance on distances used in float mode (octile weights)."""


@dataclass(frozen=True)
class Comparator:
    """Equality and order on stored distances: exact (``tol = 0``) or within ``tol``.

    Exact mode compares integer numerators (or Fractions) with ``==``; float mode treats
    values within ``tol`` as equal. Phase boundaries and path ties are decided only
    through this object, so exact instances never meet a tolerance.

    Examples
    --------
    >>> Comparator(exact=False, tol=1e-9).eq(0.1 + 0.2, 0.3)
    True
    >>> Comparator(exact=True).eq(3, 3), Comparator(exact=True).eq(0.1 + 0.2, 0.3)
    (True, False)
    """

    exact: bool
    tol: float = 0.0

    def eq(self, a: Any, b: Any) -> bool:
        """``a == b`` (within ``tol`` in float mode)."""
        if self.exact:
            return bool(a == b)
        return bool(abs(a - b) <= self.tol)

    def le(self, a: Any, b: Any) -> bool:
        """``a <= b`` (within ``tol`` in float mode)."""
        if self.exact:
            return bool(a <= b)
        return bool(a <= b + self.tol)
