"""The Gambit .efg export: an independent reader re-checks structure, payoffs and the value.

The reader and the sequence-form LP below are written from Gambit's format specification and
share no code with ``dppverify.tree_route.efg``: the tests parse the exported text back, check node
and
information-set counts against the walk tree, perfect recall, payoffs (on leaves only) against
costs recomputed from the instance document, the chance probabilities, OpenSpiel's action
ordering requirement, and that the sequence-form LP of the parsed game (scipy HiGHS) gives
``V_H`` from :func:`dppverify.game_value`.
"""


from __future__ import annotations

import itertools
import json
import re
from collections import Counter, defaultdict
from collections.abc import Iterator
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import scipy.sparse as sp
from click.testing import CliRunner
from scipy.optimize import linprog

from dppverify import game_value
from dppverify.cli import COMMANDS
from dppverify.cli.export_efg import export_efg_command
from dppverify.errors import CheckerError, HorizonError, TreeTooLargeError
from dppverify.game.instance import instance_from_json
from dppverify.tree_route.efg import efg_size, to_efg, write_efg
from dppverify.tree_route.tree import build_tree
from tests.dppverify._helpers import (
    _key,
    adjacency,
    all_walks,
    distances_to,
    grid_doc,
    make_doc,
    triangle_doc,
)

_TOKEN = re.compile(r'"([^"]*)"|([{}])|([^\s{}",]+)')


@dataclass
class Node:
    """One node of a parsed game."""

    kind: str  # "c", "p" or "t"
    player: int = 0  # 0 for chance and terminals
    infoset: int = 0
    infoset_name: str = ""
    actions: list[str] = field(default_factory=list)
    probs: list[Fraction] = field(default_factory=list)
    outcome: int = 0
    payoffs: list[Fraction] | None = None
    children: list[Node] = field(default_factory=list)
    history: list[tuple[int, int, str]] = field(default_factory=list)  # (player, infoset, action)
    reach: Fraction = Fraction(1)  # chance probability of reaching the node


@dataclass
class Game:
    """A parsed ``.efg`` game."""

    title: str
    players: list[str]
    comment: str
    root: Node

    def nodes(self) -> Iterator[Node]:
        """All nodes in preorder (the file's order)."""
        stack = [self.root]
        while stack:
            n = stack.pop()
            yield n
            stack.extend(reversed(n.children))


class _Tokens:
    def __init__(self, text: str) -> None:
        self.items: list[tuple[str, str]] = []
        for m in _TOKEN.finditer(text):
            if m.group(1) is not None:
                self.items.append(("q", m.group(1)))
            elif m.group(2) is not None:
                self.items.append(("b", m.group(2)))
            else:
                self.items.append(("w", m.group(3)))
        self.i = 0

    def peek(self) -> tuple[str, str] | None:
        return self.items[self.i] if self.i < len(self.items) else None

    def take(self, kind: str) -> str:
        tok = self.items[self.i]
        if tok[0] != kind:
            raise ValueError(f"token {self.i}: expected {kind}, got {tok}")
        self.i += 1
        return tok[1]

    def brace(self, which: str) -> None:
        if self.take("b") != which:
            raise ValueError(f"token {self.i - 1}: expected {which!r}")


def _payoffs(tok: _Tokens) -> list[Fraction]:
    tok.brace("{")
    out = []
    while tok.peek() != ("b", "}"):
        out.append(Fraction(tok.take("w")))
    tok.brace("}")
    return out


def _outcome(tok: _Tokens, node: Node) -> None:
    node.outcome = int(tok.take("w"))
    nxt = tok.peek()
    if nxt is not None and nxt[0] == "q":
        tok.take("q")
        nxt = tok.peek()
    if nxt == ("b", "{"):
        node.payoffs = _payoffs(tok)


def _node(tok: _Tokens) -> Node:
    kind = tok.take("w")
    tok.take("q")  # node name
    if kind == "t":
        node = Node("t")
        _outcome(tok, node)
        return node
    if kind == "c":
        node = Node("c", infoset=int(tok.take("w")))
    elif kind == "p":
        node = Node("p", player=int(tok.take("w")), infoset=int(tok.take("w")))
    else:
        raise ValueError(f"unknown node type {kind!r}")
    if tok.peek() is not None and tok.peek()[0] == "q":  # type: ignore[index]
        node.infoset_name = tok.take("q")
    tok.brace("{")
    while tok.peek() != ("b", "}"):
        node.actions.append(tok.take("q"))
        if kind == "c":
            node.probs.append(Fraction(tok.take("w")))
    tok.brace("}")
    _outcome(tok, node)
    node.children = [_node(tok) for _ in node.actions]
    return node


def parse(text: str) -> Game:
    """Parse ``.efg`` text (version 2, "R" format)."""
    tok = _Tokens(text)
    if tok.take("w") != "EFG" or tok.take("w") != "2" or tok.take("w") != "R":
        raise ValueError("not an EFG 2 R file")
    title = tok.take("q")
    tok.brace("{")
    players = []
    while tok.peek() != ("b", "}"):
        players.append(tok.take("q"))
    tok.brace("}")
    comment = tok.take("q") if tok.peek() is not None and tok.peek()[0] == "q" else ""  # type: ignore[index]
    root = _node(tok)
    if tok.peek() is not None:
        raise ValueError("trailing tokens after the root's subtree")
    _rebase(root, [], Fraction(1))
    return Game(title, players, comment, root)


def _rebase(node: Node, history: list[tuple[int, int, str]], reach: Fraction) -> None:
    """Recompute every node's history and chance reach top-down."""
    node.history = history
    node.reach = reach
    for a, c in enumerate(node.children):
        step = (node.player, node.infoset, node.actions[a])
        _rebase(c, [*history, step], reach * (node.probs[a] if node.kind == "c" else 1))


def own_history(node: Node, player: int) -> tuple[tuple[int, str], ...]:
    """The (infoset, action) moves of ``player`` on the way to ``node``."""
    return tuple((i, a) for p, i, a in node.history if p == player)


def sequence_form_value(game: Game, minimizer: int, maximizer: int) -> float:
    """Value (the maximiser's payoff) of a zero-sum two-player game with perfect recall.

    ``min_x max_y x^T A y`` over the players' realization plans, as one LP: the maximiser's
    best response is replaced by its dual (``min f^T q`` s.t. ``F^T q >= A^T x``).
    """
    seqs: list[dict[tuple[int, str] | None, int]] = [{None: 0}, {None: 0}]
    parent: list[dict[int, tuple[int, str] | None]] = [{}, {}]
    actions: list[dict[int, list[str]]] = [{}, {}]
    payoff: dict[tuple[int, int], float] = {}
    who = {minimizer: 0, maximizer: 1}

    def last(node: Node, k: int) -> tuple[int, str] | None:
        own = own_history(node, [minimizer, maximizer][k])
        return own[-1] if own else None

    for node in game.nodes():
        if node.kind == "p":
            k = who[node.player]
            parent[k].setdefault(node.infoset, last(node, k))
            actions[k].setdefault(node.infoset, node.actions)
            for a in node.actions:
                seqs[k].setdefault((node.infoset, a), len(seqs[k]))
        elif node.kind == "t":
            assert node.payoffs is not None
            key = (seqs[0][last(node, 0)], seqs[1][last(node, 1)])
            val = float(node.reach * node.payoffs[maximizer - 1])
            payoff[key] = payoff.get(key, 0.0) + val
    # Ordering: terminals come after the sequences they use (preorder), so ids are final.
    nx, ny = len(seqs[0]), len(seqs[1])
    infos_y = sorted(actions[1])
    row_q = {inf: r + 1 for r, inf in enumerate(infos_y)}  # row 0: the root of y
    nq = len(infos_y) + 1
    # variables: x (nx, >= 0) then q (nq, free)
    a_mat = sp.lil_matrix((ny, nx + nq))
    for (i, j), v in payoff.items():  # (A^T x)[j] - (F^T q)[j] <= 0
        a_mat[j, i] += v
    a_mat[0, nx + 0] -= 1.0  # F[root, empty] = 1
    for inf in infos_y:
        r = row_q[inf]
        a_mat[seqs[1][parent[1][inf]], nx + r] += 1.0  # F[inf, parent] = -1
        for a in actions[1][inf]:
            a_mat[seqs[1][(inf, a)], nx + r] -= 1.0  # F[inf, (inf, a)] = 1
    infos_x = sorted(actions[0])
    e_mat = sp.lil_matrix((len(infos_x) + 1, nx + nq))
    e_mat[0, 0] = 1.0
    for r, inf in enumerate(infos_x, start=1):
        e_mat[r, seqs[0][parent[0][inf]]] = -1.0
        for a in actions[0][inf]:
            e_mat[r, seqs[0][(inf, a)]] = 1.0
    b_eq = np.zeros(len(infos_x) + 1)
    b_eq[0] = 1.0
    c = np.zeros(nx + nq)
    c[nx] = 1.0
    bounds = [(0, None)] * nx + [(None, None)] * nq
    res = linprog(c, A_ub=a_mat.tocsr(), b_ub=np.zeros(ny), A_eq=e_mat.tocsr(), b_eq=b_eq,
                  bounds=bounds, method="highs")
    if res.status != 0:
        raise RuntimeError(f"sequence-form LP: {res.message}")
    return float(res.fun)


# ---------------------------------------------------------------------------------------------
# The tests
# ---------------------------------------------------------------------------------------------

KITE = make_doc([("a", "b", 1), ("a", "g2", 1), ("a", "s", 2), ("b", "g1", 1), ("b", "g2", 1),
                 ("g1", "a", 4), ("g2", "g1", 4)], "s", ["g1", "g2"], ["7/10", "3/10"])
"""V_2 = 7/2 > V_3 = 31/10: the value drops when longer walks become available."""

LADDER = make_doc([("a", "s", 1), ("b", "a", 3), ("b", "s", 3), ("g1", "a", 4), ("g1", "b", 3),
                   ("g1", "g2", 2), ("g2", "s", 4)], "s", ["g1", "g2"], ["7/10", "3/10"])
THIRDS = make_doc([("a", "b", 1), ("a", "g2", 3), ("b", "g2", 4), ("g1", "b", 1), ("s", "a", 3),
                   ("s", "g2", 2)], "s", ["g1", "g2"], ["2/3", "1/3"])
GRID = grid_doc(3, 4, (0, 1), [(2, 0), (2, 3)], ["3/5", "2/5"])
FRACTIONAL = make_doc([("s", "m", "1/3"), ("m", "g1", "5/2"), ("m", "g2", "2/7"),
                       ("s", "g2", "7/3"), ("g1", "g2", 1)], "s", ["g1", "g2"], ["4/7", "3/7"])

CASES = [("triangle", triangle_doc(), 2), ("kite", KITE, 2), ("kite", KITE, 3),
         ("ladder", LADDER, 1), ("ladder", LADDER, 2), ("thirds", THIRDS, 3),
         ("fractional", FRACTIONAL, 4),
         ("grid", GRID, 4)]
IDS = [f"{name}-H{h}" for name, _, h in CASES]


def _label(x: Any) -> str:
    return str(x)


VARIANTS = [(True, False), (False, False), (True, True), (False, True)]
VARIANT_IDS = ["observes", "blind", "observes-forced", "blind-forced"]


def _export(doc: dict[str, Any], horizon: int, observes: bool = True,
            forced: bool = False) -> Game:
    return parse(to_efg(instance_from_json(doc), horizon, attacker_observes=observes,
                        forced_moves=forced))


def _continuations(doc: dict[str, Any], horizon: int) -> dict[tuple[Any, ...], set[Any]]:
    """Walk prefix -> its possible next nodes, from the brute-force walk enumeration."""
    out: dict[tuple[Any, ...], set[Any]] = defaultdict(set)
    for w in all_walks(doc, horizon):
        for t in range(1, len(w)):
            out[w[:t]].add(w[t])
    return out


def _decode(node: Node, doc: dict[str, Any], horizon: int
            ) -> tuple[Any, tuple[Any, ...], list[Any]]:
    """(true goal, walk, allocated goal per step) of the history leading to ``node``.

    A step without an Attacker move (skipped forced move) must be the only continuation.
    """
    by_label = {_label(n["id"]): _key(n["id"]) for n in doc["graph"]["nodes"]}
    cont = _continuations(doc, horizon)
    kind, _, chance = node.history[0]
    assert kind == 0 and chance.startswith("type ")
    goal = by_label[chance.removeprefix("type ")]
    walk = [_key(doc["start"])]
    allocs: list[Any] = []
    moved = False
    for player, _, action in node.history[1:]:
        if player == 1:
            assert action.startswith("go ") and not moved
            walk.append(by_label[action.removeprefix("go ")])
            assert walk[-1] in cont[tuple(walk[:-1])]
            moved = True
        else:
            assert action.startswith("alloc ")
            if not moved:  # a forced step
                (only,) = cont[tuple(walk)]
                walk.append(only)
            allocs.append(by_label[action.removeprefix("alloc ")])
            moved = False
    return goal, tuple(walk), allocs


@pytest.mark.parametrize(("observes", "forced"), VARIANTS, ids=VARIANT_IDS)
@pytest.mark.parametrize(("name", "doc", "horizon"), CASES, ids=IDS)
def test_node_and_infoset_counts_match_the_walk_tree(name: str, doc: dict[str, Any],
                                                      horizon: int, observes: bool,
                                                      forced: bool) -> None:
    game = _export(doc, horizon, observes, forced)
    tree = build_tree(instance_from_json(doc), horizon)
    depth = [int(t) for t in tree.depth]
    n_kids = [len(tree.children(p)) for p in range(tree.n_prefixes)]
    choice = [p for p in range(tree.n_prefixes) if n_kids[p] >= (1 if forced else 2)]
    nodes = list(game.nodes())
    kinds = Counter((n.kind, n.player) for n in nodes)
    assert kinds[("c", 0)] == 1 and game.root.kind == "c"
    # every t-step prefix appears once per type and per Defender history (2^t of them)
    assert kinds[("t", 0)] == 2 * sum(2 ** depth[p] for p in tree.leaves())
    assert kinds[("p", 1)] == 2 * sum(2 ** depth[p] for p in choice)
    assert kinds[("p", 2)] == 2 * sum(2 ** (depth[p] - 1) for p in range(1, tree.n_prefixes))
    infosets = {(n.player, n.infoset) for n in nodes if n.kind == "p"}
    n_def = sum(1 for pl, _ in infosets if pl == 2)
    n_att = sum(1 for pl, _ in infosets if pl == 1)
    assert n_def == sum(2 ** (depth[p] - 1) for p in range(1, tree.n_prefixes))
    assert n_att == 2 * (sum(2 ** depth[p] for p in choice) if observes else len(choice))
    assert all(len(n.actions) >= (1 if forced else 2) for n in nodes if n.kind == "p")
    size = efg_size(tree, attacker_observes=observes, forced_moves=forced)
    assert (size.nodes, size.terminals, size.attacker_infosets, size.defender_infosets) == (
        len(nodes), kinds[("t", 0)], n_att, n_def)


def test_some_cases_have_forced_moves() -> None:
    # the forced-move variants above differ from the default ones only if moves are forced
    assert any(sum(1 for n in _export(d, h, forced=True).nodes() if len(n.actions) == 1)
               for _, d, h in CASES)


@pytest.mark.parametrize(("observes", "forced"), VARIANTS, ids=VARIANT_IDS)
@pytest.mark.parametrize(("name", "doc", "horizon"), CASES, ids=IDS)
def test_perfect_recall_and_consistent_infosets(name: str, doc: dict[str, Any], horizon: int,
                                                observes: bool, forced: bool) -> None:
    game = _export(doc, horizon, observes, forced)
    members: dict[tuple[int, int], list[Node]] = defaultdict(list)
    for n in game.nodes():
        if n.kind == "p":
            members[(n.player, n.infoset)].append(n)
    for (player, _), nodes in members.items():
        # perfect recall: the owner's own moves (infosets and actions) agree on every member
        assert len({own_history(n, player) for n in nodes}) == 1
        assert len({tuple(n.actions) for n in nodes}) == 1
        assert len({n.infoset_name for n in nodes}) == 1
        decoded = [_decode(n, doc, horizon) for n in nodes]
        types = {g for g, _, _ in decoded}
        walks = {w for _, w, _ in decoded}
        if player == 2:
            # the Defender sees the walk and its own allocations, not the type
            assert len(nodes) == 2 and len(types) == 2 and len(walks) == 1
            assert len({tuple(a) for _, _, a in decoded}) == 1
        else:
            assert len(types) == 1 and len(walks) == 1
            if observes:  # it also sees the Defender's allocations: singletons
                assert len(nodes) == 1
            else:
                assert len(nodes) == 2 ** (len(decoded[0][1]) - 1)


@pytest.mark.parametrize("forced", [False, True])
@pytest.mark.parametrize(("name", "doc", "horizon"), CASES, ids=IDS)
def test_payoffs_only_on_leaves_and_equal_to_recomputed_costs(name: str, doc: dict[str, Any],
                                                               horizon: int,
                                                               forced: bool) -> None:
    game = _export(doc, horizon, forced=forced)
    assert game.players == ["Attacker", "Defender"]
    adj = {u: dict(arcs) for u, arcs in adjacency(doc).items()}
    goals = [_key(g) for g in doc["goals"]]
    dist = {g: distances_to(doc, g) for g in goals}
    outcomes: dict[int, list[Fraction]] = {}
    seen: Counter[tuple[Any, ...]] = Counter()
    for n in game.nodes():
        if n.kind != "t":
            assert n.payoffs is None and n.outcome == 0
            continue
        assert n.payoffs is not None and n.outcome > 0
        assert outcomes.setdefault(n.outcome, n.payoffs) == n.payoffs
        attacker, defender = n.payoffs
        assert attacker == -defender  # zero-sum
        goal, walk, allocs = _decode(n, doc, horizon)
        assert len(allocs) == len(walk) - 1  # the Defender allocated every step
        assert all(b in adj[a] for a, b in itertools.pairwise(walk))
        assert walk[-1] in goals and not set(walk[:-1]) & set(goals) and len(walk) <= horizon + 1
        cost = sum((adj[a][b] for (a, b), g in zip(itertools.pairwise(walk), allocs, strict=True)
                    if g == goal), Fraction(0))
        assert defender == cost + dist[goal][walk[-1]]
        seen[(goal, walk)] += 1
    # every walk of the game, for each type, once per Defender history (2^steps)
    expected = Counter({(g, w): 2 ** (len(w) - 1) for g in goals
                        for w in all_walks(doc, horizon)})
    assert seen == expected


@pytest.mark.parametrize(("name", "doc", "horizon"), CASES, ids=IDS)
def test_chance_draws_the_type_with_the_exact_prior(name: str, doc: dict[str, Any],
                                                    horizon: int) -> None:
    game = _export(doc, horizon)
    chance = [n for n in game.nodes() if n.kind == "c"]
    assert chance == [game.root]
    assert sum(game.root.probs) == 1
    assert game.root.probs == [Fraction(b) for b in doc["prior"]]
    assert game.root.actions == [f"type {_label(g)}" for g in doc["goals"]]


@pytest.mark.parametrize(("name", "doc", "horizon"), CASES, ids=IDS)
def test_actions_listed_in_first_appearance_order(name: str, doc: dict[str, Any],
                                                  horizon: int) -> None:
    # OpenSpiel 2.0.2 sorts a node's global action ids (numbered by first appearance in the
    # file) but not its children: any other order silently permutes the children.
    rank: dict[str, int] = {}
    for n in _export(doc, horizon).nodes():
        if n.kind == "p":
            for a in n.actions:
                rank.setdefault(a, len(rank))
            ids = [rank[a] for a in n.actions]
            assert ids == sorted(ids)


@pytest.mark.parametrize(("observes", "forced"), VARIANTS, ids=VARIANT_IDS)
@pytest.mark.parametrize(("name", "doc", "horizon"), CASES[:-1], ids=IDS[:-1])
def test_sequence_form_lp_of_the_export_gives_v_h(name: str, doc: dict[str, Any], horizon: int,
                                                  observes: bool, forced: bool) -> None:
    value = game_value(instance_from_json(doc), horizon)
    assert value.bracket.closed
    exact = value.bracket.exact
    assert exact is not None
    lp = sequence_form_value(_export(doc, horizon, observes, forced), minimizer=1,
                             maximizer=2)
    assert abs(lp - float(exact)) <= 1e-9 * max(1.0, abs(float(exact)))


def test_the_value_depends_on_the_horizon_in_the_export() -> None:
    # guards against a test instance where any export would match (V_2 != V_3 for KITE)
    v2 = sequence_form_value(_export(KITE, 2), 1, 2)
    v3 = sequence_form_value(_export(KITE, 3), 1, 2)
    assert v3 < v2 - 0.1


def test_quotes_in_node_ids_are_replaced_and_names_stay_distinct() -> None:
    doc = make_doc([('s"', "g\\1", 1), ('s"', "g2", 2)], 's"', ["g\\1", "g2"], ["1/2", "1/2"])
    text = to_efg(instance_from_json(doc), 1)
    game = parse(text)
    assert game.root.actions == ["type g/1", "type g2"]
    assert {a for n in game.nodes() for a in n.actions} >= {"go g/1", "go g2", "alloc g/1"}


def test_clashing_labels_get_index_prefixes() -> None:
    doc = make_doc([(1, "1", 1), (1, 2, 1)], 1, ["1", 2], ["1/2", "1/2"])
    game = parse(to_efg(instance_from_json(doc), 1))
    assert game.root.actions == ["type v1:1", "type v2:2"]


def test_float_instances_export_decimals() -> None:
    doc = make_doc([("s", "g1", 0.1), ("s", "g2", 2.5)], "s", ["g1", "g2"], ["1/2", "1/2"])
    doc["numbers"] = "float"
    text = to_efg(instance_from_json(doc), 1)
    assert "e-" not in text and "0.1" in text
    costs = {n.payoffs[1] for n in parse(text).nodes() if n.payoffs}
    assert Fraction("0.1") in costs and Fraction("2.5") in costs


def test_size_guards_raise_before_writing(tmp_path: Path) -> None:
    inst = instance_from_json(GRID)
    nodes = efg_size(build_tree(inst, 5)).nodes
    assert to_efg(inst, 5, max_nodes=nodes)
    with pytest.raises(TreeTooLargeError, match="--max-nodes"):
        to_efg(inst, 5, max_nodes=nodes - 1)
    with pytest.raises(TreeTooLargeError, match="--max-prefixes"):
        write_efg(tmp_path / "g.efg", inst, 5, max_prefixes=88)
    assert list(tmp_path.iterdir()) == []
    with pytest.raises(HorizonError):
        to_efg(inst, 1)


def test_write_efg_is_atomic_and_reports_the_size(tmp_path: Path) -> None:
    target = tmp_path / "game.efg"
    target.write_text("old")
    size = write_efg(target, instance_from_json(KITE), 2)
    assert list(tmp_path.iterdir()) == [target]
    game = parse(target.read_text())
    assert size.nodes == sum(1 for _ in game.nodes())
    with pytest.raises(CheckerError, match="cannot write"):  # a file where a folder must be
        write_efg(target / "g.efg", instance_from_json(KITE), 2)
    assert list(tmp_path.iterdir()) == [target]


def _run(args: list[str]) -> Any:
    result = CliRunner().invoke(export_efg_command, args)
    assert "Traceback" not in result.output
    assert result.exception is None or isinstance(result.exception, SystemExit), result.exception
    return result


def test_cli_export_efg(tmp_path: Path) -> None:
    inst = tmp_path / "kite.json"
    inst.write_text(json.dumps(KITE))
    out = tmp_path / "kite.efg"
    r = _run([str(inst), "--horizon", "2", "-o", str(out)])
    assert r.exit_code == 0, r.output
    assert out.read_text() == to_efg(instance_from_json(KITE), 2)
    r = _run([str(inst), "-H", "2", "-o", str(out), "--attacker-blind"])
    assert r.exit_code == 0
    assert out.read_text() == to_efg(instance_from_json(KITE), 2, attacker_observes=False)
    assert export_efg_command in COMMANDS


@pytest.mark.parametrize("extra", [["-H", "9", "--max-nodes", "100"],
                                   ["-H", "9", "--max-prefixes", "5"], ["-H", "0"]])
def test_cli_export_efg_bad_requests_exit_2(tmp_path: Path, extra: list[str]) -> None:
    inst = tmp_path / "kite.json"
    inst.write_text(json.dumps(KITE))
    out = tmp_path / "g.efg"
    r = _run([str(inst), "-o", str(out), *extra])
    assert r.exit_code == 2 and r.output.startswith("error: ") and len(r.output.splitlines()) == 1
    assert not out.exists()


def test_cli_export_efg_bad_input_exit_2(tmp_path: Path) -> None:
    bad = tmp_path / "bad.json"
    bad.write_text("{not json")
    r = _run([str(bad), "-H", "2", "-o", str(tmp_path / "g.efg")])
    assert r.exit_code == 2 and "Traceback" not in r.output
    good = tmp_path / "kite.json"
    good.write_text(json.dumps(KITE))
    r = _run([str(good), "-H", "2", "-o", str(bad / "g.efg")])  # bad.json is not a folder
    assert r.exit_code == 2 and "cannot write" in r.output
