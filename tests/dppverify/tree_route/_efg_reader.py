"""An independent reader of Gambit's .efg text, the sequence-form LP and the test games, for the
tests of the export (``test_efg.py`` for two goals, ``test_efg_any_n.py`` for more).

Written from Gambit's format specification: no code is shared with ``dppverify.tree_route.efg``.
"""

from __future__ import annotations

import re
from collections import defaultdict
from collections.abc import Iterator
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import numpy as np
import scipy.sparse as sp
from click.testing import CliRunner
from scipy.optimize import linprog

from dppverify.cli.export_efg import export_efg_command
from dppverify.game.instance import instance_from_json
from dppverify.tree_route.efg import to_efg
from tests.dppverify._helpers import _key, all_walks, grid_doc, make_doc, triangle_doc

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


def label(x: Any) -> str:
    return str(x)


VARIANTS = [(True, False), (False, False), (True, True), (False, True)]
VARIANT_IDS = ["observes", "blind", "observes-forced", "blind-forced"]


def export(doc: dict[str, Any], horizon: int, observes: bool = True,
            forced: bool = False) -> Game:
    return parse(to_efg(instance_from_json(doc), horizon, attacker_observes=observes,
                        forced_moves=forced))


def continuations(doc: dict[str, Any], horizon: int) -> dict[tuple[Any, ...], set[Any]]:
    """Walk prefix -> its possible next nodes, from the brute-force walk enumeration."""
    out: dict[tuple[Any, ...], set[Any]] = defaultdict(set)
    for w in all_walks(doc, horizon):
        for t in range(1, len(w)):
            out[w[:t]].add(w[t])
    return out


def decode(node: Node, doc: dict[str, Any], horizon: int
            ) -> tuple[Any, tuple[Any, ...], list[Any]]:
    """(true goal, walk, allocated goal per step) of the history leading to ``node``.

    A step without an Attacker move (skipped forced move) must be the only continuation.
    """
    by_label = {label(n["id"]): _key(n["id"]) for n in doc["graph"]["nodes"]}
    cont = continuations(doc, horizon)
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


def run_cli(args: list[str]) -> Any:
    result = CliRunner().invoke(export_efg_command, args)
    assert "Traceback" not in result.output
    assert result.exception is None or isinstance(result.exception, SystemExit), result.exception
    return result
