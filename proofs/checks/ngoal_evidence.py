"""The evidence for the coalition-DP conjecture (proofs/NGOAL.md): both routes on random cases.

Run ``.venv/bin/python proofs/checks/ngoal_evidence.py [--cases 200] [--seed 0]``. Draws
random instances from four families — undirected graphs, digraphs (both with integer weights
1–4), graphs with fractional weights (denominators up to 4) and 4-connected grids with
obstacles and unit weights — with N = 2, 3, 4 goals and random priors (k_i / Σk, k_i in
1..6), and for every horizon H from the first one at which a goal is reachable to three more
(trees of at most ``--max-prefixes`` prefixes) computes ``V_H`` by the tree route (compact LP +
exact bracket) and by the coalition DP. It prints one summary line per (family, N) and exits 1
if any case disagrees, after writing the disagreeing instances to ``--out`` (a JSON list).
"""

from __future__ import annotations

import argparse
import json
import random
import sys
from collections import Counter
from fractions import Fraction
from typing import Any

from dppverify.agreement import compare_routes
from dppverify.errors import TreeTooLargeError
from dppverify.game.instance import instance_from_json
from dppverify.tree_route.tree import count_prefixes

FAMILIES = ("undirected", "digraph", "fractional", "grid")


def _prior(rng: random.Random, k: int) -> list[str]:
    ws = [rng.randint(1, 6) for _ in range(k)]
    return [str(Fraction(w, sum(ws))) for w in ws]


def _graph(rng: random.Random, family: str) -> dict[str, Any]:
    if family == "grid":
        rows, cols = rng.randint(2, 3), rng.randint(2, 4)
        cells = [(r, c) for r in range(rows) for c in range(cols)]
        blocked = {cell for cell in cells if rng.random() < 0.15}
        free = [cell for cell in cells if cell not in blocked]
        edges = [{"source": list(a), "target": list(b)} for a in free for b in free
                 if a < b and abs(a[0] - b[0]) + abs(a[1] - b[1]) == 1]
        return {"directed": False, "nodes": [{"id": list(c)} for c in free], "edges": edges}
    n = rng.randint(4, 7)
    directed = family == "digraph"
    arcs: dict[tuple[int, int], Any] = {}

    def weight() -> Any:
        if family == "fractional":
            return str(Fraction(rng.randint(1, 8), rng.randint(1, 4)))
        return rng.randint(1, 4)

    for i in range(1, n):  # a strongly connected scaffold
        arcs[(rng.randrange(i), i)] = weight()
        if directed:
            arcs[(i, rng.randrange(i))] = weight()
    for _ in range(rng.randint(0, n)):
        u, v = rng.sample(range(n), 2)
        key = (u, v) if directed else (min(u, v), max(u, v))
        arcs.setdefault(key, weight())
    return {"directed": directed, "nodes": [{"id": i} for i in range(n)],
            "edges": [{"source": u, "target": v, "weight": w} for (u, v), w in arcs.items()]}


def draw_case(rng: random.Random, family: str, k: int) -> dict[str, Any] | None:
    """One instance document of ``family`` with ``k`` goals (None if the graph is too small)."""
    graph = _graph(rng, family)
    ids = [nd["id"] for nd in graph["nodes"]]
    if len(ids) < k + 1:
        return None
    picks = rng.sample(range(len(ids)), k + 1)  # unreachable picks are redrawn by the caller
    return {"graph": graph, "start": ids[picks[0]], "goals": [ids[i] for i in picks[1:]],
            "prior": _prior(rng, k)}


def run(cases: int, seed: int, max_prefixes: int, goal_counts: tuple[int, ...]
        ) -> tuple[Counter[tuple[str, int]], Counter[tuple[str, int]], list[Any]]:
    """Compare both routes on ``cases`` instances per (family, N); returns counts and failures."""
    rng = random.Random(seed)
    pairs: Counter[tuple[str, int]] = Counter()
    exact: Counter[tuple[str, int]] = Counter()
    bad: list[Any] = []
    for family in FAMILIES:
        for k in goal_counts:
            done = 0
            while done < cases:
                doc = draw_case(rng, family, k)
                if doc is None:
                    continue
                try:
                    inst = instance_from_json(doc)
                except ValueError:
                    continue  # unreachable goals: draw again
                done += 1
                first = inst.hops[inst.start]
                for h in range(first, first + 4):
                    if count_prefixes(inst, h) > max_prefixes:
                        break
                    try:
                        a = compare_routes(inst, h, max_prefixes=max_prefixes)
                    except TreeTooLargeError:
                        break
                    pairs[(family, k)] += 1
                    exact[(family, k)] += a.exact
                    if not a.agree:
                        bad.append({"instance": doc, "horizon": h, "dp": str(a.dp),
                                    "lower": str(a.tree.bracket.lower),
                                    "upper": str(a.tree.bracket.upper),
                                    "lp": a.tree.value})
    return pairs, exact, bad


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, default=40, help="instances per (family, N)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--max-prefixes", type=int, default=4000)
    parser.add_argument("--goals", default="2,3,4", help="comma-separated N values")
    parser.add_argument("--out", default="ngoal_disagreements.json")
    args = parser.parse_args(argv)
    goal_counts = tuple(int(x) for x in args.goals.split(","))
    pairs, exact, bad = run(args.cases, args.seed, args.max_prefixes, goal_counts)
    for key in sorted(pairs):
        print(f"{key[0]:>10} N={key[1]}: {pairs[key]} (instance, H) pairs, "
              f"{exact[key]} with a closed exact bracket")
    print(f"total: {sum(pairs.values())} pairs, {sum(exact.values())} exact, "
          f"{len(bad)} disagreements")
    if bad:
        with open(args.out, "w", encoding="utf-8") as fh:
            json.dump(bad, fh, indent=1)
        print(f"disagreements written to {args.out}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
