"""Figures of the paper's Sec. VII with matplotlib (Agg backend): PNG, SVG or PDF by suffix.

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
from fractions import Fraction
from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
from matplotlib import patheffects
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.ticker import MaxNLocator

from dppio.files import write_files
from solver.errors import DPPError, InvalidInstanceError, OutputError
from solver.instance import Instance
from solver.network import GridLabels
from solver.pairs import LABELS, PAIRS, PairEvaluator

__all__ = ["PHASE_COLOURS", "STRATEGY_COLOURS", "plot_beliefs", "plot_map", "plot_voi",
           "save_figure"]

PHASE_COLOURS = {1: "#E69F00", 2: "#CC79A7", 3: "#56B4E9"}
"""Phase I (σ* = 1 along ξ²) orange, phase II (belief 1/2) pink, phase III sky blue — in every
figure (map segments, beliefs-plot bands). No strategy uses these colours."""
STRATEGY_COLOURS = {"gamma*": "#009E73", "ambiguity": "#0072B2", "exaggeration": "#8C510A"}
"""One colour per Attacker strategy in every figure: γ* green, ambiguity blue, exaggeration
brown. The Defender is told apart by the fill (σ* solid, σ' hatched) in the VoI plot."""
DEFENDER_HATCH = {"sigma*": "", "sigma'": "///"}
MARKER_COLOUR = "#222222"
FORMATS = ("png", "svg", "pdf")
"""Output formats, chosen by the file's suffix."""
VOI = "value of information"
"""Spelled out: in the figures' one font (DejaVu Sans) "VoI" reads as "Vol"."""
_STYLE: dict[Any, Any] = {"font.family": "DejaVu Sans", "font.size": 12, "axes.titlesize": 13,
          "axes.labelsize": 12, "legend.fontsize": 11, "xtick.labelsize": 11,
          "ytick.labelsize": 11, "mathtext.fontset": "dejavusans", "pdf.fonttype": 42,
          "svg.fonttype": "none"}
"""One font family for text and mathtext (DejaVu Sans); fonts embedded as TrueType."""
LARGE_MAP = 60
"""Maps with more cells than this on a side get the print rendering: paths of a fixed width
with a white casing, start and goal markers of a fixed size on top, lighter obstacles."""
PATH_STYLES = {"xi1_I": "-", "xi1_II": (0, (4, 1.5)), "xi1": "-", "xi2": (0, (1, 1.2))}
"""One line style per equilibrium path in every figure: ξ^{1,I} solid, ξ^{1,II} dashed, ξ²
dotted (colour says the Attacker's strategy, the line style which path)."""
_PHASE_NAMES = {1: "I", 2: "II", 3: "III"}


def _tex(label: str) -> str:
    """Mathtext for a path label: ``xi1_II`` -> ξ^{1,II}, ``xi2_am`` -> ξ^{2,am}, ``xi1`` -> ξ¹.

    >>> print(_tex("xi1_II"), _tex("xi1"), _tex("t"))
    $\\xi^{1,\\mathrm{II}}$ $\\xi^{1}$ t
    """
    head, _, tail = label.partition("_")
    if not head.startswith("xi"):
        return label
    sup = head[2:] + (r",\mathrm{" + tail + "}" if tail else "")
    return rf"$\xi^{{{sup}}}$"


T_I, T_II = r"$t_{\mathrm{I}}$", r"$t_{\mathrm{II}}$"
"""The phase boundaries t_I, t_II as mathtext (subscripts, never a literal underscore)."""


def _num(x: Any) -> str:
    """A number for a title or legend: exact fractions with a 3-digit decimal, floats rounded.

    >>> from fractions import Fraction
    >>> _num(Fraction(5, 22)), _num(0.20410018838561994), _num(Fraction(17)), _num(3)
    ('5/22 ≈ 0.227', '0.204', '17', '3')
    """
    if isinstance(x, Fraction):
        if x.denominator == 1:
            return str(x.numerator)
        return f"{x} ≈ {float(x):.3f}" if x.denominator <= 1000 else f"{float(x):.3f}"
    if isinstance(x, int | np.integer):
        return str(int(x))
    return f"{float(x):.3g}"


def save_figure(fig: Figure, out: str | Path) -> list[Path]:
    """Write ``fig`` to ``out`` in the format its suffix names (``.png``, ``.svg``, ``.pdf``).

    A name without one of these suffixes is refused (one file per ``-o``: ``fig.pdf`` is
    written as PDF, never as ``fig.pdf.png``). Missing parent directories are created; the
    figure is closed afterwards.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    out : str or Path
        The file to write.

    Returns
    -------
    list of Path
        The file written (a one-element list).

    Raises
    ------
    DPPError
        If the suffix is missing or not one of :data:`FORMATS`.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     fig, ax = plt.subplots()
    ...     _ = ax.plot([0, 1], [1, 0])
    ...     files = save_figure(fig, Path(d) / "figs" / "demo.pdf")
    ...     print([f.name for f in files], files[0].read_bytes()[:4])
    ...     print(sorted(p.name for p in (Path(d) / "figs").iterdir()))
    ['demo.pdf'] b'%PDF'
    ['demo.pdf']
    >>> plt.fignum_exists(fig.number)
    False
    >>> save_figure(plt.figure(), "figure")
    Traceback (most recent call last):
    ...
    solver.errors.DPPError: figure: the output file must end in .png, .svg or .pdf
    """
    if str(out) == "":
        raise OutputError("-o/--output: the output path is empty")
    p = Path(out)
    fmt = p.suffix.lower().lstrip(".")
    if fmt not in FORMATS:
        plt.close(fig)
        raise DPPError(f"{p}: the output file must end in .png, .svg or .pdf")
    buf = io.BytesIO()
    try:
        fig.savefig(buf, format=fmt, dpi=150, bbox_inches="tight")
    finally:
        plt.close(fig)
    write_files({p: buf.getvalue()})  # atomic; missing folders are created
    return [p]


def _grid(instance: Instance) -> np.ndarray:
    """The obstacle array of a grid instance: a ``.map`` grid, or an instance JSON whose node
    ids are all ``[row, col]`` cells (as ``dpp solve --save-instance`` writes them); cells
    without a node are obstacles."""
    labels = instance.network.labels
    if isinstance(labels, GridLabels):
        return labels.blocked
    cells = [n for n in labels if isinstance(n, tuple) and len(n) == 2
             and all(isinstance(x, int | np.integer) and not isinstance(x, bool) and x >= 0
                     for x in n)]
    if not cells or len(cells) != len(labels):
        raise InvalidInstanceError("map figures need a grid instance: a --map grid, or an "
                                   "instance JSON whose node ids are [row, col] cells (dpp "
                                   "solve --map ... --save-instance FILE writes one)")
    rc = np.asarray(cells, dtype=np.int64)
    h, w = int(rc[:, 0].max()) + 1, int(rc[:, 1].max()) + 1
    if h * w > 16 * len(cells) + 1024:
        raise InvalidInstanceError(f"the grid's cells span {h}x{w} but only {len(cells)} "
                                   "are nodes: not a grid map")
    blocked = np.ones((h, w), dtype=bool)
    blocked[rc[:, 0], rc[:, 1]] = False
    return blocked


def _xy(nodes: Sequence[Hashable], offset: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    rc = np.asarray([list(n) for n in nodes], dtype=np.float64)  # type: ignore[call-overload]
    return rc[:, 1] + offset, rc[:, 0] + offset


def _cell_points(ax: Axes, shape: tuple[int, ...]) -> float:
    """The size of one grid cell in points (for line widths and markers)."""
    fig = ax.get_figure(root=True)
    assert fig is not None
    width_in = ax.get_position().width * fig.get_figwidth()
    return 72.0 * width_in / max(shape)


def _large(shape: tuple[int, ...]) -> bool:
    return max(shape) > LARGE_MAP


def _casing(lw: float) -> list[Any]:
    """A white casing under a path, so it stands out from obstacles at print size."""
    return [patheffects.Stroke(linewidth=lw + 2.2, foreground="white"), patheffects.Normal()]


def _draw_grid(ax: Axes, instance: Instance) -> list[Line2D]:
    """Grid, obstacles and the start/goal markers; legend handles.

    Small maps: markers of about a cell UNDER the paths (a one-step phase stays visible).
    Large maps (:data:`LARGE_MAP`): lighter obstacles and markers of a fixed print size
    with a white edge ON TOP of the paths, so start and goals are seen at print size.
    """
    blocked = _grid(instance)
    h, w = blocked.shape
    large = _large(blocked.shape)
    ax.imshow(blocked, cmap="Greys", vmin=0, vmax=2.2 if large else 1.4, origin="upper",
              extent=(-0.5, w - 0.5, h - 0.5, -0.5), interpolation="nearest")
    if max(h, w) <= 40:
        ax.set_xticks(np.arange(-0.5, w, 1), minor=True)
        ax.set_yticks(np.arange(-0.5, h, 1), minor=True)
        ax.grid(which="minor", color="#cccccc", linewidth=0.5)
    ax.tick_params(which="minor", length=0)
    ax.xaxis.set_major_locator(MaxNLocator(5, integer=True))
    ax.yaxis.set_major_locator(MaxNLocator(5, integer=True))
    ax.set_xlim(-0.5, w - 0.5)
    ax.set_ylim(h - 0.5, -0.5)
    ax.set_xlabel("column")
    ax.set_ylabel("row")
    ms = 13.0 if large else float(np.clip(0.7 * _cell_points(ax, (h, w)), 5, 18))
    s, g1, g2 = instance.start, instance.primary, instance.secondary
    handles = []
    for node, marker, face, name in ((s, "o", "white", "start $s_0$"),
                                     (g1, "s", MARKER_COLOUR, f"$g_1$ (prior {instance.b1})"),
                                     (g2, "s", "white", f"$g_2$ (prior {instance.b2})")):
        if large:  # a white halo, then the marker, above every path
            ax.plot(node[1], node[0], marker=marker, ms=ms + 5, mfc="white",  # type: ignore[index]
                    mec="white", zorder=9, clip_on=False)
        ax.plot(node[1], node[0], marker=marker, ms=ms, mfc=face,  # type: ignore[index]
                mec=MARKER_COLOUR, mew=2, zorder=10 if large else 2, clip_on=False)
        handles.append(Line2D([], [], marker=marker, ms=11, mfc=face, mec=MARKER_COLOUR,
                              mew=2, ls="none", label=name))
    return handles


def _common(a: Sequence[Hashable], b: Sequence[Hashable]) -> int:
    n = 0
    for x, y in zip(a, b, strict=False):
        if x != y:
            break
        n += 1
    return n


def _legend_below(ax: Axes, handles: list[Any], ncol: int = 2) -> None:
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=ncol,
              frameon=False, handlelength=2.6, columnspacing=1.2)


def plot_map(instance: Instance, *, baselines: bool = True,
             game: PairEvaluator | None = None) -> Figure:
    """Equilibrium paths on the grid (ξ² coloured by phase, the primary's branches with their
    probabilities in the legend), and with ``baselines`` the ambiguity / exaggeration paths
    in a second panel. No label is drawn on the grid, so none can cover a path; start and
    goal markers lie under the paths, so even a one-step phase stays visible.

    Examples
    --------
    >>> from solver.experiments.compare import paper10_instance
    >>> fig = plot_map(paper10_instance())
    >>> print(len(fig.axes), fig.axes[0].get_title().splitlines()[0])
    2 (σ*, γ*): $t_{\\mathrm{I}}$ = 6, $t_{\\mathrm{II}}$ = 16, T = 17
    """
    with plt.rc_context(_STYLE):
        return _plot_map(instance, baselines, game or PairEvaluator.of(instance))


def _plot_map(instance: Instance, baselines: bool, game: PairEvaluator) -> Figure:
    eq = game.equilibrium
    ncols = 2 if baselines else 1
    fig, axes = plt.subplots(1, ncols, figsize=(5.4 * ncols, 6.9), squeeze=False)
    ax = axes[0][0]
    markers = _draw_grid(ax, instance)
    shape = _grid(instance).shape
    large = _large(shape)
    cell = _cell_points(ax, shape)
    lw = 2.6 if large else float(np.clip(0.16 * cell, 1.5, 7))
    casing = _casing(lw) if large else None
    xi2 = eq.secondary_path
    x, y = _xy(xi2)
    phases = eq.phases
    handles: list[Any] = []
    for ph, first, last in ((1, 1, phases.t_I), (2, phases.t_I + 1, phases.t_II),
                            (3, phases.t_II + 1, phases.T)):
        if first > last:
            continue
        ax.plot(x[first - 1:last + 1], y[first - 1:last + 1], color=PHASE_COLOURS[ph], lw=lw,
                solid_capstyle="round", solid_joinstyle="round", zorder=4,
                path_effects=casing)
        steps = f"step {first}" if first == last else f"steps {first}-{last}"
        handles.append(Line2D([], [], color=PHASE_COLOURS[ph], lw=6,
                              label=f"{_tex('xi2')} phase {_PHASE_NAMES[ph]} ({steps})"))
    for k, p in enumerate(eq.primary_paths):
        n = _common(p.nodes, xi2)
        label = f"{_tex(p.label)}, p = {p.probability}"
        ls = PATH_STYLES.get(p.label, "-")
        if n >= len(p.nodes):
            handles.append(Line2D([], [], color="none", label=f"{label} (= {_tex('xi2')})"))
            continue
        bx, by = _xy(p.nodes[n - 1:], 0.0 if large else 0.14 * (1 if k % 2 else -1))
        ax.plot(bx, by, color=STRATEGY_COLOURS["gamma*"], lw=0.75 * lw, ls=ls, zorder=5,
                path_effects=_casing(0.75 * lw) if large else None)
        ax.plot(bx[0], by[0], "D", color=STRATEGY_COLOURS["gamma*"], mec="black", ms=8,
                zorder=6)
        handles.append(Line2D([], [], color=STRATEGY_COLOURS["gamma*"], lw=3, ls=ls,
                              marker="D", ms=7, mec="black", label=f"{label} (branch)"))
    ax.set_title(f"(σ*, γ*): {T_I} = {phases.t_I}, {T_II} = {phases.t_II}, T = {phases.T}\n"
                 f"{VOI} {_num(eq.VoI)}")
    _legend_below(ax, handles + markers)
    if baselines:
        ax2 = axes[0][1]
        markers2 = _draw_grid(ax2, instance)
        bl: list[Any] = []
        for j, kind in enumerate(("ambiguity", "exaggeration")):
            att = game.attacker(kind)
            for theta, mp in ((1, att.primary[0]), (2, att.secondary[0])):
                off = 0.0 if large else -0.2 + 0.13 * (2 * j + theta - 1)
                bx, by = _xy(list(mp.nodes), off)
                ls = "-" if theta == 1 else "--"
                ax2.plot(bx, by, color=STRATEGY_COLOURS[kind], lw=0.75 * lw if large else 0.6 * lw,
                         ls=ls, zorder=4 + j,
                         path_effects=_casing(0.75 * lw) if large else None)
                tag = "am" if kind == "ambiguity" else "ex"
                bl.append(Line2D([], [], color=STRATEGY_COLOURS[kind], lw=3, ls=ls,
                                 label=f"{_tex(f'xi{theta}_{tag}')} {kind}, "
                                       f"{len(mp.walk) - 1} steps"))
        vo = {r.attacker: r.VoI for r in game.compare((("sigma*", "ambiguity"),
                                                       ("sigma*", "exaggeration")))}
        ax2.set_title(f"baselines against σ*, {VOI}:\nambiguity {_num(vo['ambiguity'])}, "
                      f"exaggeration {_num(vo['exaggeration'])}")
        _legend_below(ax2, bl + markers2)
    fig.tight_layout()
    return fig


def _phase_bands(ax: Axes, phases: Any) -> None:
    for ph, lo, hi in ((1, 0, phases.t_I), (2, phases.t_I, phases.t_II),
                       (3, phases.t_II, phases.T)):
        if hi > lo:
            ax.axvspan(lo, hi, color=PHASE_COLOURS[ph], alpha=0.18, lw=0, zorder=0)
    for t in sorted({phases.t_I, phases.t_II}):
        ax.axvline(t, color="#555555", lw=1, ls=(0, (2, 2)), zorder=1)


def plot_beliefs(instance: Instance, *, defender: str = "sigma*",
                 game: PairEvaluator | None = None) -> Figure:
    """Per type (columns): the belief ``b^1_t`` along each path (top; Bayes under γ* for the
    equilibrium paths, Dragan's belief, eq. (17), for the baselines) and the cumulative expected
    allocation to the true goal under ``defender`` (bottom). The phases of ξ² are shaded in
    their colours and ``t_I``, ``t_II`` marked; time ticks are integers.

    Examples
    --------
    >>> from solver.experiments.compare import paper10_instance
    >>> fig = plot_beliefs(paper10_instance())
    >>> print(len(fig.axes), *[t.get_text() for t in fig.axes[0].texts])
    4 $t_{\\mathrm{I}}$ $t_{\\mathrm{II}}$
    """
    with plt.rc_context(_STYLE):
        return _plot_beliefs(instance, defender, game or PairEvaluator.of(instance))


def _plot_beliefs(instance: Instance, defender: str, game: PairEvaluator) -> Figure:
    fig, axes = plt.subplots(2, 2, figsize=(10.5, 8.4), sharex=True)
    net = instance.network
    phases = game.equilibrium.phases
    dist = {1: game.d_from_start[game.g1], 2: game.d_from_start[game.g2]}
    entries: dict[str, Any] = {}
    for attacker in ("gamma*", "ambiguity", "exaggeration"):
        ev = game.evaluate(defender, attacker)
        for tr in ev.trajectories:
            col = tr.theta - 1
            steps = np.arange(len(tr.nodes))
            if attacker == "gamma*":
                belief = [float(b) for b in tr.belief_g1]
            else:
                belief = [float(b) for b in game.observer.beliefs(tr.walk)]
            ls = PATH_STYLES.get(tr.label, "-") if attacker == "gamma*" else "-"
            # γ* wide underneath, the baselines narrow on top: equal curves stay visible
            eq_path = attacker == "gamma*"
            kw: dict[str, Any] = {"ls": ls, "lw": 5.0 if eq_path else 2.2,
                                  "color": STRATEGY_COLOURS[attacker],
                                  "zorder": 3 if eq_path else 4}
            axes[0][col].plot(steps, belief, **kw)
            axes[1][col].plot(steps, [float(a) for a in tr.allocation], **kw)
            name = (f"{_tex(tr.label)} (γ*, p = {tr.probability})" if attacker == "gamma*"
                    else f"{attacker} (Dragan belief)")
            entries.setdefault(name, Line2D([], [], **kw, label=name))
    for col, theta in ((0, 1), (1, 2)):
        goal = "$g_1$" if theta == 1 else "$g_2$"
        for r in (0, 1):
            _phase_bands(axes[r][col], phases)
            axes[r][col].grid(alpha=0.3)
            axes[r][col].xaxis.set_major_locator(MaxNLocator(integer=True))
        top = axes[0][col]
        top.set_ylim(-0.04, 1.22)
        top.set_title(f"type {theta}: true goal {goal}")
        marks = ([(phases.t_I, T_I), (phases.t_II, T_II)] if phases.t_II != phases.t_I
                 else [(phases.t_I, f"{T_I} = {T_II}")])  # no phase II: one mark
        for t, name in marks:
            top.text(t, 1.2, name, ha="center", va="top", fontsize=12,
                     bbox={"fc": "white", "ec": "none", "pad": 1}, zorder=2)
        d = float(net.numbers.convert(dist[theta]))
        axes[1][col].axhline(d, color="black", lw=1.2, ls=":")
        axes[1][col].set_xlabel("time step t")
    axes[0][0].set_ylabel("belief in $g_1$")
    axes[1][0].set_ylabel("expected allocation\nto the true goal")
    entries["d"] = Line2D([], [], color="black", lw=1.2, ls=":",
                          label="$d(s_0,$ true goal$)$")
    present = {1: phases.t_I > 0, 2: phases.t_II > phases.t_I, 3: phases.T > phases.t_II}
    bands = [Patch(fc=PHASE_COLOURS[ph], alpha=0.35,
                   label=f"phase {_PHASE_NAMES[ph]} of {_tex('xi2')}")
             for ph in (1, 2, 3) if present[ph]]
    fig.suptitle(f"Beliefs and cumulative expected allocation, Defender "
                 f"{LABELS.get(defender, defender)}")
    fig.tight_layout(rect=(0, 0.13, 1, 1))
    fig.legend(handles=[*entries.values(), *bands], loc="lower center", ncol=3,
               frameon=False, bbox_to_anchor=(0.5, 0.0), handlelength=2.4)
    return fig


def plot_voi(rows: Iterable[Mapping[str, Any] | Any],
             pairs: Sequence[tuple[str, str]] = PAIRS) -> Figure:
    """Box plots of VoI by density, one box per strategy pair (means as '+'): colour = the
    Attacker's strategy, hatching = the Defender σ'.

    Examples
    --------
    >>> rows = [{"density": d, "defender": "sigma*", "attacker": "gamma*", "VoI_float": v}
    ...         for d, v in ((0, 0.25), (0, 0.25), (10, 0.2), (10, 0.3))]
    >>> fig = plot_voi(rows, pairs=[("sigma*", "gamma*")])
    >>> len(fig.axes)
    1
    """
    with plt.rc_context(_STYLE):
        return _plot_voi(rows, pairs)


def _plot_voi(rows: Iterable[Mapping[str, Any] | Any],
              pairs: Sequence[tuple[str, str]]) -> Figure:
    data: dict[tuple[int, tuple[str, str]], list[float]] = {}
    for r in rows:
        rec = r if isinstance(r, Mapping) else vars(r)
        key = (int(rec["density"]), (str(rec["defender"]), str(rec["attacker"])))
        data.setdefault(key, []).append(float(rec["VoI_float"]))
    densities = sorted({d for d, _ in data})
    if not densities:
        raise InvalidInstanceError("no rows to plot")
    pairs = [p for p in pairs if any((d, p) in data for d in densities)]
    fig, ax = plt.subplots(figsize=(max(7.0, 1.4 * len(densities)), 6.2))
    width = 0.84 / len(pairs)
    for j, pair in enumerate(pairs):
        pos = [i + (j - (len(pairs) - 1) / 2) * width for i, d in enumerate(densities)
               if (d, pair) in data]
        vals = [data[(d, pair)] for d in densities if (d, pair) in data]
        colour = STRATEGY_COLOURS.get(pair[1], "#888888")
        hatch = DEFENDER_HATCH.get(pair[0], "..")
        flat = [(x, v[0]) for x, v in zip(pos, vals, strict=True) if min(v) == max(v)]
        if flat:  # a box of equal values collapses to a line: draw a square instead
            fx, fy = zip(*flat, strict=True)
            ax.plot(fx, fy, ls="none", marker="s", ms=9, mew=1.6, mec=colour,
                    mfc="white" if hatch else colour, zorder=3)
        ax.boxplot(vals, positions=pos, widths=width * 0.85, patch_artist=True,
                   showmeans=True, meanprops={"marker": "+", "markeredgecolor": "black",
                                              "markersize": 8},
                   boxprops={"facecolor": "white" if hatch else colour, "edgecolor": colour,
                             "hatch": hatch, "linewidth": 1.6},
                   whiskerprops={"color": colour}, capprops={"color": colour},
                   medianprops={"color": "black", "linewidth": 1.6},
                   flierprops={"marker": "o", "markersize": 3, "alpha": 0.5,
                               "markeredgecolor": colour})
    ax.set_xticks(range(len(densities)), [f"{d}%" for d in densities])
    ax.set_xlabel("obstacle density")
    ax.set_ylabel(f"{VOI} $(\\bar{{U}} - U)\\,/\\,\\bar{{U}}$")
    ax.axhline(0, color="grey", lw=0.8)
    ax.grid(axis="y", alpha=0.3)
    counts = sorted({len(data.get((d, pairs[0]), [])) for d in densities})
    n = str(counts[0]) if len(counts) == 1 else "-".join(map(str, (counts[0], counts[-1])))
    ax.set_title(f"{VOI.capitalize()} by obstacle density ({n} grids each)")
    attackers = [a for a in STRATEGY_COLOURS if any(p[1] == a for p in pairs)]
    defenders = [d for d in DEFENDER_HATCH if any(p[0] == d for p in pairs)]
    handles: list[Any] = [Patch(fc=STRATEGY_COLOURS[a], ec=STRATEGY_COLOURS[a],
                     label=f"Attacker {LABELS[a]}") for a in attackers]
    # the Defender as the boxes show it: σ* filled, σ' white and hatched
    handles += [Patch(fc="white" if DEFENDER_HATCH[d] else "#999999", ec="#555555",
                      hatch=DEFENDER_HATCH[d] or None, label=f"Defender {LABELS[d]}")
                for d in defenders]
    handles += [Line2D([], [], ls="none", marker="+", ms=9, mec="black", label="mean"),
                Line2D([], [], color="black", lw=1.6, label="median"),
                Line2D([], [], ls="none", marker="s", ms=9, mfc="#999999", mec="#555555",
                       label="all grids equal")]
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.13),
              ncol=3, frameon=False)
    fig.tight_layout()
    return fig
