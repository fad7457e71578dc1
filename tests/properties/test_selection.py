"""Properties of the goal-selection value on generated instances (proofs/SELECT.md).

The solver's ``V_sel`` (its own guarantee sets) against the checker's value of the game with a
prior (its own sets, :func:`dppverify.structured.proved_value.nvalue`), instance by instance:

- ``V_sel <= V(b) − b·r`` for every prior ``b`` (SELECT.1: choosing is never worse than being
  drawn), with equality at the solver's choice ``q*``;
- ``V`` is convex in the prior (SELECT.1: a support function): on random segments, the value at
  an interior point is at most the interpolation of the endpoints;
- two goals: ``V(q) = max((1 − q)M + (2q − 1)d1, qM + (1 − 2q)d2)``, one kink at 1/2 at most
  (SELECT.10), and ``V_sel = min(d1 − r1, d2 − r2, (M − r1 − r2)/2)`` (SELECT.8).

Example counts follow the hypothesis profile (DPP_HYPOTHESIS_PROFILE; docs/audit.md).
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from hypothesis import given
from hypothesis import strategies as st

from dppverify.game.instance import instance_from_json
from dppverify.strategies import selection_instances
from dppverify.structured.normal_fixpoint import normal_sets
from dppverify.structured.proved_value import nvalue
from dppverify.structured.selection_value import value_at
from solver.selection.equilibrium import selection_equilibrium

Doc = dict[str, Any]


def _priors(n: int) -> st.SearchStrategy[list[Fraction]]:
    return st.lists(st.integers(1, 7), min_size=n, max_size=n).map(
        lambda ws: [Fraction(w, sum(ws)) for w in ws])


def _at(doc: Doc, prior: list[Fraction]) -> Fraction:
    """The checker's ``V(b)`` of the game with the prior ``b`` (interior), exactly."""
    game = {k: v for k, v in doc.items() if k not in ("goal_selection", "goal_values")}
    v = nvalue(instance_from_json({**game, "prior": [str(p) for p in prior]}), None)
    assert v.value is not None, v.reason  # the families here are certified
    return Fraction(v.value)


@given(selection_instances(max_goals=3), st.data())
def test_choosing_is_never_worse_than_being_drawn(doc: Doc, data: st.DataObject) -> None:
    eq = selection_equilibrium(doc)
    r = eq.selection.values
    b = data.draw(_priors(len(doc["goals"])))
    assert eq.value <= _at(doc, b) - sum((x * y for x, y in zip(b, r, strict=True)), Fraction(0))
    sel = instance_from_json(doc)   # the checker's own sets at the solver's choice
    at_q = value_at(normal_sets(sel), eq.choice)
    assert at_q - sum((x * y for x, y in zip(eq.choice, r, strict=True)), Fraction(0)) == eq.value


@given(selection_instances(max_goals=3, values=False), st.data())
def test_the_value_is_convex_in_the_prior(doc: Doc, data: st.DataObject) -> None:
    n = len(doc["goals"])
    b1, b2 = data.draw(_priors(n)), data.draw(_priors(n))
    lam = Fraction(data.draw(st.integers(1, 4)), 5)
    mid = [lam * x + (1 - lam) * y for x, y in zip(b1, b2, strict=True)]
    assert _at(doc, mid) <= lam * _at(doc, b1) + (1 - lam) * _at(doc, b2)


@given(selection_instances(max_goals=2))
def test_two_goals_one_kink_at_one_half_and_the_closed_form(doc: Doc) -> None:
    sel = instance_from_json(doc)
    sets = normal_sets(sel)
    d1, d2, m = sets.column(sel.start)  # type: ignore[misc]
    for k in range(1, 8):
        q = Fraction(k, 8)
        above, below = (1 - q) * m + (2 * q - 1) * d1, q * m + (1 - 2 * q) * d2
        assert _at(doc, [q, 1 - q]) == max(above, below)
    r1, r2 = sel.goal_values or (0, 0)
    assert selection_equilibrium(doc).value == min(d1 - r1, d2 - r2, (m - r1 - r2) / 2)
