"""The comparison of Sec. VII-C: six (Defender, Attacker) pairs on one grid (Figs. 7/8).

The default instance is the bundled 10×10 map ``examples:paper10`` (``dppio/data/paper10.map``,
linked from ``examples/``), start (9, 0), g1 = (0, 9) with prior 3/5, g2 = (0, 0) with prior 2/5.
"""

from __future__ import annotations

import csv
import io
from collections.abc import Mapping, Sequence
from dataclasses import asdict
from fractions import Fraction
from pathlib import Path

from dppio.examples import example_path
from dppio.text import decimal
from solver.errors import InstanceFormatError
from solver.formats.movingai import read_map
from solver.game.instance import Instance
from solver.literature.path_metrics import METRIC_FIELDS, PathMetrics, metric_row
from solver.literature.strategy_pairs import LABELS, PairResult
from solver.numbers import Number

DEFAULT_START = (9, 0)
DEFAULT_GOALS = ((0, 9), (0, 0))
DEFAULT_PRIOR = ("3/5", "2/5")



def paper10_path() -> Path:
    """Path of the bundled ``paper10.map`` (``examples:paper10``, :mod:`dppio.examples`).

    Returns
    -------
    Path
        Inside the installed package (``dppio/data/paper10.map``).

    Examples
    --------
    >>> p = paper10_path()
    >>> p.name, p.read_text().splitlines()[:3]
    ('paper10.map', ['type octile', 'height 10', 'width 10'])
    """
    return example_path("paper10", error=InstanceFormatError)


def paper10_instance() -> Instance:
    """The comparison instance on the bundled map.

    Examples
    --------
    >>> inst = paper10_instance()
    >>> inst.start, inst.primary, inst.secondary, str(inst.b1)
    ((9, 0), (0, 9), (0, 0), '3/5')
    """
    return Instance.from_grid(read_map(paper10_path()), DEFAULT_START, DEFAULT_GOALS,
                              DEFAULT_PRIOR)


def _num(x: Number) -> str:
    if isinstance(x, Fraction):
        return str(x) if x.denominator == 1 else f"{x} (≈ {decimal(x)})"
    return decimal(x)


def compare_table(results: Sequence[PairResult]) -> str:
    """A fixed-width text table of ``results`` (e.g. ``PairEvaluator.of(inst).compare(PAIRS)``):
    a header, a rule
    and one row per pair, exact values with decimals.

    Examples
    --------
    >>> from solver.game.instance import triangle
    >>> from solver.literature.strategy_pairs import PairEvaluator
    >>> results = PairEvaluator.of(triangle()).compare()
    >>> print(compare_table(results[:2]))
    Defender  Attacker  U1              U2  U             VoI
    --------  --------  --------------  --  ------------  --------------
    σ*        γ*        3               1   12/5 (≈ 2.4)  1/9 (≈ 0.1111)
    σ'        γ*        18/7 (≈ 2.571)  2   12/5 (≈ 2.4)  1/9 (≈ 0.1111)
    """
    head = ("Defender", "Attacker", "U1", "U2", "U", "VoI")
    body = [(LABELS.get(r.defender, r.defender), LABELS.get(r.attacker, r.attacker),
             _num(r.U1), _num(r.U2), _num(r.U), _num(r.VoI)) for r in results]
    widths = [max(len(row[i]) for row in (head, *body)) for i in range(len(head))]
    lines = ["  ".join(c.ljust(w) for c, w in zip(row, widths, strict=True)).rstrip()
             for row in (head, *body)]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join(lines)


def verdict(results: Sequence[PairResult]) -> str:
    """Whether the paper's observation ``U(σ',γ*) < U(σ*,γ*)`` holds on ``results`` (e.g.
    ``PairEvaluator.of(inst).compare(PAIRS)``'s): one sentence, empty when they lack one of
    the two pairs.

    Examples
    --------
    It holds on the paper's map, not on the triangle (where both Defenders get 12/5):

    >>> from solver.literature.strategy_pairs import PAIRS, PairEvaluator
    >>> results = PairEvaluator.of(paper10_instance()).compare(PAIRS)
    >>> print(verdict(results))  # doctest: +NORMALIZE_WHITESPACE
    U(σ',γ*) = 64/5 (≈ 12.8) < U(σ*,γ*) = 68/5 (≈ 13.6): the paper's observation
    U(σ',γ*) < U(σ*,γ*) holds on this instance
    >>> from solver.game.instance import triangle
    >>> from solver.literature.strategy_pairs import PairEvaluator
    >>> results = PairEvaluator.of(triangle()).compare()
    >>> "does NOT hold" in verdict(results), verdict(results[:1])
    (True, '')
    """
    by = {(r.defender, r.attacker): r for r in results}
    if ("sigma*", "gamma*") not in by or ("sigma'", "gamma*") not in by:
        return ""
    u_star, u_alt = by[("sigma*", "gamma*")].U, by[("sigma'", "gamma*")].U
    rel = "<" if u_alt < u_star else ("=" if u_alt == u_star else ">")
    holds = "holds" if rel == "<" else "does NOT hold"
    return (f"U(σ',γ*) = {_num(u_alt)} {rel} U(σ*,γ*) = {_num(u_star)}: the paper's "
            f"observation U(σ',γ*) < U(σ*,γ*) {holds} on this instance")


def compare_csv(results: Sequence[PairResult],
                metrics: Mapping[str, PathMetrics] | None = None) -> str:
    """``results`` (e.g. ``PairEvaluator.of(inst).compare(PAIRS)``'s) as CSV: a header line and one
    line per pair, exact ``p/q`` strings; with ``metrics`` (each Attacker's expected path
    metrics, :func:`solver.experiments.field_metrics.attacker_metrics`) also the field's columns
    (:data:`~solver.literature.path_metrics.METRIC_FIELDS`) after ``VoI``.

    Examples
    --------
    >>> from solver.game.instance import triangle
    >>> from solver.literature.strategy_pairs import PairEvaluator
    >>> results = PairEvaluator.of(triangle()).compare()
    >>> print(compare_csv(results[:2]), end="")
    defender,attacker,U1,U2,U,U_bar,VoI
    sigma*,gamma*,3,1,12/5,27/10,1/9
    sigma',gamma*,18/7,2,12/5,27/10,1/9
    """
    buf = io.StringIO()
    fields: tuple[str, ...] = ("defender", "attacker", "U1", "U2", "U", "U_bar", "VoI")
    if metrics is not None:
        fields += METRIC_FIELDS
    w = csv.DictWriter(buf, fieldnames=fields, lineterminator="\n")
    w.writeheader()
    for r in results:
        row = {k: str(v) for k, v in asdict(r).items()}
        if metrics is not None:
            row.update(metric_row(metrics[r.attacker]))
        w.writerow(row)
    return buf.getvalue()
