"""The paper's Section VII experiments: the comparison table and the obstacle-density sweep."""

from solver.experiments.compare import compare_table, run_compare
from solver.experiments.density import DensityConfig, run_density
from solver.experiments.summary import summarize_density

__all__ = ["DensityConfig", "compare_table", "run_compare", "run_density", "summarize_density"]
