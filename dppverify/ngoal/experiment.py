"""Experiment: the value and the VoI as goals are added one by one (N = 2 … 5).

On a MovingAI map (default: the bundled ``examples/paper10.map``, 4-connected, unit weights)
with a fixed start and an ordered list of candidate goals, for ``N = 2 … len(goals)`` the
first ``N`` goals are used with two priors — equal (``1/N`` each) and skewed
(``b_θ ∝ 2^(N-θ)``: the first goal most likely) — and the untruncated game's value
``V = V_inf`` is computed exactly by the coalition DP (``proofs/NGOAL.md``: an exact upper bound
on the value, conjectured equal), beside the complete-information value
``Ū = Σ_θ b_θ d(s0, g^θ)`` (the Defender knows the goal and guards it on every step) and
``VoI = (Ū − V) / Ū``.

Run ``python -m dppverify.ngoal.experiment [--map examples/paper10.map] [--start 9,0]
[--goals 0,9 0,0 0,5 9,9 4,4] [--csv out.csv] [--figure docs/figures/ngoal_goals.png]``.
"""

from __future__ import annotations

import argparse
import csv
import sys
import time
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from typing import Any

from dppverify.exact import Number
from dppverify.ngoal.coalition import coalition_value
from dppverify.ngoal.instance import ninstance_from_json

__all__ = ["GoalRow", "goal_series", "grid_document", "read_map", "skewed_prior"]

PASSABLE = frozenset(".GS")
DEFAULT_GOALS = ((0, 9), (0, 0), (0, 5), (9, 9), (4, 4))


def read_map(text: str) -> tuple[str, ...]:
    """The rows of a MovingAI ``.map`` file (``.``, ``G``, ``S`` passable).

    Raises
    ------
    ValueError
        If the header or the grid is malformed.

    Examples
    --------
    >>> read_map("type octile\\nheight 2\\nwidth 3\\nmap\\n..@\\n...\\n")
    ('..@', '...')
    """
    lines = text.splitlines()
    try:
        head = {ln.split()[0]: ln.split()[1] for ln in lines[:3]}
        height, width = int(head["height"]), int(head["width"])
        start = lines.index("map") + 1
    except (KeyError, IndexError, ValueError):
        raise ValueError("not a MovingAI map: expected type/height/width/map header") from None
    rows = tuple(lines[start:start + height])
    if len(rows) != height or any(len(r) != width for r in rows):
        raise ValueError(f"map grid is not {height} rows of {width} cells")
    return rows


def grid_document(rows: Sequence[str], start: tuple[int, int], goals: Sequence[tuple[int, int]],
                  prior: Sequence[Fraction]) -> dict[str, Any]:
    """A 4-connected unit-weight instance document on the passable cells of ``rows``.

    Examples
    --------
    >>> doc = grid_document(("...", ".@."), (1, 0), [(0, 2), (1, 2)], [Fraction(1, 2)] * 2)
    >>> len(doc["graph"]["nodes"]), len(doc["graph"]["edges"]), doc["prior"]
    (5, 4, ['1/2', '1/2'])
    """
    cells = [(r, c) for r, row in enumerate(rows) for c, ch in enumerate(row) if ch in PASSABLE]
    free = set(cells)
    edges = [{"source": [r, c], "target": [r + dr, c + dc]} for r, c in cells
             for dr, dc in ((0, 1), (1, 0)) if (r + dr, c + dc) in free]
    return {"graph": {"directed": False, "nodes": [{"id": [r, c]} for r, c in cells],
                      "edges": edges},
            "start": list(start), "goals": [list(g) for g in goals],
            "prior": [str(p) for p in prior]}


def skewed_prior(n: int) -> tuple[Fraction, ...]:
    """``b_θ ∝ 2^(n-θ)``, θ = 1 … n.

    Examples
    --------
    >>> [str(b) for b in skewed_prior(3)]
    ['4/7', '2/7', '1/7']
    """
    total = 2 ** n - 1
    return tuple(Fraction(2 ** (n - 1 - i), total) for i in range(n))


@dataclass(frozen=True)
class GoalRow:
    """One point of the series: N goals, a prior, ``V``, ``Ū`` and ``VoI`` (exact)."""

    n_goals: int
    prior_kind: str
    prior: tuple[Fraction, ...]
    value: Number
    complete: Number
    voi: Fraction
    layers: int
    seconds: float


def goal_series(rows: Sequence[str], start: tuple[int, int], goals: Sequence[tuple[int, int]]
                ) -> list[GoalRow]:
    """The value and VoI for ``N = 2 … len(goals)`` with equal and skewed priors.

    Examples
    --------
    >>> rows = ("....", ".@@.", "....")
    >>> [(r.n_goals, r.prior_kind, str(r.value), str(r.voi)) for r in
    ...  goal_series(rows, (2, 0), [(0, 3), (2, 3), (0, 0)])][:2]
    [(2, 'equal', '5/2', '3/8'), (2, 'skewed', '10/3', '3/13')]
    """
    out = []
    for n in range(2, len(goals) + 1):
        for kind, prior in (("equal", tuple(Fraction(1, n) for _ in range(n))),
                            ("skewed", skewed_prior(n))):
            inst = ninstance_from_json(grid_document(rows, start, goals[:n], prior))
            t0 = time.perf_counter()
            v = coalition_value(inst, None)
            seconds = time.perf_counter() - t0
            ubar = sum((b * Fraction(inst.dist_to[t][inst.start]) for t, b in enumerate(prior)),
                       Fraction(0))
            voi = (ubar - Fraction(v.value)) / ubar
            out.append(GoalRow(n, kind, prior, v.value, ubar, voi,
                               v.layers, seconds))
    return out


def _cell(text: str) -> tuple[int, int]:
    r, c = text.split(",")
    return int(r), int(c)


def _figure(rows: list[GoalRow], path: str, title: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.6))
    for kind, marker in (("equal", "o"), ("skewed", "s")):
        pts = [r for r in rows if r.prior_kind == kind]
        ns = [r.n_goals for r in pts]
        ax1.plot(ns, [float(r.value) for r in pts], marker=marker, label=f"V, {kind} prior")
        ax1.plot(ns, [float(r.complete) for r in pts], marker=marker, linestyle="--",
                 label=f"Ū (complete information), {kind}")
        ax2.plot(ns, [float(r.voi) for r in pts], marker=marker, label=f"{kind} prior")
    ax1.set_xlabel("number of goals N")
    ax1.set_ylabel("Attacker's expected cost")
    ax1.legend(fontsize=7)
    ax2.set_xlabel("number of goals N")
    ax2.set_ylabel("VoI = (Ū − V) / Ū")
    ax2.legend(fontsize=7)
    for ax in (ax1, ax2):
        ax.set_xticks(sorted({r.n_goals for r in rows}))
    fig.suptitle(title, fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main(argv: list[str] | None = None) -> int:
    """Command line: print the table, optionally write a CSV and the figure."""
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--map", default="examples/paper10.map")
    parser.add_argument("--start", type=_cell, default=(9, 0))
    parser.add_argument("--goals", type=_cell, nargs="+", default=list(DEFAULT_GOALS))
    parser.add_argument("--csv")
    parser.add_argument("--figure")
    args = parser.parse_args(argv)
    try:
        rows = read_map(Path(args.map).read_text(encoding="utf-8"))
        series = goal_series(rows, args.start, args.goals)
    except (OSError, ValueError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    print("N  prior   V          U_bar      VoI        layers  seconds")
    for r in series:
        print(f"{r.n_goals}  {r.prior_kind:<6}  {float(r.value):<9.4f}  {float(r.complete):<9.4f}"
              f"  {float(r.voi):<9.4f}  {r.layers:<6}  {r.seconds:.2f}")
    if args.csv:
        with open(args.csv, "w", newline="", encoding="utf-8") as fh:
            w = csv.writer(fh)
            w.writerow(["n_goals", "prior_kind", "prior", "V", "U_bar", "VoI", "layers"])
            for r in series:
                w.writerow([r.n_goals, r.prior_kind, " ".join(map(str, r.prior)), r.value,
                            r.complete, r.voi, r.layers])
    if args.figure:
        _figure(series, args.figure, f"{args.map}, start {args.start}, goals added in the "
                                     f"order {', '.join(map(str, args.goals))}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
