"""Export the truncated game as a Gambit ``.efg`` file (for peer tools: Gambit, OpenSpiel).

The exported extensive-form game is the truncated game of proofs/LP.md with the Defender's
allocations made explicit moves. One writer serves any number of goals
(:class:`~dppverify.game.instance.Instance`, :class:`~dppverify.tree_route.tree.WalkTree`;
``docs/formats.md`` §1, "N goals"); with N types:

1. **chance** draws the Attacker's type θ (its true goal g^θ, θ = 1 … N) with the prior ``b``
   (exact rationals); in the goal-selection game (``goal_values`` given, proofs/SELECT.md) the
   root is instead the **Attacker's** own decision ``choose <goal>`` (one information set), and
   every payoff is shifted by the chosen goal's value (the Attacker pays its cost minus
   ``r_θ``);
2. the **Attacker** (player 1) of that type chooses the next node of the walk; its
   information set is its type plus everything it has seen: the walk and the Defender's past
   allocations (``attacker_observes=True``, the default) or only the walk
   (``attacker_observes=False``). Where the walk has only one continuation the move is
   forced and, by default, not written as a decision node (``forced_moves=False``): Gambit
   17.0.0b2's ``lp_solve`` returns a wrong value on games with one-action information sets
   (``docs/peers.md``); ``forced_moves=True`` writes them anyway;
3. after every step the **Defender** (player 2) puts the step's whole weight on one of the N
   goals (action ``alloc <goal>``; a mixed action is a fractional allocation, the payoff being
   linear in it). Its information set is the walk prefix **plus its own past allocations**:
   the game must have perfect recall, otherwise Gambit refuses it and OpenSpiel's
   sequence-form LP silently solves a different game;
4. the walk ends at the first goal (a leaf of :class:`~dppverify.tree_route.tree.WalkTree`, with its
   pruning). Only terminal nodes carry outcomes (OpenSpiel rejects payoffs elsewhere): the
   Attacker pays ``Σ_t w(e_t)·[step t was allocated to its true goal] + d(end, true goal)``,
   the Defender receives it (zero-sum).

The value of this game for the Defender is ``V_H`` (:func:`dppverify.game_value`, any number
of goals) in both variants: observing the Defender's past moves is worthless to the Attacker
(they never change the state), which is what the peer cross-check in ``tests/peers`` confirms
(for two goals and for N = 3, 4).

Size: a prefix with ``t`` steps appears ``N^t`` times per type (once per Defender history),
so the game has ``1 + N·Σ_p (N^t·[p a choice] + N^(t-1)·[t ≥ 1] + N^t·[p leaf])`` nodes,
where "a choice" means a prefix with two or more children (any inner prefix with
``forced_moves=True``); the count is exact (Python integers), so the size guard holds at any
horizon. Only tiny horizons are practical for the peers (``docs/peers.md``).
A Defender history is written as the allocated goals' numbers ``1 … N`` (``h-`` when empty);
from ten goals on they are separated by dots.

Two format details that matter to OpenSpiel 2.0.2 (its ``.efg`` parser): labels are quoted
without escapes, so ``"`` and ``\\`` in node ids are replaced by ``'`` and ``/``; and it maps a
node's children to GLOBAL action ids sorted by first appearance in the file, so every node
lists its actions in the order their names first appeared (otherwise children are silently
permuted). Both Gambit and OpenSpiel read rationals ``p/q``; OpenSpiel needs ``|p|, q < 2^31``.

Examples
--------
>>> from dppverify.game.instance import instance_from_json
>>> inst = instance_from_json({"graph": {"nodes": [{"id": "s"}, {"id": "g1"}, {"id": "g2"}],
...     "edges": [{"source": "s", "target": "g2", "weight": 2},
...               {"source": "g2", "target": "g1", "weight": 2},
...               {"source": "s", "target": "g1", "weight": 3}]},
...     "start": "s", "goals": ["g1", "g2"], "prior": ["7/10", "3/10"]})
>>> text = to_efg(inst, 1)
>>> print(text)  # doctest: +ELLIPSIS
EFG 2 R "dppverify truncated DPP game, H = 1" { "Attacker" "Defender" }
"..."
<BLANKLINE>
c "" 1 "type" { "type g1" 7/10 "type g2" 3/10 } 0
p "" 1 1 "T1 p0 h-" { "go g1" "go g2" } 0
p "" 2 1 "D p1 h-" { "alloc g1" "alloc g2" } 0
t "" 1 "cost 3" { -3 3 }
t "" 2 "cost 0" { 0 0 }
p "" 2 2 "D p2 h-" { "alloc g1" "alloc g2" } 0
t "" 3 "cost 4" { -4 4 }
t "" 4 "cost 2" { -2 2 }
p "" 1 2 "T2 p0 h-" { "go g1" "go g2" } 0
p "" 2 1 "D p1 h-" { "alloc g1" "alloc g2" } 0
t "" 4 "cost 2" { -2 2 }
t "" 5 "cost 5" { -5 5 }
p "" 2 2 "D p2 h-" { "alloc g1" "alloc g2" } 0
t "" 2 "cost 0" { 0 0 }
t "" 4 "cost 2" { -2 2 }
<BLANKLINE>
>>> efg_size(build_tree(inst, 1)).nodes
15

With three goals the chance node has three branches and the Defender three actions:

>>> from dppverify.game.examples import star3
>>> print("".join(to_efg(star3(), 1).splitlines(keepends=True)[3:9]), end="")
c "" 1 "type" { "type a" 1/2 "type b" 1/3 "type c" 1/6 } 0
p "" 2 1 "D p1 h-" { "alloc a" "alloc b" "alloc c" } 0
t "" 1 "cost 2" { -2 2 }
t "" 2 "cost 0" { 0 0 }
t "" 2 "cost 0" { 0 0 }
p "" 2 1 "D p1 h-" { "alloc a" "alloc b" "alloc c" } 0
"""

from __future__ import annotations

import sys
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path

import numpy as np
from tqdm import tqdm

from dppverify.errors import TreeTooLargeError
from dppverify.exact import Number
from dppverify.formats.files import write_files
from dppverify.game.instance import Instance
from dppverify.tree_route.tree import DEFAULT_MAX_PREFIXES, WalkTree, build_tree

__all__ = ["DEFAULT_MAX_EFG_NODES", "EfgSize", "efg_size", "to_efg", "tree_to_efg", "write_efg"]

DEFAULT_MAX_EFG_NODES = 2_000_000
"""Default size guard on the exported game's node count (:class:`TreeTooLargeError` above)."""

ATTACKER, DEFENDER = 1, 2
"""Gambit player numbers (OpenSpiel: players 0 and 1)."""


@dataclass(frozen=True)
class EfgSize:
    """Size of the exported game, counted from the walk tree.

    Attributes
    ----------
    nodes : int
        All game nodes: the chance root, decision nodes and terminals.
    terminals, attacker_nodes, defender_nodes : int
        Nodes of each kind.
    attacker_infosets, defender_infosets : int
        Information sets of each player.
    """

    nodes: int
    terminals: int
    attacker_nodes: int
    defender_nodes: int
    attacker_infosets: int
    defender_infosets: int


def efg_size(tree: WalkTree, *, attacker_observes: bool = True,
             forced_moves: bool = False, selection: bool = False) -> EfgSize:
    """Count the exported game's nodes and information sets without writing it
    (``selection``: the goal-selection game, whose root is the Attacker's choice).

    Exact at any size (Python integers: ``N^t`` copies of a ``t``-step prefix), so it is
    the size guard of :func:`tree_to_efg`.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> inst = triangle()
    >>> efg_size(build_tree(inst, 1))
    EfgSize(nodes=15, terminals=8, attacker_nodes=2, defender_nodes=4, attacker_infosets=2, \
defender_infosets=2)
    >>> from dppverify.game.examples import star3
    >>> from dppverify.tree_route.tree import build_tree
    >>> efg_size(build_tree(star3(), 2)).nodes
    136
    """
    n = len(tree.instance.goals)
    depth = tree.depth.astype(np.int64)
    kids = tree.child_stop - tree.child_start
    choice = kids >= (1 if forced_moves else 2)  # prefixes written as Attacker nodes
    top = int(depth.max()) + 1
    power = [n ** t for t in range(top)]  # Defender histories before a t-step prefix: N^t

    def copies(mask: np.ndarray, shift: int = 0) -> int:
        per_depth = np.bincount(depth[mask], minlength=top).tolist()
        return sum(c * power[t - shift] for t, c in enumerate(per_depth) if c and t >= shift)

    inner_copies = copies(choice)
    dnodes = copies(depth >= 1, shift=1)
    leaves = copies(kids == 0)
    a_infosets = n * (inner_copies if attacker_observes else int(np.count_nonzero(choice)))
    root = int(selection)  # the goal choice is one more Attacker node and information set
    return EfgSize(nodes=1 + n * (inner_copies + dnodes + leaves), terminals=n * leaves,
                   attacker_nodes=n * inner_copies + root, defender_nodes=n * dnodes,
                   attacker_infosets=a_infosets + root, defender_infosets=dnodes)


def _label(text: str) -> str:
    """A label safe inside Gambit quotes for every reader (no escapes)."""
    return text.replace('"', "'").replace("\\", "/").replace("\n", " ")


def _node_names(instance: Instance) -> list[str]:
    """One distinct, quote-safe name per node (its id; ``v<i>:`` prefixed on a clash)."""
    names = []
    for v in instance.nodes:
        if isinstance(v, tuple):
            names.append(_label(str(list(v)) if v else "[]"))
        else:
            names.append(_label(str(v)))
    if len(set(names)) < len(names):
        names = [f"v{i}:{n}" for i, n in enumerate(names)]
    return names


def _number(x: Number) -> str:
    """A payoff or probability in .efg syntax: ``p/q`` for rationals, positional decimals."""
    if isinstance(x, float):
        return str(np.format_float_positional(x, unique=True, trim="-"))
    f = Fraction(x)
    return str(f.numerator) if f.denominator == 1 else f"{f.numerator}/{f.denominator}"


class _Writer:
    """Preorder emission of the game tree (one ``.efg`` line per node)."""

    def __init__(self, tree: WalkTree, attacker_observes: bool, forced_moves: bool,
                 goal_values: Sequence[Number] | None = None) -> None:
        self.tree = tree
        self.values = goal_values
        self.forced = forced_moves
        self.inst = tree.instance
        self.observes = attacker_observes
        self.names = _node_names(self.inst)
        self.goal_names = [self.names[g] for g in self.inst.goals]
        self.types = range(len(self.goal_names))
        self.sep = "" if len(self.goal_names) <= 9 else "."  # histories stay unambiguous
        self.infosets: tuple[dict[tuple[object, ...], int], dict[tuple[object, ...], int]] = (
            {}, {})
        self.outcomes: dict[Number, int] = {}
        self.action_rank: dict[str, int] = {}  # player-action names by first appearance
        self.exact = self.inst.exact
        self.numbers = self.inst.numbers
        self.zero: Number = self.numbers.zero()

    def _infoset(self, player: int, key: tuple[object, ...]) -> int:
        table = self.infosets[player - 1]
        if key not in table:
            table[key] = len(table) + 1
        return table[key]

    def _ordered(self, named: list[tuple[str, int]]) -> list[tuple[str, int]]:
        """Actions in first-appearance order of their names (OpenSpiel's global action ids)."""
        big = len(self.action_rank) + len(named)
        out = sorted(named, key=lambda a: self.action_rank.get(a[0], big))
        for name, _ in out:
            self.action_rank.setdefault(name, len(self.action_rank))
        return out

    def _terminal(self, cost: Number) -> str:
        cost = self.numbers.convert(cost)
        num = self.outcomes.setdefault(cost, len(self.outcomes) + 1)
        c = _number(cost)
        neg = _number(-cost) if cost != 0 else c
        return f't "" {num} "cost {c}" {{ {neg} {c} }}'

    @staticmethod
    def _hist(h: str) -> str:
        return h or "-"

    def lines(self) -> Iterator[str]:
        inst = self.inst
        if self.values is not None:  # the goal-selection game: the Attacker chooses its goal
            num = self._infoset(ATTACKER, ("goal",))
            acts = " ".join(f'"choose {name}"' for name in self.goal_names)
            yield f'p "" {ATTACKER} {num} "goal" {{ {acts} }} 0'
            for theta in self.types:
                yield from self._attacker(theta, 0, "", -self.numbers.convert(self.values[theta]))
            return
        branches = " ".join(f'"type {name}" {_number(p)}'
                            for name, p in zip(self.goal_names, inst.prior, strict=True))
        yield f'c "" 1 "type" {{ {branches} }} 0'
        for theta in self.types:
            yield from self._attacker(theta, 0, "", self.zero)

    def _attacker(self, theta: int, p: int, hist: str, cost: Number) -> Iterator[str]:
        """Attacker of type ``theta`` at prefix ``p`` after Defender history ``hist``."""
        tree = self.tree
        if tree.child_start[p] == tree.child_stop[p]:
            v = int(tree.node[p])
            yield self._terminal(cost + self.inst.dist_to[theta][v])
            return
        if not self.forced and tree.child_stop[p] - tree.child_start[p] == 1:
            yield from self._defender(theta, int(tree.child_start[p]), hist, cost)
            return
        key: tuple[object, ...] = (theta, p, hist) if self.observes else (theta, p)
        num = self._infoset(ATTACKER, key)
        name = f"T{theta + 1} p{p} h{self._hist(hist)}" if self.observes else f"T{theta + 1} p{p}"
        acts = self._ordered([(f"go {self.names[int(tree.node[c])]}", c)
                              for c in tree.children(p)])
        labels = " ".join(f'"{a}"' for a, _ in acts)
        yield f'p "" {ATTACKER} {num} "{name}" {{ {labels} }} 0'
        for _, c in acts:
            yield from self._defender(theta, c, hist, cost)

    def _defender(self, theta: int, p: int, hist: str, cost: Number) -> Iterator[str]:
        """Defender allocating the last step of prefix ``p`` after its own history ``hist``."""
        num = self._infoset(DEFENDER, (p, hist))
        acts = self._ordered([(f"alloc {self.goal_names[k]}", k) for k in self.types])
        labels = " ".join(f'"{a}"' for a, _ in acts)
        yield f'p "" {DEFENDER} {num} "D p{p} h{self._hist(hist)}" {{ {labels} }} 0'
        w = self.tree.weight[p]
        for _, k in acts:
            step = f"{self.sep}{k + 1}" if hist else str(k + 1)
            yield from self._attacker(theta, p, hist + step, cost + w if k == theta else cost)


def tree_to_efg(tree: WalkTree, *, attacker_observes: bool = True, forced_moves: bool = False,
                max_nodes: int = DEFAULT_MAX_EFG_NODES, title: str | None = None,
                goal_values: Sequence[Number] | None = None) -> str:
    """The ``.efg`` text of the game on an already built walk tree (see :func:`to_efg`).

    Parameters
    ----------
    tree : WalkTree
        The walk tree of the truncated game (any number of goals).
    attacker_observes, forced_moves, max_nodes, title, goal_values
        As for :func:`to_efg`.

    Returns
    -------
    str
        The Gambit ``.efg`` text.

    Raises
    ------
    TreeTooLargeError
        If the game has more than ``max_nodes`` nodes.

    Examples
    --------
    On the triangle (H = 1) the primary type's walk ``s -> g2`` costs 4 when the Defender
    allocates the step to g1 (weight 2 + d(g2, g1) = 2) and 2 when it allocates to g2:

    >>> from dppverify.game.examples import triangle
    >>> from dppverify.tree_route.tree import build_tree
    >>> inst = triangle()
    >>> tree = build_tree(inst, 1)
    >>> text = tree_to_efg(tree)
    >>> text == to_efg(inst, 1)
    True
    >>> print("".join(text.splitlines(keepends=True)[3:6]), end="")
    c "" 1 "type" { "type g1" 7/10 "type g2" 3/10 } 0
    p "" 1 1 "T1 p0 h-" { "go g1" "go g2" } 0
    p "" 2 1 "D p1 h-" { "alloc g1" "alloc g2" } 0
    >>> tree_to_efg(tree, max_nodes=10)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.TreeTooLargeError: the .efg game for H = 1 has 15 nodes ...
    """
    selection = goal_values is not None
    size = efg_size(tree, attacker_observes=attacker_observes, forced_moves=forced_moves,
                    selection=selection)
    if size.nodes > max_nodes:
        raise TreeTooLargeError(
            f"the .efg game for H = {tree.horizon} has {size.nodes} nodes ({tree.n_prefixes} "
            f"walk prefixes, each repeated for every Defender history), more than the limit of "
            f"{max_nodes}; lower the horizon or raise the limit (--max-nodes)")
    n = len(tree.instance.goals)
    goals = f"N = {n} goals, " if n > 2 else ""
    game = "goal-selection DPP game" if selection else "DPP game"
    head = _label(title or f"dppverify truncated {game}, {goals}H = {tree.horizon}")
    view = ("the Attacker observes the Defender's past allocations" if attacker_observes else
            "the Attacker does not observe the Defender's allocations")
    root = ("the Attacker chooses its goal at the root and pays its cost minus the goal's value"
            if selection else "chance draws the Attacker's true goal")
    comment = (f"Player 1 = Attacker (pays the cost), player 2 = Defender (receives it); "
               f"{root}; {view}; the Defender's information "
               f"set is the walk prefix plus its own past allocations (perfect recall); "
               f"{tree.n_prefixes} walk prefixes, {size.nodes} game nodes.")
    out = [f'EFG 2 R "{head}" {{ "Attacker" "Defender" }}', f'"{_label(comment)}"', ""]
    out.extend(_Writer(tree, attacker_observes, forced_moves, goal_values).lines())
    out.append("")
    return "\n".join(out)


def to_efg(instance: Instance, horizon: int, *, attacker_observes: bool = True,
           forced_moves: bool = False, max_prefixes: int = DEFAULT_MAX_PREFIXES,
           max_nodes: int = DEFAULT_MAX_EFG_NODES, title: str | None = None,
           goal_values: Sequence[Number] | None = None) -> str:
    """The truncated game of ``instance`` with horizon ``horizon`` as Gambit ``.efg`` text.

    Parameters
    ----------
    instance : Instance
        The game, with ``N >= 2`` goals.
    horizon : int
        ``H``: walks have at most ``H`` steps (:func:`~dppverify.tree_route.tree.build_tree`).
    attacker_observes : bool
        Whether the Attacker's information sets include the Defender's past allocations
        (default) or only the walk. The value is the same (see the module docstring).
    forced_moves : bool
        Also write the Attacker's one-action decision nodes (default: skip them; the game
        is the same, and Gambit 17.0.0b2's ``lp_solve`` mis-solves one-action infosets).
    max_prefixes : int
        Size guard on the walk tree.
    max_nodes : int
        Size guard on the exported game (it has ``N^t`` copies of each ``t``-step prefix).
    title : str, optional
        The game's title in the file.
    goal_values : sequence of numbers, optional
        The goal-selection game (proofs/SELECT.md): the root is the Attacker's choice of its
        goal instead of chance, and it pays its cost minus ``goal_values[θ]``; the instance's
        prior is not used.

    Raises
    ------
    HorizonError
        If no walk reaches a goal within ``horizon`` steps.
    TreeTooLargeError
        If the walk tree or the game exceeds its size limit.

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> inst = triangle()
    >>> to_efg(inst, 1).splitlines()[3]
    'c "" 1 "type" { "type g1" 7/10 "type g2" 3/10 } 0'
    >>> to_efg(inst, 1, goal_values=[0, 1]).splitlines()[3:5]
    ['p "" 1 1 "goal" { "choose g1" "choose g2" } 0', 'p "" 1 2 "T1 p0 h-" { "go g1" "go g2" } 0']
    """
    tree = build_tree(instance, horizon, max_prefixes=max_prefixes)
    return tree_to_efg(tree, attacker_observes=attacker_observes, forced_moves=forced_moves,
                       max_nodes=max_nodes, title=title, goal_values=goal_values)


def write_efg(path: str | Path, tree: WalkTree, *, attacker_observes: bool = True,
              forced_moves: bool = False, max_nodes: int = DEFAULT_MAX_EFG_NODES,
              title: str | None = None, progress: bool = False,
              goal_values: Sequence[Number] | None = None) -> EfgSize:
    """Write :func:`tree_to_efg` of ``tree`` to ``path`` atomically (a temporary file, then a
    rename).

    Returns the game's size. Nothing is written when the game cannot be built. With
    ``progress``, a tqdm bar on stderr shows the export (``build_tree(..., progress=True)``
    shows the tree's build).

    Raises
    ------
    CheckerError
        As :func:`tree_to_efg`; or the file cannot be written (one-line message).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from dppverify.game.examples import triangle
    >>> from dppverify.tree_route.tree import build_tree
    >>> tree = build_tree(triangle(), 1)
    >>> with tempfile.TemporaryDirectory() as d:
    ...     size = write_efg(pathlib.Path(d) / "game.efg", tree)
    ...     first = (pathlib.Path(d) / "game.efg").read_text().split()[0]
    >>> size.nodes, first
    (15, 'EFG')
    """
    with tqdm(total=1, desc=f"export .efg ({tree.n_prefixes} prefixes)", disable=not progress,
              leave=False, file=sys.stderr) as bar:
        text = tree_to_efg(tree, attacker_observes=attacker_observes, forced_moves=forced_moves,
                           max_nodes=max_nodes, title=title, goal_values=goal_values)
        bar.update(1)
    write_files({Path(path): text})  # all or nothing, mode from the umask
    return efg_size(tree, attacker_observes=attacker_observes, forced_moves=forced_moves,
                    selection=goal_values is not None)
