"""The .efg export of N-goal games (dppverify.tree_route.efg with an Instance), re-checked
independently.

The exported text is parsed back with the independent reader of
``tests/dppverify/tree_route/_efg_reader.py`` (written from Gambit's format specification, no code
shared with ``dppverify.tree_route.efg``) and checked against brute-force walk enumeration on the
instance document: node and information
set counts (``N^t`` copies of a ``t``-step prefix), perfect recall, what each player sees,
payoffs recomputed from the document, the chance node, OpenSpiel's action order, and that the
sequence-form LP of the parsed game (scipy HiGHS) gives the tree route's exact ``V_H``
(:func:`dppverify.tree_route.value_lp.game_value`) and the coalition DP's value. The two-goal
export is pinned byte for byte (digests of the output before the writer became N-generic).
"""

from __future__ import annotations

import hashlib
import itertools
import json
from collections import Counter, defaultdict
from fractions import Fraction
from pathlib import Path
from typing import Any

import pytest

from dppverify.errors import HorizonError, TreeTooLargeError
from dppverify.game.examples import star3_document
from dppverify.game.instance import instance_from_json
from dppverify.structured.coalition import coalition_value
from dppverify.tree_route.efg import efg_size, to_efg, tree_to_efg, write_efg
from dppverify.tree_route.tree import build_tree
from dppverify.tree_route.value_lp import game_value
from tests.dppverify._helpers import _key, adjacency, all_walks, distances_to, grid_doc, make_doc
from tests.dppverify._helpers import triangle_doc as _triangle_doc
from tests.dppverify.tree_route._efg_reader import (
    CASES,
    FRACTIONAL,
    GRID,
    IDS,
    KITE,
    LADDER,
    THIRDS,
    VARIANT_IDS,
    VARIANTS,
    Node,
    decode,
    export,
    own_history,
    parse,
    run_cli,
    sequence_form_value,
)

# ---------------------------------------------------------------------------------------------
# N-goal cases (tiny: the peers in tests/peers solve the same games)
# ---------------------------------------------------------------------------------------------

STAR3 = star3_document()
"""The bundled hub: V_2 = V_3 = 3/2 (hand-computed in tests/dppverify/test_certify_any_n.py)."""

DROP3 = make_doc([("g2", "g1", 3), ("g3", "s", 3), ("v0", "g2", 2), ("v0", "v1", 1),
                  ("v0", "v2", 1), ("v2", "s", 3)], "s", ["g1", "g2", "g3"],
                 ["1/2", "1/3", "1/6"], nodes=["s", "v0", "v1", "v2", "g1", "g2", "g3"])
"""V_2 = 21/2 > V_3 = 5: the value drops when longer walks become available."""

KITE3 = make_doc([("s", "a", 1), ("s", "b", 2), ("a", "g1", 2), ("a", "g2", 1), ("b", "g2", 1),
                  ("b", "g3", 2), ("a", "b", 1), ("g1", "g3", 3), ("s", "g3", 4)], "s",
                 ["g1", "g2", "g3"], ["1/2", "1/3", "1/6"])
FRAC3 = make_doc([("s", "m", "1/3"), ("m", "g1", "5/2"), ("m", "g2", "2/7"), ("m", "g3", "3/2"),
                  ("s", "g2", "7/3"), ("g1", "g2", 1), ("g3", "g1", "1/2")], "s",
                 ["g1", "g2", "g3"], ["2/5", "2/5", "1/5"])
DIRECTED3 = make_doc([("s", "a", 1), ("a", "g1", 1), ("a", "b", 1), ("b", "g2", 1),
                      ("b", "g3", 1), ("s", "g3", 3), ("g1", "g2", 2), ("g2", "g3", 2),
                      ("g3", "g1", 2), ("b", "s", 1)], "s", ["g1", "g2", "g3"],
                     ["1/3", "1/3", "1/3"], directed=True)
GRID3 = grid_doc(3, 3, (1, 1), [(0, 0), (0, 2), (2, 1)], ["1/2", "1/4", "1/4"])
STAR4 = make_doc([("s", "m", 1), ("m", "g1", 1), ("m", "g2", 1), ("m", "g3", 2), ("m", "g4", 1),
                  ("s", "g1", 2), ("s", "g4", 3)], "s", ["g1", "g2", "g3", "g4"],
                 ["2/5", "1/5", "1/5", "1/5"])

NCASES = [("star3", STAR3, 2), ("star3", STAR3, 3), ("drop3", DROP3, 2), ("drop3", DROP3, 3),
          ("kite3", KITE3, 2), ("frac3", FRAC3, 3), ("directed3", DIRECTED3, 3),
          ("grid3", GRID3, 2), ("star4", STAR4, 2)]
NIDS = [f"{name}-H{h}" for name, _, h in NCASES]


# ---------------------------------------------------------------------------------------------
# The two-goal export is unchanged (its bytes before the writer became N-generic)
# ---------------------------------------------------------------------------------------------

_FLOAT = make_doc([("s", "g1", 0.1), ("s", "g2", 2.5)], "s", ["g1", "g2"], ["1/2", "1/2"])
_FLOAT["numbers"] = "float"
_DOCS = {"triangle": _triangle_doc(), "kite": KITE, "ladder": LADDER, "thirds": THIRDS,
         "fractional": FRACTIONAL, "grid": GRID, "float": _FLOAT}
# (case, H, attacker_observes, forced_moves, sha256 prefix, length): dppverify.tree_route.efg at
# c2a9ea7
PINNED = [
    ("triangle", 3, True, False, "518a43e348526ef1", 891),
    ("triangle", 3, False, False, "82414bfaf8a8ccf8", 888),
    ("kite", 3, True, False, "f08b5852dbf7833f", 3598),
    ("kite", 3, True, True, "2e0f91d420b6377a", 3666),
    ("kite", 3, False, False, "4b68bb2a7bc1ced0", 3554),
    ("kite", 3, False, True, "e7ec50711621faf8", 3614),
    ("ladder", 2, True, False, "9f12e72f06add131", 1672),
    ("ladder", 2, True, True, "19ef4928888841db", 1945),
    ("ladder", 2, False, False, "1e25b67d4dd1382a", 1669),
    ("ladder", 2, False, True, "36d34cefa8b1164b", 1917),
    ("thirds", 3, True, False, "008a1dac48dc7841", 4511),
    ("thirds", 3, False, True, "d96fd5b865730132", 4707),
    ("fractional", 4, True, False, "4fe095c4b089a7e2", 8080),
    ("fractional", 4, False, False, "b63d184bede21e83", 7932),
    ("grid", 4, True, False, "4cdce935f6d76535", 19743),
    ("grid", 4, True, True, "9c54f6c512ede4f1", 24950),
    ("grid", 4, False, False, "fc4d826cd1634e5e", 19605),
    ("grid", 4, False, True, "15a3e58f07519596", 24148),
    ("float", 1, True, False, "6b2d1084caa01e37", 925),
    ("float", 1, False, False, "a92fbdeacc8686d9", 922),
]


@pytest.mark.parametrize(("name", "horizon", "observes", "forced", "digest", "length"), PINNED,
                         ids=[f"{c[0]}-H{c[1]}-{c[2]}-{c[3]}" for c in PINNED])
def test_two_goal_export_bytes_are_unchanged(name: str, horizon: int, observes: bool,
                                             forced: bool, digest: str, length: int) -> None:
    text = to_efg(instance_from_json(_DOCS[name]), horizon, attacker_observes=observes,
                  forced_moves=forced)
    assert (hashlib.sha256(text.encode()).hexdigest()[:16], len(text)) == (digest, length)


@pytest.mark.parametrize("name", ["triangle", "kite", "ladder", "thirds", "fractional", "grid"])
@pytest.mark.parametrize(("observes", "forced"), VARIANTS, ids=VARIANT_IDS)
def test_two_goals_read_as_n_goals_export_the_same_bytes(name: str, observes: bool,
                                                         forced: bool) -> None:
    doc = _DOCS[name]
    h = {"triangle": 3, "kite": 3, "ladder": 2, "thirds": 3, "fractional": 4, "grid": 4}[name]
    two = to_efg(instance_from_json(doc), h, attacker_observes=observes, forced_moves=forced)
    n = to_efg(instance_from_json(doc), h, attacker_observes=observes, forced_moves=forced)
    assert n == two


# ---------------------------------------------------------------------------------------------
# Structure, payoffs and value of N-goal exports
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize(("observes", "forced"), VARIANTS, ids=VARIANT_IDS)
@pytest.mark.parametrize(("name", "doc", "horizon"), CASES + NCASES, ids=IDS + NIDS)
def test_node_and_infoset_counts_are_n_to_the_t(name: str, doc: dict[str, Any], horizon: int,
                                                observes: bool, forced: bool) -> None:
    """Every t-step prefix appears once per type and per Defender history (N^t of them), for
    N = 2 (the two-goal cases) and more."""
    n = len(doc["goals"])
    game = export(doc, horizon, observes, forced)
    tree = build_tree(instance_from_json(doc), horizon)
    depth = [int(t) for t in tree.depth]
    kids = [len(tree.children(p)) for p in range(tree.n_prefixes)]
    choice = [p for p in range(tree.n_prefixes) if kids[p] >= (1 if forced else 2)]
    nodes = list(game.nodes())
    kinds = Counter((x.kind, x.player) for x in nodes)
    assert kinds[("c", 0)] == 1 and game.root.kind == "c" and len(game.root.children) == n
    assert kinds[("t", 0)] == n * sum(n ** depth[p] for p in tree.leaves().tolist())
    assert kinds[("p", 1)] == n * sum(n ** depth[p] for p in choice)
    d_nodes = sum(n ** (depth[p] - 1) for p in range(1, tree.n_prefixes))
    assert kinds[("p", 2)] == n * d_nodes
    infosets = {(x.player, x.infoset) for x in nodes if x.kind == "p"}
    n_att = sum(1 for pl, _ in infosets if pl == 1)
    n_def = sum(1 for pl, _ in infosets if pl == 2)
    assert n_def == d_nodes
    assert n_att == n * (sum(n ** depth[p] for p in choice) if observes else len(choice))
    assert all(len(x.actions) == n for x in nodes if x.kind == "p" and x.player == 2)
    assert all(len(x.actions) >= (1 if forced else 2) for x in nodes if x.kind == "p")
    size = efg_size(tree, attacker_observes=observes, forced_moves=forced)
    assert (size.nodes, size.terminals, size.attacker_infosets, size.defender_infosets) == (
        len(nodes), kinds[("t", 0)], n_att, n_def)


@pytest.mark.parametrize(("observes", "forced"), VARIANTS, ids=VARIANT_IDS)
@pytest.mark.parametrize(("name", "doc", "horizon"), NCASES, ids=NIDS)
def test_perfect_recall_and_what_each_player_sees(name: str, doc: dict[str, Any], horizon: int,
                                                  observes: bool, forced: bool) -> None:
    n = len(doc["goals"])
    members: dict[tuple[int, int], list[Node]] = defaultdict(list)
    for x in export(doc, horizon, observes, forced).nodes():
        if x.kind == "p":
            members[(x.player, x.infoset)].append(x)
    for (player, _), nodes in members.items():
        assert len({own_history(x, player) for x in nodes}) == 1  # perfect recall
        assert len({tuple(x.actions) for x in nodes}) == 1
        assert len({x.infoset_name for x in nodes}) == 1
        decoded = [decode(x, doc, horizon) for x in nodes]
        types = {g for g, _, _ in decoded}
        walks = {w for _, w, _ in decoded}
        if player == 2:  # the walk and its own allocations, one node per type
            assert len(nodes) == n and len(types) == n and len(walks) == 1
            assert len({tuple(a) for _, _, a in decoded}) == 1
        else:  # its type and the walk (and the allocations when it observes them)
            assert len(types) == 1 and len(walks) == 1
            steps = len(decoded[0][1]) - 1
            assert len(nodes) == (1 if observes else n ** steps)


@pytest.mark.parametrize("forced", [False, True])
@pytest.mark.parametrize(("name", "doc", "horizon"), CASES + NCASES, ids=IDS + NIDS)
def test_payoffs_only_on_leaves_and_equal_to_recomputed_costs(name: str, doc: dict[str, Any],
                                                               horizon: int,
                                                               forced: bool) -> None:
    """Zero-sum payoffs on the leaves only, one per outcome, each the cost recomputed from the
    instance document (what lands on the true goal plus its terminal cost); every walk of the
    game for each type once per Defender history (N^steps), for N = 2 and more."""
    game = export(doc, horizon, forced=forced)
    assert game.players == ["Attacker", "Defender"]
    adj = {u: dict(arcs) for u, arcs in adjacency(doc).items()}
    goals = [_key(g) for g in doc["goals"]]
    dist = {g: distances_to(doc, g) for g in goals}
    outcomes: dict[int, list[Fraction]] = {}
    seen: Counter[tuple[Any, ...]] = Counter()
    for x in game.nodes():
        if x.kind != "t":
            assert x.payoffs is None and x.outcome == 0
            continue
        assert x.payoffs is not None and x.outcome > 0
        assert outcomes.setdefault(x.outcome, x.payoffs) == x.payoffs
        attacker, defender = x.payoffs
        assert attacker == -defender  # zero-sum
        goal, walk, allocs = decode(x, doc, horizon)
        assert len(allocs) == len(walk) - 1  # the Defender allocated every step
        assert all(b in adj[a] for a, b in itertools.pairwise(walk))
        assert walk[-1] in goals and not set(walk[:-1]) & set(goals) and len(walk) <= horizon + 1
        cost = sum((adj[a][b] for (a, b), g in zip(itertools.pairwise(walk), allocs, strict=True)
                    if g == goal), Fraction(0))
        assert defender == cost + dist[goal][walk[-1]]  # what lands on its true goal
        seen[(goal, walk)] += 1
    n = len(goals)
    assert seen == Counter({(g, w): n ** (len(w) - 1) for g in goals
                            for w in all_walks(doc, horizon)})


@pytest.mark.parametrize(("name", "doc", "horizon"), NCASES, ids=NIDS)
def test_chance_node_and_action_order(name: str, doc: dict[str, Any], horizon: int) -> None:
    game = export(doc, horizon)
    assert [x for x in game.nodes() if x.kind == "c"] == [game.root]
    assert game.root.probs == [Fraction(b) for b in doc["prior"]]
    assert game.root.actions == [f"type {g}" for g in doc["goals"]]
    assert f"N = {len(doc['goals'])} goals, H = {horizon}" in game.title
    rank: dict[str, int] = {}  # OpenSpiel 2.0.2: actions in first-appearance order
    for x in game.nodes():
        if x.kind == "p":
            for a in x.actions:
                rank.setdefault(a, len(rank))
            assert [rank[a] for a in x.actions] == sorted(rank[a] for a in x.actions)


@pytest.mark.parametrize(("observes", "forced"), VARIANTS, ids=VARIANT_IDS)
@pytest.mark.parametrize(("name", "doc", "horizon"), NCASES, ids=NIDS)
def test_sequence_form_lp_of_the_export_gives_the_tree_value_and_the_dp(
        name: str, doc: dict[str, Any], horizon: int, observes: bool, forced: bool) -> None:
    inst = instance_from_json(doc)
    exact = game_value(inst, horizon).bracket.exact
    assert exact is not None
    assert coalition_value(inst, horizon).value == exact
    lp = sequence_form_value(export(doc, horizon, observes, forced), minimizer=1, maximizer=2)
    assert abs(lp - float(exact)) <= 1e-9 * max(1.0, abs(float(exact)))


def test_the_value_depends_on_the_horizon_in_the_export() -> None:
    # guards against cases where any export would match: V_2 = 21/2, V_3 = 5 for DROP3
    v2 = sequence_form_value(export(DROP3, 2), 1, 2)
    v3 = sequence_form_value(export(DROP3, 3), 1, 2)
    assert abs(v2 - 10.5) < 1e-9 and abs(v3 - 5) < 1e-9


def test_ten_goals_or_more_separate_the_history_digits() -> None:
    # eleven goals: g1 and g11 after the corridor s-a-b, the nine others one step from a;
    # after the steps s-a and a-b, "1"+"11" and "11"+"1" are different histories
    goals = [f"g{i}" for i in range(1, 12)]
    doc = make_doc([("s", "a", 1), ("a", "b", 1), ("b", "g1", 1), ("b", "g11", 1),
                    *[("a", g, 1) for g in goals[1:10]]], "s", goals, ["1/11"] * 11)
    inst = instance_from_json(doc)
    text = to_efg(inst, 3)
    assert '"D p12 h1.11"' in text and '"D p12 h11.1"' in text
    game = parse(text)
    members: dict[tuple[int, int], list[Node]] = defaultdict(list)
    for x in game.nodes():
        if x.kind == "p":
            members[(x.player, x.infoset)].append(x)
    assert all(len({own_history(x, pl) for x in xs}) == 1 for (pl, _), xs in members.items())
    n_def = sum(1 for pl, _ in members if pl == 2)
    assert n_def == efg_size(build_tree(inst, 3)).defender_infosets


@pytest.mark.parametrize(("doc", "horizon", "prefixes", "too_short"),
                         [(GRID, 5, 88, 1), (GRID3, 3, 5, 0)], ids=["N=2", "N=3"])
def test_size_guards_and_horizon_errors(tmp_path: Path, doc: dict[str, Any], horizon: int,
                                        prefixes: int, too_short: int) -> None:
    """The size guards refuse before anything is written; a horizon the game cannot take is
    refused; the written export has exactly the nodes the size said."""
    inst = instance_from_json(doc)
    nodes = efg_size(build_tree(inst, horizon)).nodes
    assert to_efg(inst, horizon, max_nodes=nodes)
    with pytest.raises(TreeTooLargeError, match="--max-nodes"):
        to_efg(inst, horizon, max_nodes=nodes - 1)
    with pytest.raises(TreeTooLargeError, match="--max-prefixes"):
        to_efg(inst, horizon, max_prefixes=prefixes)
    with pytest.raises(TreeTooLargeError, match="--max-nodes"):
        write_efg(tmp_path / "g.efg", build_tree(inst, horizon), max_nodes=nodes - 1)
    assert list(tmp_path.iterdir()) == []
    with pytest.raises(HorizonError):
        to_efg(inst, too_short)
    size = write_efg(tmp_path / "g.efg", build_tree(inst, horizon))
    assert size.nodes == nodes == sum(1 for _ in parse((tmp_path / "g.efg").read_text()).nodes())


def test_size_is_exact_beyond_64_bits() -> None:
    # a forced corridor of 80 steps: 2^80 Defender histories (an int64 count wrapped around)
    edges = [(i, i + 1, 1) for i in range(80)] + [(80, "g1", 1), (80, "g2", 1)]
    two = instance_from_json(make_doc(edges, 0, ["g1", "g2"], ["1/2", "1/2"]))
    size = efg_size(build_tree(two, 81))
    assert size.defender_infosets == sum(2 ** (t - 1) for t in range(1, 81)) + 2 * 2 ** 80
    assert size.nodes > 2 ** 80
    with pytest.raises(TreeTooLargeError, match="--max-nodes"):
        tree_to_efg(build_tree(two, 81))
    three = instance_from_json(make_doc([*edges, (80, "g3", 1)], 0, ["g1", "g2", "g3"],
                                         ["1/3", "1/3", "1/3"]))
    assert efg_size(build_tree(three, 81)).defender_infosets > 3 ** 80


# ---------------------------------------------------------------------------------------------
# dpp export-efg with an N-goal instance
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("flags", [[], ["--attacker-blind"], ["--forced-moves"], ["--progress"],
                                   ["--attacker-blind", "--forced-moves", "--no-progress"]])
def test_cli_export_efg_n_goals(tmp_path: Path, flags: list[str]) -> None:
    path = tmp_path / "kite3.json"
    path.write_text(json.dumps(KITE3))
    out = tmp_path / "kite3.efg"
    r = run_cli([str(path), "-H", "2", "-o", str(out), *flags])
    assert r.exit_code == 0, r.output
    inst = instance_from_json(KITE3)
    assert out.read_text() == to_efg(inst, 2, attacker_observes="--attacker-blind" not in flags,
                                     forced_moves="--forced-moves" in flags)
    size = efg_size(build_tree(inst, 2), attacker_observes="--attacker-blind" not in flags,
                    forced_moves="--forced-moves" in flags)
    assert f"{size.nodes} game nodes" in r.output and "N = 3 goals" in r.output


@pytest.mark.parametrize(("doc", "horizon"), [(KITE, 9), (KITE3, 3)], ids=["N=2", "N=3"])
@pytest.mark.parametrize("extra", [["--max-nodes", "100"], ["--max-prefixes", "5"], ["H=0"]])
def test_cli_export_efg_refusals_are_one_line(tmp_path: Path, doc: dict[str, Any], horizon: int,
                                              extra: list[str]) -> None:
    """Too large a game (nodes, prefixes) or ``-H 0``: one line, exit 2, nothing written."""
    path = tmp_path / "game.json"
    path.write_text(json.dumps(doc))
    out = tmp_path / "g.efg"
    flags = ["-H", "0"] if extra == ["H=0"] else ["-H", str(horizon), *extra]
    r = run_cli([str(path), "-o", str(out), *flags])
    assert r.exit_code == 2 and r.output.startswith("error: ") and len(r.output.splitlines()) == 1
    assert not out.exists()


def test_cli_export_efg_invalid_n_goal_instance(tmp_path: Path) -> None:
    bad = dict(KITE3, prior=["1/2", "1/3", "1/3"])
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(bad))
    r = run_cli([str(path), "-H", "2", "-o", str(tmp_path / "g.efg")])
    assert r.exit_code == 2 and len(r.output.splitlines()) == 1
    assert "prior: must sum to exactly 1" in r.output
    assert not (tmp_path / "g.efg").exists()
