"""Guarantee rules with many extra normals: the checker's time against an exact judge's.

Each row is a guarantee-rule profile (``docs/formats.md`` §2b) on a finite game (a hub gadget
without return arcs, or an acyclic digraph: every walk has at most a few steps, so an
enumeration of the walks is exact), with ``h`` the optimal cover dual of the rule's sets at the
start and each type on its judge-cheapest walk. Timed, in one process, interleaved:

- ``checker``: ``dppverify.certify`` on the untruncated game (structured route, ``H = inf``):
  the rule's sets, the arc test (the vertices of ``F_v``, ``proofs/NRULE.md`` NR.2(b)), the
  exact search where it is needed, the Defender's side;
- ``tree``: ``dppverify.certify`` by the tree route at the longest walk (the other route);
- ``judge``: the independent exact judge of the tests (``tests/dppverify/structured/
  _rule_judge.py``: its own layered DP over the solver's vertex tables, its own lexicographic
  minimum by vertex enumeration, every walk enumerated): every type's least cost against the
  rule, which decides the Attacker's regrets. Rules with 64 normals are beyond it (its
  vertex enumeration of ``F`` takes ``C(|A| + N, N - 1)`` bases per state): ``-``.

The target is ``checker / judge <= 5`` on the N = 5 rows with 10–30 extra normals. ``--quick`` runs
the two N = 4 rows (tests/test_benchmarks.py).

Run: ``PYTHONPATH=. .venv/bin/python benchmarks/bench_guarantee_normals.py [--quick]``.
"""

from __future__ import annotations

import argparse
import itertools
import math
import os
import random
import time
from fractions import Fraction
from typing import Any

from dppverify.certify import certify
from dppverify.game.instance import Instance, instance_from_json
from dppverify.structured.cover import min_cover_vectors
from dppverify.structured.guarantee import guarantee_sets
from tests.dppverify.structured._instances import digraph
from tests.dppverify.structured._rule_judge import layered_dp, min_over_walks
from tests.solver._ngoal_families import hub

Normal = tuple[int, ...]


def random_normals(rng: random.Random, n: int, k: int, top: int = 3) -> list[Normal]:
    """``k`` distinct valid extra normals (entries ``0..top``, not 0/1, gcd 1)."""
    out: set[Normal] = set()
    while len(out) < k:
        a = tuple(rng.randint(0, top) for _ in range(n))
        if any(x > 1 for x in a) and math.gcd(*a) == 1:
            out.add(a)
    return sorted(out)


def pattern_normals(*patterns: Normal) -> list[Normal]:
    """Every permutation of the patterns (the facets seen on the N-goal gadgets)."""
    return sorted({p for pat in patterns for p in itertools.permutations(pat)})


def longest_walk(inst: Instance) -> int:
    """The longest walk's steps (the games here are finite)."""
    goals = set(inst.goals)

    def depth(v: int) -> int:
        if v in goals:
            return 0
        return 1 + max((depth(u) for u, _ in inst.succ[v] if inst.hops[u] >= 0), default=-1)

    return depth(inst.start)


def case(name: str, doc: dict[str, Any], normals: list[Normal]) -> dict[str, Any]:
    """The row's instance, profile and judge inputs."""
    inst = instance_from_json(doc)
    sets = guarantee_sets(inst, normals)
    col = sets.column(inst.start)
    assert col is not None
    h = list(min_cover_vectors(sets.normals, col, inst.prior).dual)
    return {"name": name, "doc": doc, "inst": inst, "normals": normals, "h": h,
            "all": sets.normals, "steps": longest_walk(inst)}


def judge(row: dict[str, Any]) -> list[tuple[Fraction | None, tuple[int, ...] | None]]:
    """Every type's least cost against the rule over every walk (exact: a finite game)."""
    inst, normals = row["inst"], row["all"]
    m = layered_dp(inst, normals)
    return [min_over_walks(inst, row["h"], normals, m, t, row["steps"])
            for t in range(inst.n_goals)]


def profile(row: dict[str, Any], walks: list[tuple[int, ...] | None]) -> dict[str, Any]:
    """Each type on the given walk (the judge's cheapest one), the rule with ``h``."""
    inst = row["inst"]
    attacker = []
    for t, walk in enumerate(walks):
        if walk is None:  # no judge (64 normals): the shortest walk to the type's goal
            walk = _shortest(inst, inst.goals[t])
        attacker.append([{"path": [inst.nodes[v] for v in walk], "probability": 1}])
    return {"format": "dpp-ngoal-profile/1", "attacker": attacker,
            "defender": {"rule": "guarantee", "h": [str(x) for x in row["h"]],
                         "normals": [list(a) for a in row["normals"]]}}


def _shortest(inst: Instance, goal: int) -> tuple[int, ...]:
    frontier: list[tuple[int, ...]] = [(inst.start,)]
    while frontier:
        nxt = []
        for walk in frontier:
            for u, _ in inst.succ[walk[-1]]:
                if u == goal:
                    return (*walk, u)
                if not inst.is_goal(u):
                    nxt.append((*walk, u))
        frontier = nxt
    raise AssertionError("the goal is unreachable")


def rows(quick: bool) -> list[dict[str, Any]]:
    """The benchmark's cases."""
    rng = random.Random(20260)
    out = [case("hub N=4, 64 random normals", hub(random.Random(11), 4, dag=True),
                random_normals(rng, 4, 64)),
           case("hub N=4, 12 normals (2,2,2,1) (2,1,1,0)", hub(random.Random(12), 4, dag=True),
                pattern_normals((2, 2, 2, 1), (2, 1, 1, 0)))]
    if quick:
        return out
    p20a = pattern_normals((2, 2, 2, 1, 0))  # 20 permutations
    p20b = pattern_normals((2, 2, 2, 1, 1))  # 10 permutations
    dag = digraph(random.Random(5), 5, acyclic=True)
    out += [case("hub N=5 (10 nodes), 64 random normals", _hub_with(10, 5),
                 random_normals(rng, 5, 64)),
            case("hub N=5, 20 normals (2,2,2,1,0)", hub(random.Random(13), 5, dag=True), p20a),
            case("hub N=5, 10 normals (2,2,2,1,1)", hub(random.Random(14), 5, dag=True), p20b),
            case("hub N=5, 30 normals, both patterns", hub(random.Random(15), 5, dag=True),
                 p20a + p20b),
            case("dag N=5, 20 normals (2,2,2,1,0)", dag, p20a)]
    return out


def _hub_with(nodes: int, n: int) -> dict[str, Any]:
    """A finite hub gadget with exactly ``nodes`` nodes (seeds tried in order)."""
    for seed in itertools.count():
        doc = hub(random.Random(seed), n, dag=True)
        if len(doc["graph"]["nodes"]) == nodes:
            return doc
    raise AssertionError  # pragma: no cover


def main() -> None:
    """Print one row per case: seconds of the checker, the tree route and the judge."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true",
                    help="the N = 4 rows only (also DPP_BENCH_QUICK=1)")
    args = ap.parse_args()
    quick = bool(args.quick or os.environ.get("DPP_BENCH_QUICK"))
    print(f"{'case':42} {'|A|':>4} {'verdict':>7} {'checker s':>9} {'tree s':>7} "
          f"{'judge s':>8} {'ratio':>6}")
    for row in rows(quick):
        many = len(row["normals"]) > 32
        t0 = time.perf_counter()
        best = None if many else judge(row)
        t_judge = None if many else time.perf_counter() - t0
        prof = profile(row, [None] * row["inst"].n_goals if best is None
                       else [w for _, w in best])
        t0 = time.perf_counter()
        cert = certify(row["doc"], prof, horizon="inf", route="structured")
        t_check = time.perf_counter() - t0
        br = cert.check("pbne.attacker_br")
        assert br.status in ("pass", "fail"), br.message  # decided
        if best is not None:  # the checker's exact minima against the judge's
            u = cert.check("value.U").numbers
            for t, (least, _) in enumerate(best):
                regret = Fraction(str(br.numbers[f"regret{t + 1}"] or 0))
                claimed = Fraction(str(u[f"U{t + 1}"])) - regret
                assert least is not None, row["name"]
                assert least >= claimed if regret == 0 else least == claimed, row["name"]
        t0 = time.perf_counter()
        tree = certify(row["doc"], prof, horizon=row["steps"], route="tree")
        t_tree = time.perf_counter() - t0
        assert tree.verdict == cert.verdict, row["name"]
        ratio = "-" if t_judge is None else f"{t_check / t_judge:.2f}"
        judge_s = "-" if t_judge is None else f"{t_judge:.2f}"
        print(f"{row['name']:42} {len(row['all']):>4} {cert.verdict:>7} {t_check:>9.2f} "
              f"{t_tree:>7.2f} {judge_s:>8} {ratio:>6}", flush=True)


if __name__ == "__main__":
    main()
