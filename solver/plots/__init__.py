"""Figures of the paper's Sec. VII with matplotlib (Agg backend): PNG, SVG or PDF by suffix.

- :func:`plot_map` — the grid, obstacles, start and goals, the equilibrium paths with ξ²
  coloured by phase and the primary's branches labelled with their mixing probabilities
  (like Fig. 7), and beside them the ambiguity and exaggeration paths;
- :func:`plot_beliefs` — per type, the belief ``b^1_t`` along each path and the cumulative
  expected allocation to the true goal (like Fig. 8);
- :func:`plot_voi` — VoI box plots by density and strategy pair (like Fig. 9);
- :func:`plot_ngoal_map` — an N-goal equilibrium: each type's walks on the grid and the
  Defender's σ along them.
"""

import matplotlib

matplotlib.use("Agg")  # before any module of this package imports pyplot

from solver.plots.goal_walks import plot_ngoal_map
from solver.plots.grid import plot_beliefs, plot_map
from solver.plots.style import PATH_STYLES, PHASE_COLOURS, STRATEGY_COLOURS, save_figure
from solver.plots.voi import plot_voi

__all__ = ["PATH_STYLES", "PHASE_COLOURS", "STRATEGY_COLOURS", "plot_beliefs", "plot_map",
           "plot_ngoal_map", "plot_voi", "save_figure"]
