"""The field's path metrics on ``paper10.map``: pinned by hand, and by an independent
computation (its own map reader, breadth-first distances and truthfulness test), against what
``dpp experiment compare --output-dir`` writes (``docs/experiments.md``, "The field's
metrics")."""

from __future__ import annotations

import csv
from collections import deque
from fractions import Fraction
from pathlib import Path

import pytest
from click.testing import CliRunner

from dpp import main
from solver.literature.path_metrics import PERCENTS

ROOT = Path(__file__).resolve().parents[3]
PAPER10 = ROOT / "examples" / "paper10.map"
START, G1, G2 = (9, 0), (0, 9), (0, 0)

Cell = tuple[int, int]


@pytest.fixture(scope="module")
def written(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("compare")
    r = CliRunner().invoke(main, ["experiment", "compare", "--output-dir", str(out),
                                  "--no-progress"])
    assert r.exit_code == 0, r.output
    return out


def _csv(path: Path) -> list[dict[str, str]]:
    with open(path, encoding="utf-8", newline="") as fh:
        return list(csv.DictReader(fh))


# ------------------------------------------------------------------ the independent computation
def _free() -> set[Cell]:
    rows = PAPER10.read_text().splitlines()[4:]
    return {(r, c) for r, line in enumerate(rows) for c, ch in enumerate(line) if ch == "."}


def _bfs(free: set[Cell], source: Cell) -> dict[Cell, int]:
    """4-connected unit-step distances from ``source`` (the map's grid is undirected)."""
    dist = {source: 0}
    queue = deque([source])
    while queue:
        r, c = queue.popleft()
        for nxt in ((r - 1, c), (r + 1, c), (r, c - 1), (r, c + 1)):
            if nxt in free and nxt not in dist:
                dist[nxt] = dist[(r, c)] + 1
                queue.append(nxt)
    return dist


def _metrics(route: list[Cell], real: Cell, bogus: Cell) -> dict[str, Fraction]:
    """The definitions of docs/experiments.md written out again, on unit-step routes."""
    free = _free()
    dr, db = _bfs(free, real), _bfs(free, bogus)

    def truthful(v: Cell) -> bool:
        return v != bogus and dr[v] - dr[START] < db[v] - db[START]

    flags = [truthful(v) for v in route]
    k = len(route) - 1
    last = max(i for i, t in enumerate(flags) if not t)
    out = {"cost": Fraction(k), "cost_ratio": Fraction(k, dr[START]), "ldp": Fraction(last, k),
           "deceptive_density": (Fraction(sum(not t for t in flags[1:last + 1]), last)
                                 if last else Fraction(0))}
    # the node at P %: the reference script's path has no start node, u_1 ... u_K
    out |= {f"truthful_{p}": Fraction(int(flags[1 + p * (k - 1) // 100])) for p in PERCENTS}
    return out


def _route(walk: list[Cell], real: Cell) -> list[Cell]:
    """The walk, continued to ``real`` when it stopped at the other goal: on paper10 that
    continuation is along the free top row, the only shortest path between the goals."""
    if walk[-1] == real:
        return walk
    assert {walk[-1], real} == {G1, G2}
    step = 1 if real == G1 else -1
    return walk + [(0, c) for c in range(walk[-1][1] + step, real[1] + step, step)]


def test_pi_d1_by_hand(written: Path) -> None:
    # The primary type's pi_d1 walks a shortest path to g2 = (0,0) (17 steps: d(s0, g2) = 17)
    # and its route goes on along the top row to g1 = (0,9) (9 steps): cost 26, and
    # d(s0, g1) = 18, so the cost ratio is 26/18 = 13/9. A node v is truthful iff
    # d(v, g1) - 18 < d(v, g2) - 17, i.e. d(v, g1) - d(v, g2) < 1. On the way to g2,
    # d(v, g2) = 17 - k and d(v, g1) >= 18 - k: never truthful. On the top row at (0, c):
    # 9 - c - c < 1 iff c >= 5. So the last deceptive node is (0, 4), step 17 + 4 = 21:
    # LDP 21/26, and every node up to it deceives: density 1. Truthful at P %: the reference
    # script's path u_1 ... u_26 (no start node) read at int(P/100 * 25), the node
    # 1 + floor(P * 25 / 100) = 3, 7, 13, 19, 23, 25: steps 3..19 come before (0, 3) ->
    # 0, 0, 0, 0; 23 = (0, 6) and 25 = (0, 8) -> 1, 1.
    row = next(r for r in _csv(written / "walks.csv")
               if r["attacker"] == "pi_d1" and r["type"] == "1")
    assert (row["goal"], row["walk"], row["probability"], row["steps"]) == ("0,9", "xi1_pi_d1",
                                                                             "1", "26")
    assert [row[k] for k in ("cost", "cost_ratio", "ldp", "deceptive_density")] == [
        "26", "13/9", "21/26", "1"]
    assert [row[f"truthful_{p}"] for p in PERCENTS] == ["0", "0", "0", "0", "1", "1"]


def test_every_walk_matches_the_independent_computation(written: Path) -> None:
    from solver.experiments.compare import paper10_instance
    from solver.literature.strategy_pairs import PairEvaluator

    game = PairEvaluator.of(paper10_instance())
    rows = _csv(written / "walks.csv")
    assert {r["attacker"] for r in rows} == {"gamma*", "ambiguity", "exaggeration", "pi_d1",
                                             "pi_d2", "pi_d3", "pi_d4"}
    for r in rows:
        att = game.attacker(r["attacker"])
        paths = att.primary if r["type"] == "1" else att.secondary
        (walk,) = [p for p in paths if p.label == r["walk"]]
        real, bogus = (G1, G2) if r["type"] == "1" else (G2, G1)
        want = _metrics(_route(list(walk.nodes), real), real, bogus)
        got = {k: Fraction(r[k]) for k in want}
        assert got == want, (r["attacker"], r["walk"])
        assert Fraction(r["probability"]) == walk.probability


def test_the_pairs_carry_the_expectation_over_the_prior_and_the_walks(written: Path) -> None:
    # gamma*: the primary type (prior 3/5) takes xi1_I (1/3, LDP 6/18) or xi1_II (2/3, LDP
    # 19/24), the secondary (2/5) xi2 (LDP 6/17): E[LDP] = 3/5 (1/9 + 19/36) + 2/5 * 6/17
    # = 107/204; E[cost] = 3/5 (18/3 + 2 * 24/3) + 2/5 * 17 = 20.
    walks = _csv(written / "walks.csv")
    pairs = _csv(written / "compare.csv")
    assert len(pairs) == 14
    prior = {"1": Fraction(3, 5), "2": Fraction(2, 5)}
    for pair in pairs:
        mine = [w for w in walks if w["attacker"] == pair["attacker"]]
        for key in ("cost", "cost_ratio", "ldp", "deceptive_density",
                    *(f"truthful_{p}" for p in PERCENTS)):
            expected = sum((prior[w["type"]] * Fraction(w["probability"]) * Fraction(w[key])
                            for w in mine), Fraction(0))
            assert Fraction(pair[key]) == expected, (pair["attacker"], key)
    star = next(p for p in pairs if (p["defender"], p["attacker"]) == ("sigma*", "gamma*"))
    assert (star["ldp"], star["cost"], star["truthful_50"]) == ("107/204", "20", "3/5")


def test_truthful_at_p_percent_reads_the_reference_script_s_node_by_hand() -> None:
    """One route whose truthful@ columns depend on the index, computed by hand: the 1 x 4
    corridor, start (0,0), real goal g_r = (0,3), bogus goal g_b = (0,1); the route is
    u_0 .. u_3 = (0,0), (0,1), (0,2), (0,3) (K = 3).

    Truthful (costdif(v, g) = d(v, g) - d(s0, g)): u_0 never (0 < 0 fails); u_1 = g_b never
    (the definition excludes the bogus goal); u_2: costdif(u_2, g_r) = 1 - 3 = -2 <
    costdif(u_2, g_b) = 1 - 1 = 0, truthful; u_3 = g_r: -3 < 2 - 1, truthful.

    The reference script's path has no start node (path1[1:] + path2[1:] = u_1 u_2 u_3) and
    reads path[int(P/100 * 2)]: u_1 for P = 10, 25 and u_2 for P = 50 ... 99, so
    truthful@ = 0, 0, 1, 1, 1, 1. (Node floor(P * K / 100) of u_0 .. u_3 would give u_0, u_0,
    u_1, u_2, u_2, u_2: 0, 0, 0, 1, 1, 1 — the reading dppverify had before.)"""
    import numpy as np

    from solver.game.instance import Instance
    from solver.literature.walk_metrics import RouteMeter

    inst = Instance.from_grid(np.zeros((1, 4), dtype=bool), (0, 0), ((0, 3), (0, 1)),
                              ("1/2", "1/2"))
    meter = RouteMeter.of(inst)
    net = inst.network
    theta = 1 if net.labels[meter.g1] == (0, 3) else 2  # the type whose goal is (0,3)
    walk = [net.index_of(c) for c in ((0, 0), (0, 1), (0, 2), (0, 3))]
    m = meter.walk_metrics(walk, theta)
    assert [str(t) for t in m.truthful] == ["0", "0", "1", "1", "1", "1"]
    assert (str(m.ldp), str(m.deceptive_density)) == ("1/3", "1")
