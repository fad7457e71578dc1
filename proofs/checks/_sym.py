"""Small sympy helpers shared by the symbolic proof checks (``proofs/checks/check_*.py``).

Inequalities are checked by writing every hypothesis ``a <= b`` as ``b = a + slack`` with a
nonnegative (or positive) sympy symbol ``slack``; the conclusion must then be an expression
sympy proves nonnegative (or positive) from the symbols' assumptions alone.
"""

from __future__ import annotations

import sympy as sp

__all__ = ["is_nonneg", "is_pos", "is_zero", "nonneg", "pos"]


def nonneg(names: str) -> tuple[sp.Symbol, ...]:
    """Nonnegative real symbols.

    Examples
    --------
    >>> a, b = nonneg("a b")
    >>> is_nonneg(a * b + a)
    True
    """
    return tuple(sp.symbols(names, nonnegative=True, real=True, seq=True))


def pos(names: str) -> tuple[sp.Symbol, ...]:
    """Positive real symbols."""
    return tuple(sp.symbols(names, positive=True, real=True, seq=True))


def is_nonneg(expr: sp.Expr) -> bool:
    """True when sympy proves ``expr >= 0`` (after simplification)."""
    return bool(sp.simplify(expr).is_nonnegative)


def is_pos(expr: sp.Expr) -> bool:
    """True when sympy proves ``expr > 0`` (after simplification)."""
    return bool(sp.simplify(expr).is_positive)


def is_zero(expr: sp.Expr) -> bool:
    """True when ``expr`` simplifies to 0."""
    return sp.simplify(expr) == 0
