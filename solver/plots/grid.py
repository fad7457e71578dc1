"""The map figures: the equilibrium walks on the grid (:func:`plot_map`, like the paper's
Fig. 7) and the beliefs and allocations along them (:func:`plot_beliefs`, like Fig. 8)."""

from __future__ import annotations

from collections.abc import Hashable, Sequence
from typing import Any, cast

import matplotlib.pyplot as plt
import numpy as np
from matplotlib import patheffects
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.ticker import MaxNLocator

from dppio.text import count
from solver.errors import InvalidInstanceError
from solver.game.instance import Instance
from solver.graph.network import GridLabels
from solver.literature.strategy_pairs import LABELS, PairEvaluator
from solver.plots.style import (
    LARGE_MAP,
    LARGE_MARKER,
    MARKER_COLOUR,
    PATH_STYLES,
    PHASE_COLOURS,
    STRATEGY_COLOURS,
    STYLE,
    T_I,
    T_II,
    VOI,
    num_label,
    tex_label,
)

_PHASE_NAMES = {1: "I", 2: "II", 3: "III"}


def grid_array(instance: Any) -> np.ndarray:
    """The obstacle array of a grid instance: a ``.map`` grid, or an instance JSON whose node
    ids are all ``[row, col]`` cells (as ``dpp solve --save-instance`` writes them); cells
    without a node are obstacles.

    Examples
    --------
    >>> from solver.experiments.compare import paper10_instance
    >>> blocked = grid_array(paper10_instance())
    >>> blocked.shape, int(blocked.sum())
    ((10, 10), 16)
    """
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


def _cell(node: Hashable) -> tuple[int, int]:
    """A grid node id: the cell ``(row, col)``."""
    return cast("tuple[int, int]", node)


def _xy(nodes: Sequence[Hashable], offset: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    rc = np.asarray([_cell(n) for n in nodes], dtype=np.float64)
    return rc[:, 1] + offset, rc[:, 0] + offset


def grid_cell_points(ax: Axes, shape: tuple[int, ...]) -> float:
    """The size of one grid cell in points (for line widths and markers).

    Examples
    --------
    >>> fig, ax = plt.subplots(figsize=(4, 4))
    >>> bool(grid_cell_points(ax, (10, 10)) > 0)
    True
    >>> plt.close(fig)
    """
    fig = ax.get_figure(root=True)
    assert fig is not None
    width_in = ax.get_position().width * fig.get_figwidth()
    return 72.0 * width_in / max(shape)


def large_map(shape: tuple[int, ...]) -> bool:
    """Whether a grid gets the print rendering (:data:`~solver.plots.style.LARGE_MAP`).

    Examples
    --------
    >>> large_map((10, 10)), large_map((256, 256))
    (False, True)
    """
    return max(shape) > LARGE_MAP




def _casing(lw: float) -> list[Any]:
    """A white casing under a path, so it stands out from obstacles at print size."""
    return [patheffects.Stroke(linewidth=lw + 2.2, foreground="white"), patheffects.Normal()]


def draw_grid_background(ax: Axes, instance: Any) -> np.ndarray:
    """The grid of ``instance`` (anything with a grid ``network``): obstacles, cell lines on
    small maps, integer ticks, and the axes' limits with room for the corner markers.

    On a large map the start and goal markers have a fixed print size, many cells wide: the
    limits leave that much room around the grid, so a marker in a corner stays inside the
    frame (it covered the ``0`` tick labels and reached the next panel's title).

    Returns
    -------
    numpy.ndarray
        The obstacle array (True = blocked).

    Examples
    --------
    >>> from solver.experiments.compare import paper10_instance
    >>> fig, ax = plt.subplots()
    >>> draw_grid_background(ax, paper10_instance()).shape, tuple(map(float, ax.get_xlim()))
    ((10, 10), (-0.5, 9.5))
    >>> plt.close(fig)
    """
    blocked = grid_array(instance)
    h, w = blocked.shape
    large = large_map(blocked.shape)
    ax.imshow(blocked, cmap="Greys", vmin=0, vmax=2.2 if large else 1.4, origin="upper",
              extent=(-0.5, w - 0.5, h - 0.5, -0.5), interpolation="nearest")
    if max(h, w) <= 40:
        ax.set_xticks(np.arange(-0.5, w, 1), minor=True)
        ax.set_yticks(np.arange(-0.5, h, 1), minor=True)
        ax.grid(which="minor", color="#cccccc", linewidth=0.5)
    ax.tick_params(which="minor", length=0)
    ax.xaxis.set_major_locator(MaxNLocator(5, integer=True))
    ax.yaxis.set_major_locator(MaxNLocator(5, integer=True))
    ax.set_xlabel("column")
    ax.set_ylabel("row")
    ax.set_xlim(-0.5, w - 0.5)
    ax.set_ylim(h - 0.5, -0.5)
    if large:  # half a haloed marker (LARGE_MARKER + 5 points) of room on every side
        pad = 0.5 * (LARGE_MARKER + 5) / grid_cell_points(ax, (h, w))
        ax.set_xlim(-0.5 - pad, w - 0.5 + pad)
        ax.set_ylim(h - 0.5 + pad, -0.5 - pad)
    return blocked


def _draw_grid(ax: Axes, instance: Instance) -> list[Line2D]:
    """Grid, obstacles and the start/goal markers; legend handles.

    Small maps: markers of about a cell UNDER the paths (a one-step phase stays visible).
    Large maps (:data:`LARGE_MAP`): lighter obstacles and markers of a fixed print size
    with a white edge ON TOP of the paths, so start and goals are seen at print size; the
    axes leave room for them (:func:`draw_grid_background`).
    """
    blocked = draw_grid_background(ax, instance)
    h, w = blocked.shape
    large = large_map(blocked.shape)
    ms = LARGE_MARKER if large else float(np.clip(0.7 * grid_cell_points(ax, (h, w)), 5, 18))
    s, g1, g2 = instance.start, instance.primary, instance.secondary
    handles = []
    for node, marker, face, name in ((s, "o", "white", "start $s_0$"),
                                     (g1, "s", MARKER_COLOUR, f"$g_1$ (prior {instance.b1})"),
                                     (g2, "s", "white", f"$g_2$ (prior {instance.b2})")):
        row, col = _cell(node)
        if large:  # a white halo, then the marker, above every path
            ax.plot(col, row, marker=marker, ms=ms + 5, mfc="white", mec="white", zorder=9)
        ax.plot(col, row, marker=marker, ms=ms, mfc=face,
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

    Parameters
    ----------
    instance : Instance
        A two-goal grid game (node ids ``(row, col)``).
    baselines : bool
        Also draw the literature's ambiguity and exaggeration paths, in a second panel.
    game : PairEvaluator, optional
        The instance's evaluator, when the caller has one already (else built here).

    Returns
    -------
    matplotlib.figure.Figure
        The figure (write it with :func:`save_figure`).

    Examples
    --------
    >>> from solver.experiments.compare import paper10_instance
    >>> fig = plot_map(paper10_instance())
    >>> print(len(fig.axes), fig.axes[0].get_title().splitlines()[0])
    2 (σ*, γ*): $t_{\\mathrm{I}}$ = 6, $t_{\\mathrm{II}}$ = 16, T = 17
    """
    with plt.rc_context(STYLE):
        return _plot_map(instance, baselines, game or PairEvaluator.of(instance))


def _plot_map(instance: Instance, baselines: bool, game: PairEvaluator) -> Figure:
    eq = game.equilibrium
    ncols = 2 if baselines else 1
    fig, axes = plt.subplots(1, ncols, figsize=(5.4 * ncols, 6.9), squeeze=False)
    ax = axes[0][0]
    markers = _draw_grid(ax, instance)
    shape = grid_array(instance).shape
    large = large_map(shape)
    cell = grid_cell_points(ax, shape)
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
                              label=f"{tex_label('xi2')} phase {_PHASE_NAMES[ph]} ({steps})"))
    branched = False
    for k, p in enumerate(eq.primary_paths):
        n = _common(p.nodes, xi2)
        label = f"{tex_label(p.label)}, p = {p.probability}"
        ls = PATH_STYLES.get(p.label, "-")
        if n >= len(p.nodes):
            handles.append(Line2D([], [], color="none", label=f"{label} (= {tex_label('xi2')})"))
            continue
        bx, by = _xy(p.nodes[n - 1:], 0.0 if large else 0.14 * (1 if k % 2 else -1))
        ax.plot(bx, by, color=STRATEGY_COLOURS["gamma*"], lw=0.75 * lw, ls=ls, zorder=5,
                path_effects=_casing(0.75 * lw) if large else None)
        ax.plot(bx[0], by[0], "D", color=STRATEGY_COLOURS["gamma*"], mec="black", ms=8,
                zorder=6)
        # no marker on the handle: it would hide the dash pattern (ξ^{1,II} drawn solid)
        handles.append(Line2D([], [], color=STRATEGY_COLOURS["gamma*"], lw=2.2, ls=ls,
                              label=f"{label} (branch)"))
        branched = True
    ax.set_title(f"(σ*, γ*): {T_I} = {phases.t_I}, {T_II} = {phases.t_II}, T = {phases.T}\n"
                 f"{VOI} {num_label(eq.VoI)}")
    if branched:
        handles.append(Line2D([], [], color=STRATEGY_COLOURS["gamma*"], marker="D", ms=7,
                              mec="black", ls="none",
                              label=f"where a branch leaves {tex_label('xi2')}"))
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
                                 label=f"{tex_label(f'xi{theta}_{tag}')} {kind}, "
                                       f"{count(len(mp.walk) - 1, 'step')}"))
        vo = {r.attacker: r.VoI for r in game.compare((("sigma*", "ambiguity"),
                                                       ("sigma*", "exaggeration")))}
        ax2.set_title(f"baselines against σ*, {VOI}:\nambiguity {num_label(vo['ambiguity'])}, "
                      f"exaggeration {num_label(vo['exaggeration'])}")
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

    Parameters
    ----------
    instance : Instance
        A two-goal grid game.
    defender : str
        The Defender whose allocations are drawn (``"sigma*"`` or ``"sigma'"``).
    game : PairEvaluator, optional
        The instance's evaluator, when the caller has one already (else built here).

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> from solver.experiments.compare import paper10_instance
    >>> fig = plot_beliefs(paper10_instance())
    >>> print(len(fig.axes), *[t.get_text() for t in fig.axes[0].texts])
    4 $t_{\\mathrm{I}}$ $t_{\\mathrm{II}}$
    """
    with plt.rc_context(STYLE):
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
            name = (f"{tex_label(tr.label)} (γ*, p = {tr.probability})" if attacker == "gamma*"
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
                   label=f"phase {_PHASE_NAMES[ph]} of {tex_label('xi2')}")
             for ph in (1, 2, 3) if present[ph]]
    fig.suptitle(f"Beliefs and cumulative expected allocation, Defender "
                 f"{LABELS.get(defender, defender)}")
    fig.tight_layout(rect=(0, 0.13, 1, 1))
    fig.legend(handles=[*entries.values(), *bands], loc="lower center", ncol=3,
               frameon=False, bbox_to_anchor=(0.5, 0.0), handlelength=2.4)
    return fig
