"""Certifying the solver's own profile on long directed paths: the cost grows linearly in the walk.

The instance is a directed path ``0 → 1 → … → n`` of unit arcs with ``g1 = n`` at its end and
``g2 = n + 1`` hanging off its last-but-one node (arcs ``n-1 → g2``, ``g1 ⇄ g2``), prior
3/5 – 2/5: both types walk ``n`` steps together before they part, so every walk of the profile
is ``n`` steps long. For each ``n`` the solver's profile (``solver.solve``) is certified on
the untruncated game by ``dppverify.certify`` from the two JSON documents (as ``dpp certify``
reads them); the time is the best of ``--repeat`` runs. The growth exponent is the slope of
``log(seconds)`` against ``log(n)`` (least squares over every size), measured in one run:
linear cost is 1, and the target is at most 1.2. A Defender rule that builds a tuple per step
(``walk[:t+1]``) makes it 2.

Run: ``.venv/bin/python benchmarks/bench_walk_growth.py [--sizes 2000 ... 64000] [--repeat 3]``
(``--quick``: three small sizes, one run, no target; exits 1 when the full run misses it).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
from typing import Any

from _timing import best

import solver
from dppverify import certify

SIZES = (2_000, 4_000, 8_000, 16_000, 32_000, 64_000)
TARGET = 1.2


def path_document(n: int) -> dict[str, Any]:
    """The directed path of ``n`` steps to ``g1`` with ``g2`` beside its end (see above)."""
    edges = [{"source": i, "target": i + 1, "weight": 1} for i in range(n)]
    edges += [{"source": n - 1, "target": n + 1, "weight": 1},
              {"source": n, "target": n + 1, "weight": 1},
              {"source": n + 1, "target": n, "weight": 1}]
    return {"graph": {"directed": True, "nodes": [{"id": i} for i in range(n + 2)],
                      "edges": edges},
            "start": 0, "goals": [n, n + 1], "prior": ["3/5", "2/5"]}


def growth_exponent(sizes: list[int], seconds: list[float]) -> float:
    """The least-squares slope of ``log(seconds)`` against ``log(size)``.

    Examples
    --------
    >>> round(growth_exponent([1, 2, 4], [3.0, 6.0, 12.0]), 6)
    1.0
    >>> round(growth_exponent([1, 2, 4], [1.0, 4.0, 16.0]), 6)
    2.0
    """
    xs = [math.log(s) for s in sizes]
    ys = [math.log(t) for t in seconds]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return (sum((x - mx) * (y - my) for x, y in zip(xs, ys, strict=True))
            / sum((x - mx) ** 2 for x in xs))


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--sizes", type=int, nargs="*", default=list(SIZES))
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--quick", action="store_true",
                    help="tiny sizes, for the test suite (also DPP_BENCH_QUICK=1)")
    args = ap.parse_args()
    quick = args.quick or bool(os.environ.get("DPP_BENCH_QUICK"))
    if quick:
        args.sizes, args.repeat = [250, 500, 1_000], 1
    print(f"{'steps':>7} {'solve s':>8} {'certify s':>9} {'s per 1000 steps':>16}  verdict")
    timings = []
    for n in args.sizes:
        doc = path_document(n)
        t_solve, profile = best(lambda doc=doc: json.loads(json.dumps(
            solver.solve(doc).to_json())), 1)
        t_cert, cert = best(lambda doc=doc, profile=profile: certify(doc, profile),
                            args.repeat)
        if cert.verdict != "pass":
            print(f"n = {n}: the solver's profile is not certified: {cert.verdict}")
            return 1
        timings.append(t_cert)
        print(f"{n:>7} {t_solve:>8.2f} {t_cert:>9.3f} {1000 * t_cert / n:>16.4f}  "
              f"{cert.verdict}", flush=True)
    slope = growth_exponent(args.sizes, timings)
    if quick:
        print(f"growth exponent {slope:.2f} (quick mode: sizes too small to judge)")
        return 0
    met = slope <= TARGET
    print(f"growth exponent {slope:.2f} over {args.sizes[0]:,}..{args.sizes[-1]:,} steps "
          f"(target <= {TARGET}: {'met' if met else 'NOT MET'})")
    return 0 if met else 1


if __name__ == "__main__":
    sys.exit(main())
