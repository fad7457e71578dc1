"""The fast paths of reading an instance agree exactly with the plain Python ones.

- instance: regular documents (cell, string or int ids, dict edges) are read without a Python
  loop per edge, and the exact distances come from scipy on scaled integers when every path
  sum stays below 2**53; every field equals the plain reading (``fast=False``), types included,
  and invalid documents get the plain reading's message;
- past the 2**53 guard the exact Python Dijkstra runs (the same results);
- value_dp: goal_terminal_arcs (from the instance's arc arrays) equals the plain loop, and
  the three fields (one array, one sparse step for all three) equal the plain recursion;
- json_reading.parse_json: the text fast path (json's own int, depth from the text) equals the
  hook-per-number reading (which ``bytes`` input still takes), results and messages.
"""

from __future__ import annotations

import copy
import json
import math
from fractions import Fraction
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dppverify.errors import InvalidInstanceError
from dppverify.formats.json_reading import parse_json
from dppverify.game import instance_reading as instance_module
from dppverify.game.arc_rows import ArcRows
from dppverify.game.distances import EXACT_FLOAT_LIMIT, exact_distances_to
from dppverify.game.graph_reading import regular_graph
from dppverify.game.instance import Instance, _read_game, arc_arrays
from dppverify.strategies import grid_worlds, instances, many_goal_instances, weighted_graphs
from dppverify.twogoal.value_dp import _Frontier, value_fields
from dppverify.twogoal.value_fixpoint import goal_terminal_arcs
from tests.dppverify._helpers import instance_documents

random_docs = instance_documents(max_nodes=8, max_weight=5, float_nodes=6, grid_size=4,
                                 grid_cells=12)

FIELDS = ("nodes", "directed", "succ", "pred", "start", "goals", "prior", "exact", "dist_to",
          "hops")


def _types(x: Any) -> Any:
    if isinstance(x, tuple | ArcRows):  # succ, pred: the rows they stand for
        return tuple(_types(y) for y in x)
    return type(x)


def _read(doc: Any, *, fast: bool) -> Any:
    """The instance's fields (with their types), or the error message."""
    try:
        g = _read_game(copy.deepcopy(doc), fast=fast)
    except (InvalidInstanceError, ValueError, TypeError) as exc:
        return ("error", type(exc).__name__, str(exc))
    return ({f: getattr(g, f) for f in FIELDS}, {f: _types(getattr(g, f)) for f in FIELDS},
            dict(g.index))


def _same(doc: Any) -> Any:
    fast, slow = _read(doc, fast=True), _read(doc, fast=False)
    assert fast == slow
    return fast


def _relabel(doc: dict[str, Any], f: Any) -> dict[str, Any]:
    """The document with every node id ``x`` written as ``f(x)``."""
    out = copy.deepcopy(doc)
    g = out["graph"]
    for nd in g["nodes"]:
        nd["id"] = f(nd["id"])
    for e in g["edges"]:
        e["source"], e["target"] = f(e["source"]), f(e["target"])
    out["start"] = f(out["start"])
    out["goals"] = [f(x) for x in out["goals"]]
    return out


@settings(deadline=None, max_examples=80)
@given(random_docs, st.sampled_from(["as is", "strings", "cells"]))
def test_regular_documents_read_the_same_fast_and_plain(doc: dict[str, Any], ids: str) -> None:
    if ids == "strings":
        doc = _relabel(doc, lambda x: f"n{x}")
    elif ids == "cells" and not isinstance(doc["start"], list):
        doc = _relabel(doc, lambda x: [x, -x])
    assert regular_graph(doc["graph"], doc.get("numbers", "exact") == "exact") is not None
    got = _same(doc)
    assert got[0] != "error"


@settings(deadline=None, max_examples=30)
@given(many_goal_instances(max_goals=4))
def test_ngoal_documents_read_the_same_fast_and_plain(doc: dict[str, Any]) -> None:
    _same(doc)


def _corrupt(doc: dict[str, Any], how: str, k: int) -> dict[str, Any]:
    out = copy.deepcopy(doc)
    nodes, edges = out["graph"]["nodes"], out["graph"]["edges"]
    e = edges[k % len(edges)]
    if how == "duplicate edge":
        edges.append(dict(e))
    elif how == "reversed duplicate":
        edges.append({"source": e["target"], "target": e["source"], "weight": 1})
    elif how == "unknown node":
        e["target"] = "nowhere"
    elif how == "zero weight":
        e["weight"] = 0
    elif how == "bad weight":
        e["weight"] = "x"
    elif how == "bool weight":
        e["weight"] = True
    elif how == "bool id":
        e["source"] = True
    elif how == "float id":
        e["source"] = float(e["source"]) if isinstance(e["source"], int) else 1.5
    elif how == "duplicate node":
        nodes.append(dict(nodes[k % len(nodes)]))
    elif how == "edge without target":
        del e["target"]
    elif how == "edge is a list":
        edges[k % len(edges)] = [e["source"], e["target"]]
    elif how == "node without id":
        nodes[k % len(nodes)] = {"name": 1}
    elif how == "missing weight":
        del e["weight"]
    elif how == "links":
        out["graph"]["links"] = out["graph"].pop("edges")
    return out


CORRUPTIONS = ("duplicate edge", "reversed duplicate", "unknown node", "zero weight",
               "bad weight", "bool weight", "bool id", "float id", "duplicate node",
               "edge without target", "edge is a list", "node without id", "missing weight",
               "links")


@settings(deadline=None, max_examples=120)
@given(st.one_of(instances(graphs=weighted_graphs(min_nodes=3, max_nodes=6)),
                 grid_worlds(max_size=3, max_cells=8)),
       st.sampled_from(CORRUPTIONS), st.integers(min_value=0, max_value=20))
def test_irregular_and_invalid_documents_get_the_plain_result(doc: dict[str, Any], how: str,
                                                              k: int) -> None:
    _same(_corrupt(doc, how, k))


def test_invalid_documents_keep_their_messages() -> None:
    doc = {"graph": {"nodes": [{"id": [0, 0]}, {"id": [0, 1]}, {"id": [1, 1]}],
                     "edges": [{"source": [0, 0], "target": [0, 1]},
                               {"source": [0, 1], "target": [1, 1]},
                               {"source": [0, 1], "target": [0, 0], "weight": 2}]},
           "start": [0, 0], "goals": [[0, 1], [1, 1]], "prior": ["1/2", "1/2"]}
    got = _same(doc)
    assert got[2] == "graph.edges[2]: duplicate edge [0, 1] -> [0, 0]"
    doc["graph"]["edges"][2] = {"source": [0, 0], "target": [1, 1], "weight": "-1"}
    assert _same(doc)[2] == "graph.edges[2].weight: must be positive, got -1"


def _grid(rows: int, cols: int, weight: Any) -> dict[str, Any]:
    cells = [(r, c) for r in range(rows) for c in range(cols)]
    edges = [{"source": [r, c], "target": [r + dr, c + dc], "weight": weight}
             for r, c in cells for dr, dc in ((0, 1), (1, 0)) if r + dr < rows and c + dc < cols]
    return {"graph": {"directed": False, "nodes": [{"id": list(x)} for x in cells],
                      "edges": edges},
            "start": [rows - 1, 0], "goals": [[0, cols - 1], [0, 0]], "prior": ["3/5", "2/5"]}


@pytest.mark.parametrize("weight", ["1", "2/7", str(2**40), f"{2**60}/3", str(7 * 10**30)])
def test_the_float64_guard_and_its_fallback(weight: str) -> None:
    doc = _grid(4, 5, weight)
    got = _same(doc)
    inst = _read_game(doc)
    arcs = arc_arrays(inst)
    w = Fraction(weight)
    total = w * w.denominator * len(arcs.codes)
    scipy_ok = exact_distances_to(arcs, inst.n_nodes, inst.goals) is not None
    assert scipy_ok == (total < EXACT_FLOAT_LIMIT)
    d = got[0]["dist_to"][1]  # to (0, 0): Manhattan distance times the weight
    assert d[inst.index[(3, 4)]] == 7 * w
    assert type(d[inst.index[(3, 4)]]) is (int if (7 * w).denominator == 1 else Fraction)


def test_the_guard_boundary_exactly() -> None:
    """Total scaled weight 2**53 - 1: scipy; 2**53: the Python Dijkstra; both exact."""
    doc = {"graph": {"directed": True, "nodes": [{"id": i} for i in range(3)],
                     "edges": [{"source": 0, "target": 1, "weight": 0},
                               {"source": 1, "target": 2, "weight": 0},
                               {"source": 2, "target": 0, "weight": 0},
                               {"source": 0, "target": 2, "weight": 0}]},
           "start": 0, "goals": [1, 2], "prior": ["1/2", "1/2"]}
    for total, scipy_ok in ((EXACT_FLOAT_LIMIT - 1, True), (EXACT_FLOAT_LIMIT, False)):
        a, rest = divmod(total, 4)
        weights = [a, a, a, a + rest]
        for e, w in zip(doc["graph"]["edges"], weights, strict=True):
            e["weight"] = w
        got = _same(doc)
        inst = _read_game(doc)
        assert (exact_distances_to(arc_arrays(inst), 3, inst.goals) is not None) == scipy_ok
        assert got[0]["dist_to"][1][0] == min(2 * a, a + rest)  # exact past 2**53 too


def _plain_goal_terminal_arcs(inst: Instance, extra: tuple[Any, ...]) -> tuple[Any, ...]:
    """The loop goal_terminal_arcs ran before it read the arc arrays."""
    tails, starts, heads, raw = [], [], [], []
    for v in range(inst.n_nodes):
        if inst.is_goal(v) or not inst.succ[v]:
            continue
        tails.append(v)
        starts.append(len(heads))
        for u, w in inst.succ[v]:
            heads.append(u)
            raw.append(w)
    if not inst.exact:
        return tails, starts, heads, [float(w) for w in raw], 1, "float64"
    den = 1
    for w in [*set(raw), *extra]:
        if type(w) is Fraction:
            den = math.lcm(den, w.denominator)
    scaled = [int(w * den) for w in raw]
    return (tails, starts, heads, scaled, den,
            "int64" if max(scaled, default=0) < 2**60 else "object")


@settings(deadline=None, max_examples=60)
@given(random_docs, st.sampled_from([(), (Fraction(1, 7),), (5, Fraction(3, 4))]),
       st.booleans())
def test_goal_terminal_arcs_equal_the_plain_loop(doc: dict[str, Any], extra: tuple[Any, ...],
                                                 huge: bool) -> None:
    if huge and doc.get("numbers") != "float":
        for e in doc["graph"]["edges"]:
            e["weight"] = str(Fraction(e["weight"]) * 10**20)
    inst = _read_game(doc, fast=huge)  # arrays from either reading
    a = goal_terminal_arcs(inst, extra=extra if inst.exact else ())
    want = _plain_goal_terminal_arcs(inst, extra if inst.exact else ())
    got = (a.tails.tolist(), a.starts.tolist(), a.heads.tolist(), a.weights.tolist(), a.scale,
           str(a.weights.dtype))
    assert got == want
    assert [type(x) for x in got[3]] == [type(x) for x in want[3]]


def test_arc_arrays_are_kept_per_instance() -> None:
    inst = _read_game(_grid(2, 2, 1))
    assert arc_arrays(inst) is instance_module._ARC_ARRAYS[inst]
    plain = _read_game(_grid(2, 2, 1), fast=False)
    assert plain not in instance_module._ARC_ARRAYS
    a, b = arc_arrays(inst), arc_arrays(plain)
    assert (a.tails.tolist(), a.heads.tolist(), a.weights()) == (b.tails.tolist(),
                                                                b.heads.tolist(), b.weights())


# --- parse_json ----------------------------------------------------------------------------

json_scalars = st.one_of(
    st.integers(min_value=-10**30, max_value=10**30), st.booleans(), st.none(),
    st.text(alphabet='ab[]{}"\\/ é', max_size=6),
    st.floats(allow_nan=False, allow_infinity=False),  # JSON decimal literals, exponents too
)


def _json_texts() -> st.SearchStrategy[str]:
    values = st.recursive(json_scalars, lambda kids: st.one_of(
        st.lists(kids, max_size=3), st.dictionaries(st.text(alphabet="ab]{", max_size=3), kids,
                                                    max_size=3)), max_leaves=12)
    return values.map(json.dumps)


def _parse(text: str | bytes) -> Any:
    try:
        doc = parse_json(text)
    except ValueError as exc:
        return ("error", type(exc).__name__, str(exc))
    return doc, repr(doc)  # repr: types too (Fraction vs int)


def _same_parse(text: str) -> Any:
    fast, plain = _parse(text), _parse(text.encode("utf-8"))  # bytes: the hook path
    assert fast == plain
    return fast


@settings(deadline=None, max_examples=150)
@given(_json_texts(), st.integers(min_value=0, max_value=70))
def test_parse_json_fast_path_equals_the_hooks(text: str, depth: int) -> None:
    _same_parse(text)
    _same_parse("[" * depth + text + "]" * depth)
    _same_parse('{"a": ' * depth + text + "}" * depth)


@pytest.mark.parametrize("text", [
    "[" * 64 + "]" * 64, "[" * 65 + "]" * 65, '["]]]]", ' + "[" * 63 + "]" * 63 + "]",
    '["]]]]", ' + "[" * 64 + "]" * 64 + "]", '["\\"]]]", ' + "[" * 64 + "]" * 64 + "]",
    '{"[[[[": ' * 64 + "1" + "}" * 64, "[" + "1" * 999 + "]", "[" + "1" * 1000 + "]",
    "[-" + "1" * 999 + "]", '["' + "1" * 2000 + '", 2]', "[0.25, 1e3, -2, 1E-2]",
    "[1" + "0" * 5000 + "]", '{"a": 1, "a": [2]}', "[1, 2", "",
])
def test_parse_json_edge_cases(text: str) -> None:
    _same_parse(text)


def test_parse_json_values_and_messages() -> None:
    assert _same_parse("[" * 64 + "]" * 64)[0] is not None
    assert _same_parse("[" * 65 + "]" * 65) == ("error", "ValueError",
                                                "JSON nested deeper than 64 levels")
    assert _same_parse("[-" + "1" * 1000 + "]")[2].endswith(
        "a numeral of 1001 characters is beyond the limit of 1000")
    doc, _ = _same_parse('{"p": 0.6, "q": 2, "r": "0.5"}')
    assert doc == {"p": Fraction(3, 5), "q": 2, "r": "0.5"} and type(doc["q"]) is int



# --- value_dp: the three fields side by side against the plain recursion -------------------

def _plain_fields(inst: Instance, horizon: int | None) -> tuple[list[Any], int, bool]:
    """D1, D2, m by the recursion of value_dp's docstring, on Python numbers."""
    r = inst.roles()
    n, inf = inst.n_nodes, math.inf
    cap = 2 * n + 2
    limit = cap if horizon is None else min(horizon, cap)
    goal_vals = {r.g1: (0, r.d2[r.g1], r.d2[r.g1]), r.g2: (r.d1[r.g2], 0, r.d1[r.g2])}
    f = [list(goal_vals.get(v, (inf, inf, inf))) for v in range(n)]
    steps, fixpoint = 0, False
    while steps < limit:
        new = []
        for v in range(n):
            if v in goal_vals:
                new.append(list(goal_vals[v]))
                continue
            row = [min((w + f[u][i] for u, w in inst.succ[v]), default=inf) for i in range(3)]
            row[2] = min(row[2], row[0] + row[1])
            new.append(row)
        steps += 1
        if new == f:
            fixpoint = True
            break
        f = new
    if steps == cap:
        fixpoint = True
    return [[f[v][i] for v in range(n)] for i in range(3)], steps, fixpoint


@settings(deadline=None, max_examples=60)
@given(random_docs, st.integers(min_value=0, max_value=8), st.booleans())
def test_value_fields_equal_the_plain_recursion(doc: dict[str, Any], extra: int,
                                                huge: bool) -> None:
    if huge and doc.get("numbers") != "float":  # Python-integer arithmetic
        for e in doc["graph"]["edges"]:
            e["weight"] = str(Fraction(e["weight"]) * 10**20)
    inst = _read_game(doc)
    for h in (inst.hops[inst.start] + extra, extra, None):
        f = value_fields(inst, h)
        want, steps, fixpoint = _plain_fields(inst, h)
        got = [[f.number(x) for x in col] for col in (f.d1, f.d2, f.m)]
        assert (got, f.steps, f.fixpoint) == (want, steps, fixpoint)
        assert f.arithmetic == ("float64" if not inst.exact else
                                "python-int" if huge else "int64")


def test_value_fields_equal_the_plain_recursion_on_a_maze(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """A 9x12 grid with walls: long wavefronts, so most steps are sparse ones."""
    sparse = []
    step = _Frontier.step
    monkeypatch.setattr(_Frontier, "step", lambda *a: sparse.append(1) or step(*a))
    doc = _grid(9, 12, "1/2")
    walls = {(r, 4) for r in range(8)} | {(r, 8) for r in range(1, 9)}
    g = doc["graph"]
    g["nodes"] = [nd for nd in g["nodes"] if tuple(nd["id"]) not in walls]
    g["edges"] = [e for e in g["edges"]
                  if tuple(e["source"]) not in walls and tuple(e["target"]) not in walls]
    inst = _read_game(doc)
    for h in (10, 37, None):
        want, steps, fixpoint = _plain_fields(inst, h)
        for method in ("layers", "auto"):  # auto: the Dijkstra fixpoint where H reaches it
            f = value_fields(inst, h, method=method)  # type: ignore[arg-type]
            assert ([[f.number(x) for x in col] for col in (f.d1, f.d2, f.m)], f.steps,
                    f.fixpoint) == (want, steps, fixpoint)
    assert f.fixpoint and f.steps > 30 and len(sparse) > 60
