"""Reading the ``dpp`` instance JSON (``docs/formats.md`` §1) and the compact map instance
(``dpp-map-instance/1``, §1c: a grid game by reference to its ``.map`` file) into an
:class:`~solver.game.instance.Instance`, for any number of goals.

A document listing two goals is read under the two-goal rules (``"numbers": "float"``
allowed); one listing more under the N-goal rules (exact numbers only), as the checker reads
them. ``two_goals=True``: the caller takes two goals only, and more are refused in one line.
"""

from __future__ import annotations

from collections.abc import Mapping
from fractions import Fraction
from pathlib import Path
from typing import Any

import networkx as nx

from dppio.limits import check_rational
from dppio.text import json_shown, plural
from solver.errors import InstanceFormatError, InvalidInstanceError
from solver.formats.json_text import parse_json_text, read_json
from solver.formats.map_instance import MAP_INSTANCE_FORMAT, read_map_document, two_goals_only
from solver.formats.nodes import node_from_json
from solver.game.instance import Instance
from solver.numbers import parse_number

SELECTION_REFUSAL = ("goal_selection: this is a goal-selection instance (the Attacker chooses its "
                     "goal; there is no prior), not a game with a prior: read it with "
                     "solver.selection.instance.selection_from_json (dpp solve takes it as "
                     "such)")
"""The one line the prior game's reader gives a goal-selection document."""


def load_instance(path: str | Path, *, two_goals: bool = False) -> Instance:
    """Load an instance JSON file (:func:`instance_from_json` on its document; errors name the
    file).

    Parameters
    ----------
    path : str or Path
        An instance file (a node-link document, or a compact map instance).
    two_goals : bool
        Take two goals only.

    Returns
    -------
    Instance

    Raises
    ------
    InstanceFormatError
        Not an instance document (the message names the file).
    InvalidInstanceError
        A document that is not a valid game (the message names the file).

    Examples
    --------
    >>> import tempfile, json, os
    >>> doc = {"graph": {"directed": False, "nodes": [{"id": "s"}, {"id": "a"}, {"id": "b"}],
    ...        "edges": [{"source": "s", "target": "a"}, {"source": "s", "target": "b"}]},
    ...        "start": "s", "goals": ["a", "b"], "prior": [0.6, 0.4]}
    >>> with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
    ...     json.dump(doc, f)
    >>> load_instance(f.name).b1
    Fraction(3, 5)
    >>> os.unlink(f.name)
    """
    doc = read_json(path)  # its errors name the file
    try:
        return instance_from_json(doc, base=Path(path).parent, two_goals=two_goals)
    except InstanceFormatError as exc:  # one line naming the file
        raise InstanceFormatError(f"{path}: {exc}") from None
    except InvalidInstanceError as exc:
        raise InvalidInstanceError(f"{path}: {exc}") from None


def instance_from_json(data: dict[str, Any] | str, *, base: Path | None = None,
                       two_goals: bool = False) -> Instance:
    """Build an :class:`Instance` from the instance JSON document (dict or text), any ``N``.

    Parameters
    ----------
    data : dict or str
        The document of ``docs/formats.md`` §1, or its JSON text (decimals read exactly); or
        a compact map instance (§1c), read from its ``.map`` file straight into CSR arrays.
    base : Path, optional
        The directory a compact map instance's relative ``map`` path is relative to (the
        instance file's; default: the working directory).
    two_goals : bool
        Take two goals only: a document listing more is refused (:data:`two_goals_only`).

    Returns
    -------
    Instance

    Raises
    ------
    InstanceFormatError
        Malformed document (missing keys, bad JSON, wrong shapes).
    InvalidInstanceError
        A well-formed document that is not a valid game (e.g. unknown nodes).

    Examples
    --------
    >>> text = ('{"graph": {"nodes": [{"id": "s"}, {"id": "g1"}, {"id": "g2"}], "edges": '
    ...         '[{"source": "s", "target": "g1"}, {"source": "s", "target": "g2"}]}, '
    ...         '"start": "s", "goals": ["g1", "g2"], "prior": [0.7, 0.3]}')
    >>> inst = instance_from_json(text)
    >>> inst.primary, inst.secondary, inst.b1
    ('g1', 'g2', Fraction(7, 10))
    >>> instance_from_json({"graph": {"nodes": [], "edges": []}})
    Traceback (most recent call last):
    solver.errors.InstanceFormatError: instance is missing keys: start, goals, prior
    >>> doc = {"graph": {"nodes": [{"id": x} for x in "sabc"],
    ...        "edges": [{"source": "s", "target": x} for x in "abc"]},
    ...        "start": "s", "goals": ["a", "b", "c"], "prior": ["1/2", "1/4", "1/4"]}
    >>> instance_from_json(doc).n_goals
    3
    >>> instance_from_json(doc, two_goals=True)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    solver.errors.InstanceFormatError: 'goals' lists 3 goals: this takes two-goal instances only ...
    """
    if isinstance(data, str):
        data = parse_json_text(data)
    if not isinstance(data, dict):
        raise InstanceFormatError(f"instance must be a JSON object, got {type(data).__name__}")
    if "goal_selection" in data:
        raise InstanceFormatError(SELECTION_REFUSAL)
    if data.get("format") == MAP_INSTANCE_FORMAT:
        return _from_map_document(data, base, two_goals)
    float_weights = _float_mode(data)
    goals, prior = data["goals"], data["prior"]
    if isinstance(goals, list) and len(goals) > 2:  # N goals: the N-goal rules
        if two_goals:
            raise InstanceFormatError(two_goals_only(len(goals)))
        if float_weights:
            raise InvalidInstanceError("the N-goal solver is exact only: \"numbers\": \"float\" "
                                       "is not supported for more than two goals")
        if not isinstance(prior, list):
            raise InstanceFormatError("'goals' and 'prior' must be lists")
        graph = _graph_from_node_link(data["graph"], float_weights=False)
        return Instance(graph, node_from_json(data["start"]),
                        tuple(node_from_json(g) for g in goals), tuple(prior))
    graph = _graph_from_node_link(data["graph"], float_weights=float_weights)
    if not isinstance(goals, list) or len(goals) != 2:
        raise InstanceFormatError(f"'goals' must be a list of two node ids, got "
                                  f"{json_shown(goals)}")
    if not isinstance(prior, list) or len(prior) != 2:
        raise InstanceFormatError(f"'prior' must be a list of two numbers, one per goal, got "
                                  f"{json_shown(prior)}")
    return Instance(
        graph,
        node_from_json(data["start"]),
        (node_from_json(goals[0]), node_from_json(goals[1])),
        (parse_number(prior[0], where="prior[0]"), parse_number(prior[1], where="prior[1]")),
    )


def _float_mode(data: dict[str, Any]) -> bool:
    """Whether a node-link document has every key and asks for float weights."""
    missing = [k for k in ("graph", "start", "goals", "prior") if k not in data]
    if missing:
        raise InstanceFormatError(f"instance is missing {plural(len(missing), 'key')}: "
                                  f"{', '.join(missing)}")
    mode = data.get("numbers", "exact")
    if mode not in ("exact", "float"):
        raise InstanceFormatError(f"numbers: expected \"exact\" or \"float\", got {mode!r}")
    return bool(mode == "float")


def as_instance(instance: Instance | Mapping[str, Any] | str | Path | nx.Graph, *,
                start: Any = None, goals: Any = None, prior: Any = None,
                weight: str = "weight") -> Instance:
    """An :class:`Instance` from any form the front door takes: itself, an instance document
    (a dict), the path of an instance file, or a ``networkx`` graph with ``start``, ``goals``
    and ``prior`` (converted here, once, by :class:`Instance` itself: ``weight`` names the
    edge attribute, as in networkx).

    Examples
    --------
    >>> from solver.game.instance import triangle
    >>> as_instance(triangle().to_json()).b1
    Fraction(7, 10)
    >>> g = nx.Graph([("s", "g2", {"weight": 2}), ("g2", "g1", {"weight": 2}),
    ...               ("s", "g1", {"weight": 3})])
    >>> inst = as_instance(g, start="s", goals=["g1", "g2"], prior=["7/10", "3/10"])
    >>> inst.start, inst.primary, inst.b1
    ('s', 'g1', Fraction(7, 10))
    >>> as_instance(3)
    Traceback (most recent call last):
    solver.errors.InvalidInstanceError: an instance must be an Instance, an instance document \
(dict), a file path or a networkx graph; got int
    """
    if isinstance(instance, nx.Graph):
        missing = [k for k, v in (("start", start), ("goals", goals), ("prior", prior))
                   if v is None]
        if missing:
            raise InvalidInstanceError(
                f"a networkx graph needs {', '.join(k + '=' for k in missing)} (the start "
                "node, the goal nodes, their prior)")
        return Instance(instance, start, tuple(goals), tuple(prior), weight=weight)
    if start is not None or goals is not None or prior is not None:
        raise InvalidInstanceError("start=, goals= and prior= go with a networkx graph; an "
                                   f"instance given as {type(instance).__name__} has its own")
    if isinstance(instance, Instance):
        return instance
    if isinstance(instance, Mapping):
        return instance_from_json(dict(instance))
    if isinstance(instance, str | Path):
        return load_instance(instance)
    raise InvalidInstanceError("an instance must be an Instance, an instance document (dict), "
                               f"a file path or a networkx graph; got {type(instance).__name__}")


def _from_map_document(data: dict[str, Any], base: Path | None, two_goals: bool) -> Instance:
    """The grid instance of a compact map document (its map's sha256 checked)."""
    blocked, start, cells, prior, connectivity, ref = read_map_document(
        data, base, count=2 if two_goals else None)
    try:
        return Instance.from_grid(blocked, start, cells,
                                  [parse_number(p, where=f"prior[{i}]")
                                   for i, p in enumerate(prior)],
                                  connectivity=connectivity)
    except InvalidInstanceError as exc:
        raise InvalidInstanceError(f"{ref[:200]}: {exc}") from None


def _graph_from_node_link(g: Any, *, float_weights: bool) -> nx.Graph:
    if not isinstance(g, dict):
        raise InstanceFormatError("'graph' must be a node-link JSON object")
    if g.get("multigraph", False):
        raise InvalidInstanceError("multigraphs are not supported: merge parallel edges")
    nodes = g.get("nodes")
    edges = g.get("edges", g.get("links"))
    if not isinstance(nodes, list):
        raise InstanceFormatError("'graph.nodes' must be a list of {\"id\": ...} objects")
    if not isinstance(edges, list):
        raise InstanceFormatError("'graph.edges' must be a list of edge objects")
    directed = g.get("directed", False)
    if not isinstance(directed, bool):
        raise InstanceFormatError(f"graph.directed: expected true/false, got {directed!r}")
    graph: nx.Graph = nx.DiGraph() if directed else nx.Graph()
    for k, nd in enumerate(nodes):
        if not isinstance(nd, dict) or "id" not in nd:
            raise InstanceFormatError(f"graph.nodes[{k}] must be an object with an 'id'")
        node = node_from_json(nd["id"])
        if node in graph:
            raise InvalidInstanceError(f"graph.nodes[{k}]: duplicate node id {nd['id']!r}")
        graph.add_node(node)
    for k, e in enumerate(edges):
        if not isinstance(e, dict) or "source" not in e or "target" not in e:
            raise InstanceFormatError(f"graph.edges[{k}] must have 'source' and 'target'")
        u, v = node_from_json(e["source"]), node_from_json(e["target"])
        for end in (u, v):
            if end not in graph:
                raise InvalidInstanceError(f"graph.edges[{k}] uses unknown node {end!r}")
        raw = e.get("weight", 1)
        if float_weights and isinstance(raw, Fraction):
            # the size limit first: float() of a decimal literal such as 1e400 overflows
            check_rational(raw, where=f"weight of edge ({u!r}, {v!r})",
                           error=InvalidInstanceError)
            raw = float(raw)
        w = parse_number(raw, where=f"weight of edge ({u!r}, {v!r})", allow_float=float_weights)
        if graph.has_edge(u, v):
            raise InvalidInstanceError(f"graph.edges[{k}]: duplicate edge ({u!r}, {v!r})")
        graph.add_edge(u, v, weight=w)
    return graph
