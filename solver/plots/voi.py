"""VoI box plots by obstacle density and strategy pair (like the paper's Fig. 9)."""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from typing import Any

import matplotlib.pyplot as plt
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from solver.errors import InvalidInstanceError
from solver.literature.strategy_pairs import FIGURE_LABELS, LABELS, PAIRS
from solver.plots.style import DEFENDER_HATCH, STRATEGY_COLOURS, STYLE, VOI


def plot_voi(rows: Iterable[Mapping[str, Any] | Any],
             pairs: Sequence[tuple[str, str]] = PAIRS) -> Figure:
    """Box plots of VoI by density, one box per strategy pair (means as '+'): colour = the
    Attacker's strategy, hatching = the Defender σ'.

    Parameters
    ----------
    rows : iterable of mappings or density rows
        The sweep's rows (``density``, ``defender``, ``attacker``, ``VoI_float``).
    pairs : sequence of (str, str)
        The (Defender, Attacker) pairs, one box each per density.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> rows = [{"density": d, "defender": "sigma*", "attacker": "gamma*", "VoI_float": v}
    ...         for d, v in ((0, 0.25), (0, 0.25), (10, 0.2), (10, 0.3))]
    >>> fig = plot_voi(rows, pairs=[("sigma*", "gamma*")])
    >>> len(fig.axes)
    1
    """
    with plt.rc_context(STYLE):
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
                     label=f"Attacker {FIGURE_LABELS[a]}") for a in attackers]
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
