"""The one game instance type for any number of goals, and how a read graph becomes one.

:class:`Instance` is frozen: nodes, arcs (as arrays, :class:`~dppverify.game.arc_rows.ArcRows`),
start, goals, prior and the full-graph distances to every goal. Two goals are the case
``N = 2``: :attr:`Instance.primary_goal_index`, :attr:`Instance.tied` and
:meth:`Instance.roles` are the paper's (primary, secondary) views and raise
:class:`NotTwoGoalsError` for ``N != 2``.
:func:`finish_game` builds the instance from a read graph; the readers of documents and maps
(:mod:`dppverify.game.instance`, :mod:`dppverify.game.grids`) build on it.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from dppverify.errors import NotTwoGoalsError
from dppverify.exact import Number
from dppverify.formats.json_reading import Node
from dppverify.game.arc_rows import ArcRows
from dppverify.game.graph_reading import ReadGraph, Rows
from dppverify.game.instance_reading import game_parts, remember_arrays
from dppverify.numbers import NumberMode, number_mode


@dataclass(frozen=True)
class Roles:
    """Which goal plays ``g1`` (primary) and which ``g2`` (secondary), with priors/distances.

    Attributes
    ----------
    g1, g2 : int
        Node indices of the primary and secondary goals.
    b1, b2 : Fraction
        Their priors (``b1 >= b2``, except when a profile labels a 1/2-1/2 tie the other way,
        which the paper's footnote 2 allows).
    d1, d2 : tuple
        Full-graph distances from every node to ``g1`` / ``g2`` (``math.inf`` if unreachable).
    """

    g1: int
    g2: int
    b1: Fraction
    b2: Fraction
    d1: tuple[Number, ...]
    d2: tuple[Number, ...]

    def dist(self, role: int) -> tuple[Number, ...]:
        """Distances to the true goal of type ``role`` (1 = primary, 2 = secondary: the
        paper's labels, not goal indices)."""
        return self.d1 if role == 1 else self.d2

    def prior(self, role: int) -> Fraction:
        """Prior of type ``role`` (1 = primary, 2 = secondary)."""
        return self.b1 if role == 1 else self.b2


@dataclass(frozen=True, eq=False)
class Instance:
    """A validated game instance with ``N >= 2`` goals: graph, start, goals, prior, distances.

    Nodes are numbered ``0 .. n-1`` in document order; ``nodes[i]`` is the id of node ``i``.
    The goals are numbered by their *goal index* ``θ ∈ 0 .. N-1`` (document order): type ``θ``
    walks to ``goals[θ]`` with prior ``prior[θ]``.

    Attributes
    ----------
    nodes : sequence
        Node ids (JSON lists converted to tuples): a tuple, or for a grid read from its map
        the cells made on access (:class:`~dppverify.game.grids.GridCells`).
    index : Mapping
        Node id -> index.
    directed : bool
        False when every edge can be walked both ways.
    succ, pred : ArcRows
        ``succ[u]`` = arcs ``(v, w)`` leaving ``u``; ``pred[v]`` = arcs ``(u, w)`` entering ``v``
        (tuples built on access from arrays, :class:`~dppverify.game.arc_rows.ArcRows`).
    start : int
        ``s0``.
    goals : tuple of int
        The goals in document order (``goals[θ]``: the goal of goal index ``θ``).
    prior : tuple of Fraction
        Exact priors, ``prior[θ]`` (always exact, also in float mode).
    exact : bool
        False in float mode (``"numbers": "float"``, two goals only): weights are binary floats.
    dist_to : tuple
        ``dist_to[θ][v]`` = full-graph ``d(v, goals[θ])`` (``math.inf`` if unreachable).
    hops : tuple of int
        Fewest steps from each node to the nearest goal (``-1`` if none): tree pruning.
    goal_values : tuple of Fraction or None
        None for the game with a prior. The goal-selection game (``docs/formats.md`` §1, "Goal
        selection"; proofs/SELECT.md): the Attacker *chooses* its goal and pays its cost minus
        ``goal_values[θ]``; there is no prior, and :attr:`prior` is then the uniform reference
        prior (the one the value at the uniform prior is reported for).

    Examples
    --------
    >>> doc = {"graph": {"directed": False, "nodes": [{"id": "s"}, {"id": "g1"}, {"id": "g2"}],
    ...        "edges": [{"source": "s", "target": "g2", "weight": 2},
    ...                  {"source": "g2", "target": "g1", "weight": 2},
    ...                  {"source": "s", "target": "g1", "weight": 3}]},
    ...        "start": "s", "goals": ["g1", "g2"], "prior": ["7/10", "3/10"]}
    >>> from dppverify.game.instance import instance_from_json
    >>> inst = instance_from_json(doc)
    >>> r = inst.roles()
    >>> inst.nodes[r.g1], r.b1, r.d1[inst.start], r.d2[r.g1]
    ('g1', Fraction(7, 10), 3, 2)
    >>> doc = {"graph": {"nodes": [{"id": "s"}, {"id": "a"}, {"id": "b"}, {"id": "c"}],
    ...        "edges": [{"source": "s", "target": "a"}, {"source": "s", "target": "b"},
    ...                  {"source": "s", "target": "c", "weight": 2}]},
    ...        "start": "s", "goals": ["a", "b", "c"], "prior": ["1/2", "1/3", "1/6"]}
    >>> inst = instance_from_json(doc)
    >>> inst.n_goals, inst.prior[2], inst.terminal(inst.goals[0], 2), inst.exact
    (3, Fraction(1, 6), 3, True)
    >>> inst.roles()
    Traceback (most recent call last):
    dppverify.errors.NotTwoGoalsError: roles: the (primary, secondary) labelling is for two \
goals; this instance has 3
    """

    nodes: Sequence[Node]
    index: Mapping[Node, int]
    directed: bool
    succ: Rows
    pred: Rows
    start: int
    goals: tuple[int, ...]
    prior: tuple[Fraction, ...]
    exact: bool
    dist_to: tuple[tuple[Number, ...], ...]
    hops: tuple[int, ...]
    goal_values: tuple[Fraction, ...] | None = None

    @property
    def goal_selection(self) -> bool:
        """True for the goal-selection game (:attr:`goal_values` set)."""
        return self.goal_values is not None

    @property
    def numbers(self) -> NumberMode:
        """The number mode (:mod:`dppverify.numbers`): exact, or float within a relative
        tolerance."""
        return number_mode(self.exact)

    @property
    def n_nodes(self) -> int:
        """Number of nodes."""
        return len(self.nodes)

    @property
    def n_goals(self) -> int:
        """Number of goals ``N``."""
        return len(self.goals)

    def is_goal(self, node: int) -> bool:
        """True for the candidate goals."""
        return node in self.goals

    def goal_index(self, node: int) -> int | None:
        """The goal index ``θ`` (document position) of goal ``node``; None if not a goal.

        Examples
        --------
        >>> from dppverify.game.examples import triangle
        >>> [triangle().goal_index(v) for v in range(3)]
        [None, 0, 1]
        """
        try:
            return self.goals.index(node)
        except ValueError:
            return None

    def terminal(self, goal: int, theta: int) -> Number:
        """Type ``θ``'s terminal cost at goal node ``goal``: ``d(goal, g^θ)``."""
        return self.dist_to[theta][goal]

    def weight(self, u: int, v: int) -> Number | None:
        """Weight of the arc ``u -> v``, or None when there is no such arc."""
        if isinstance(self.succ, ArcRows):
            return self.succ.find(u, v)
        for head, w in self.succ[u]:
            if head == v:
                return w
        return None

    def weights_along(self, walk: Sequence[int]) -> list[Number | None]:
        """``weight(walk[t-1], walk[t])`` for ``t = 1 .. len(walk) - 1`` (None: no such arc).

        Examples
        --------
        >>> from dppverify.game.examples import triangle
        >>> triangle().weights_along([0, 2, 1, 1])
        [2, 2, None]
        """
        if isinstance(self.succ, ArcRows) and len(walk) > 8:
            return self.succ.find_many(walk[:-1], walk[1:])
        return [self.weight(walk[t - 1], walk[t]) for t in range(1, len(walk))]

    def label(self, v: int) -> Node:
        """The node id of index ``v``."""
        return self.nodes[v]

    def labels(self, walk: tuple[int, ...] | list[int]) -> tuple[Node, ...]:
        """Node ids of a walk given as indices."""
        return tuple(self.nodes[v] for v in walk)

    # --- the two-goal views (N = 2): the paper's primary and secondary goals ---

    def _two(self, view: str) -> None:
        if len(self.goals) != 2:
            raise NotTwoGoalsError(f"{view}: the (primary, secondary) labelling is for two "
                                   f"goals; this instance has {len(self.goals)}")

    @property
    def primary_goal_index(self) -> int:
        """Goal index (0 or 1) of the primary goal: larger prior, ``goals[0]`` at a tie.

        Raises :class:`NotTwoGoalsError` unless ``N = 2`` (as :attr:`tied`, :meth:`roles`).
        """
        self._two("primary_goal_index")
        return 1 if self.prior[1] > self.prior[0] else 0

    @property
    def tied(self) -> bool:
        """True at prior 1/2 - 1/2, where either goal may be called primary (footnote 2)."""
        self._two("tied")
        return self.prior[0] == self.prior[1]

    def roles(self, primary_goal_index: int | None = None) -> Roles:
        """The (primary, secondary) labelling; default: the instance's primary goal."""
        self._two("roles")
        i = self.primary_goal_index if primary_goal_index is None else primary_goal_index
        j = 1 - i
        return Roles(g1=self.goals[i], g2=self.goals[j], b1=self.prior[i], b2=self.prior[j],
                     d1=self.dist_to[i], d2=self.dist_to[j])


def finish_game(graph: ReadGraph, *, exact: bool, start: Any, goals: Any,
                prior: Any) -> Instance:
    """The game on a read graph: start, goals and prior (as JSON values) checked, distances.

    Shared by the JSON reader and the ``.map`` reader (:mod:`dppverify.formats.movingai`), so
    that a map read straight into arrays gives the very instance its JSON document gives
    (:func:`~dppverify.game.instance_reading.game_parts` does the work).

    Examples
    --------
    >>> g = {"nodes": [{"id": "s"}, {"id": "a"}, {"id": "b"}],
    ...      "edges": [{"source": "s", "target": "a"}, {"source": "a", "target": "b"}]}
    >>> from dppverify.game.graph_reading import read_graph
    >>> inst = finish_game(read_graph(g, True), exact=True, start="s", goals=["a", "b"],
    ...                    prior=["1/2", "1/2"])
    >>> inst.dist_to, inst.hops
    (((1, 0, 1), (2, 1, 0)), (1, 0, 0))
    """
    parts = game_parts(graph, exact=exact, start=start, goals=goals, prior=prior)
    game = Instance(**parts.fields)
    remember_arrays(game, graph[5], parts.scaled)
    return game
