"""The guarantee rule (N goals, ``docs/formats.md`` §2b): its DP labels, its start set, its arc
condition and its σ on the profile's prefixes, checked exactly (proofs/KERNEL.md K.7).

The witness gives the labels ``m_a(v)`` (integers over ``S``), covers for the packing
directions, and for every prefix of the profile's walks the rule's σ with one dual certificate
per lexicographic stage. The vertex tables of the rule's fixed polytopes (the dominated covers
of each normal, the packing polytope) are listed by :func:`vertices` once per rule.
"""

from __future__ import annotations

from fractions import Fraction
from itertools import combinations, pairwise, repeat
from math import lcm
from operator import le, mul
from typing import Any

from dppverify.kernel.graph import exact
from dppverify.kernel.profile import Guarantee
from dppverify.kernel.reading import INF, Instance, labels, number
from dppverify.kernel.table import Memory, first_failure
from dppverify.kernel.verdict import BadInput, Beyond, Undecided

MAX_BASES = 20_000
"""Most candidate bases the kernel tries for one vertex table (beyond: not decided); the
packing polytope of ``|A|`` normals has ``Σ_{k <= N} C(|A| + N, k)``."""

Vec = tuple[Fraction, ...]


def _solve(cols: list[tuple[int, ...]], rhs: tuple[Any, ...]) -> list[Fraction] | None:
    """The unique ``x`` with ``Σ_j x_j cols[j] = rhs``, or None (dependent or inconsistent):
    fraction-free Gaussian elimination on integers."""
    k, rows = len(cols), [[c[i] for c in cols] + [rhs[i]] for i in range(len(rhs))]
    for j in range(k):
        if (piv := next((r for r in range(j, len(rows)) if rows[r][j]), None)) is None:
            return None
        rows[j], rows[piv] = rows[piv], rows[j]
        p = rows[j]
        rows = [row if r == j or not row[j] else [p[j] * x - row[j] * y for x, y in
                                                  zip(row, p, strict=True)]
                for r, row in enumerate(rows)]
    return None if any(row[k] for row in rows[k:]) else [Fraction(rows[j][k], rows[j][j])
                                                          for j in range(k)]


def vertices(cols: list[tuple[int, ...]], rhs: tuple[Any, ...]) -> list[Vec]:
    """Every vertex of ``{x >= 0 : Σ_j x_j cols[j] = rhs}``: its basic feasible solutions.

    Examples
    --------
    >>> [[str(x) for x in v] for v in vertices([(1, 0), (0, 1), (1, 1)], (1, 1))]
    [['0', '0', '1'], ['1', '1', '0']]
    """
    out = []
    bases = [K for k in range(1, len(rhs) + 1) for K in combinations(range(len(cols)), k)]
    if len(bases) > MAX_BASES:
        raise Beyond(f"a vertex table of the rule's normals needs {len(bases)} bases, "
                        f"beyond the kernel's bound of {MAX_BASES}")
    for K in bases:
        if (x := _solve([cols[j] for j in K], rhs)) is not None and min(x) > 0:
            out.append(tuple(x[K.index(j)] if j in K else Fraction(0) for j in range(len(cols))))
    return out


def _combine(c: Vec, rows: list[list[Any]], L: int) -> list[Any]:
    """``L·Σ_j c_j rows[j]`` node by node, in integers (``L·c`` must be integral)."""
    terms = [row if cj * L == 1 else list(map(mul, row, repeat(int(cj * L))))
             for cj, row in zip(c, rows, strict=True) if cj]
    return terms[0] if len(terms) == 1 else list(map(sum, zip(*terms, strict=True)))


def _lcm(vecs: list[Vec]) -> int:
    return lcm(*(x.denominator for v in vecs for x in v))


def _dot(a: Any, b: Any) -> Any:
    return sum(map(mul, a, b))


def _nums(raw: Any, k: int, what: str) -> list[Fraction]:
    """``k`` exact numbers of the witness (bad input otherwise)."""
    xs = [number(x) for x in raw] if type(raw) is list and len(raw) == k else [None]
    if None in xs:
        raise BadInput(f"witness: {what} must be a list of {k} numbers")
    return xs  # type: ignore[return-value]


class GuaranteeRule:
    """The guarantee rule on an instance, its witness checked (K.7)."""

    def __init__(self, inst: Instance, rule: Guarantee, D: list[list[Any]], S: int, wit: Any,
                 mixtures: Any, dead: list[int]) -> None:
        self.inst, self.rule, self.S = inst, rule, S
        A, n, N, graph = rule.normals, inst.graph.n, len(inst.goals), inst.graph
        if type(wit) is not dict or set(wit) - {"m", "covers", "steps"} or \
                type(wit.get("m")) is not list or len(wit["m"]) != len(A):
            raise BadInput(f"witness: guarantee must have \"m\" ({len(A)} lists), \"steps\" "
                           "and optionally \"covers\"")
        m = self.m = [labels(xs, n, f"guarantee.m[{i}]", dead) for i, xs in enumerate(wit["m"])]
        for i, a in enumerate(A):  # the DP's equations (NR.1(c)): goals, steps, splits
            for g in inst.goals:
                if m[i][g] != _dot(a, (d[g] for d in D)):
                    raise Undecided(f"guarantee.m[{i}] at goal {inst.show(g)}: m_a(g) = "
                                    "a·d(g, g^.) fails")
            dom = [j for j, b in enumerate(A) if b != a and all(map(le, b, a))]
            table = vertices([A[j] for j in dom], a) if dom else []
            L = _lcm(table)
            mi = _combine((Fraction(1),), [m[i]], L)
            best = graph.relax(mi, Fraction(max(a) * S * L), INF)
            for c in table:
                best = list(map(min, best, _combine(c, [m[j] for j in dom], L)))
            for g in inst.goals:
                best[g] = mi[g]
            if best != mi:
                v = next(v for v in range(n) if best[v] != m[i][v])
                raise Undecided(f"guarantee.m[{i}] at node {inst.show(v)}: m_a(v) = min(steps, "
                                "dominated covers) fails: not the rule's DP")
        s0 = inst.start
        for i, a in enumerate(A):
            if not _dot(a, rule.h) * S <= m[i][s0]:
                raise Undecided(f"h is not in the start set: a·h <= m_a(s0) fails for a = {a}")
        self._arc_condition(wit.get("covers", []))
        self.order = sorted(range(N), key=lambda t: (-inst.prior[t], t))
        self.children: dict[tuple[int, int], int] = {}
        self.sigma: list[Vec] = []
        state = [rule.h]
        steps = wit.get("steps")
        for mix in mixtures:
            for w, _ in mix:
                p = -1
                for v, u in pairwise(w):
                    q = self.children.setdefault((p, u), len(self.sigma))
                    if q == len(self.sigma):
                        r, wt = state[p + 1], graph.weight(v, u)
                        if type(steps) is not list or q >= len(steps):
                            raise BadInput("witness: guarantee.steps must list every prefix of "
                                           "the profile's walks")
                        self.sigma.append(s := self._step(q, steps[q], r, u, wt))  # type: ignore[arg-type]
                        state.append(tuple(x - wt * y for x, y in zip(r, s, strict=True)))  # type: ignore[operator]
                    p = q
        if type(steps) is not list or len(steps) != len(self.sigma):
            raise BadInput(f"witness: guarantee.steps must have {len(self.sigma)} records")

    def _arc_condition(self, covers: Any) -> None:
        """``h_{F_v}(y_λ) <= w + λ·m(u)`` on every live arc for every vertex ``λ`` of the packing
        polytope not implied by the DP's equations (NR.2), ``h_{F_v}`` bounded above by the
        witness's covers (and ``λ`` itself)."""
        A, N, S = self.rule.normals, len(self.inst.goals), self.S
        extras = len(A) > 2 ** N - 1
        units = [tuple(int(i == j) for i in range(N)) for j in range(N)]
        mus: dict[Vec, list[Vec]] = {}
        for k, c in enumerate(covers if type(covers) is list else [None]):
            mu = tuple(_nums(c, len(A), f"guarantee.covers[{k}]"))
            if min(mu) < 0:
                raise BadInput(f"witness: guarantee.covers[{k}] has a negative weight")
            mus.setdefault(tuple(_dot(mu, (a[i] for a in A)) for i in range(N)), []).append(mu)
        for lam in vertices([*A, *units], (1,) * N):
            lam = lam[:len(A)]
            y = tuple(_dot(lam, (a[i] for a in A)) for i in range(N))
            if not any(lam) or (sum(map(bool, lam)) == 1 and max(y) == 1) or (
                    not extras and set(y) <= {0, 1}):
                continue  # implied by the DP's step and split equations (K.7)
            cands = [*mus.get(y, []), lam]
            L = _lcm(cands)
            upper = list(map(min, *(_combine(mu, self.m, L) for mu in cands))) if len(cands) > 1 \
                else _combine(lam, self.m, L)
            rhs = self.inst.graph.relax(_combine(lam, self.m, L), Fraction(S * L), INF)
            v = first_failure(upper, rhs, self.inst.goals)
            if v is not None:
                raise Undecided(f"the arc condition F_v in F_u + wΔ fails at node "
                                f"{self.inst.show(v)} in the direction y = "
                                f"({', '.join(map(str, y))})")

    def _step(self, q: int, rec: Any, r: Vec, u: int, w: Fraction) -> Vec:
        """The σ of prefix ``q`` (entering ``u`` from state ``r``), checked to be the
        lexicographic minimum of ``F`` by its primal point and one dual per stage."""
        A, N, S, o = self.rule.normals, len(r), self.S, self.order
        at = f"guarantee.steps[{q}]"
        rec = rec if type(rec) is dict else {}
        s, duals = _nums(rec.get("sigma"), N, f"{at}.sigma"), rec.get("duals")
        if type(duals) is not list or len(duals) != N - 1:
            raise BadInput(f"witness: {at}.duals must be {N - 1} records")
        beta = [(_dot(a, r) - Fraction(self.m[i][u], S)) / w for i, a in enumerate(A)]
        if min(s) < 0 or sum(s) != 1 or any(_dot(a, s) < b for a, b in zip(A, beta, strict=True)):
            raise Undecided(f"{at}: sigma is not in the rule's set F")
        for k, dual in enumerate(duals):
            dual = dual if type(dual) is dict else {}
            y = _nums(dual.get("y"), len(A), f"{at}.duals[{k}].y")
            fix = _nums(dual.get("fix"), k, f"{at}.duals[{k}].fix")
            z = _nums([dual.get("z")], 1, f"{at}.duals[{k}].z")[0]
            ok = min(y) >= 0 and all(_dot(y, (a[i] for a in A)) + z + _dot(fix, (
                int(j == i) for j in o)) <= int(i == o[k]) for i in range(N)) and \
                _dot(y, beta) + z + _dot(fix, (s[j] for j in o)) >= s[o[k]]
            if not ok:
                raise Undecided(f"guarantee.steps[{q}]: the dual of stage {k + 1} does not prove "
                                "sigma the lexicographic minimum")
        return tuple(s)

    def check_type(self, theta: int, rec: Any, dead: list[int], u_scaled: Fraction) -> None:
        """Type ``θ``'s bound: ``U_θ <= h_θ`` (NR.2)."""
        if not u_scaled <= self.rule.h[theta] * self.S:
            raise Undecided(f"type {theta}: U <= h fails (U = {u_scaled / self.S}, h = "
                            f"{self.rule.h[theta]}): the guarantee does not prove regret 0")

    def start(self) -> Memory:
        """The memory at the start: the root prefix."""
        return (-1, None)

    def step(self, mem: Memory, v: int, u: int, w: Fraction) -> tuple[Memory, Any]:
        """The step's costs ``S·w·σ(θ)`` at a prefix of the profile's walks (None elsewhere)."""
        q = self.children.get((mem[0], u))
        if q is None:
            return (-1, None), None
        return (q, None), tuple(exact(w * self.S * x) for x in self.sigma[q])

