"""What every figure shares: colours, line styles, fonts, number labels, and
:func:`save_figure` (PNG, SVG or PDF by the file's suffix, written atomically)."""

from __future__ import annotations

import io
from fractions import Fraction
from pathlib import Path
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.figure import Figure

from dppio.files import write_files
from dppio.text import decimal
from solver.errors import DPPError, OutputError

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
STYLE: dict[Any, Any] = {"font.family": "DejaVu Sans", "font.size": 12, "axes.titlesize": 13,
          "axes.labelsize": 12, "legend.fontsize": 11, "xtick.labelsize": 11,
          "ytick.labelsize": 11, "mathtext.fontset": "dejavusans", "pdf.fonttype": 42,
          "svg.fonttype": "none"}
"""One font family for text and mathtext (DejaVu Sans); fonts embedded as TrueType."""
LARGE_MARKER = 13.0
"""The size (points) of the start and goal markers on a large map."""
GOAL_COLOURS = ("#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00")
"""N-goal figures: one colour per goal, the same for the type walking to it (up to 5)."""
LARGE_MAP = 60
"""Maps with more cells than this on a side get the print rendering: paths of a fixed width
with a white casing, start and goal markers of a fixed size on top, lighter obstacles."""
PATH_STYLES = {"xi1_I": "-", "xi1_II": (0, (4, 1.5)), "xi1": "-", "xi2": (0, (1, 1.2))}
"""One line style per equilibrium path in every figure: ξ^{1,I} solid, ξ^{1,II} dashed, ξ²
dotted (colour says the Attacker's strategy, the line style which path)."""
def tex_label(label: str) -> str:
    """Mathtext for a path label: ``xi1_II`` -> ξ^{1,II}, ``xi2_am`` -> ξ^{2,am}, ``xi1`` -> ξ¹.

    >>> print(tex_label("xi1_II"), tex_label("xi1"), tex_label("t"))
    $\\xi^{1,\\mathrm{II}}$ $\\xi^{1}$ t
    """
    head, _, tail = label.partition("_")
    if not head.startswith("xi"):
        return label
    sup = head[2:] + (r",\mathrm{" + tail + "}" if tail else "")
    return rf"$\xi^{{{sup}}}$"


T_I, T_II = r"$t_{\mathrm{I}}$", r"$t_{\mathrm{II}}$"
"""The phase boundaries t_I, t_II as mathtext (subscripts, never a literal underscore)."""


def num_label(x: Any) -> str:
    """A number for a title or legend: an exact fraction with its decimal beside it, a float
    as a decimal (:func:`dppio.text.decimal`, the one rule of every output).

    >>> from fractions import Fraction
    >>> num_label(Fraction(5, 22)), num_label(0.20410018838561994)
    ('5/22 ≈ 0.2273', '0.2041')
    >>> num_label(Fraction(17)), num_label(3)
    ('17', '3')
    """
    if isinstance(x, Fraction):
        if x.denominator == 1:
            return str(x.numerator)
        return f"{x} ≈ {decimal(x)}" if x.denominator <= 1000 else decimal(x)
    if isinstance(x, int | np.integer):
        return str(int(x))
    return decimal(float(x))


def check_suffix(out: str | Path) -> None:
    """Refuse an output name whose suffix is not a figure format, before any work.

    Raises
    ------
    DPPError
        As :func:`save_figure` would, after the figure was computed.

    Examples
    --------
    >>> check_suffix("map.pdf")
    >>> check_suffix("map.txt")
    Traceback (most recent call last):
    solver.errors.DPPError: map.txt: the output file must end in .png, .svg or .pdf
    """
    if str(out) and Path(out).suffix.lower().lstrip(".") not in FORMATS:
        raise DPPError(f"{Path(out)}: the output file must end in .png, .svg or .pdf")


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
    write_files({p: figure_bytes(fig, fmt)}, error=OutputError)  # atomic; folders created
    return [p]


def figure_bytes(fig: Figure, fmt: str) -> bytes:
    """The figure as a ``fmt`` file's bytes (``png``, ``svg``, ``pdf``: as :func:`save_figure`
    writes it), for a command that commits it together with other files; the figure is
    closed.

    Examples
    --------
    >>> fig, ax = plt.subplots()
    >>> figure_bytes(fig, "png")[:4]
    b'\x89PNG'
    """
    buf = io.BytesIO()
    try:
        fig.savefig(buf, format=fmt, dpi=150, bbox_inches="tight")
    finally:
        plt.close(fig)
    return buf.getvalue()
