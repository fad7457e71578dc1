"""The goal-selection figure: ``V(q)`` against the prior ``q`` of g1 with its minimum ``V_sel``
marked, and the gain of choosing over the paper's prior, by obstacle density
(proofs/SELECT.md; ``dpp experiment goal-selection``)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from fractions import Fraction
from typing import Any

import matplotlib.pyplot as plt
from matplotlib.figure import Figure

from solver.errors import InvalidInstanceError
from solver.plots.style import MARKER_COLOUR, STYLE
from solver.selection.mixture import minimising_choices, value_curve

PRIOR = Fraction(3, 5)
"""The paper's prior of g1, marked on the curves."""


def plot_selection(rows: Sequence[Any], *, per_density: int = 1) -> Figure:
    """Left: ``V(q)`` of the first ``per_density`` maps of each density, the minimum ``V_sel``
    as a filled dot at the choice ``q*`` (a flat minimum shaded: every choice on it is
    optimal), the paper's ``V(3/5)`` as an open one. Right: the gain ``V(3/5) − V_sel`` by
    density (box plots, means as '+').

    ``rows``: records with the attributes (or keys) of
    :class:`solver.experiments.selection.SelectionRow`: ``density``, ``d1``, ``d2``, ``M``,
    ``V_sel``, ``V_prior``, ``q1``, ``gain_float``.

    Examples
    --------
    >>> row = {"density": 0, "d1": "18", "d2": "17", "M": "25", "V_prior": "68/5",
    ...        "V_sel": "25/2", "q1": "1/2", "gain_float": 1.1}
    >>> len(plot_selection([row]).axes)
    2
    """
    if not rows:
        raise InvalidInstanceError("no rows to plot")
    with plt.rc_context(STYLE):
        return _plot(rows, per_density)


def _record(r: Any) -> Mapping[str, Any]:
    return r if isinstance(r, Mapping) else vars(r)


def _plot(rows_in: Sequence[Any], per_density: int) -> Figure:
    rows = [_record(r) for r in rows_in]
    densities = sorted({int(r["density"]) for r in rows})
    cmap = plt.get_cmap("viridis")
    colour = {d: cmap(0.85 * i / max(1, len(densities) - 1)) for i, d in enumerate(densities)}
    fig, (left, right) = plt.subplots(1, 2, figsize=(12.0, 5.0),
                                      gridspec_kw={"width_ratios": [1.35, 1]})
    for d in densities:
        for i, r in enumerate([r for r in rows if int(r["density"]) == d][:per_density]):
            d1, d2, m, v = (Fraction(r[k]) for k in ("d1", "d2", "M", "V_sel"))
            qs = [k / 200 for k in range(201)]
            label = f"{d} % obstacles" if i == 0 else None
            left.plot(qs, value_curve(d1, d2, m, qs), color=colour[d], lw=1.8, label=label)
            q1, vsel = float(Fraction(r["q1"])), float(v)
            lo, hi = (float(x) for x in minimising_choices(d1, d2, m, v))
            if hi > lo:  # a flat minimum: every choice on it is optimal (q* its midpoint)
                left.plot([lo, hi], [vsel, vsel], color=colour[d], lw=6, alpha=0.35,
                          solid_capstyle="round")
            left.plot([q1], [vsel], "o", color=colour[d], ms=8, mec=MARKER_COLOUR, mew=0.8,
                      zorder=5)
            left.plot([float(PRIOR)], [float(Fraction(r["V_prior"]))], "o", mfc="white",
                      mec=colour[d], mew=1.6, ms=7, zorder=5)
    left.axvline(float(PRIOR), color="#888888", ls=":", lw=1.2)
    left.text(float(PRIOR) - 0.01, 0.97, "paper's prior 3/5", transform=left.get_xaxis_transform(),
              color="#555555", fontsize=10, ha="right", va="top")
    left.plot([], [], "o", color="#999999", mec=MARKER_COLOUR, label=r"minimum $V_{\mathrm{sel}}$")
    left.plot([], [], "o", mfc="white", mec="#555555", label=r"$V(3/5)$")
    left.set_xlim(0, 1)
    left.set_xlabel(r"prior $q$ of the goal $g^1$ (top right)")
    left.set_ylabel(r"game value $V(q)$ (Defender's guarantee)")
    left.set_title("the value against the prior; the Attacker picks its minimum")
    handles, labels = left.get_legend_handles_labels()
    left.grid(alpha=0.25)
    gains = [[float(r["gain_float"]) for r in rows if int(r["density"]) == d]
             for d in densities]
    box = right.boxplot(gains, patch_artist=True, widths=0.6, showmeans=True,
                        meanprops={"marker": "+", "markeredgecolor": MARKER_COLOUR,
                                   "markersize": 9},
                        medianprops={"color": MARKER_COLOUR})
    for patch, d in zip(box["boxes"], densities, strict=True):
        patch.set_facecolor(colour[d])
        patch.set_alpha(0.75)
    right.set_xticks(range(1, len(densities) + 1), [f"{d} %" for d in densities])
    right.set_xlabel("obstacle density")
    right.set_ylabel(r"gain of choosing $V(3/5) - V_{\mathrm{sel}}$")
    right.set_title(f"what choosing gains the Attacker ({len(rows)} maps)")
    right.grid(axis="y", alpha=0.25)
    fig.legend(handles, labels, loc="lower center", ncol=min(7, len(labels)), frameon=False,
               fontsize=10, bbox_to_anchor=(0.5, 0.0))
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    return fig
