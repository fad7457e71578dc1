"""The N-goal map figure: each type's equilibrium walks on the grid, and the Defender's σ
along them (:func:`plot_ngoal_map`, what ``dpp plot map`` draws for three goals or more).

Left: the grid with the start, the goals (one colour per goal, the same colour for the type
walking to it) and every walk of the profile, coloured by its type, the most probable walk of
a type solid and the others dashed; walks the types share are drawn side by side on small
maps. Right: one panel per type, along its most probable walk, the Defender's distribution σ
over the goals after each step (the guarantee rule, stacked, in the goals' colours), so one
sees where the Defender guards the type's own goal and where it is deceived.
"""

from __future__ import annotations

from collections.abc import Hashable, Sequence
from typing import TYPE_CHECKING, Any, cast

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.ticker import MaxNLocator

from dppio.text import count
from solver.plots.grid import draw_grid_background, grid_cell_points, large_map
from solver.plots.style import GOAL_COLOURS, MARKER_COLOUR, STYLE, VOI, num_label

if TYPE_CHECKING:
    from solver.coalitions.construction import CoalitionEquilibrium



def _cell(labels: Sequence[Hashable], v: int) -> tuple[int, int]:
    """Node ``v``'s grid cell ``(row, col)``."""
    return cast("tuple[int, int]", labels[v])


def _walk_xy(cells: Sequence[tuple[int, int]], offset: float) -> tuple[np.ndarray, np.ndarray]:
    rc = np.asarray(cells, dtype=np.float64)
    return rc[:, 1] + offset, rc[:, 0] + offset


def plot_ngoal_map(eq: CoalitionEquilibrium) -> Figure:
    """The walks of an N-goal equilibrium on its grid and the Defender's σ along them.

    Parameters
    ----------
    eq : CoalitionEquilibrium
        :func:`solver.coalitions.construction.coalition_equilibrium` on a grid game (node ids
        ``(row, col)``).

    Returns
    -------
    matplotlib.figure.Figure
        The map (left) and one σ panel per type (right).

    Examples
    --------
    >>> from solver.formats.movingai import read_map
    >>> from solver.coalitions.construction import coalition_equilibrium
    >>> from solver.game.instance import Instance
    >>> from solver.experiments.compare import paper10_path
    >>> game = Instance.from_grid(read_map(paper10_path()), (9, 0), [(0, 9), (0, 0), (9, 9)],
    ...                           ["1/2", "1/3", "1/6"])
    >>> fig = plot_ngoal_map(coalition_equilibrium(game))
    >>> len(fig.axes), fig.axes[1].get_title()
    (4, 'type 1: goal $g^1$ (0, 9), prior 1/2; walk p = 2/3')
    """
    with plt.rc_context(STYLE):
        return _plot(eq)


def _plot(eq: CoalitionEquilibrium) -> Figure:
    game = eq.instance
    n = game.n_goals
    labels = game.network.labels
    fig = plt.figure(figsize=(11.5, max(6.9, 1.9 * n + 1.6)))
    grid = fig.add_gridspec(n, 2, width_ratios=(1.15, 1), hspace=0.55, wspace=0.22)
    ax = fig.add_subplot(grid[:, 0])
    blocked = draw_grid_background(ax, game)
    shape = blocked.shape
    large = large_map(shape)
    cell = grid_cell_points(ax, shape)
    lw = 2.4 if large else float(np.clip(0.14 * cell, 1.3, 6))
    handles: list[Any] = []
    for theta in range(n):
        colour = GOAL_COLOURS[theta]
        offset = 0.0 if large else (theta - (n - 1) / 2) * min(0.5 / n, 0.14)
        for k, (walk, _) in enumerate(eq.mixtures[theta]):
            x, y = _walk_xy([_cell(labels, v) for v in walk], offset)
            ax.plot(x, y, color=colour, lw=lw if k == 0 else 0.7 * lw,
                    ls="-" if k == 0 else (0, (3, 1.5)), zorder=4 + (n - theta) * 0.01,
                    solid_capstyle="round", solid_joinstyle="round")
        walks = len(eq.mixtures[theta])
        handles.append(Line2D([], [], color=colour, lw=4,
                              label=f"type {theta + 1} ({count(walks, 'walk')}), "
                                    f"U = {num_label(eq.costs[theta])}"))
    ms = 13.0 if large else float(np.clip(0.7 * cell, 5, 16))
    markers = [(game.s0, "o", "white", "start $s_0$")]
    markers += [(g, "s", GOAL_COLOURS[t], f"$g^{t + 1}$ (prior {game.prior[t]})")
                for t, g in enumerate(game.targets)]
    for node, marker, face, name in markers:
        row, col = _cell(labels, node)
        ax.plot(col, row, marker=marker, ms=ms, mfc=face, mec=MARKER_COLOUR, mew=2,
                zorder=10)
        handles.append(Line2D([], [], marker=marker, ms=10, mfc=face, mec=MARKER_COLOUR,
                              mew=2, ls="none", label=name))
    ax.set_title(f"N = {n} goals: U = {num_label(eq.U)}, Ū = {num_label(eq.U_bar)}\n"
                 f"{VOI} {num_label(eq.VoI)}")
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=2,
              frameon=False, handlelength=2.2, columnspacing=1.0)
    for theta in range(n):
        _sigma_panel(fig.add_subplot(grid[theta, 1]), eq, theta)
    fig.axes[-1].set_xlabel("step t along the type's most probable walk")
    fig.legend(handles=[Patch(fc=GOAL_COLOURS[t], label=f"σ on $g^{t + 1}$") for t in range(n)],
               loc="upper center", bbox_to_anchor=(0.74, 0.995), ncol=min(n, 5),
               frameon=False, handlelength=1.4, columnspacing=0.9, fontsize=10)
    fig.subplots_adjust(left=0.06, right=0.98, top=0.9, bottom=0.2)
    return fig


def _sigma_panel(ax: Any, eq: CoalitionEquilibrium, theta: int) -> None:
    """σ after each step of type ``theta``'s most probable walk, stacked over the goals."""
    game = eq.instance
    walk, p = eq.mixtures[theta][0]
    sig = eq.defender_along(walk)
    steps = np.arange(1, len(walk))
    bottom = np.zeros(len(sig))
    for g in range(game.n_goals):
        share = np.array([float(s[g]) for s in sig])
        ax.bar(steps, share, bottom=bottom, width=1.0, color=GOAL_COLOURS[g], lw=0,
               align="center")
        bottom += share
    ax.set_ylim(0, 1)
    ax.set_xlim(0.5, max(len(walk) - 0.5, 1.5))
    ax.set_yticks([0, 0.5, 1])
    ax.xaxis.set_major_locator(MaxNLocator(6, integer=True))
    ax.tick_params(labelsize=9)
    ax.set_ylabel("σ", fontsize=10)
    cell = game.network.labels[game.targets[theta]]
    mixed = "" if p == 1 else f"; walk p = {p}"
    ax.set_title(f"type {theta + 1}: goal $g^{theta + 1}$ {cell}, prior "
                 f"{game.prior[theta]}{mixed}", fontsize=10)
