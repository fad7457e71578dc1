"""An independent judge for the guarantee rule with normals (tests only; slow and simple).

Nothing here uses the checker's code: the rule's DP is the layered recursion of
``proofs/NRULE.md`` (dominated covers, NG.7's layers until one repeats) in Fractions over the
cover polytopes' vertex tables of the *solver* (:func:`solver.coalitions.vertex_tables.
vertex_table`, an implementation the checker does not share); the rule's ``σ`` is the
lexicographic minimum found by enumerating the vertices of ``F``; best responses enumerate
the walks (deduplicated by node and state).
"""

from __future__ import annotations

import functools
import itertools
from collections.abc import Sequence
from fractions import Fraction

import numpy as np

from dppverify.game.instance import Instance
from solver.coalitions.vertex_tables import vertex_table

Normal = tuple[int, ...]


def solve(mat: list[list[Fraction]], n: int) -> list[Fraction] | None:
    """Gauss-Jordan on an ``n × (n+1)`` augmented matrix; None if singular."""
    a = [row[:] for row in mat]
    for col in range(n):
        piv = next((r for r in range(col, n) if a[r][col] != 0), None)
        if piv is None:
            return None
        a[col], a[piv] = a[piv], a[col]
        p = a[col][col]
        a[col] = [x / p for x in a[col]]
        for r in range(n):
            if r != col and a[r][col] != 0:
                f = a[r][col]
                a[r] = [x - f * y for x, y in zip(a[r], a[col], strict=True)]
    return [a[i][n] for i in range(n)]


@functools.cache
def cover_vertices(columns: tuple[Normal, ...], rhs: Normal) -> list[dict[int, Fraction]]:
    """Every vertex of ``{c >= 0 : Σ c_j columns[j] = rhs}`` (the solver's exact vertex
    enumeration: the checker's is the code under test)."""
    return vertex_table(list(columns), rhs).vertices()


def layered_dp(inst: Instance, normals: Sequence[Normal], max_layers: int = 400
               ) -> dict[Normal, dict[int, Fraction]]:
    """The rule's DP (dominated covers) by layers from ``H = 0`` until a layer repeats
    (memoised by the game's arcs and distances and the normals: the tests ask twice)."""
    key = (tuple(inst.nodes), tuple(inst.goals), tuple(tuple(x) for x in inst.succ),
           tuple(tuple(x) for x in inst.dist_to), tuple(tuple(a) for a in normals), max_layers)
    if key not in _LAYERED:
        _LAYERED[key] = _layered_dp(inst, normals, max_layers)
    return _LAYERED[key]


_LAYERED: dict[tuple[object, ...], dict[Normal, dict[int, Fraction]]] = {}


def _layered_dp(inst: Instance, normals: Sequence[Normal], max_layers: int
                ) -> dict[Normal, dict[int, Fraction]]:
    n = inst.n_nodes
    goals = set(inst.goals)
    order = sorted(normals, key=lambda a: (sum(a), a))
    splits = {}
    for a in order:
        cols = [b for b in normals if b != a and all(x <= y for x, y in zip(b, a, strict=True))]
        splits[a] = (cols, cover_vertices(tuple(cols), a) if sum(a) > 1 else [])
    terminal = {a: {g: sum((Fraction(a[t]) * Fraction(inst.dist_to[t][g])
                            for t in range(len(a))), Fraction(0)) for g in goals}
                for a in normals}
    layer: dict[Normal, dict[int, Fraction]] = {a: dict(terminal[a]) for a in normals}
    top = max(inst.hops)
    for k in range(1, max_layers + 1):
        new: dict[Normal, dict[int, Fraction]] = {}
        for a in order:
            row = dict(terminal[a])
            for v in range(n):
                if v in goals:
                    continue
                best = None
                for u, w in inst.succ[v]:
                    if u in layer[a]:
                        x = Fraction(w) * max(a) + layer[a][u]
                        best = x if best is None or x < best else best
                cols, verts = splits[a]
                for vert in verts:
                    if all(v in new[cols[j]] for j in vert):
                        x = sum((c * new[cols[j]][v] for j, c in vert.items()), Fraction(0))
                        best = x if best is None or x < best else best
                if best is not None:
                    row[v] = best
            new[a] = row
        if k > top and new == layer:
            return new
        layer = new
    raise AssertionError("the layered DP did not repeat")


def judge_sigma(r: Sequence[Fraction], u: int, w: Fraction, normals: Sequence[Normal],
                m: dict[Normal, dict[int, Fraction]], order: Sequence[int]
                ) -> tuple[Fraction, ...]:
    """The rule's ``σ``: the lexicographic minimum of ``F`` by enumerating its vertices.

    A vertex is ``n - 1`` tight constraints and ``Σσ = 1``. The integer matrices' determinants
    (float64, rounded: entries at most 16, so ``|det| < 2^27`` by Hadamard's bound and the
    rounding error is far below 1/2) drop the singular choices; a float solve drops those
    violating a constraint by more than ``1e-6`` of the data's size (the rounding error of a
    5 × 5 integer system with ``|det| >= 1`` is below ``1e-9`` of it); every survivor is
    solved and checked again in Fractions, so no vertex is decided in floating point.
    Memoised by state (the walk enumeration meets the same states again).
    """
    key = (tuple(r), u, w, tuple(order), id(m))
    if key in _SIGMA:
        return _SIGMA[key]
    n = len(r)
    rows = []
    for a in normals:
        if u not in m[a]:
            continue
        need = (sum((Fraction(x) * y for x, y in zip(a, r, strict=True)), Fraction(0))
                - m[a][u]) / w
        if need > 0:
            rows.append((a, need))
    if not rows:
        out = tuple(Fraction(int(i == order[-1])) for i in range(n))
    else:
        out = _lexmin_vertices(rows, n, order)
    _SIGMA[key] = out
    return out


_SIGMA: dict[tuple[object, ...], tuple[Fraction, ...]] = {}


def _lexmin_vertices(rows: list[tuple[Normal, Fraction]], n: int, order: Sequence[int]
                     ) -> tuple[Fraction, ...]:
    cons = rows + [(tuple(int(i == j) for j in range(n)), Fraction(0)) for i in range(n)]
    mats = np.array([list(a) for a, _ in cons], dtype=np.int64)
    rhs = np.array([float(q) for _, q in cons])
    choice = np.array(list(itertools.combinations(range(len(cons)), n - 1)), dtype=np.int64)
    if n == 1:
        choice = np.zeros((1, 0), dtype=np.int64)
    full = np.concatenate([mats[choice], np.ones((choice.shape[0], 1, n), dtype=np.int64)],
                          axis=1)
    det = np.rint(np.linalg.det(full.astype(np.float64)))  # integers of at most 16^4·5!
    good = det != 0
    full, choice = full[good], choice[good]
    b = np.concatenate([rhs[choice], np.ones((choice.shape[0], 1))], axis=1)
    x = np.linalg.solve(full.astype(np.float64), b[..., None])[..., 0]
    scale = 1.0 + float(np.abs(rhs).max())
    ok = np.all(x >= -1e-6 * scale, axis=1) & np.all(
        mats.astype(np.float64) @ x.T >= rhs[:, None] - 1e-6 * scale, axis=0)
    best: tuple[list[Fraction], list[Fraction]] | None = None
    for ch in choice[ok].tolist():
        mat = [[Fraction(x) for x in cons[i][0]] + [cons[i][1]] for i in ch]
        mat.append([Fraction(1)] * n + [Fraction(1)])
        sol = solve(mat, n)
        if sol is None or any(v < 0 for v in sol):
            continue
        if any(sum((Fraction(ai) * xi for ai, xi in zip(a, sol, strict=True)), Fraction(0)) < q
               for a, q in rows):
            continue
        key = [sol[o] for o in order]
        if best is None or key < best[0]:
            best = (key, sol)
    if best is None:
        return tuple(Fraction(int(i == order[0])) for i in range(n))
    return tuple(best[1])


def priority(inst: Instance) -> tuple[int, ...]:
    """Goals by decreasing prior, ties by index."""
    return tuple(sorted(range(inst.n_goals), key=lambda t: (-inst.prior[t], t)))


def walk_cost(inst: Instance, h: Sequence[Fraction], normals: Sequence[Normal],
              m: dict[Normal, dict[int, Fraction]], walk: Sequence[int], theta: int) -> Fraction:
    """Type ``theta``'s cost of ``walk`` against the rule (stage costs plus the terminal)."""
    r = [Fraction(x) for x in h]
    cost = Fraction(0)
    order = priority(inst)
    for v, u in itertools.pairwise(walk):
        w = Fraction(inst.weight(v, u))  # type: ignore[arg-type]
        s = judge_sigma(r, u, w, normals, m, order)
        cost += w * s[theta]
        r = [x - w * y for x, y in zip(r, s, strict=True)]
    return cost + Fraction(inst.dist_to[theta][walk[-1]])


def min_over_walks(inst: Instance, h: Sequence[Fraction], normals: Sequence[Normal],
                   m: dict[Normal, dict[int, Fraction]], theta: int, max_steps: int
                   ) -> tuple[Fraction | None, tuple[int, ...] | None]:
    """Type ``theta``'s least cost over the walks of at most ``max_steps`` steps."""
    goals = set(inst.goals)
    order = priority(inst)
    reach = set(m[normals[0]])
    frontier: dict[tuple[int, tuple[Fraction, ...]], tuple[int, ...]] = {
        (inst.start, tuple(Fraction(x) for x in h)): (inst.start,)}
    best: tuple[Fraction, tuple[int, ...]] | None = None
    for k in range(max_steps + 1):
        nxt: dict[tuple[int, tuple[Fraction, ...]], tuple[int, ...]] = {}
        for (v, r), walk in frontier.items():
            if v in goals:
                c = Fraction(h[theta]) - r[theta] + Fraction(inst.dist_to[theta][v])
                if best is None or c < best[0]:
                    best = (c, walk)
                continue
            if k == max_steps:
                continue
            for u, w in inst.succ[v]:
                if u not in reach:
                    continue
                wf = Fraction(w)
                s = judge_sigma(r, u, wf, normals, m, order)
                r2 = tuple(x - wf * y for x, y in zip(r, s, strict=True))
                nxt.setdefault((u, r2), (*walk, u))
        frontier = nxt
    return (None, None) if best is None else best
