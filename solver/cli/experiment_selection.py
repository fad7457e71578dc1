"""``dpp experiment goal-selection``: what choosing its goal gains the Attacker, on the maps of
the density sweep (:mod:`solver.experiments.selection`, proofs/SELECT.md)."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import TYPE_CHECKING

import click

from dppio.cli.conventions import output_dir_option, progress_option, status, want_progress
from dppio.files import write_files
from solver.cli.common import check_grid_count, dumps, int_list
from solver.errors import InvalidInstanceError, OutputError
from solver.limits import MAX_DENSITY_GRIDS, MAX_DENSITY_SIZE

if TYPE_CHECKING:
    from matplotlib.figure import Figure


@click.command("goal-selection",
               short_help="V(b) at the paper's prior against V_sel on the density sweep's maps.")
@click.option("--samples", type=click.IntRange(min=1, max=MAX_DENSITY_GRIDS), default=50,
              show_default=True, help="Grids per density.")
@click.option("--densities", default="0,10,20,30,40", show_default=True,
              help="Obstacle densities in percent, comma-separated.")
@click.option("--seed", type=click.IntRange(min=0, max=2**63 - 1), default=0,
              show_default=True, help="Seed: the same grids as dpp experiment density.")
@click.option("--size", type=click.IntRange(min=2, max=MAX_DENSITY_SIZE), default=20,
              show_default=True, help="Grid side length.")
@click.option("--curves", type=click.IntRange(min=0, max=20), default=1, show_default=True,
              help="Maps per density whose V(q) the figure draws.")
@output_dir_option("Directory for selection.csv, summary.txt, summary.json and "
                   "selection.png / selection.pdf.", default="out/goal-selection")
@click.option("--json", "as_json", is_flag=True,
              help="Print summary.json instead of the text summary.")
@progress_option
def selection_command(samples: int, densities: str, seed: int, size: int, curves: int,
                      output_dir: str, as_json: bool, progress: bool | None) -> None:
    """The goal-selection game on the maps of the density sweep.

    For each grid (start bottom-left, g1 top-right, g2 top-left, as dpp experiment density):
    the paper's value V(b) at b = (3/5, 2/5), the value V_sel when the Attacker chooses its
    goal, the choice q*, the Defender's mixture weight α and the gain V(b) − V_sel, all
    exact; the figure draws V(q) against q with its minimum marked, and the gain by density.

    \b
    Examples:
      dpp experiment goal-selection                       # 5 x 50 grids, 20 x 20
      dpp experiment goal-selection --samples 200 --output-dir out/sel
    """
    from tqdm import tqdm

    from solver.experiments.density import DensityConfig
    from solver.experiments.selection import rows_to_csv, selection_rows, summarize_selection
    from solver.plots.selection import plot_selection

    if str(output_dir) == "":
        raise InvalidInstanceError("--output-dir: the output path is empty")
    dens = int_list(densities, "--densities")
    check_grid_count(samples, dens)
    config = DensityConfig(size=size, densities=dens, samples=samples, seed=seed,
                           start=(size - 1, 0), goals=((0, size - 1), (0, 0)))
    with tqdm(total=samples * len(config.densities), unit="grid", file=sys.stderr,
              disable=not want_progress(progress), desc="goal selection") as bar:
        rows = selection_rows(config, progress=bar.update)
    summary = summarize_selection(rows)
    d = Path(output_dir)
    summary_json = dumps({"config": {
        "size": size, "densities": list(config.densities), "samples": samples, "seed": seed,
        "start": list(config.start), "goals": [list(g) for g in config.goals],
        "prior": list(config.prior)}, **summary.to_json()})
    files: dict[Path, str | bytes] = {d / "selection.csv": rows_to_csv(rows),
                                      d / "summary.txt": summary.text() + "\n",
                                      d / "summary.json": summary_json}
    if curves:
        files |= _figures(plot_selection(rows, per_density=curves), d)
    write_files(files, error=OutputError)  # all or nothing
    click.echo(summary_json if as_json else summary.text(), nl=not as_json)
    status(f"wrote {d / 'selection.csv'} ({len(rows)} maps), summary.txt, summary.json"
           + (", selection.png, selection.pdf" if curves else ""))


def _figures(fig: Figure, folder: Path) -> dict[Path, str | bytes]:
    """The figure as PNG (150 dpi, print size) and PDF bytes, written with the rest."""
    import io

    import matplotlib.pyplot as plt

    out: dict[Path, str | bytes] = {}
    for suffix, dpi in (("png", 150), ("pdf", 150)):  # the PDF is vector: dpi only for images
        buf = io.BytesIO()
        fig.savefig(buf, format=suffix, bbox_inches="tight", dpi=dpi)
        out[folder / f"selection.{suffix}"] = buf.getvalue()
    plt.close(fig)
    return out
