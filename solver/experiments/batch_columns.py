"""The field's columns of a ``dpp batch`` row: the published length, our distance, the path
metrics of the equilibrium Attacker and the certificate's exploitability.

- ``scen_optimal``: MovingAI's optimal length as the ``.scen`` line writes it (8-connected,
  no corner cutting; ``tests/maps/test_published_lengths.py`` reproduces every shipped line);
- ``distance``: our ``d(start, goal)`` in the batch's grid (``--connectivity``: 4 gives the
  exact integer, ≥ the published length; 8 gives the float that reproduces it);
- the path metrics of γ* (:mod:`solver.literature.path_metrics`), the expectation over both
  types (by the prior) and their walks — the mixture's expectation;
- ``nash_conv``: the certificate's exploitability (``docs/formats.md`` §3, 0 for a certified
  equilibrium).
"""

from __future__ import annotations

from collections.abc import Hashable, Mapping
from typing import Any

from solver.literature.path_metrics import metric_row
from solver.literature.walk_metrics import RouteMeter
from solver.twogoal.equilibrium import Equilibrium


def line_columns(eq: Equilibrium, goal: Hashable) -> dict[str, str]:
    """``distance`` (to the scenario's ``goal``) and the metric columns of one solved line.

    Examples
    --------
    >>> from solver.experiments.compare import paper10_instance
    >>> from solver.twogoal.equilibrium import paper_equilibrium
    >>> cols = line_columns(paper_equilibrium(paper10_instance()), (0, 9))
    >>> cols["distance"], cols["cost"], cols["ldp"], cols["truthful_50"]
    ('18', '20', '107/204', '3/5')
    """
    inst = eq.instance
    meter = RouteMeter.of(inst)
    walks = meter.strategy(eq.primary_paths, (eq.secondary,))
    d_to = meter.d_to_g1 if goal == inst.primary else meter.d_to_g2
    d = inst.network.numbers.convert(d_to[meter.start])
    return {"distance": repr(d) if isinstance(d, float) else str(d),
            **metric_row(meter.expectation(walks))}


def exploitability_cell(cert: Any) -> str:
    """The ``nash_conv`` cell of a certificate: its exact NashConv (``p/q``), the float in
    float mode, empty when the certificate could not state it.

    Examples
    --------
    >>> class Cert:
    ...     exploitability = {"nash_conv": "0", "exact": True}
    >>> exploitability_cell(Cert())
    '0'
    """
    doc = getattr(cert, "exploitability", None)
    if doc is not None and not isinstance(doc, Mapping):
        doc = doc.to_json()
    if not isinstance(doc, Mapping) or doc.get("nash_conv") is None:
        return ""
    return str(doc["nash_conv"])
