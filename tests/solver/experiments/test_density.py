"""The density sweep: sampling, reproducibility across executors (incl. Dask), summary."""

from __future__ import annotations

from fractions import Fraction

import networkx as nx
import pytest

from solver import Instance
from solver.errors import InvalidInstanceError
from solver.experiments.density import (
    DensityConfig,
    rows_from_csv,
    rows_to_csv,
    run_density,
    tasks_of,
)
from solver.experiments.sampling import sample_grid
from solver.experiments.summary import summarize_density
from solver.literature.strategy_pairs import PAIRS, PairEvaluator

SMALL = DensityConfig(size=8, start=(7, 0), goals=((0, 7), (0, 0)), densities=(0, 20, 40),
                      samples=3, seed=5, chunk=2)


def _grid_graph(blocked: object) -> nx.Graph:
    g = nx.grid_2d_graph(*blocked.shape)  # type: ignore[attr-defined]
    g.remove_nodes_from([tuple(map(int, c)) for c in zip(*blocked.nonzero(), strict=True)])  # type: ignore[attr-defined]
    return g


@pytest.mark.parametrize("density", [0, 10, 30, 40])
def test_samples_are_valid_and_reproducible(density: int) -> None:
    start, goals = (11, 0), ((0, 11), (0, 0))
    for k in range(4):
        s = sample_grid(12, density, k, 3, start, goals)
        assert int(s.blocked.sum()) == round(density / 100 * 144)
        assert not any(s.blocked[c] for c in (start, *goals))
        g = _grid_graph(s.blocked)
        for goal, other in ((goals[0], goals[1]), (goals[1], goals[0])):
            assert nx.has_path(g.subgraph(set(g) - {other}), start, goal)
        again = sample_grid(12, density, k, 3, start, goals)
        assert (again.blocked == s.blocked).all() and again.attempts == s.attempts
    assert (sample_grid(12, 30, 0, 3, start, goals).blocked
            != sample_grid(12, 30, 0, 4, start, goals).blocked).any()


def test_rows_recomputed_from_the_grids() -> None:
    rows = run_density(SMALL, workers=1)
    assert len(rows) == len(SMALL.densities) * SMALL.samples * len(PAIRS)
    for r in rows[:: len(PAIRS) + 1]:
        s = sample_grid(SMALL.size, r.density, r.sample, SMALL.seed, SMALL.start, SMALL.goals)
        inst = Instance.from_grid(s.blocked, SMALL.start, SMALL.goals, SMALL.prior)
        game = PairEvaluator.of(inst)
        ref = game.pair(r.defender, r.attacker)
        assert Fraction(r.VoI) == ref.VoI and r.VoI_float == float(ref.VoI)
        assert r.obstacles == int(s.blocked.sum())


def test_process_pool_and_dask_give_the_same_rows() -> None:
    distributed = pytest.importorskip("distributed")
    local = run_density(SMALL, workers=2)
    assert local == run_density(SMALL, workers=1)
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False,
                                  dashboard_address=None) as cluster:
        seen: list[int] = []
        remote = run_density(SMALL, dask_address=cluster.scheduler_address,
                             progress=seen.append)
    assert remote == local
    assert sum(seen) == SMALL.samples * len(SMALL.densities)
    assert len(seen) == len(tasks_of(SMALL))


def test_csv_round_trip_and_summary() -> None:
    rows = run_density(SMALL, workers=1)
    back = list(rows_from_csv(rows_to_csv(rows)))
    assert len(back) == len(rows)
    a, b = summarize_density(rows), summarize_density(back)
    assert a.text() == b.text()
    s = a.stats[(20, ("sigma*", "gamma*"))]
    vals = sorted(float(Fraction(r.VoI)) for r in rows
                  if r.density == 20 and (r.defender, r.attacker) == ("sigma*", "gamma*"))
    assert s.n == len(vals) and s.min == vals[0] and s.max == vals[-1]
    assert abs(s.mean - sum(vals) / len(vals)) < 1e-12


def _synthetic(means: dict[int, list[str]]) -> list[dict[str, object]]:
    out = []
    for d, values in means.items():
        for k, v in enumerate(values):
            for pair in PAIRS:
                out.append({"density": d, "sample": k, "defender": pair[0],
                            "attacker": pair[1], "VoI": v})
    return out


def test_claims_can_fail() -> None:
    rising = summarize_density(_synthetic({0: ["1/4", "1/4"], 10: ["1/3", "1/2"]}))
    verdict = {c.text: c.holds for c in rising.claims}
    assert not verdict["mean VoI of (σ*, γ*) falls as the density grows (strictly, "
                       "at every step)"]
    assert verdict["spread of VoI of (σ*, γ*) grows with the density (range max-min)"]
    falling = summarize_density(_synthetic({0: ["1/2", "1/4"], 10: ["1/4", "1/4"]}))
    verdict = {c.text: c.holds for c in falling.claims}
    assert verdict["mean VoI of (σ*, γ*) falls as the density grows (strictly, at "
                   "every step)"]
    assert not verdict["spread of VoI of (σ*, γ*) grows with the density "
                       "(standard deviation)"]


@pytest.mark.parametrize("kwargs", [{"densities": (100,)}, {"samples": 0},
                                    {"start": (0, 0)}, {"start": (30, 0)},
                                    {"prior": ("1", "0")}])
def test_bad_config(kwargs: dict[str, object]) -> None:
    with pytest.raises(InvalidInstanceError):
        DensityConfig(**kwargs)  # type: ignore[arg-type]
