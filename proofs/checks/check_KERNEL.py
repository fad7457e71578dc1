"""Checks for proofs/KERNEL.md: K.1 (the Bellman equation pins the distances), K.3 (the closed
form ``min(P(v), Q(v) − c)`` of the progress default is the exact least cost from ``(v, c)``)
and K.7's vertex tables, against exhaustive enumeration on small random graphs (seeded).

Independent of the code under test: distances by plain Bellman–Ford, costs walk by walk over
every walk of at most ``2n`` steps (enough: a cheapest completion is a path to the node that
attains the running minimum followed by a path to a goal, KERNEL K.3), vertices of the
packing polytope against the checker's own enumeration (``dppverify.structured.cover``).
"""

from __future__ import annotations

import random
from fractions import Fraction
from itertools import product

from dppverify.kernel.guarantee import vertices
from dppverify.structured.cover import basic_solutions, zero_one_normals

INF = float("inf")


def _graph(rng: random.Random) -> tuple[int, dict[int, dict[int, Fraction]], list[int]]:
    n = rng.randint(3, 5)
    succ: dict[int, dict[int, Fraction]] = {v: {} for v in range(n)}
    for _ in range(rng.randint(n, 2 * n + 2)):
        a, b = rng.sample(range(n), 2)
        succ[a][b] = Fraction(rng.randint(1, 4), rng.choice([1, 1, 2]))
        if rng.random() < 0.6:
            succ[b][a] = succ[a][b]
    return n, succ, rng.sample(range(n), 2)


def _distances(n: int, succ: dict[int, dict[int, Fraction]], g: int) -> list[object]:
    d: list[object] = [INF] * n
    d[g] = Fraction(0)
    for _ in range(n):
        for v in range(n):
            for u, w in succ[v].items():
                if d[u] != INF and (d[v] == INF or w + d[u] < d[v]):  # type: ignore[operator]
                    d[v] = w + d[u]  # type: ignore[operator]
    return d


def _walks(n: int, succ: dict[int, dict[int, Fraction]], goals: list[int], v: int):  # type: ignore[no-untyped-def]
    stack = [(v,)]
    while stack:
        w = stack.pop()
        if w[-1] in goals:
            yield w
        elif len(w) <= 2 * n:
            stack += [(*w, u) for u in succ[w[-1]]]


def test_K1_the_bellman_equation_has_only_the_distances_as_solutions() -> None:
    rng = random.Random(1)
    for _ in range(200):
        n, succ, (g, _) = _graph(rng)
        d = _distances(n, succ, g)
        # every label vector over the values near d that satisfies the equation is d itself
        for v in range(n):
            for delta in (Fraction(-1, 2), Fraction(1, 3)):
                if d[v] == INF or v == g:
                    continue
                bent = list(d)
                bent[v] = d[v] + delta  # type: ignore[operator]
                ok = all(bent[x] == min((w + bent[u] for u, w in succ[x].items()), default=INF)
                         for x in range(n) if x != g)
                assert not ok


def test_K3_the_closed_form_is_the_least_cost_from_every_state() -> None:
    rng = random.Random(2)
    checked = 0
    for _ in range(60):
        n, succ, (g, h) = _graph(rng)  # g: the rule's goal, h: the other type's goal
        dg, dh = _distances(n, succ, g), _distances(n, succ, h)
        goals = [g, h]
        if INF in (dh[g], dg[h]):
            continue

        def other_cost(walk: tuple[int, ...], c: object) -> object:
            total, cm = Fraction(0), c
            for a, b in zip(walk, walk[1:], strict=False):
                c2 = min(cm, dg[b])  # type: ignore[type-var]
                total += succ[a][b] - (cm - c2)  # type: ignore[operator]
                cm = c2
            return total + dh[walk[-1]]  # type: ignore[operator]

        P, Q = [], []
        for v in range(n):
            ws = list(_walks(n, succ, goals, v))
            P.append(min((sum((succ[a][b] for a, b in zip(w, w[1:], strict=False)),
                              Fraction(0)) + dh[w[-1]] for w in ws), default=INF))  # type: ignore[operator]
            Q.append(min((sum((succ[a][b] for a, b in zip(w, w[1:], strict=False)),
                              Fraction(0)) + dh[w[-1]] + min(dg[x] for x in w)  # type: ignore[operator, type-var]
                          for w in ws), default=INF))
        for v, x in product(range(n), range(n)):
            c = dg[x]
            if c == INF or dg[v] == INF or c > dg[v] or P[v] == INF or v in goals:  # type: ignore[operator]
                continue
            best = min(other_cost(w, c) for w in _walks(n, succ, goals, v))  # type: ignore[type-var]
            assert best == min(P[v], Q[v] - c), (v, c)  # type: ignore[operator]
            checked += 1
        # (P1)-(P4) hold for the tight labels
        for v in range(n):
            if P[v] == INF or v in goals:
                continue
            for u, w in succ[v].items():
                assert P[v] <= w + P[u] and Q[v] <= w + Q[u]  # type: ignore[operator]
            if dg[v] != INF:
                assert Q[v] <= dg[v] + P[v]  # type: ignore[operator]
    assert checked > 60


def test_K7_the_kernel_lists_the_packing_polytope_vertices_of_the_checker() -> None:
    for n in (2, 3, 4):
        A = zero_one_normals(n)
        units = tuple(tuple(int(i == j) for i in range(n)) for j in range(n))
        mine = {v[:len(A)] for v in vertices([*A, *units], (1,) * n)}
        table = basic_solutions(A + units, (1,) * n)
        theirs = set()
        for vert in table.vertices:
            lam = [Fraction(0)] * len(A)
            for pos, col in enumerate(table.columns):
                if col < len(A):
                    lam[col] = vert[pos]
            theirs.add(tuple(lam))
        assert mine - {(Fraction(0),) * len(A)} == theirs - {(Fraction(0),) * len(A)}
