"""The packing polytope ``P_A = {λ >= 0 : Σ_a λ_a a <= 1}`` of a set of normals: its vertices and
their directions ``y_λ = Σ_a λ_a a``, exactly (the arc certificate of ``proofs/NGOAL.md`` NG.8
and the direction form of ``proofs/NRULE.md`` NR.2(a)).

A vertex ``λ != 0`` has ``max y_λ = 1``; one with fewer than ``N`` basic normals has a
non-all-ones ``y``; so the vertices the tests need are found from bases of at most ``N - 1``
normals and as many coordinates (:func:`_packing_bases`), far fewer than the polytope's.
"""

from __future__ import annotations

import itertools
from fractions import Fraction
from functools import cache

import numpy as np

from dppverify.structured.cover import Normal
from dppverify.structured.exact_bases import dets


@cache
def packing_vertices(normals: tuple[Normal, ...], every: bool = False
                     ) -> tuple[tuple[tuple[Fraction, ...], tuple[Fraction, ...]], ...]:
    """The vertices ``λ`` of ``{λ >= 0 : Σ_n λ_n n <= 1}`` with ``y_λ = Σ_n λ_n n`` not 0/1.

    Returned as pairs ``(λ, y_λ)``. Vertices whose ``y_λ`` is a 0/1 vector are left out unless
    ``every``: for closed support numbers the arc condition holds for them automatically
    (``proofs/NGOAL.md`` NG.8); ``λ = 0`` is always left out. Enumerated by their bases
    (:func:`_packing_bases`): a vertex whose ``y`` is not the all-ones vector has fewer than
    ``N`` basic normals, so only those bases are tried unless ``every``.

    Examples
    --------
    >>> from dppverify.structured.cover import zero_one_normals
    >>> len(packing_vertices(zero_one_normals(3)))
    0
    >>> sorted({y for _, y in packing_vertices(zero_one_normals(4))})[0]
    (Fraction(1, 2), Fraction(1, 1), Fraction(1, 1), Fraction(1, 1))
    """
    n = len(normals[0])
    out = set()
    for lam_sparse, y in _packing_bases(normals, n if every else n - 1):
        if any(x not in (0, 1) for x in y) or every:
            lam = [Fraction(0)] * len(normals)
            for j, c in lam_sparse:
                lam[j] = c
            out.add((tuple(lam), y))
    return tuple(sorted(out))


def _packing_bases(normals: tuple[Normal, ...], t_max: int, lambdas: bool = True
                   ) -> set[tuple[tuple[tuple[int, Fraction], ...], tuple[Fraction, ...]]]:
    """The vertices ``λ != 0`` of ``{λ >= 0 : Σ_n λ_n n <= 1}`` with at most ``t_max`` basic
    normals, as ``(((j, λ_j > 0), …), y_λ)``.

    A vertex has basic normals ``B`` and basic slacks ``S``; with ``T`` the other coordinates,
    ``y_T = 1``, ``B_T λ_B = 1_T`` (``B_T`` non-singular, ``|B| = |T|``), ``λ_B >= 0`` and
    ``y_S <= 1``: every choice of ``t = |B| = |T|`` normals and coordinates is tried, with exact
    integer determinants (vectorised; the entries are small). A degenerate vertex has several
    bases and is kept once. Without ``lambdas`` only the distinct ``y_λ`` are kept (with an
    empty ``λ``): the directions alone are far fewer than the vertices.
    """
    n = len(normals[0])
    amat = np.array(normals, dtype=np.int64)  # K × n
    k = amat.shape[0]
    found: set[tuple[tuple[tuple[int, Fraction], ...], tuple[Fraction, ...]]] = set()
    seen: set[tuple[int, ...]] = set()
    for t in range(1, t_max + 1):
        combos_all = itertools.combinations(range(k), t)
        while True:
            combos = np.array(list(itertools.islice(combos_all, 200_000)), dtype=np.int64)
            if combos.size == 0:
                break
            cols = amat[combos]  # (C, t, n): the t normals of every combination
            for tset in itertools.combinations(range(n), t):
                entries = [[np.ascontiguousarray(cols[:, c, tset[r]]) for c in range(t)]
                           for r in range(t)]
                det = dets(entries)
                ok = det != 0
                if not ok.any():
                    continue
                sub = [[e[ok] for e in row] for row in entries]
                d = det[ok]
                ones = np.ones(d.size, dtype=np.int64)
                lam = np.stack([dets([[ones if c == i else sub[r][c] for c in range(t)]
                                      for r in range(t)]) for i in range(t)], axis=1)
                lam = lam * np.where(d > 0, 1, -1).astype(d.dtype)[:, None]  # λ·|det|
                feas = np.all(lam >= 0, axis=1)
                if not feas.any():
                    continue
                y = (lam[feas][:, :, None] * cols[ok][feas]).sum(axis=1)  # y·|det|
                ad = np.abs(d[feas])
                keep = np.all(y <= ad[:, None], axis=1)
                if not lambdas:
                    nums = np.concatenate([y[keep], ad[keep][:, None]], axis=1)
                    nums //= np.gcd.reduce(nums, axis=1)[:, None]  # lowest terms: one key per y
                    seen.update(map(tuple, np.unique(nums, axis=0).tolist()))
                    continue
                nums = np.concatenate([lam[feas][keep], y[keep], ad[keep][:, None]], axis=1)
                nums //= np.gcd.reduce(nums, axis=1)[:, None]  # lowest terms: one key per λ
                rows = np.concatenate([combos[ok][feas][keep], nums], axis=1)
                seen.update(map(tuple, np.unique(rows, axis=0).tolist()))
        for row in seen:  # the same λ (or y) from another T: in lowest terms, kept once
            den = row[-1]
            if not lambdas:
                found.add(((), tuple(Fraction(x, den) for x in row[:-1])))
                continue
            lam_row = tuple((j, Fraction(c, den)) for j, c in
                            zip(row[:t], row[t:2 * t], strict=True) if c)
            found.add((lam_row, tuple(Fraction(x, den) for x in row[2 * t:-1])))
        seen.clear()
    return found


@cache
def packing_directions(normals: tuple[Normal, ...]) -> tuple[tuple[Fraction, ...], ...]:
    """Every non-zero ``y_λ = Σ_n λ_n n`` over the vertices ``λ`` of ``{λ >= 0 : Σ_n λ_n n <= 1}``.

    Every such ``y`` has ``max y = 1`` (a vertex ``λ != 0`` has a tight row), and a vertex with
    ``N`` basic normals has ``y = 1``: so the directions are the all-ones vector and those of
    :func:`_packing_bases` with fewer than ``N`` basic normals. ``normals`` must contain the
    unit vectors.

    Examples
    --------
    >>> from dppverify.structured.cover import zero_one_normals
    >>> ys = packing_directions(zero_one_normals(4))
    >>> len(ys), sum(1 for y in ys if any(x not in (0, 1) for x in y))
    (19, 4)
    >>> len(packing_directions(zero_one_normals(5))) - 31
    45
    """
    n = len(normals[0])
    found = {y for _, y in _packing_bases(normals, n - 1, lambdas=False)}
    found.add((Fraction(1),) * n)
    return tuple(sorted(found))
