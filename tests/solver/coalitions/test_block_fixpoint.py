"""The block fixpoint and its ranks agree with the layered DP (proofs/NEXACT.md NX.7).

The layered normal-restricted DP (:func:`solver.coalitions.normal_dp.layered_dp`) is the
oracle: on random digraphs, grids and hub gadgets (N = 2..5), with the 0/1 normals and with
extra normals, under both readings of the closure (all covers; the written rule's dominated
covers), :func:`~solver.coalitions.normal_dp.normal_dp` gives the same values ``m*``
(exactly, as fractions), the same finite nodes, the same ranks and the same ``K``; and the
whole construction writes the same profile document either way.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from solver.coalitions import normal_dp as gs
from solver.coalitions.arc_graph import ArcGraph
from solver.coalitions.block_fixpoint import block_fixpoint
from solver.coalitions.budget import BudgetExceeded
from solver.coalitions.construction import arc_graph, coalition_equilibrium
from solver.coalitions.normal_system import NormalSystem, symmetric_closure
from solver.coalitions.vertex_tables import zero_one_normals
from solver.game.instance_reading import instance_from_json
from tests.solver._ngoal_families import GADGET, draw

EXTRA = {3: [(2, 2, 1)], 4: [(2, 2, 2, 1)], 5: [(2, 2, 1, 1, 1)]}


def _layered(graph: ArcGraph, system: NormalSystem, max_layers: int) -> gs.Fixpoint:
    fix = gs.layered_dp(graph, system, check_layers=False, max_layers=max_layers)
    assert isinstance(fix, gs.Fixpoint)
    return fix


def _assert_same(old: gs.Fixpoint, new: gs.Fixpoint) -> None:
    assert np.array_equal(old.finite, new.finite)
    assert np.array_equal(old.rank, new.rank)
    assert old.layers == new.layers
    for j in range(len(old.system.normals)):
        for v in np.flatnonzero(old.finite).tolist():
            assert old.value(j, v) == new.value(j, v), (old.system.normals[j], v)


def _systems(n: int) -> list[NormalSystem]:
    out = []
    for extra in ([], EXTRA.get(n, [])):
        normals = symmetric_closure([*zero_one_normals(n), *extra])
        out += [NormalSystem(normals), NormalSystem(normals, dominated=True)]
    return out


def _graph(doc: dict[str, Any]) -> ArcGraph:
    graph, _ = arc_graph(instance_from_json(doc))
    return graph


def _block_applies(graph: ArcGraph, system: NormalSystem) -> bool:
    return block_fixpoint(graph, system, 10_000) is not None


def _normal_dp_equals_layered_dp(family: str, seed: int, n: int) -> None:
    graph = _graph(draw(family, seed, n))
    for system in _systems(n):
        assert _block_applies(graph, system)  # the fast route is the one tested
        _assert_same(_layered(graph, system, 10_000), gs.normal_dp(graph, system, 10_000))


GRAPHS = {"family": st.sampled_from(["digraph", "grid", "hub"]),
          "seed": st.integers(0, 10 ** 6), "n": st.integers(2, 5)}


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(**dict(GRAPHS, n=st.integers(2, 4)))
def test_normal_dp_equals_layered_dp(family: str, seed: int, n: int) -> None:
    """Up to four goals here (a five-goal hub's layered DP alone takes 20 s: the campaign
    below; test_same_profile_as_the_layered_route has a five-goal hub and digraph)."""
    _normal_dp_equals_layered_dp(family, seed, n)


@pytest.mark.slow
@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(**GRAPHS)
def test_normal_dp_equals_layered_dp_campaign(family: str, seed: int, n: int) -> None:
    _normal_dp_equals_layered_dp(family, seed, n)


def test_normal_dp_on_the_gadget() -> None:
    graph = _graph(GADGET)
    for system in _systems(4):
        _assert_same(_layered(graph, system, 10_000), gs.normal_dp(graph, system, 10_000))


def test_budget_of_layers_is_the_same() -> None:
    """``max_layers`` is met or missed as by the layered DP: ``K`` below it passes, else the
    budget is reached."""
    graph = _graph(draw("grid", 7, 3))
    system = _systems(3)[0]
    k = _layered(graph, system, 10_000).layers
    assert gs.normal_dp(graph, system, k + 1).layers == k
    with pytest.raises(BudgetExceeded):
        _layered(graph, system, k)
    with pytest.raises(BudgetExceeded):
        gs.normal_dp(graph, system, k)


@pytest.mark.parametrize("family,seed,n", [("hub", 3, 4), ("hub", 11, 5), ("grid", 5, 4),
                                            ("digraph", 2, 5), ("gadget", 0, 4)])
def test_same_profile_as_the_layered_route(family: str, seed: int, n: int,
                                           monkeypatch: pytest.MonkeyPatch) -> None:
    doc = GADGET if family == "gadget" else draw(family, seed, n)
    new = coalition_equilibrium(instance_from_json(doc)).to_json()
    monkeypatch.setattr(gs, "normal_dp", _layered)
    old = coalition_equilibrium(instance_from_json(doc)).to_json()
    assert new == old
