"""The game instance for any number of goals: one frozen type, its readers, its arrays.

The checker reads instances itself (``docs/formats.md`` §1) and validates the paper's
assumptions (Section III-A), for ``N >= 2`` goals: positive weights, distinct goals, a prior in
(0, 1) summing to exactly 1, and finite full-graph distances from the start to every goal and
between any two goals (assumption (R) of proofs/README.md; the terminal costs ``d(g^i, g^j)``).
Every violation raises :class:`InvalidInstanceError` with a one-line message naming what and
where (the parsing itself is :mod:`dppverify.game.instance_reading` and
:mod:`dppverify.game.graph_reading`).

Two goals are the case ``N = 2``: a document listing exactly two goals is read under the
two-goal rules (float weights allowed, ``"numbers": "float"``; the two-goal messages), and the
instance has the paper's (primary, secondary) views :attr:`Instance.primary_slot`,
:attr:`Instance.tied` and :meth:`Instance.roles`, which raise :class:`NotTwoGoalsError` for
``N != 2``. A reader asked for ``two_goals=True`` refuses a document with more goals.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from typing import Any

from dppverify.errors import InvalidInstanceError, NotTwoGoalsError
from dppverify.exact import Number
from dppverify.formats.json_reading import (
    JsonReadError,
    Node,
    node_from_json,
    node_to_json,
    parse_json_text,
    read_json_file,
    show_node,
)
from dppverify.game.distances import ArcArrays, ArcRows
from dppverify.game.graph_reading import Rows, read_graph, require
from dppverify.game.instance_reading import (
    NGOAL_REFUSAL,
    arc_arrays,
    game_parts,
    goal_distance_fields,
    remember_arrays,
    two_goal_rules,
)
from dppverify.numbers import NumberMode, number_mode

__all__ = ["NGOAL_REFUSAL", "Instance", "Node", "Roles", "arc_arrays", "as_instance",
           "finish_game", "goal_distance_fields", "instance_from_json", "load_instance",
           "node_from_json", "node_to_json", "show_node"]


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

    def dist(self, theta: int) -> tuple[Number, ...]:
        """Distances to the true goal of type ``theta`` (1 = primary, 2 = secondary: the
        paper's labels, not goal indices)."""
        return self.d1 if theta == 1 else self.d2

    def prior(self, theta: int) -> Fraction:
        """Prior of type ``theta`` (1 = primary, 2 = secondary)."""
        return self.b1 if theta == 1 else self.b2


@dataclass(frozen=True, eq=False)
class Instance:
    """A validated game instance with ``N >= 2`` goals: graph, start, goals, prior, distances.

    Nodes are numbered ``0 .. n-1`` in document order; ``nodes[i]`` is the id of node ``i``.
    The goals are numbered by their *goal index* ``θ ∈ 0 .. N-1`` (document order): type ``θ``
    walks to ``goals[θ]`` with prior ``prior[θ]``.

    Attributes
    ----------
    nodes : tuple
        Node ids (JSON lists converted to tuples).
    index : Mapping
        Node id -> index.
    directed : bool
        False when every edge can be walked both ways.
    succ, pred : ArcRows
        ``succ[u]`` = arcs ``(v, w)`` leaving ``u``; ``pred[v]`` = arcs ``(u, w)`` entering ``v``
        (tuples built on access from arrays, :class:`~dppverify.game.distances.ArcRows`).
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

    Examples
    --------
    >>> doc = {"graph": {"directed": False, "nodes": [{"id": "s"}, {"id": "g1"}, {"id": "g2"}],
    ...        "edges": [{"source": "s", "target": "g2", "weight": 2},
    ...                  {"source": "g2", "target": "g1", "weight": 2},
    ...                  {"source": "s", "target": "g1", "weight": 3}]},
    ...        "start": "s", "goals": ["g1", "g2"], "prior": ["7/10", "3/10"]}
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

    nodes: tuple[Node, ...]
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
    def primary_slot(self) -> int:
        """Goal index (0 or 1) of the primary goal: larger prior, ``goals[0]`` at a tie.

        Raises :class:`NotTwoGoalsError` unless ``N = 2`` (as :attr:`tied`, :meth:`roles`).
        """
        self._two("primary_slot")
        return 1 if self.prior[1] > self.prior[0] else 0

    @property
    def tied(self) -> bool:
        """True at prior 1/2 - 1/2, where either goal may be called primary (footnote 2)."""
        self._two("tied")
        return self.prior[0] == self.prior[1]

    def roles(self, primary_slot: int | None = None) -> Roles:
        """The (primary, secondary) labelling; default: the instance's primary goal."""
        self._two("roles")
        i = self.primary_slot if primary_slot is None else primary_slot
        j = 1 - i
        return Roles(g1=self.goals[i], g2=self.goals[j], b1=self.prior[i], b2=self.prior[j],
                     d1=self.dist_to[i], d2=self.dist_to[j])


def as_instance(instance: Any, *, two_goals: bool = False) -> Instance:
    """An :class:`Instance` from any of the forms the public API accepts (duck typing).

    Parameters
    ----------
    instance : Instance, Mapping, str, Path, or an object with ``to_json()``
        Returned as is; parsed (a document); loaded (a file path); or, for any object with a
        ``to_json()`` method returning a document (e.g. the solver's ``Instance``), parsed
        from that document. ``dppverify`` never imports the solver: only the JSON is used.
    two_goals : bool
        Read exactly two goals (as :func:`instance_from_json`); an :class:`Instance` given
        as is must then have two goals.

    Raises
    ------
    InvalidInstanceError
        The input is none of these, or not a valid instance.

    Examples
    --------
    >>> from dppverify.game.examples import triangle_document
    >>> class Foreign:  # any object that can write the instance JSON
    ...     def to_json(self):
    ...         return triangle_document()
    >>> as_instance(Foreign()).prior
    (Fraction(7, 10), Fraction(3, 10))
    >>> as_instance(42)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    dppverify.errors.InvalidInstanceError: an instance must be ... with to_json(); got int ...
    """
    if isinstance(instance, Instance):
        if two_goals:
            require(instance.n_goals == 2, NGOAL_REFUSAL.format(n=instance.n_goals))
        return instance
    if isinstance(instance, Mapping):
        return instance_from_json(instance, two_goals=two_goals)
    if isinstance(instance, str | Path):
        return load_instance(instance, two_goals=two_goals)
    to_json = getattr(instance, "to_json", None)
    if callable(to_json):
        doc = to_json()
        if isinstance(doc, Mapping | str | bytes):
            return instance_from_json(doc, two_goals=two_goals)
    raise InvalidInstanceError(
        "an instance must be an Instance, a JSON document (dict), a file path or an object "
        f"with to_json(); got {type(instance).__name__} (the solver's Instance and "
        "Equilibrium have to_json())")


def load_instance(path: str | Path, *, two_goals: bool = False) -> Instance:
    """Read and validate an instance file (:func:`instance_from_json` on its document).

    A relative map path of a compact map instance is relative to the file's directory.

    Raises
    ------
    InvalidInstanceError
        One line ``PATH: what is wrong`` for unreadable, malformed or invalid instances.

    Examples
    --------
    >>> load_instance("/nonexistent.json")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: /nonexistent.json: cannot read instance file ...
    """
    p = Path(path)
    try:
        doc = read_json_file(p, kind="instance")
    except JsonReadError as exc:
        raise InvalidInstanceError(f"{p}: {exc}") from None
    try:
        return instance_from_json(doc, two_goals=two_goals, base=p.parent)
    except InvalidInstanceError as exc:
        raise InvalidInstanceError(f"{p}: {exc}") from None


def instance_from_json(doc: Any, *, two_goals: bool = False,
                       base: Path | None = None) -> Instance:
    """Build a validated :class:`Instance` from an instance document (dict or JSON text).

    The one instance reader of the checker, for any ``N >= 2`` goals. A document listing
    exactly two goals is read under the two-goal rules (``"numbers": "float"`` allowed, the
    two-goal messages); one listing more is read under the N-goal rules (exact numbers only).
    ``two_goals=True``: the caller reads two goals only; more are refused
    (:data:`NGOAL_REFUSAL`). A compact map instance (``"format": "dpp-map-instance/1"``,
    :mod:`dppverify.formats.map_instance`) is read from its map; a relative map path is
    relative to ``base`` (the instance file's directory; the working directory when None).

    Raises
    ------
    InvalidInstanceError
        For malformed documents and instances violating the game's assumptions: one line
        naming what is wrong and where.

    Examples
    --------
    >>> instance_from_json('{"graph": {"nodes": [{"id": 1}], "edges": []}, "start": 1, '
    ...                    '"goals": [1, 1], "prior": [0.5, 0.5]}')
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: goals: the two goals must differ, both are 1
    >>> instance_from_json('{"graph": {"nodes": [{"id": 1}, {"id": 2}], "edges": []}, '
    ...     '"start": 1, "goals": [1, 2, 1], "prior": [0.5, 0.25, 0.25]}')
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: goals[2]: goal 1 is listed twice
    >>> from dppverify.game.examples import star3_document, triangle_document
    >>> instance_from_json({**star3_document(), "numbers": "float"})
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: numbers: N-goal instances must be exact \
("numbers": "exact")
    >>> instance_from_json(star3_document(), two_goals=True)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: goals: this instance lists 3 goals; the two-goal ...
    >>> instance_from_json({**triangle_document(), "numbers": "float"}).exact
    False
    """
    if isinstance(doc, str | bytes):
        try:
            doc = parse_json_text(doc)
        except JsonReadError as exc:
            raise InvalidInstanceError(str(exc)) from None
    if isinstance(doc, Mapping) and "format" in doc:
        from dppverify.formats.map_instance import is_map_document

        if is_map_document(doc):
            from dppverify.game.grids import map_game  # grids builds on this module

            return map_game(doc, two_goals=two_goals, base=base)
    try:
        return _read_game(doc, two_goals)
    except InvalidInstanceError:
        raise
    except (ValueError, TypeError) as exc:  # parse_number / node_from_json messages
        raise InvalidInstanceError(str(exc)) from None


def _read_game(doc: Any, two_goals: bool = False, *, fast: bool = True) -> Instance:
    require(isinstance(doc, Mapping), f"instance must be a JSON object, got {type(doc).__name__}")
    missing = [k for k in ("graph", "start", "goals", "prior") if k not in doc]
    require(not missing, f"instance is missing key(s): {', '.join(missing)}")
    mode = doc.get("numbers", "exact")
    if two_goal_rules(doc["goals"], two_goals):
        require(mode in ("exact", "float"),
                f"numbers: expected \"exact\" or \"float\", got {mode!r}")
    else:
        require(mode == "exact", "numbers: N-goal instances must be exact (\"numbers\": \"exact\")")
    exact = mode == "exact"
    ids, index, directed, succ_t, pred_t, arcs = read_graph(doc["graph"], exact, fast=fast)
    return finish_game(ids, index, directed, succ_t, pred_t, arcs, exact=exact,
                       start=doc["start"], goals=doc["goals"], prior=doc["prior"],
                       two_goals=two_goals)


def finish_game(ids: list[Node], index: dict[Node, int], directed: bool, succ_t: Rows,
                pred_t: Rows, arcs: ArcArrays | None, *, exact: bool, start: Any, goals: Any,
                prior: Any, two_goals: bool = False) -> Instance:
    """The game on a read graph: start, goals and prior (as JSON values) checked, distances.

    Shared by the JSON reader and the ``.map`` reader (:mod:`dppverify.formats.movingai`), so
    that a map read straight into arrays gives the very instance its JSON document gives
    (:func:`~dppverify.game.instance_reading.game_parts` does the work).

    Examples
    --------
    >>> g = {"nodes": [{"id": "s"}, {"id": "a"}, {"id": "b"}],
    ...      "edges": [{"source": "s", "target": "a"}, {"source": "a", "target": "b"}]}
    >>> inst = finish_game(*read_graph(g, True), exact=True, start="s", goals=["a", "b"],
    ...                    prior=["1/2", "1/2"])
    >>> inst.dist_to, inst.hops
    (((1, 0, 1), (2, 1, 0)), (1, 0, 0))
    """
    parts = game_parts(ids, index, directed, succ_t, pred_t, arcs, exact=exact, start=start,
                       goals=goals, prior=prior, two_goals=two_goals)
    game = Instance(**parts.fields)
    remember_arrays(game, arcs, parts.scaled)
    return game


def goal_count(doc: Any) -> int | None:
    """The number of goals an instance document lists (None if ``goals`` is not a list).

    Examples
    --------
    >>> from dppverify.game.examples import star3_document
    >>> goal_count(star3_document()), goal_count({"goals": "g"})
    (3, None)
    """
    return len(doc["goals"]) if isinstance(doc, Mapping) and isinstance(
        doc.get("goals"), list) else None


def read_instance_document(path: str | Path) -> Any:
    """The JSON document of an instance file, read once (bounded), not yet validated.

    Raises
    ------
    InvalidInstanceError
        ``PATH: cannot read instance file (reason)`` or the JSON error.

    Examples
    --------
    >>> read_instance_document("/nonexistent.json")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: /nonexistent.json: cannot read instance file ...
    """
    try:
        return read_json_file(Path(path), kind="instance")
    except JsonReadError as exc:
        raise InvalidInstanceError(f"{path}: {exc}") from None
