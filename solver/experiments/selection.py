"""``dpp experiment goal-selection``: what choosing its goal gains the Attacker, over the maps of
the density sweep (proofs/SELECT.md).

For each grid of the sweep (:func:`solver.experiments.sampling.sample_grid`, the same grids as
``dpp experiment density`` for the same seed): the paper's value at its prior ``b = (3/5,
2/5)`` (the paper's σ*, :func:`~solver.twogoal.equilibrium.paper_equilibrium`), the
goal-selection value ``V_sel`` with the choice ``q*`` and the mixture weight ``α``
(:func:`~solver.selection.equilibrium.selection_equilibrium`, from the exact guarantee sets:
another route), and the gain ``V(b) − V_sel``. Two checks on every map: ``V_sel <= V(b)``
(SELECT.1) and ``V(1/2) = M/2 >= V_sel`` with ``V_sel = min(d1, d2, M/2)`` (SELECT.8), where
``V(1/2)`` is again the paper's construction.
"""

from __future__ import annotations

import statistics
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from dppio.text import decimal
from solver.experiments.density import DensityConfig
from solver.experiments.density import rows_to_csv as density_csv
from solver.experiments.sampling import sample_grid
from solver.game.instance import Instance
from solver.selection.equilibrium import selection_equilibrium
from solver.selection.instance import SelectionInstance
from solver.twogoal.equilibrium import paper_equilibrium


@dataclass(frozen=True)
class SelectionRow:
    """One map: exact values as ``p/q`` strings (``q1``: the choice's weight on g1)."""

    density: int
    sample: int
    obstacles: int
    d1: str
    d2: str
    M: str
    V_prior: str
    V_half: str
    V_sel: str
    q1: str
    alpha: str
    gain: str
    gain_float: float


CSV_FIELDS = tuple(SelectionRow.__dataclass_fields__)


def _row(config: DensityConfig, density: int, k: int) -> SelectionRow:
    grid = sample_grid(config.size, density, k, config.seed, config.start, config.goals)
    at_prior = Instance.from_grid(grid.blocked, config.start, config.goals, config.prior)
    at_half = Instance.from_grid(grid.blocked, config.start, config.goals, ("1/2", "1/2"))
    uniform = Instance(at_half.network, at_half.start, at_half.goals, ("1/2", "1/2"))
    eq = selection_equilibrium(SelectionInstance(uniform, (Fraction(0), Fraction(0))),
                               rule="mixture")
    assert eq.mixture is not None
    v_prior = paper_equilibrium(at_prior).U
    v_half = paper_equilibrium(at_half).U
    return SelectionRow(density, k, int(grid.blocked.sum()), str(eq.mixture.d1),
                        str(eq.mixture.d2), str(eq.mixture.M), str(v_prior), str(v_half),
                        str(eq.value), str(eq.choice[0]), str(eq.mixture.alpha),
                        str(v_prior - eq.value), float(v_prior - eq.value))


def selection_rows(config: DensityConfig, progress: Callable[[int], None] | None = None
                   ) -> list[SelectionRow]:
    """Every map of the sweep, in (density, sample) order.

    Examples
    --------
    >>> cfg = DensityConfig(size=4, start=(3, 0), goals=((0, 3), (0, 0)), densities=(0,),
    ...                     samples=1)
    >>> r = selection_rows(cfg)[0]
    >>> r.d1, r.d2, r.M, r.V_prior, r.V_sel, r.q1, r.alpha, r.gain
    ('6', '3', '6', '18/5', '3', '1/4', '0', '3/5')
    """
    rows = []
    for d in config.densities:
        for k in range(config.samples):
            rows.append(_row(config, d, k))
            if progress is not None:
                progress(1)
    return rows


@dataclass(frozen=True)
class SelectionSummary:
    """Per density: the means of ``V(b)``, ``V_sel`` and the gain, how often choosing gains
    anything, the choices (``other``: a tie, the barycentre of an interval of optimal choices,
    SELECT.3), and the two checks of every map."""

    by_density: dict[int, dict[str, Any]]
    maps: int
    checks_hold: bool
    violations: list[str]

    def text(self) -> str:
        """The text ``dpp experiment goal-selection`` prints."""
        lines = [f"goal selection on {self.maps} maps of the density sweep (b = 3/5 on g1 for "
                 "the paper's value V(b)):", "density  maps  mean V(b)  mean V_sel  mean gain  "
                 "gain > 0  q* = 1/2  q* = g1  q* = g2  other q*"]
        for d, s in self.by_density.items():
            lines.append(f"{d:>6}%  {s['maps']:>4}  {decimal(s['mean_V_prior']):>9}  "
                         f"{decimal(s['mean_V_sel']):>10}  {decimal(s['mean_gain']):>9}  "
                         f"{s['gain_positive']:>8}  {s['q_half']:>8}  {s['q_g1']:>7}  "
                         f"{s['q_g2']:>7}  {s['q_other']:>8}")
        lines.append("checks on every map: V_sel <= V(b) and V_sel = min(d1, d2, M/2) with "
                     "V(1/2) = M/2 from the paper's construction: "
                     + ("hold" if self.checks_hold else f"FAIL ({'; '.join(self.violations[:3])})"))
        return "\n".join(lines)

    def to_json(self) -> dict[str, Any]:
        """The summary as JSON (densities as string keys)."""
        return {"maps": self.maps, "checks_hold": self.checks_hold,
                "violations": self.violations,
                "by_density": {str(d): s for d, s in self.by_density.items()}}


def summarize_selection(rows: Iterable[SelectionRow]) -> SelectionSummary:
    """The summary of the sweep's rows, and the two checks on every map.

    Examples
    --------
    >>> cfg = DensityConfig(size=4, start=(3, 0), goals=((0, 3), (0, 0)), densities=(0,),
    ...                     samples=2)
    >>> s = summarize_selection(selection_rows(cfg))
    >>> s.checks_hold, s.by_density[0]["maps"], s.by_density[0]["gain_positive"]
    (True, 2, 2)
    """
    groups: dict[int, list[SelectionRow]] = {}
    violations: list[str] = []
    for r in rows:
        groups.setdefault(r.density, []).append(r)
        d1, d2, m, vb, vh, vs = (Fraction(x) for x in (r.d1, r.d2, r.M, r.V_prior, r.V_half,
                                                       r.V_sel))
        if not (vs <= vb and vh == m / 2 and vs == min(d1, d2, m / 2)):
            violations.append(f"density {r.density} sample {r.sample}")
    out: dict[int, dict[str, Any]] = {}
    for d, rs in groups.items():
        def mean(key: str, rs: Sequence[SelectionRow] = rs) -> float:
            return statistics.fmean(float(Fraction(getattr(r, key))) for r in rs)
        out[d] = {"maps": len(rs), "mean_V_prior": mean("V_prior"), "mean_V_sel": mean("V_sel"),
                  "mean_gain": mean("gain"),
                  "max_gain": max(float(Fraction(r.gain)) for r in rs),
                  "gain_positive": sum(Fraction(r.gain) > 0 for r in rs),
                  "q_half": sum(Fraction(r.q1) == Fraction(1, 2) for r in rs),
                  "q_g1": sum(Fraction(r.q1) == 1 for r in rs),
                  "q_g2": sum(Fraction(r.q1) == 0 for r in rs),
                  "q_other": sum(Fraction(r.q1) not in (0, Fraction(1, 2), 1) for r in rs)}
    return SelectionSummary(out, sum(len(rs) for rs in groups.values()), not violations,
                            violations)


def rows_to_csv(rows: Sequence[SelectionRow]) -> str:
    """The rows as CSV text (header :data:`CSV_FIELDS`; the density sweep's writer).

    Examples
    --------
    >>> row = SelectionRow(0, 0, 0, "6", "3", "6", "18/5", "3", "3", "1/4", "0", "3/5", 0.6)
    >>> print(rows_to_csv([row]), end="")
    density,sample,obstacles,d1,d2,M,V_prior,V_half,V_sel,q1,alpha,gain,gain_float
    0,0,0,6,3,6,18/5,3,3,1/4,0,3/5,0.6
    """
    return density_csv(rows, CSV_FIELDS)
