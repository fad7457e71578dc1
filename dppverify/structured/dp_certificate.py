"""The arc certificate of the structured route's DPs (``proofs/NGOAL.md`` NG.8).

A normal-restricted DP (:mod:`dppverify.structured.normal_dp`; with the 0/1 normals the
coalition DP of :mod:`dppverify.structured.coalition`) describes outer sets
``F_v^k = { r : n·r <= m_n(v, k) ∀ n ∈ M }`` ⊇ ``G_v^k``. They are the true guarantee sets —
and the DP value is ``V_H`` — as soon as every arc satisfies ``F_v^k ⊆ F_u^{k-1} + w·Δ^N``
(NG.8). By Farkas' lemma that holds iff for every vertex ``λ`` of the packing polytope
``P_M = { λ >= 0 : Σ_n λ_n n <= 1 }``

    h_{F_v}(y_λ) <= w + Σ_n λ_n m_n(u),          y_λ = Σ_n λ_n n,

where ``h_{F_v}(y)`` is the cheapest cover of ``y`` by the normals at ``v``. Vertices with
``y_λ`` a 0/1 vector satisfy it automatically (step and closure), so only the few others are
checked (:func:`direction_checks`): none for N = 3 (which proves NG.4: the coalition DP is the
value), the four permutations of (1, 1, 1, 1/2) for N = 4 and 45 vectors for N = 5.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from functools import cache

import numpy as np

from dppverify.game.instance import Instance
from dppverify.structured.coalition import CoalitionRunner, CoalitionValue
from dppverify.structured.cover import (
    Normal,
    Table,
    cheapest,
    symmetric_table,
    zero_one_normals,
)
from dppverify.structured.packing import packing_vertices


@dataclass(frozen=True)
class DirectionCheck:
    """The arc test for one direction ``y``: cover table of ``s·y`` and the ``λ`` values.

    Attributes
    ----------
    scale : int
        ``s``: ``s·y`` is an integer vector.
    cover : Table
        The vertices of ``{c >= 0 : Σ_n c_n n = s·y}``; its columns index the normals.
    lams : numpy.ndarray
        ``(n_lambda, |M|)``: ``lam_lcm · λ`` for every packing vertex ``λ`` with ``y_λ = y``.
    lam_lcm : int
        The common denominator of the ``λ`` values.
    y : tuple of Fraction
        The direction.
    """

    scale: int  # s: s·y is an integer vector
    cover: Table  # vertices of {c >= 0 : Σ_n c_n n = s·y}, columns index the normals
    lams: np.ndarray  # (n_lambda, |M|): lcm_l · λ
    lam_lcm: int
    y: tuple[Fraction, ...]


@cache
def direction_checks(normals: tuple[Normal, ...], every: bool = False
                     ) -> tuple[DirectionCheck, ...]:
    """The arc tests of a set of normals: one per direction ``y_λ`` that is not a 0/1 vector
    (every non-zero direction with ``every``: for support numbers that are not closed, e.g. the
    guarantee rule's with extra normals, ``proofs/NRULE.md`` NR.2).

    Examples
    --------
    >>> len(direction_checks(zero_one_normals(3))), len(direction_checks(zero_one_normals(4)))
    (0, 4)
    >>> [str(x) for x in direction_checks(zero_one_normals(4))[0].y]
    ['1/2', '1', '1', '1']
    """
    groups: dict[tuple[Fraction, ...], list[tuple[Fraction, ...]]] = {}
    for lam, y in packing_vertices(normals, every):
        groups.setdefault(y, []).append(lam)
    out = []
    for y, lams in sorted(groups.items()):
        s = math.lcm(*(x.denominator for x in y))
        cover = symmetric_table(normals, tuple(int(x * s) for x in y))
        lcm = math.lcm(*(x.denominator for lam in lams for x in lam))
        arr = np.array([[int(x * lcm) for x in lam] for lam in lams], dtype=np.int64)
        out.append(DirectionCheck(s, cover, arr, lcm, y))
    return tuple(out)


Arc = tuple[int, int, tuple[Fraction, ...]]
"""A failing arc ``(v, u, y)``: tail, head and the direction ``y`` where it fails."""


def failing_arcs(checks: tuple[DirectionCheck, ...], new: np.ndarray, fin_new: np.ndarray,
                 old: np.ndarray, fin_old: np.ndarray, src: np.ndarray, dst: np.ndarray,
                 wts: np.ndarray) -> list[Arc]:
    """Arcs violating ``F_v ⊆ F_u + wΔ`` (NG.8(c)), the first one per failing direction.

    ``new``/``old`` are ``(|M|, nodes)`` integer numerators at one scale ``D`` (``new`` at the
    arcs' tails, ``old`` at their heads), ``wts`` the arc weights times ``D``.

    Examples
    --------
    One arc ``0 -> 1`` of weight 1 and four goals; the sets at node 1 are the 0/1 bounds
    ``|S|``. At node 0 the bounds ``|S| + 1`` fit the arc; raising the bound of the whole set
    above what the step allows makes the direction ``(1/2, 1, 1, 1)``'s test fail:

    >>> checks = direction_checks(zero_one_normals(4))
    >>> at_u = np.array([[bin(s).count("1")] * 2 for s in range(1, 16)])
    >>> arc = np.array([0]), np.array([1]), np.array([1])
    >>> fin = np.array([True, True])
    >>> failing_arcs(checks, at_u + 1, fin, at_u, fin, *arc)
    []
    >>> at_v = at_u + 1
    >>> at_v[14] += 1
    >>> [(v, u, [str(x) for x in y]) for v, u, y in failing_arcs(checks, at_v, fin, at_u,
    ...                                                           fin, *arc)][:1]
    [(0, 1, ['1/2', '1', '1', '1'])]
    """
    if not checks:
        return []
    arcs = fin_new[src] & fin_old[dst]
    if not arcs.any():
        return []
    src, dst, wts = src[arcs], dst[arcs], wts[arcs]
    out: list[Arc] = []
    for chk in checks:
        bad = np.flatnonzero(failing_arc_mask(chk, new, old, src, dst, wts))
        if bad.size:
            i = int(bad[0])
            out.append((int(src[i]), int(dst[i]), chk.y))
    return out


def failing_arc_mask(chk: DirectionCheck, new: np.ndarray, old: np.ndarray, src: np.ndarray,
                     dst: np.ndarray, wts: np.ndarray) -> np.ndarray:
    """Which arcs violate ``h_{F_v}(y) <= w + λ·m(u)`` in one direction (NG.8(c)).

    ``new`` (at the tails) and ``old`` (at the heads) are ``(|M|, nodes)`` integer numerators
    at one scale ``D``, ``wts`` the arc weights times ``D``; returns a boolean per arc.

    Examples
    --------
    >>> chk = direction_checks(zero_one_normals(4))[0]
    >>> at_u = np.array([[bin(s).count("1")] * 2 for s in range(1, 16)])
    >>> failing_arc_mask(chk, at_u + 1, at_u, np.array([0]), np.array([1]),
    ...                  np.array([1])).tolist()
    [False]
    """
    nodes_v, nodes_u = np.unique(src), np.unique(dst)
    mnew, mold = new[:, nodes_v].T, old[:, nodes_u].T
    cols = np.asarray(chk.cover.columns, dtype=np.int64)
    hv = np.asarray(cheapest(mnew[:, cols], chk.cover.scaled), dtype=object)
    mu = np.asarray(cheapest(mold, chk.lams.T), dtype=object)
    hv_arc = hv[np.searchsorted(nodes_v, src)]
    mu_arc = mu[np.searchsorted(nodes_u, dst)]
    # h_v(y) <= w + λ·m_u at scale D: h_v(y) = hv / (lcm_T · s), λ·m_u = mu / lcm_λ
    lhs = hv_arc * chk.lam_lcm
    rhs = (np.asarray(wts, dtype=object) * chk.cover.lcm * chk.lam_lcm * chk.scale
           + mu_arc * chk.cover.lcm * chk.scale)
    return np.asarray(lhs > rhs, dtype=bool)


def certified_coalition_dp(inst: Instance, horizon: int | None, max_layers: int | None, *,
                           certify: bool = True
                           ) -> tuple[CoalitionValue, list[Arc],
                                      tuple[CoalitionRunner, dict[int, np.ndarray]] | None]:
    """The coalition DP's value, its failing arcs (empty: certified) and the ``H = inf`` fixpoint.

    The certificate is checked at every layer (finite ``H``) or at the repeated layer
    (``H = inf``; NG.8 then covers every ``H`` from that layer on); for N <= 3 there is
    nothing to check (NG.4). ``certify=False`` skips it. The fixpoint ``(runner, layer)`` is
    returned for ``H = inf`` only.

    Examples
    --------
    >>> from dppverify.game.examples import hub4
    >>> coal, fails, fixpoint = certified_coalition_dp(hub4(), None, None)
    >>> coal.value, [str(x) for x in fails[0][2]], fixpoint is not None
    (Fraction(25, 14), ['1', '1', '1', '1/2'], True)
    """
    run = CoalitionRunner(inst)
    fails: list[Arc] = []
    checks = (direction_checks(zero_one_normals(inst.n_goals)) if inst.n_goals > 3 and certify
              else ())

    def check(new: dict[int, np.ndarray], old: dict[int, np.ndarray]) -> None:
        if checks and not fails:  # NG.4: nothing to check for N <= 3
            a, fa = run.stacked(new)
            b, fb = (a, fa) if new is old else run.stacked(old)
            fails.extend(failing_arcs(checks, a, fa, b, fb, run.src, run.dst, run.wts))

    if horizon is not None:
        layer = run.layer0()
        for k in range(1, horizon + 1):
            nxt = run.step(layer, k)
            check(nxt, layer)
            layer = nxt
        return run.value(layer, horizon, horizon), fails, None
    fixpoint, k = run.fixpoint(max_layers)
    check(fixpoint, fixpoint)
    return run.value(fixpoint, None, k), fails, (run, fixpoint)
