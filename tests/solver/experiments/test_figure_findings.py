"""The figure findings of a review of every figure, each checked on the figure objects
(docs/figures/ has the contact sheet of all figures at print size)."""

from __future__ import annotations

import matplotlib
import networkx as nx
import numpy as np
import pytest
from matplotlib.colors import to_rgba
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from solver import Instance
from solver.experiments.compare import paper10_instance, paper10_path
from solver.plots import PATH_STYLES, plot_beliefs, plot_map, plot_voi
from solver.twogoal.equilibrium import paper_equilibrium
from solver.twogoal.report import summarize

matplotlib.use("Agg")

EDGES = [(0, 1, 2), (0, 2, 2), (0, 4, 4), (1, 2, 3), (1, 3, 1), (1, 4, 4), (2, 3, 1), (2, 4, 2),
         (3, 4, 3)]


def no_phase_ii() -> Instance:
    """A five-node game whose ξ² has no phase II (t_I = t_II = 1, T = 2): one primary path."""
    g = nx.Graph()
    g.add_weighted_edges_from(EDGES)
    return Instance(g, 0, (4, 3), ("3/5", "2/5"))


def _legend(fig) -> list:  # type: ignore[no-untyped-def]
    legends = [*fig.legends, *(ax.get_legend() for ax in fig.axes if ax.get_legend())]
    return [h for leg in legends for h in leg.legend_handles]


def _labels(fig) -> list[str]:  # type: ignore[no-untyped-def]
    legends = [*fig.legends, *(ax.get_legend() for ax in fig.axes if ax.get_legend())]
    return [t.get_text() for leg in legends for t in leg.get_texts()]


def test_beliefs_legend_tells_the_equilibrium_paths_apart() -> None:
    fig = plot_beliefs(paper10_instance())
    styles = {}
    for h, label in zip(_legend(fig), _labels(fig), strict=True):
        if "γ*" in label:
            offset, dashes = h._unscaled_dash_pattern  # what is drawn: solid, dashes, dots
            styles[label.split(" ")[0]] = (offset, tuple(dashes or ()))
    assert len(styles) == 3 and len(set(styles.values())) == 3, styles
    assert set(PATH_STYLES) >= {"xi1_I", "xi1_II", "xi2"}


def test_t_i_is_a_subscript_not_a_literal_underscore() -> None:
    fig = plot_beliefs(paper10_instance())
    texts = [t.get_text() for ax in fig.axes for t in ax.texts]
    assert texts and all("_{" in t and t.startswith("$") for t in texts)
    title = plot_map(paper10_instance(), baselines=False).axes[0].get_title()
    assert "t_I" not in title and r"$t_{\mathrm{I}}$" in title


def test_one_font_family_and_no_serif_math() -> None:
    fig = plot_voi([{"density": 0, "defender": "sigma*", "attacker": "gamma*", "VoI_float": 0.2}],
                   pairs=[("sigma*", "gamma*")])
    for text in fig.findobj(matplotlib.text.Text):
        if text.get_text():
            assert text.get_fontfamily() == ["DejaVu Sans"], text.get_text()
    assert "Vo" not in fig.axes[0].get_title() or "value of information" in \
        fig.axes[0].get_title().lower()


def test_without_phase_ii_the_labels_and_legend_say_so() -> None:
    inst = no_phase_ii()
    eq = paper_equilibrium(inst)
    assert eq.phases.t_I == eq.phases.t_II and [p.label for p in eq.primary_paths] == ["xi1"]
    text = summarize(eq)
    assert "ξ¹ " in text and "xi1" not in text
    labels = _labels(plot_beliefs(inst))
    assert not any("phase II " in t for t in labels), labels
    assert any("phase I " in t for t in labels) and any("phase III" in t for t in labels)
    assert not any("xi1" in t for t in labels)
    marks = [t.get_text() for t in plot_beliefs(inst).axes[0].texts]
    assert marks == [r"$t_{\mathrm{I}}$ = $t_{\mathrm{II}}$"]


def test_baseline_legend_explains_its_numbers() -> None:
    labels = _labels(plot_map(paper10_instance()))
    baselines = [t for t in labels if "ambiguity" in t or "exaggeration" in t]
    assert len(baselines) == 4 and all(t.endswith(" steps") for t in baselines), baselines


def test_voi_legend_matches_the_boxes_and_equal_values_stay_visible() -> None:
    rows = [{"density": d, "defender": de, "attacker": "gamma*", "VoI_float": v}
            for d, vals in ((0, (0.25, 0.25, 0.25)), (10, (0.2, 0.3, 0.25)))
            for v in vals for de in ("sigma*", "sigma'")]
    fig = plot_voi(rows, pairs=[("sigma*", "gamma*"), ("sigma'", "gamma*")])
    handles = dict(zip(_labels(fig), _legend(fig), strict=True))
    sigma_star, sigma_prime = handles["Defender σ*"], handles["Defender σ'"]
    assert isinstance(sigma_star, Patch) and sigma_star.get_facecolor() != to_rgba("white")
    assert sigma_prime.get_facecolor() == to_rgba("white") and sigma_prime.get_hatch()
    squares = [ln for ln in fig.axes[0].lines if ln.get_marker() == "s"]
    assert squares and all(np.allclose(ln.get_ydata(), 0.25) for ln in squares)
    assert "all grids equal" in handles


def test_large_maps_get_print_size_paths_and_markers() -> None:
    blocked = np.zeros((120, 120), dtype=bool)
    blocked[40:80, 30:90] = True
    inst = Instance.from_grid(blocked, (119, 0), ((0, 119), (0, 0)), ("3/5", "2/5"))
    ax = plot_map(inst, baselines=False).axes[0]
    paths = [ln for ln in ax.lines if len(ln.get_xdata()) > 2]
    assert paths and min(ln.get_linewidth() for ln in paths) >= 1.9
    assert all(ln.get_path_effects() for ln in paths)  # a white casing
    markers = [ln for ln in ax.lines if ln.get_marker() in ("o", "s")]
    assert markers and min(ln.get_markersize() for ln in markers) >= 12
    assert min(ln.get_zorder() for ln in markers) > max(ln.get_zorder() for ln in paths)


@pytest.mark.parametrize("kind", ["map", "beliefs"])
def test_legend_mathtext_is_consistent(kind: str) -> None:
    fig = plot_map(paper10_instance()) if kind == "map" else plot_beliefs(paper10_instance())
    labels = _labels(fig)
    assert not any("_I" in t.replace(r"_{\mathrm{I", "") for t in labels), labels
    assert all(isinstance(h, Line2D | Patch) for h in _legend(fig))


# ---------------------------------------------------- the second review's figure findings
def _extent(fig, artist):  # type: ignore[no-untyped-def]
    fig.canvas.draw()
    return artist.get_window_extent(fig.canvas.get_renderer())


def test_corner_markers_stay_inside_the_frame_on_large_maps() -> None:
    """On a large map the start and goal markers (fixed print size) in the corners
    covered the '0' tick labels and reached the next panel's title."""
    blocked = np.zeros((200, 200), dtype=bool)
    blocked[60:140, 50:150] = True
    inst = Instance.from_grid(blocked, (199, 0), ((0, 199), (0, 0)), ("3/5", "2/5"))
    fig = plot_map(inst)
    for ax in fig.axes:
        frame = _extent(fig, ax.patch)
        markers = [ln for ln in ax.lines if ln.get_marker() in ("o", "s")]
        assert markers
        for ln in markers:
            box = _extent(fig, ln)
            assert frame.x0 - 0.5 <= box.x0 and box.x1 <= frame.x1 + 0.5, (box, frame)
            assert frame.y0 - 0.5 <= box.y0 and box.y1 <= frame.y1 + 0.5, (box, frame)
        ticks = [t for t in ax.get_xticklabels() + ax.get_yticklabels() if t.get_text() == "0"]
        assert ticks
        for t in ticks:
            assert not any(_extent(fig, t).overlaps(_extent(fig, ln)) for ln in markers)
    title = _extent(fig, fig.axes[1].title)
    assert not any(_extent(fig, ln).overlaps(title) for ln in fig.axes[0].lines
                   if ln.get_marker() in ("o", "s"))


def test_baselines_legend_covers_no_bar() -> None:
    """The legend covered the tallest bar of baselines.png."""
    from solver.experiments.baselines import instances, plot_baselines, run_baselines

    fig = plot_baselines(run_baselines(instances(1, (), ())))
    legends = [*fig.legends, *(ax.get_legend() for ax in fig.axes if ax.get_legend())]
    assert legends
    bars = [p for ax in fig.axes for p in ax.patches if p.get_height() != 0]
    assert bars
    for leg in legends:
        box = _extent(fig, leg)
        assert not any(box.overlaps(_extent(fig, b)) for b in bars)


def test_the_n_goal_map_draws_every_walk_and_the_defenders_sigma() -> None:
    from solver.coalitions.construction import coalition_equilibrium
    from solver.formats.movingai import read_map
    from solver.plots import plot_ngoal_map
    from solver.plots.style import GOAL_COLOURS

    game = Instance.from_grid(read_map(paper10_path()), (9, 0),
                              [(0, 9), (0, 0), (9, 9)], ["1/2", "1/3", "1/6"])
    eq = coalition_equilibrium(game)
    fig = plot_ngoal_map(eq)
    ax, panels = fig.axes[0], fig.axes[1:]
    walks = [ln for ln in ax.lines if len(ln.get_xdata()) > 1]
    assert len(walks) == sum(len(m) for m in eq.mixtures)
    for theta, mixture in enumerate(eq.mixtures):  # each type's walks in its goal's colour
        mine = [ln for ln in walks if to_rgba(ln.get_color()) == to_rgba(GOAL_COLOURS[theta])]
        assert len(mine) == len(mixture)
    assert len(panels) == game.n_goals
    for theta, panel in enumerate(panels):  # σ stacks to 1 after every step of the walk
        walk = eq.mixtures[theta][0][0]
        heights = np.zeros(len(walk) - 1)
        for bar in panel.patches:
            heights[round(bar.get_x() + bar.get_width() / 2) - 1] += bar.get_height()
        assert np.allclose(heights, 1.0)
