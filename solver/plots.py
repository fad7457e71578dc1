"""Figures of the paper's Sec. VII with matplotlib (Agg backend): PNG and SVG.

- :func:`plot_map` — the grid, obstacles, start and goals, the equilibrium paths with ξ²
  coloured by phase and the primary's branches labelled with their mixing probabilities
  (like Fig. 7), and beside them the ambiguity and exaggeration paths;
- :func:`plot_beliefs` — per type, the belief ``b^1_t`` along each path and the cumulative
  expected allocation to the true goal (like Fig. 8);
- :func:`plot_voi` — VoI box plots by density and strategy pair (like Fig. 9).
"""

from __future__ import annotations

import io
from collections.abc import Hashable, Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from solver.errors import InvalidInstanceError, OutputError
from solver.instance import Instance
from solver.io_utils import write_files
from solver.network import GridLabels
from solver.pairs import PAIRS, PairEvaluator

__all__ = ["PHASE_COLOURS", "plot_beliefs", "plot_map", "plot_voi", "save_figure"]

PHASE_COLOURS = {1: "#e69f00", 2: "#8e44ad", 3: "#0072b2"}
"""Phase I (σ* = 1 along ξ²) orange, phase II (belief 1/2) purple, phase III blue."""
G1_COLOUR, G2_COLOUR = "#d62728", "#1f5fbf"
PAIR_COLOURS = {("sigma*", "gamma*"): "#2ca02c", ("sigma'", "gamma*"): "#98df8a",
                ("sigma*", "ambiguity"): "#9467bd", ("sigma*", "exaggeration"): "#ff7f0e",
                ("sigma'", "ambiguity"): "#c5b0d5", ("sigma'", "exaggeration"): "#ffbb78"}
_SYM = {"sigma*": "σ*", "sigma'": "σ'", "gamma*": "γ*", "ambiguity": "am",
        "exaggeration": "ex"}


_PATH_COLOURS = {"xi1_I": "#2ca02c", "xi1_II": "#17becf", "xi1": "#2ca02c", "xi2": "#2ca02c",
                 "xi1_am": "#9467bd", "xi2_am": "#9467bd", "xi1_ex": "#ff7f0e",
                 "xi2_ex": "#ff7f0e"}


def _tex(label: str) -> str:
    """Mathtext for a path label: ``xi1_II`` -> ξ^{1,II}, ``xi2_am`` -> ξ^{2,am}."""
    head, _, tail = label.partition("_")
    if not head.startswith("xi"):
        return label
    sup = head[2:] + (r",\mathrm{" + tail + "}" if tail else "")
    return rf"$\xi^{{{sup}}}$"


def save_figure(fig: Figure, out: str | Path) -> list[Path]:
    """Write ``fig``: to ``out`` if it ends in ``.png`` or ``.svg``, else to ``out.png`` and
    ``out.svg``. Returns the files written.

    The files are written together or not at all (:func:`solver.io_utils.write_files`:
    missing folders are created); the figure is closed afterwards.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    out : str or Path
        The file, or a stem for both formats.

    Returns
    -------
    list of Path

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     fig, ax = plt.subplots()
    ...     _ = ax.plot([0, 1], [1, 0])
    ...     files = save_figure(fig, Path(d) / "figs" / "demo")
    ...     print([f.name for f in files], all(f.stat().st_size > 0 for f in files))
    ...     print([f.name for f in save_figure(plt.figure(), Path(d) / "one.svg")])
    ['demo.png', 'demo.svg'] True
    ['one.svg']
    >>> plt.fignum_exists(fig.number)
    False
    """
    if str(out) == "":
        raise OutputError("-o/--output: the output path is empty")
    p = Path(out)
    targets = [p] if p.suffix.lower() in (".png", ".svg") else [
        p.with_name(p.name + ".png"), p.with_name(p.name + ".svg")]
    rendered: dict[Path, bytes] = {}
    try:
        for t in targets:
            buf = io.BytesIO()
            fig.savefig(buf, format=t.suffix[1:].lower(), dpi=110, bbox_inches="tight")
            rendered[t] = buf.getvalue()
    finally:
        plt.close(fig)
    write_files(rendered)  # all formats or none
    return targets


def _grid(instance: Instance) -> np.ndarray:
    labels = instance.network.labels
    if not isinstance(labels, GridLabels):
        raise InvalidInstanceError("map figures need a grid instance (a .map file)")
    return labels.blocked


def _xy(nodes: Sequence[Hashable], offset: tuple[float, float] = (0.0, 0.0)
        ) -> tuple[np.ndarray, np.ndarray]:
    rc = np.asarray([list(n) for n in nodes], dtype=np.float64)  # type: ignore[call-overload]
    return rc[:, 1] + float(offset[0]), rc[:, 0] + float(offset[1])


def _draw_grid(ax: Axes, instance: Instance) -> None:
    blocked = _grid(instance)
    h, w = blocked.shape
    ax.imshow(blocked, cmap="Greys", vmin=0, vmax=1.25, origin="upper",
              extent=(-0.5, w - 0.5, h - 0.5, -0.5))
    ax.set_xticks(np.arange(-0.5, w, 1), minor=True)
    ax.set_yticks(np.arange(-0.5, h, 1), minor=True)
    ax.grid(which="minor", color="#bbbbbb", linewidth=0.4)
    ax.tick_params(which="minor", length=0)
    step = max(1, w // 10)
    ax.set_xticks(range(0, w, step))
    ax.set_yticks(range(0, h, step))
    ax.set_xlabel("column")
    ax.set_ylabel("row")
    s = instance.start
    ax.plot(s[1], s[0], "o", ms=13, mfc="#2ca02c", mec="black", zorder=6)  # type: ignore[index]
    ax.annotate("s0", (s[1], s[0]), ha="center", va="center", fontsize=7,  # type: ignore[index]
                color="white", weight="bold", zorder=7)
    for goal, colour, name in ((instance.primary, G1_COLOUR, "g1"),
                               (instance.secondary, G2_COLOUR, "g2")):
        ax.plot(goal[1], goal[0], marker="s", ms=14, mfc=colour, mec="black",  # type: ignore[index]
                zorder=6)
        ax.annotate(name, (goal[1], goal[0]), ha="center", va="center", fontsize=7,  # type: ignore[index]
                    color="white", weight="bold", zorder=7)


def _common(a: Sequence[Hashable], b: Sequence[Hashable]) -> int:
    n = 0
    for x, y in zip(a, b, strict=False):
        if x != y:
            break
        n += 1
    return n


def plot_map(instance: Instance, *, baselines: bool = True,
             game: PairEvaluator | None = None) -> Figure:
    """Equilibrium paths on the grid (ξ² coloured by phase, branches with probabilities),
    and with ``baselines`` the ambiguity / exaggeration paths in a second panel.

    Examples
    --------
    >>> from solver.experiments.compare import paper10_instance
    >>> fig = plot_map(paper10_instance())
    >>> len(fig.axes)
    2
    """
    game = game or PairEvaluator.of(instance)
    eq = game.equilibrium
    fig, axes = plt.subplots(1, 2 if baselines else 1, figsize=(13 if baselines else 7, 6.4),
                             squeeze=False)
    ax = axes[0][0]
    _draw_grid(ax, instance)
    xi2 = eq.secondary_path
    handles: list[Line2D] = []
    x, y = _xy(xi2)
    seen: set[int] = set()
    names = {1: "phase I", 2: "phase II", 3: "phase III"}
    for t in range(1, len(xi2)):
        ph = eq.phases.phase_of_step(t)
        ax.plot(x[t - 1:t + 1], y[t - 1:t + 1], color=PHASE_COLOURS[ph], lw=4,
                solid_capstyle="round", zorder=3)
        if ph not in seen:
            seen.add(ph)
            handles.append(Line2D([], [], color=PHASE_COLOURS[ph], lw=4,
                                  label=f"{_tex('xi2')} {names[ph]} (type 2, p = 1)"))
    styles = ["--", ":"]
    for k, p in enumerate(eq.primary_paths):
        n = _common(p.nodes, xi2)
        label = _tex(p.label)
        if n >= len(p.nodes):
            handles.append(Line2D([], [], color="none",
                                  label=f"{label} = {_tex('xi2')} (type 1, p = {p.probability})"))
            continue
        bx, by = _xy(p.nodes[n - 1:], (0.12 * (k + 1) - 0.18, 0.12 * (k + 1) - 0.18))
        ax.plot(bx, by, color=G1_COLOUR, lw=2.4, ls=styles[k % 2], zorder=4)
        ax.plot(bx[0], by[0], "D", color="black", ms=7, zorder=5)
        ax.annotate(f"{label}: p = {p.probability}", (bx[0], by[0]),
                    xytext=(8, 10 - 22 * k), textcoords="offset points", fontsize=9,
                    bbox={"boxstyle": "round", "fc": "white", "alpha": 0.85}, zorder=8)
        handles.append(Line2D([], [], color=G1_COLOUR, lw=2.4, ls=styles[k % 2],
                              label=f"{label}: {_tex('xi2')}[0..{n - 1}] + shortest path to g1 "
                                    f"(type 1, p = {p.probability})"))
    phases = eq.phases
    ax.set_title(f"Equilibrium (σ*, γ*): t_I = {phases.t_I}, t_II = {phases.t_II}, "
                 f"T = {phases.T}, "
                 f"VoI* = {eq.VoI} (≈{float(eq.VoI):.3f})", fontsize=10)
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.1), fontsize=8,
              ncol=1, frameon=False)
    if baselines:
        ax2 = axes[0][1]
        _draw_grid(ax2, instance)
        bl: list[Line2D] = []
        for j, kind in enumerate(("ambiguity", "exaggeration")):
            att = game.attacker(kind)
            for theta, mp, colour in ((1, att.primary[0], G1_COLOUR),
                                      (2, att.secondary[0], G2_COLOUR)):
                off = (-0.15 + 0.1 * (2 * j + theta - 1),) * 2
                bx, by = _xy(list(mp.nodes), off)
                ls = "-" if kind == "ambiguity" else "--"
                ax2.plot(bx, by, color=colour, lw=2.2, ls=ls, zorder=3 + j)
                tag = "am" if kind == "ambiguity" else "ex"
                bl.append(Line2D([], [], color=colour, lw=2.2, ls=ls,
                                 label=f"{_tex(f'xi{theta}_{tag}')} ({kind}, type {theta}, "
                                       f"{len(mp.walk) - 1} steps)"))
        vo = {r.attacker: r.VoI for r in game.compare((("sigma*", "ambiguity"),
                                                       ("sigma*", "exaggeration")))}
        ax2.set_title(f"Dragan baselines (eq. (18)): VoI vs σ*: ambiguity "
                      f"{float(vo['ambiguity']):.3f}, exaggeration "
                      f"{float(vo['exaggeration']):.3f}", fontsize=10)
        ax2.legend(handles=bl, loc="upper center", bbox_to_anchor=(0.5, -0.1), fontsize=8,
                   ncol=1, frameon=False)
    fig.suptitle(f"start {instance.start}, g1 = {instance.primary} (prior {instance.b1}), "
                 f"g2 = {instance.secondary} (prior {instance.b2})", fontsize=11)
    return fig


def plot_beliefs(instance: Instance, *, defender: str = "sigma*",
                 game: PairEvaluator | None = None) -> Figure:
    """Per type (columns): the belief ``b^1_t`` along each path (top; Bayes under γ* for the
    equilibrium paths, Dragan's belief, eq. (17), for the baselines) and the cumulative expected
    allocation to the true goal under ``defender`` (bottom).

    Examples
    --------
    >>> from solver.experiments.compare import paper10_instance
    >>> fig = plot_beliefs(paper10_instance())
    >>> len(fig.axes)
    4
    """
    game = game or PairEvaluator.of(instance)
    fig, axes = plt.subplots(2, 2, figsize=(12, 7.5), sharex="col")
    net = instance.network
    dist = {1: game.d_from_start[game.g1], 2: game.d_from_start[game.g2]}
    styles = {"gamma*": "-", "ambiguity": "--", "exaggeration": ":"}
    for attacker in ("gamma*", "ambiguity", "exaggeration"):
        ev = game.evaluate(defender, attacker)
        for tr in ev.trajectories:
            theta = tr.theta
            col = theta - 1
            steps = np.arange(len(tr.nodes))
            if attacker == "gamma*":
                belief = [float(b) for b in tr.belief_g1]
                source = "Bayes, γ*"
            else:
                belief = [float(b) for b in game.observer.beliefs(tr.walk)]
                source = "Dragan eq. (17)"
            name = _tex(tr.label)
            prob = f", p = {tr.probability}" if attacker == "gamma*" else ""
            colour = _PATH_COLOURS.get(tr.label, "#7f7f7f")
            kw = {"ls": styles[attacker], "lw": 2, "marker": "o", "ms": 2.5, "color": colour}
            axes[0][col].plot(steps, belief, label=f"{name} ({source}{prob})", **kw)
            axes[1][col].plot(steps, [float(a) for a in tr.allocation],
                              label=f"{name}: total cost {float(tr.cost):.4g}", **kw)
    for col, theta in ((0, 1), (1, 2)):
        goal = "g1" if theta == 1 else "g2"
        axes[0][col].axhline(0.5, color="grey", lw=0.8, ls="-.")
        axes[0][col].set_ylim(-0.03, 1.03)
        axes[0][col].set_ylabel("belief b¹_t (g1 is true)")
        axes[0][col].set_title(f"type {theta} (true goal {goal})")
        d = float(net.numbers.convert(dist[theta]))
        axes[1][col].axhline(d, color="grey", lw=0.8, ls="-.",
                             label=f"d(s0, {goal}) = {d:g} (complete information)")
        axes[1][col].set_ylabel(f"cumulative expected allocation to {goal}")
        axes[1][col].set_xlabel("time step t")
        for r in (0, 1):
            axes[r][col].legend(fontsize=7.5, loc="best")
            axes[r][col].grid(alpha=0.3)
    fig.suptitle(f"Beliefs and expected allocation under {_SYM.get(defender, defender)} "
                 "(allocation excludes the terminal cost)", fontsize=11)
    fig.tight_layout()
    return fig


def plot_voi(rows: Iterable[Mapping[str, Any] | Any],
             pairs: Sequence[tuple[str, str]] = PAIRS) -> Figure:
    """Box plots of VoI by density, one box per strategy pair (means as '+').

    Examples
    --------
    >>> rows = [{"density": d, "defender": "sigma*", "attacker": "gamma*", "VoI_float": v}
    ...         for d, v in ((0, 0.25), (0, 0.25), (10, 0.2), (10, 0.3))]
    >>> fig = plot_voi(rows, pairs=[("sigma*", "gamma*")])
    >>> len(fig.axes)
    1
    """
    data: dict[tuple[int, tuple[str, str]], list[float]] = {}
    for r in rows:
        rec = r if isinstance(r, Mapping) else vars(r)
        key = (int(rec["density"]), (str(rec["defender"]), str(rec["attacker"])))
        data.setdefault(key, []).append(float(rec["VoI_float"]))
    densities = sorted({d for d, _ in data})
    if not densities:
        raise InvalidInstanceError("no rows to plot")
    pairs = [p for p in pairs if any((d, p) in data for d in densities)]
    fig, ax = plt.subplots(figsize=(max(7, 1.1 * len(densities) * len(pairs) / 3), 5))
    width = 0.8 / len(pairs)
    for j, pair in enumerate(pairs):
        pos = [i + (j - (len(pairs) - 1) / 2) * width for i, d in enumerate(densities)
               if (d, pair) in data]
        vals = [data[(d, pair)] for d in densities if (d, pair) in data]
        colour = PAIR_COLOURS.get(pair, "#888888")
        ax.boxplot(vals, positions=pos, widths=width * 0.85, patch_artist=True,
                   showmeans=True, meanprops={"marker": "+", "markeredgecolor": "black",
                                              "markersize": 7},
                   boxprops={"facecolor": colour}, medianprops={"color": "black"},
                   flierprops={"marker": "o", "markersize": 2.5, "alpha": 0.5})
    ax.set_xticks(range(len(densities)), [f"{d}%" for d in densities])
    ax.set_xlabel("obstacle density")
    ax.set_ylabel("VoI = (Ū − U) / Ū")
    ax.axhline(0, color="grey", lw=0.8)
    ax.grid(axis="y", alpha=0.3)
    n = {d: len(data.get((d, pairs[0]), [])) for d in densities}
    ax.set_title("VoI by obstacle density and strategy pair "
                 f"(samples per density: {', '.join(str(n[d]) for d in densities)}; "
                 "+ = mean, line = median)", fontsize=10)
    ax.legend(handles=[plt.Rectangle((0, 0), 1, 1, fc=PAIR_COLOURS.get(p, "#888888"),
                                     ec="black", label=f"({_SYM[p[0]]}, {_SYM[p[1]]})")
                       for p in pairs], fontsize=8, loc="upper center",
              bbox_to_anchor=(0.5, -0.13), ncol=min(6, len(pairs)), frameon=False)
    fig.tight_layout()
    return fig
