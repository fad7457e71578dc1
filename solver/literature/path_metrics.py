"""The field's path metrics (Masters & Sardina, IJCAI 2017): definitions on one route, pure.

Masters and Sardina ("Deceptive Path-Planning", IJCAI 2017, Sec. 3 and 6) rank a path by the
position of its **last deceptive point** (LDP) and its **deceptive density**, and their
reference script (``ssardina-research/p4-simulator-gr``, ``src/DPP/dpp.py``) writes, per path,
its ``cost`` and whether the node reached at 10, 25, 50, 75, 90 and 99 % of the path is
truthful. This module holds those definitions once, on a **route** ``u_0 … u_K`` (``K ≥ 1``
steps, ``u_0`` the start, ``u_K`` the real goal) given by whether each node is truthful
(:func:`solver.literature.masters_sardina.truthful`), the route's cost and the optimal cost
``d(s0, g_r)``; :mod:`solver.literature.walk_metrics` builds the routes of the game's walks.

Definitions (``docs/experiments.md``, "The field's metrics", says where each reading comes
from and which reading we took where the paper is ambiguous):

- ``cost``: the route's cost; ``cost_ratio = cost / d(s0, g_r)`` (≥ 1).
- **path fraction** of node ``u_k``: ``k / K``, the share of the route's *steps* taken, as
  the reference script indexes its path (equal to the share of the cost on unit-weight
  graphs, e.g. every 4-connected grid).
- ``ldp``: the path fraction of the last node that is not truthful, ``k* / K`` with
  ``k* = max{k : u_k not truthful}`` (``u_0`` is never truthful, so ``k*`` exists); every node
  after it is truthful.
- ``deceptive_density``: the share of deceptive (not truthful) nodes among ``u_1 … u_k*``, the
  steps up to and including the LDP (1 when no truthful node comes before the LDP, the
  paper's "maximum deceptive density"; 0 when ``k* = 0``).
- ``truthful_P`` (P ∈ 10, 25, 50, 75, 90, 99): 1 if node ``u_j`` with
  ``j = 1 + ⌊P·(K−1)/100⌋`` is truthful, else 0 — the reference script's index: its path has
  no start node (``path1[1:] + path2[1:]``: ``u_1 … u_K``), and it reads
  ``path[int(P/100 * (len(path) - 1))]``, here in integers.

For a mixture of routes every metric is the probability-weighted mean
(:func:`expectation`): ``truthful_P`` becomes the probability that the Attacker is truthful at
``P`` % of its route. With rational inputs every number is an exact ``Fraction``.

Examples
--------
A route of four steps whose first two nodes after the start deceive:

>>> m = route_metrics([False, False, False, True, True], cost=4, optimal=2)
>>> str(m.cost_ratio), str(m.ldp), str(m.deceptive_density), [str(t) for t in m.truthful]
('2', '1/2', '1', ['0', '0', '0', '1', '1', '1'])
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction

from solver.numbers import Number

PERCENTS = (10, 25, 50, 75, 90, 99)
"""The path percentages of the reference script's truthfulness columns."""

METRIC_FIELDS = ("cost", "cost_ratio", "ldp", "deceptive_density",
                 *(f"truthful_{p}" for p in PERCENTS))
"""The metric columns of every comparison CSV, in order."""


@dataclass(frozen=True)
class PathMetrics:
    """The metrics of one route, or their expectation over a mixture of routes.

    Attributes
    ----------
    cost, cost_ratio : Number
        The route's cost and its ratio to ``d(s0, g_r)`` (Fractions on rational instances).
    ldp : Fraction
        The last deceptive point as a path fraction.
    deceptive_density : Fraction
        The share of deceptive nodes among the steps up to the LDP.
    truthful : tuple of Fraction
        Per :data:`PERCENTS`: 0 or 1 for a route, a probability for a mixture.
    """

    cost: Number
    cost_ratio: Number
    ldp: Fraction
    deceptive_density: Fraction
    truthful: tuple[Fraction, ...]


def route_metrics(truthful: Sequence[bool], *, cost: Number, optimal: Number) -> PathMetrics:
    """The metrics of the route whose nodes ``u_0 … u_K`` are ``truthful`` or not.

    Parameters
    ----------
    truthful : sequence of bool
        Per node of the route, start first: whether it is truthful (``K + 1 ≥ 2`` entries).
    cost : Number
        The route's cost.
    optimal : Number
        ``d(s0, g_r)``, positive.

    Returns
    -------
    PathMetrics

    Examples
    --------
    The reference script's index for 99 % of a 10-step route is node ``1 + ⌊99·9/100⌋ = 9``,
    not 10; for 10 % of a 3-step route node ``1 + ⌊10·2/100⌋ = 1``, never the start:

    >>> m = route_metrics([False] * 10 + [True], cost=10, optimal=10)
    >>> str(m.ldp), m.truthful[-1]
    ('9/10', Fraction(0, 1))
    >>> [int(t) for t in route_metrics([False, True, True, True], cost=3, optimal=3).truthful]
    [1, 1, 1, 1, 1, 1]
    >>> route_metrics([False], cost=0, optimal=1)
    Traceback (most recent call last):
    ValueError: a route needs at least one step
    """
    flags = [bool(t) for t in truthful]
    k_steps = len(flags) - 1
    if k_steps < 1:
        raise ValueError("a route needs at least one step")
    last = max(k for k, t in enumerate(flags) if not t) if not all(flags) else 0
    deceptive = sum(1 for t in flags[1:last + 1] if not t)
    density = Fraction(deceptive, last) if last else Fraction(0)
    at = tuple(Fraction(int(flags[1 + p * (k_steps - 1) // 100])) for p in PERCENTS)
    exact = not isinstance(cost, float) and not isinstance(optimal, float)
    ratio = Fraction(cost) / Fraction(optimal) if exact else float(cost) / float(optimal)
    return PathMetrics(Fraction(cost) if exact else float(cost), ratio, Fraction(last, k_steps),
                       density, at)


def expectation(items: Sequence[tuple[Fraction, PathMetrics]]) -> PathMetrics:
    """The probability-weighted mean of each metric over ``(weight, metrics)`` pairs (weights
    summing to 1; exact when the weights and the metrics are).

    Examples
    --------
    >>> a = route_metrics([False, False, True], cost=3, optimal=2)
    >>> b = route_metrics([False, True, True], cost=2, optimal=2)
    >>> e = expectation([(Fraction(1, 4), a), (Fraction(3, 4), b)])
    >>> str(e.cost), str(e.ldp), [str(t) for t in e.truthful]
    ('9/4', '1/8', ['3/4', '3/4', '3/4', '3/4', '3/4', '3/4'])
    """
    if not items:
        raise ValueError("an expectation needs at least one route")

    def mean(values: Sequence[Number]) -> Number:
        total: Number = 0
        for (w, _), v in zip(items, values, strict=True):
            total = total + w * v
        return total

    return PathMetrics(
        cost=mean([m.cost for _, m in items]),
        cost_ratio=mean([m.cost_ratio for _, m in items]),
        ldp=Fraction(mean([m.ldp for _, m in items])),
        deceptive_density=Fraction(mean([m.deceptive_density for _, m in items])),
        truthful=tuple(Fraction(mean([m.truthful[i] for _, m in items]))
                       for i in range(len(PERCENTS))))


def metric_row(m: PathMetrics) -> dict[str, str]:
    """The metrics as CSV cells (:data:`METRIC_FIELDS`): exact ``p/q`` strings, floats as
    ``repr``.

    Examples
    --------
    >>> metric_row(route_metrics([False, True], cost=Fraction(3, 2), optimal=1))["cost_ratio"]
    '3/2'
    """
    def cell(x: Number) -> str:
        return repr(x) if isinstance(x, float) else str(x)

    values = (m.cost, m.cost_ratio, m.ldp, m.deceptive_density, *m.truthful)
    return {k: cell(v) for k, v in zip(METRIC_FIELDS, values, strict=True)}
