"""Whether a point lies in ``F_u + wΔ^N``: one small exact LP and the certificate it leaves.

For ``F_u = { r : a·r <= m_a(u), a ∈ A }`` (non-negative integer normals) and a point ``r``,
Farkas' lemma gives (``proofs/NRULE.md`` NR.2)

    r ∈ F_u + wΔ^N   iff   φ = max { λ·b : λ >= 0, Σ_a λ_a a <= 1 } <= w,
    b_a = a·r - m_a(u),

and LP duality ``φ = min { 1·s : s >= 0, a·s >= b_a ∀ a }``. :func:`sum_membership` solves the
maximum by the primal simplex method in exact rationals (``N`` rows, Bland's rule, from the
slack basis ``λ = 0``, which is feasible) and returns the verdict with its certificate, checked
by plain arithmetic before it is returned:

- *inside*: the dual ``s`` (``s >= 0``, ``a·s >= b_a`` for every ``a``, ``1·s <= w``), so
  ``r - s ∈ F_u`` with ``s ∈ (1·s)Δ^N ⊆ wΔ^N`` up to the down-closure;
- *outside*: the optimal vertex ``λ`` of the packing polytope (``Σ_a λ_a a <= 1``,
  ``λ·b > w``); ``y = Σ_a λ_a a`` is a direction in which ``h_{F_v}(y) >= y·r > w + λ·m(u)``
  for every set ``F_v`` containing ``r``.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction

from dppverify.structured.cover import Normal


@dataclass(frozen=True)
class Membership:
    """The verdict of :func:`sum_membership` and its certificate.

    Attributes
    ----------
    inside : bool
        ``φ <= w``.
    value : Fraction
        ``φ``, the least ``1·s`` (0 when every ``b_a <= 0``).
    s : tuple of Fraction
        An optimal dual: ``s >= 0`` with ``a·s >= b_a`` for every normal.
    lam : tuple of tuple of (int, Fraction)
        An optimal vertex ``λ`` of ``{λ >= 0 : Σ_a λ_a a <= 1}`` as ``(normal index, λ_a > 0)``.
    """

    inside: bool
    value: Fraction
    s: tuple[Fraction, ...]
    lam: tuple[tuple[int, Fraction], ...]

    def direction(self, normals: Sequence[Normal]) -> tuple[Fraction, ...]:
        """``y_λ = Σ_a λ_a a`` (its largest entry is 1 unless ``λ = 0``)."""
        n = len(normals[0])
        return tuple(sum((c * normals[j][i] for j, c in self.lam), Fraction(0))
                     for i in range(n))


def sum_membership(normals: Sequence[Normal], b: Sequence[int | Fraction],
                   w: int | Fraction) -> Membership:
    """``max { λ·b : λ >= 0, Σ_a λ_a a <= 1 }`` against ``w``, exactly, with its certificate.

    Parameters
    ----------
    normals : sequence of Normal
        ``A``: non-negative integer vectors of one length ``N``.
    b : sequence
        ``b_a = a·r - m_a(u)`` per normal (any common positive scale, with ``w`` at it too).
    w : int or Fraction
        The arc's weight (at that scale).

    Examples
    --------
    The point ``r = (2, 2)`` against ``F_u = {r_1, r_2 <= 1, r_1 + r_2 <= 1}`` and ``w = 2``:
    ``b = (1, 1, 3)``, the pair's row gives ``φ = 3 > 2`` (``s`` would have to be
    ``(s_1, s_2)`` with ``s_1 + s_2 >= 3``):

    >>> zo = [(1, 0), (0, 1), (1, 1)]
    >>> out = sum_membership(zo, [1, 1, 3], 2)
    >>> out.inside, out.value, [str(x) for x in out.direction(zo)]
    (False, Fraction(3, 1), ['1', '1'])
    >>> sum_membership(zo, [1, 1, 3], 3).inside
    True
    """
    n = len(normals[0])
    cols = [j for j, x in enumerate(b) if x > 0]  # a column with b_a <= 0 never enters
    wf = Fraction(w)
    if not cols:
        return _checked(normals, b, wf, Membership(True, Fraction(0), (Fraction(0),) * n, ()))
    k = len(cols)
    # tableau: rows θ, columns λ_{cols}, then the slacks; basis[θ] = column index
    tab = [[Fraction(normals[j][i]) for j in cols] + [Fraction(int(i == t)) for t in range(n)]
           + [Fraction(1)] for i in range(n)]
    cost = [Fraction(b[j]) for j in cols] + [Fraction(0)] * n
    basis = list(range(k, k + n))
    while True:
        cb = [cost[basis[i]] for i in range(n)]
        entering = None
        for c in range(k + n):  # Bland: the first column with a positive reduced cost
            if c in basis:
                continue
            if cost[c] - sum((cb[i] * tab[i][c] for i in range(n) if tab[i][c]),
                             Fraction(0)) > 0:
                entering = c
                break
        if entering is None:
            break
        leave = None
        for i in range(n):
            if tab[i][entering] > 0:
                ratio = tab[i][-1] / tab[i][entering]
                if leave is None or (ratio, basis[i]) < leave[:2]:
                    leave = (ratio, basis[i], i)
        assert leave is not None  # bounded: every column has a positive entry
        row = leave[2]
        piv = tab[row][entering]
        tab[row] = [x / piv for x in tab[row]]
        for i in range(n):
            if i != row and tab[i][entering]:
                f = tab[i][entering]
                tab[i] = [x - f * y for x, y in zip(tab[i], tab[row], strict=True)]
        basis[row] = entering
    cb = [cost[basis[i]] for i in range(n)]
    value = sum((cb[i] * tab[i][-1] for i in range(n)), Fraction(0))
    s = tuple(sum((cb[i] * tab[i][k + t] for i in range(n)), Fraction(0)) for t in range(n))
    lam = tuple(sorted((cols[basis[i]], tab[i][-1]) for i in range(n)
                       if basis[i] < k and tab[i][-1]))
    return _checked(normals, b, wf, Membership(value <= wf, value, s, lam))


def _checked(normals: Sequence[Normal], b: Sequence[int | Fraction], w: Fraction,
             out: Membership) -> Membership:
    """Check both certificates by arithmetic: ``s`` dual feasible, ``λ`` primal feasible, and
    equal objectives (so both are optimal and the verdict follows from either)."""
    n = len(normals[0])
    if any(x < 0 for x in out.s) or any(
            sum((a[i] * out.s[i] for i in range(n) if a[i]), Fraction(0)) < b[j]
            for j, a in enumerate(normals) if b[j] > 0):
        raise AssertionError("sum_membership: the dual is not feasible")
    if any(c <= 0 for _, c in out.lam) or any(x > 1 for x in out.direction(normals)):
        raise AssertionError("sum_membership: λ is not in the packing polytope")
    if sum(out.s, Fraction(0)) != out.value or sum(
            (c * b[j] for j, c in out.lam), Fraction(0)) != out.value:
        raise AssertionError("sum_membership: the objectives differ")
    return out
