"""The field's path metrics of every Attacker an experiment compares, as tables and CSV.

For each named Attacker (γ*, Dragan's ambiguity and exaggeration, Masters & Sardina's
π_d1–π_d4) on one instance: the metrics of each of its walks
(:class:`~solver.literature.walk_metrics.WalkMetrics`) and their expectation over the prior
and the walks' probabilities (:mod:`solver.literature.path_metrics`). The metrics describe the
Attacker's walks only, so they are the same against σ* and σ'.

Examples
--------
>>> from solver.experiments.compare import paper10_instance
>>> from solver.literature.strategy_pairs import PairEvaluator
>>> m = attacker_metrics(PairEvaluator.of(paper10_instance()), ("gamma*",))
>>> [(w.label, str(w.probability), str(w.metrics.ldp)) for w in m["gamma*"].walks]
[('xi1_I', '1/3', '1/3'), ('xi1_II', '2/3', '19/24'), ('xi2', '1', '6/17')]
>>> str(m["gamma*"].expected.cost), str(m["gamma*"].expected.ldp)
('20', '107/204')
"""

from __future__ import annotations

import csv
import io
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction

from dppio.text import decimal
from solver.literature.path_metrics import METRIC_FIELDS, PERCENTS, PathMetrics, metric_row
from solver.literature.strategy_pairs import LABELS, PairEvaluator
from solver.literature.walk_metrics import RouteMeter, WalkMetrics
from solver.numbers import Number

WALK_FIELDS = ("attacker", "type", "goal", "walk", "probability", "steps", *METRIC_FIELDS)
"""The columns of a walks CSV (one row per walk of each Attacker), before any leading
columns naming the instance."""


@dataclass(frozen=True)
class AttackerMetrics:
    """One Attacker's walks with their metrics, and the expectation over the prior."""

    walks: tuple[WalkMetrics, ...]
    expected: PathMetrics


def attacker_metrics(game: PairEvaluator, names: Iterable[str]) -> dict[str, AttackerMetrics]:
    """The metrics of each named Attacker's walks on ``game``'s instance, and their
    expectation (see the module docstring).

    Examples
    --------
    >>> from solver.game.instance import triangle
    >>> m = attacker_metrics(PairEvaluator.of(triangle()), ("gamma*", "ambiguity"))
    >>> str(m["gamma*"].expected.cost), str(m["ambiguity"].expected.cost)
    ('3', '27/10')
    """
    meter = RouteMeter.of(game.instance, game.d_to_g1, game.d_to_g2)
    out = {}
    for name in dict.fromkeys(names):
        att = game.attacker(name)
        walks = meter.strategy(att.primary, att.secondary)
        out[name] = AttackerMetrics(walks, meter.expectation(walks))
    return out


def walks_csv(metrics: Mapping[str, AttackerMetrics], goals: tuple[str, str],
              lead: Sequence[tuple[str, str]] = ()) -> str:
    """One CSV row per walk of each Attacker: its type (1 primary, 2 secondary), the type's
    goal (``goals``: how the primary and secondary goal are written), the walk's name,
    probability, route steps and metrics; ``lead`` adds leading ``(column, value)`` cells.

    Examples
    --------
    >>> from solver.experiments.compare import paper10_instance
    >>> m = attacker_metrics(PairEvaluator.of(paper10_instance()), ("pi_d1",))
    >>> print(walks_csv(m, ("0,9", "0,0")).splitlines()[1])
    pi_d1,1,"0,9",xi1_pi_d1,1,26,26,13/9,21/26,1,0,0,0,0,1,1
    """
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    if not lead:
        w.writerow(WALK_FIELDS)
    for name, am in metrics.items():
        for walk in am.walks:
            cells = metric_row(walk.metrics)
            w.writerow((*(v for _, v in lead), name, walk.theta, goals[walk.theta - 1],
                        walk.label, str(walk.probability), walk.steps,
                        *(cells[k] for k in METRIC_FIELDS)))
    return buf.getvalue()


def _show(x: Number) -> str:
    return str(x) if isinstance(x, Fraction) and x.denominator == 1 else decimal(x)


def metrics_table(metrics: Mapping[str, AttackerMetrics]) -> str:
    """A fixed-width table of each Attacker's expected metrics (decimals; the CSV has the
    exact values).

    Examples
    --------
    >>> from solver.experiments.compare import paper10_instance
    >>> m = attacker_metrics(PairEvaluator.of(paper10_instance()), ("gamma*", "pi_d1"))
    >>> print(metrics_table(m))
    Attacker  cost  cost ratio  LDP     density  truthful at 10 25 50 75 90 99 %
    --------  ----  ----------  ------  -------  -------------------------------
    γ*        20    1.133       0.5245  1        0 0 0.6 0.6 1 1
    π_d1      26.4  1.502       0.8254  1        0 0 0 0 1 1
    """
    head = ("Attacker", "cost", "cost ratio", "LDP", "density",
            "truthful at " + " ".join(str(p) for p in PERCENTS) + " %")
    body = []
    for name, am in metrics.items():
        e = am.expected
        body.append((LABELS.get(name, name), _show(e.cost), _show(e.cost_ratio), _show(e.ldp),
                     _show(e.deceptive_density),
                     " ".join(decimal(t) for t in e.truthful)))
    widths = [max(len(r[i]) for r in (head, *body)) for i in range(len(head))]
    lines = ["  ".join(c.ljust(w) for c, w in zip(r, widths, strict=True)).rstrip()
             for r in (head, *body)]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join(lines)
