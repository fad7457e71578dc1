"""Experiment: the N-goal equilibrium as goals are added (``dpp experiment ngoal``).

On MovingAI maps (4-connected, unit weights) one rule places a start and five goals
(:func:`corner_cells`); for ``N = 2 … 5`` the first ``N`` goals are used with equal priors
(``1/N``) and skewed priors (``b_θ ∝ 2^(N-θ)``). Each game is solved by the N-goal
construction (:func:`solver.coalitions.construction.coalition_equilibrium`, proofs/NEXACT.md)
and the profile is handed to a certifier (the command line passes the checker: structured
route, ``H = inf``).
Reported, all exact:

- ``U``: the Attacker's expected cost in the profile, the game's value ``V_inf`` (NEXACT NX.5:
  proved by the solver's own exact checks; ``certified`` says whether the independent checker
  confirmed it); empty (``-``) only where the solver's budget ended first (``certified``:
  ``not solved``);
- ``U_bar = Σ_θ b_θ d(s0, g^θ)`` (complete information) and ``VoI = (U_bar − U) / U_bar``;
- ``deception = 1 − Σ_θ b_θ E[guarded_θ] / Σ_θ b_θ E[L_θ]``: the fraction of the walked
  distance on which the Defender's weight is on a wrong goal;
- ``detour = Σ_θ b_θ E[L_θ + d(end, g^θ)] / U_bar − 1``: how much longer the walks (plus the
  terminal distance when a walk ends at another goal) are than shortest paths.

``dpp experiment ngoal --values`` runs the value-only series instead (:func:`value_series`):
no profile is solved; the untruncated game's value ``V`` is computed by a valuer the command
line passes (the checker's guarantee sets, ``proofs/NGOAL.md``: the value for ``N <= 3`` and,
where certified, for ``N = 4, 5``; where it is not proved, ``V`` is the coalition DP's upper
bound and the row says so: ``V_exact`` false, hollow in the figure), beside
``U_bar`` and ``VoI = (U_bar − V) / U_bar``.
"""

from __future__ import annotations

import csv
import io
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, TypeVar

import numpy as np
from scipy import ndimage

from solver.coalitions.construction import (
    CoalitionEquilibrium,
    FixpointNotReached,
    coalition_equilibrium,
)
from solver.errors import InvalidInstanceError
from solver.game.instance import MAX_GOALS, Instance

Cell = tuple[int, int]
Certifier = Callable[[Cell, Sequence[Cell], Sequence[Fraction], CoalitionEquilibrium], str]


@dataclass(frozen=True)
class GameValue:
    """What a valuer says of one game: ``V`` (or an upper bound on it), ``U_bar``, whether
    ``V`` is proved, and the layers of the coalition DP."""

    value: Fraction
    complete: Fraction
    exact: bool
    layers: int


Valuer = Callable[[Cell, Sequence[Cell], Sequence[Fraction]], GameValue]


Row = TypeVar("Row")


def _series(n_max: int, row: Callable[[int, str, tuple[Fraction, ...]], Row],
            progress: Callable[[Row], None] | None) -> list[Row]:
    """``row(N, prior kind, prior)`` for ``N = 2 … n_max`` and the two priors of the series,
    equal (``1/N``) and skewed (:func:`skewed_prior`), each passed to ``progress`` when done."""
    out = []
    for n in range(2, n_max + 1):
        for kind, prior in (("equal", tuple(Fraction(1, n) for _ in range(n))),
                            ("skewed", skewed_prior(n))):
            out.append(row(n, kind, prior))
            if progress is not None:
                progress(out[-1])
    return out


def skewed_prior(n: int) -> tuple[Fraction, ...]:
    """``b_θ ∝ 2^(n-θ)``, θ = 1 … n.

    Examples
    --------
    >>> [str(b) for b in skewed_prior(3)]
    ['4/7', '2/7', '1/7']
    """
    total = 2 ** n - 1
    return tuple(Fraction(2 ** (n - 1 - i), total) for i in range(n))


def corner_cells(blocked: np.ndarray, n_goals: int = MAX_GOALS) -> tuple[Cell, tuple[Cell, ...]]:
    """A start and ``n_goals`` goals placed by one rule on any map.

    The start is the free cell nearest (Manhattan, then row, then column) to the bottom-left
    corner; the goals are the cells of the start's 4-connected region nearest to the top-right
    corner, the top-left corner, the middle of the top row, the bottom-right corner and the
    centre, in that order, each distinct from the start and the goals before it.

    Examples
    --------
    >>> grid = np.zeros((3, 4), dtype=bool); grid[1, 1:3] = True
    >>> corner_cells(grid, 3)
    ((2, 0), ((0, 3), (0, 0), (0, 2)))
    """
    h, w = blocked.shape
    free = np.argwhere(~blocked)
    if free.size == 0:
        raise InvalidInstanceError("the map has no free cell")

    def nearest(target: Cell, cells: np.ndarray) -> Cell:
        d = np.abs(cells[:, 0] - target[0]) + np.abs(cells[:, 1] - target[1])
        key = np.lexsort((cells[:, 1], cells[:, 0], d))
        return int(cells[key[0], 0]), int(cells[key[0], 1])

    start = nearest((h - 1, 0), free)
    labels, _ = ndimage.label(~blocked)  # 4-connected regions
    region = np.argwhere(labels == labels[start])
    goals: list[Cell] = []
    targets = [(0, w - 1), (0, 0), (0, w // 2), (h - 1, w - 1), ((h - 1) // 2, (w - 1) // 2)]
    for target in targets[:n_goals]:
        taken = {start, *goals}
        left = np.array([c for c in region.tolist() if tuple(c) not in taken])
        if left.size == 0:
            raise InvalidInstanceError(f"the start's region has {len(region)} cells: too few "
                                       f"for {n_goals} goals")
        goals.append(nearest(target, left))
    return start, tuple(goals)


VERDICTS = {"pass": "pass", "fail": "refuted", "error": "undecided"}
"""How a checker verdict reads in the table (the checker's ``error`` is "could not decide")."""


@dataclass(frozen=True)
class NGoalRow:
    """One game of the series (exact numbers; ``certified``: ``pass``, ``refuted``,
    ``undecided`` (the checker could not decide), ``not run``, or ``not solved`` when the
    solver's budget ended first — then ``U``, ``VoI``, ``deception``, ``detour`` are None)."""

    map_name: str
    n_goals: int
    prior_kind: str
    prior: tuple[Fraction, ...]
    U: Fraction | None
    U_bar: Fraction
    VoI: Fraction | None
    deception: Fraction | None
    detour: Fraction | None
    certified: str
    solve_seconds: float
    certify_seconds: float


def ngoal_series(blocked: np.ndarray, start: Cell, goals: Sequence[Cell], *, map_name: str,
                 certify: Certifier | None = None, max_goals: int = MAX_GOALS,
                 progress: Callable[[NGoalRow], None] | None = None,
                 starting: Callable[[int, str], None] | None = None) -> list[NGoalRow]:
    """Solve (and certify) the games with the first ``N = 2 … max_goals`` goals, two priors.

    ``starting(N, prior kind)`` is called before each game, ``progress(row)`` after it.

    Examples
    --------
    >>> grid = np.zeros((3, 4), dtype=bool); grid[1, 1:3] = True
    >>> rows = ngoal_series(grid, (2, 0), [(0, 3), (2, 3), (0, 0)], map_name="tiny")
    >>> [(r.n_goals, r.prior_kind, str(r.U), str(r.VoI), r.certified) for r in rows][:2]
    [(2, 'equal', '5/2', '3/8', 'not run'), (2, 'skewed', '10/3', '3/13', 'not run')]
    """
    def row(n: int, kind: str, prior: tuple[Fraction, ...]) -> NGoalRow:
        if starting is not None:
            starting(n, kind)
        t0 = time.perf_counter()
        game = Instance.from_grid(blocked, start, goals[:n], [str(b) for b in prior])
        try:
            eq = coalition_equilibrium(game)
        except FixpointNotReached:
            u_bar = sum((b * game.distance(t, game.s0) for t, b in enumerate(prior)),
                        Fraction(0))
            return NGoalRow(map_name, n, kind, prior, None, u_bar, None, None, None,
                            "not solved", time.perf_counter() - t0, 0.0)
        t1 = time.perf_counter()
        verdict = ("not run" if certify is None else
                   VERDICTS.get(v := certify(start, goals[:n], prior, eq), v))
        t2 = time.perf_counter()
        walked = sum((b * x for b, x in zip(prior, eq.walked, strict=True)), Fraction(0))
        guarded = sum((b * x for b, x in zip(prior, eq.guarded, strict=True)), Fraction(0))
        travelled = walked + eq.U - guarded  # the walks and the terminal distances
        return NGoalRow(map_name, n, kind, prior, eq.U, eq.U_bar, eq.VoI,
                        1 - guarded / walked if walked else Fraction(0),
                        travelled / eq.U_bar - 1 if eq.U_bar else Fraction(0), verdict,
                        t1 - t0, t2 - t1)

    return _series(min(len(goals), max_goals), row, progress)


def ngoal_csv(rows: Sequence[NGoalRow]) -> str:
    """The rows as CSV (exact numbers as ``p/q``).

    Examples
    --------
    >>> grid = np.zeros((3, 4), dtype=bool); grid[1, 1:3] = True
    >>> ngoal_csv(ngoal_series(grid, (2, 0), [(0, 3), (2, 3)], map_name="t")).splitlines()[1]
    't,2,equal,1/2 1/2,5/2,4,3/8,1/2,0,not run'
    """
    return _csv(("map", "n_goals", "prior_kind", "prior", "U", "U_bar", "VoI", "deception",
                 "detour", "certified"),
                ((r.map_name, r.n_goals, r.prior_kind, " ".join(map(str, r.prior)),
                  _blank(r.U), r.U_bar, _blank(r.VoI), _blank(r.deception), _blank(r.detour),
                  r.certified) for r in rows))


def _blank(x: Fraction | None) -> object:
    return "" if x is None else x


def _csv(header: Sequence[str], rows: Iterable[Sequence[object]]) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(header)
    w.writerows(rows)
    return buf.getvalue()


def ngoal_figure(rows: Sequence[NGoalRow]) -> Any:
    """Three panels against N: the Attacker's cost relative to ``U_bar``, the VoI and the
    deception; one colour per map, solid = equal prior, dashed = skewed. Every plotted value is
    the game's exact value (proofs/NEXACT.md); filled markers where the checker certified the
    profile, hollow where it did not (counted in the title); games the solver's budget left
    unsolved are not plotted (counted in the title).

    Examples
    --------
    >>> grid = np.zeros((3, 4), dtype=bool); grid[1, 1:3] = True
    >>> fig = ngoal_figure(ngoal_series(grid, (2, 0), [(0, 3), (2, 3), (0, 0)], map_name="t"))
    >>> len(fig.axes)
    3
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = list(dict.fromkeys(r.map_name for r in rows))
    solved = [r for r in rows if r.U is not None]
    fig, axes = plt.subplots(1, 3, figsize=(12, 3.8))
    panels: tuple[tuple[str, Callable[[NGoalRow], Fraction]], ...] = (
        ("U / U_bar (Attacker's cost, relative)", lambda r: Fraction(r.U or 0) / r.U_bar),
        ("VoI = (U_bar - U) / U_bar", lambda r: Fraction(r.VoI or 0)),
        ("deception (share of the walk guarded wrong)", lambda r: Fraction(r.deception or 0)))
    for ax, (label, get) in zip(axes, panels, strict=True):
        for k, name in enumerate(names):
            for kind, style in (("equal", "-"), ("skewed", "--")):
                pts = [r for r in solved if r.map_name == name and r.prior_kind == kind]
                if not pts:
                    continue
                x = [r.n_goals for r in pts]
                ax.plot(x, [float(get(r)) for r in pts], style, color=f"C{k}",
                        label=f"{name}, {kind}" if ax is axes[0] else None)
                ok = [r for r in pts if r.certified == "pass"]
                no = [r for r in pts if r.certified != "pass"]
                ax.plot([r.n_goals for r in ok], [float(get(r)) for r in ok], "o",
                        color=f"C{k}")
                ax.plot([r.n_goals for r in no], [float(get(r)) for r in no], "o",
                        markerfacecolor="white", color=f"C{k}")
        ax.set_xlabel("number of goals N")
        ax.set_title(label, fontsize=10)
        ax.set_xticks(sorted({r.n_goals for r in rows}))
        ax.grid(alpha=0.3)
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=min(len(labels), 5), fontsize=8.5,
               frameon=False)
    hollow = sum(1 for r in solved if r.certified != "pass")
    unsolved = len(rows) - len(solved)
    notes = []
    if hollow:
        notes.append(f"hollow: {hollow} not certified by the checker")
    if unsolved:
        notes.append(f"{unsolved} not solved within the budget (not plotted)")
    fig.suptitle("N-goal equilibria: exact values (filled: certified by the checker"
                 + ("; " + "; ".join(notes) if notes else "") + ")", fontsize=10)
    rows_of_legend = -(-len(labels) // 5)
    fig.tight_layout(rect=(0, 0.05 * rows_of_legend + 0.02, 1, 1))
    return fig


@dataclass(frozen=True)
class ValueRow:
    """One game of the value-only series: N goals, a prior, ``V``, ``U_bar``, ``VoI`` (exact);
    ``exact`` is false where ``V`` is only the coalition DP's upper bound."""

    map_name: str
    n_goals: int
    prior_kind: str
    prior: tuple[Fraction, ...]
    value: Fraction
    complete: Fraction
    voi: Fraction
    layers: int
    seconds: float
    exact: bool = True


def value_series(start: Cell, goals: Sequence[Cell], value: Valuer, *, map_name: str = "map",
                 max_goals: int = MAX_GOALS,
                 progress: Callable[[ValueRow], None] | None = None) -> list[ValueRow]:
    """The value and VoI for ``N = 2 … len(goals)`` goals with equal and skewed priors.

    Examples
    --------
    A valuer that knows one game only (the command line passes the checker's):

    >>> def value(start, goals, prior):
    ...     return GameValue(Fraction(5, 2), Fraction(4), True, 3)
    >>> [(r.n_goals, r.prior_kind, str(r.value), str(r.voi)) for r in
    ...  value_series((2, 0), [(0, 3), (2, 3)], value)]
    [(2, 'equal', '5/2', '3/8'), (2, 'skewed', '5/2', '3/8')]
    """
    def row(n: int, kind: str, prior: tuple[Fraction, ...]) -> ValueRow:
        t0 = time.perf_counter()
        v = value(start, goals[:n], prior)
        return ValueRow(map_name, n, kind, prior, v.value, v.complete,
                        (v.complete - v.value) / v.complete, v.layers, time.perf_counter() - t0,
                        v.exact)

    return _series(min(len(goals), max_goals), row, progress)


def value_csv(rows: Sequence[ValueRow]) -> str:
    """The value-only rows as CSV (exact numbers as ``p/q``; ``V_exact`` true or false).

    Examples
    --------
    >>> row = ValueRow("t", 2, "equal", (Fraction(1, 2),) * 2, Fraction(5, 2), Fraction(4),
    ...                Fraction(3, 8), 3, 0.0)
    >>> print(value_csv([row]), end="")
    map,n_goals,prior_kind,prior,V,U_bar,VoI,layers,V_exact
    t,2,equal,1/2 1/2,5/2,4,3/8,3,true
    """
    return _csv(("map", "n_goals", "prior_kind", "prior", "V", "U_bar", "VoI", "layers",
                 "V_exact"),
                ((r.map_name, r.n_goals, r.prior_kind, " ".join(map(str, r.prior)), r.value,
                  r.complete, r.voi, r.layers, "true" if r.exact else "false") for r in rows))


def value_figure(rows: Sequence[ValueRow], title: str) -> Any:
    """The value-only series: one map, ``V`` and ``Ū`` (left) and the VoI (right); several
    maps, the VoI per prior, a line per map. A value not proved is a hollow marker.

    Examples
    --------
    >>> row = ValueRow("t", 2, "equal", (Fraction(1, 2),) * 2, Fraction(5, 2), Fraction(4),
    ...                Fraction(3, 8), 3, 0.0)
    >>> len(value_figure([row], "t").axes)
    2
    """
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
