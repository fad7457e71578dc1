"""The checker's own ``.map`` reader and grid builder agree with the solver's.

``dppverify.formats.movingai`` shares no code with ``solver.formats.movingai`` /
``Instance.from_grid``; on the bundled paper map and the 12 standard MovingAI maps both must
give the same obstacles and the same instance document (node ids ``[row, col]``, the same
edges and weights, float mode for octile grids), and so the same checker instance.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import networkx as nx
import numpy as np
import pytest

from dppverify.errors import InvalidInstanceError as CheckerInvalid
from dppverify.formats import movingai as checker_maps
from dppverify.formats.map_instance import MapReference
from dppverify.game import grids as checker_grids
from dppverify.game.instance import instance_from_json
from solver.errors import InvalidInstanceError as SolverInvalid
from solver.formats import movingai as solver_maps
from solver.game.instance import Instance
from solver.game.instance_writing import instance_to_json
from tests.maps._maps import PAPER10, STANDARD, corner_cells, standard_map_path


def _checker_map_instance(path: Path, start: tuple[int, int],
                          goals: tuple[tuple[int, int], tuple[int, int]],
                          prior: tuple[str, str]) -> Any:
    """The checker's game of a ``.map`` file: its reader, then the one step from a map to
    the game (errors name the file)."""
    return checker_grids.reference_game(MapReference(
        checker_maps.read_map(path), start, goals, prior, 4, str(path)))

MAPS = [PAPER10, *(standard_map_path(name) for name in STANDARD)]
SMALL = [p for p in MAPS if p.stat().st_size < 5_000]  # up to 64x64 cells


def _blocked(grid: checker_maps.GridMap) -> np.ndarray:
    return np.array([[not grid.free(r, c) for c in range(grid.width)]
                     for r in range(grid.height)])


def _documents(path: Path, connectivity: int) -> tuple[dict[str, Any], dict[str, Any]]:
    blocked = solver_maps.read_map(path)
    start, g1, g2 = corner_cells(blocked)
    solver_doc = instance_to_json(Instance.from_grid(blocked, start, (g1, g2), ("3/5", "2/5"),
                                                     connectivity=connectivity))
    checker_doc = checker_maps.grid_document(checker_maps.read_map(path), start, (g1, g2),
                                             ("3/5", "2/5"), connectivity=connectivity)
    return solver_doc, checker_doc


def test_all_twelve_standard_maps_are_there() -> None:
    assert len(STANDARD) == 12
    assert {"Berlin_1_256", "empty-8-8", "maze-128-128-10", "room-64-64-16"} <= set(STANDARD)


@pytest.mark.parametrize("path", MAPS, ids=lambda p: p.stem)
def test_same_obstacles(path: Path) -> None:
    grid = checker_maps.read_map(path)
    blocked = solver_maps.read_map(path)
    assert blocked.shape == (grid.height, grid.width)
    assert np.array_equal(_blocked(grid), blocked)
    assert 0 < blocked.sum() or path.stem.startswith("empty")


@pytest.mark.parametrize("path", MAPS, ids=lambda p: p.stem)
def test_same_document_4_connected(path: Path) -> None:
    solver_doc, checker_doc = _documents(path, 4)
    assert checker_doc == solver_doc
    assert "numbers" not in checker_doc
    assert {e["weight"] for e in checker_doc["graph"]["edges"]} == {"1"}


@pytest.mark.parametrize("path", SMALL, ids=lambda p: p.stem)
def test_same_document_octile(path: Path) -> None:
    solver_doc, checker_doc = _documents(path, 8)
    assert checker_doc == solver_doc
    assert checker_doc["numbers"] == "float"
    assert {e["weight"] for e in checker_doc["graph"]["edges"]} == {1.0, 2 ** 0.5}


@pytest.mark.parametrize("name", ["paper10", "room-32-32-4", "maze-32-32-2"])
@pytest.mark.parametrize("connectivity", [4, 8])
def test_same_checker_instance(name: str, connectivity: int) -> None:
    path = PAPER10 if name == "paper10" else standard_map_path(name)
    solver_doc, checker_doc = _documents(path, connectivity)
    a, b = instance_from_json(solver_doc), instance_from_json(checker_doc)
    assert a.nodes == b.nodes and a.nodes[0] == tuple(solver_doc["graph"]["nodes"][0]["id"])
    assert (a.succ, a.start, a.goals, a.prior, a.exact) == (b.succ, b.start, b.goals, b.prior,
                                                            b.exact)
    assert a.exact == (connectivity == 4)
    assert a.dist_to == b.dist_to


def test_paper_map_instance() -> None:
    """The bundled map against networkx's grid graph and BFS distances."""
    inst = _checker_map_instance(PAPER10, (9, 0), ((0, 9), (0, 0)), ("0.6", "0.4"))
    blocked = solver_maps.read_map(PAPER10)
    g = nx.grid_2d_graph(*blocked.shape)
    g.remove_nodes_from(map(tuple, np.argwhere(blocked).tolist()))
    assert set(inst.nodes) == set(g.nodes) and inst.n_nodes == 100 - int(blocked.sum())
    assert sum(len(s) for s in inst.succ) == 2 * g.number_of_edges()
    assert inst.nodes[inst.start] == (9, 0)
    for i, goal in enumerate([(0, 9), (0, 0)]):
        assert inst.dist_to[i][inst.start] == nx.shortest_path_length(g, (9, 0), goal)


@pytest.mark.parametrize("cell,words", [
    ((3, 8), ["start cell (3, 8) is an obstacle", "10x10"]),
    ((10, 0), ["start cell (10, 0) is outside the 10x10", "rows 0-9"]),
    ((0, -1), ["start cell (0, -1) is outside the 10x10", "columns 0-9"]),
])
def test_bad_start_cell_is_named_by_both_builders(cell: tuple[int, int],
                                                   words: list[str]) -> None:
    with pytest.raises(CheckerInvalid) as checker_err:
        _checker_map_instance(PAPER10, cell, ((0, 9), (0, 0)), ("0.6", "0.4"))
    with pytest.raises(SolverInvalid) as solver_err:
        Instance.from_grid(solver_maps.read_map(PAPER10), cell, ((0, 9), (0, 0)), ("3/5", "2/5"))
    for message in (str(checker_err.value), str(solver_err.value)):
        assert all(w in message for w in words), message
        assert "not found in graph" not in message


def test_bad_goal_cell_is_named() -> None:
    with pytest.raises(CheckerInvalid, match=r"goal cell \(10, 9\) is outside"):
        _checker_map_instance(PAPER10, (9, 0), ((10, 9), (0, 0)), ("0.6", "0.4"))
    with pytest.raises(CheckerInvalid, match=r"goal cell \(5, 0\) is an obstacle"):
        _checker_map_instance(PAPER10, (9, 0), ((0, 9), (5, 0)), ("0.6", "0.4"))
    with pytest.raises(SolverInvalid, match=r"goal cell \(5, 0\) is an obstacle"):
        Instance.from_grid(solver_maps.read_map(PAPER10), (9, 0), ((0, 9), (5, 0)), ("3/5", "2/5"))


HEADER = "type octile\nheight 2\nwidth 3\nmap\n"


@pytest.mark.parametrize("text,message", [
    (HEADER + "...\n...\n...\n", "line 7: more map rows than height 2"),
    (HEADER + "...\n", "expected 2 map rows, found 1"),
    (HEADER + "...\n....\n", "line 6: expected 3 characters, found 4"),
    (HEADER + "...\n.x.\n", "line 6: unknown map character 'x' at column 1"),
    (HEADER + "...\n. .\n", "unknown map character ' '"),
    ("height 2\ntype octile\nwidth 3\nmap\n...\n...\n", "line 1: expected 'type octile'"),
    ("type tile\nheight 2\nwidth 3\nmap\n...\n...\n", "line 1: expected 'type octile'"),
    ("type octile\nheight two\nwidth 3\nmap\n...\n...\n", "line 2: height must be a positive"),
    ("type octile\nheight 0\nwidth 3\nmap\n", "line 2: height must be a positive"),
    ("type octile\nheight 2\nwidth -3\nmap\n...\n...\n", "line 3: width must be a positive"),
    ("type octile\nheight 2\nwidth 3\nmaps\n...\n...\n", "line 4: expected 'map'"),
    ("type octile\nheight 2\n", "truncated header"),
    ("", "truncated header"),
])
def test_strict_reader_refuses(tmp_path: Path, text: str, message: str) -> None:
    p = tmp_path / "bad.map"
    p.write_text(text)
    with pytest.raises(CheckerInvalid) as err:
        checker_maps.read_map(p)
    assert message in str(err.value) and str(p) in str(err.value)
    assert "\n" not in str(err.value)


def test_reader_accepts_crlf_and_trailing_blank_lines(tmp_path: Path) -> None:
    p = tmp_path / "ok.map"
    p.write_bytes(b"type octile\r\nheight 2\r\nwidth 3\r\nmap\r\n.@.\r\nTGS\r\n\r\n")
    grid = checker_maps.read_map(p)
    assert grid.rows == (".@.", "TGS")
    assert [grid.free(1, c) for c in range(3)] == [False, True, True]


def test_reader_refuses_non_ascii(tmp_path: Path) -> None:
    p = tmp_path / "bad.map"
    p.write_bytes(HEADER.encode() + "..\u00e9\n...\n".encode())
    with pytest.raises(CheckerInvalid, match="not an ASCII map file"):
        checker_maps.read_map(p)


# ---------------------------------------------------------------- goal-selection documents
def _selection_documents() -> list[dict[str, Any]]:
    from solver.formats.movingai import map_file, read_map_bytes
    sha = read_map_bytes(map_file(str(PAPER10)))[1]
    inline = {k: v for k, v in instance_to_json(Instance.from_grid(
        solver_maps.read_map(PAPER10), (9, 0), ((0, 9), (0, 0), (9, 9)),
        ("1/3", "1/3", "1/3"))).items() if k != "prior"}
    return [
        {"format": "dpp-map-instance/1", "map": str(PAPER10), "map_sha256": sha,
         "start": [9, 0], "goals": [[0, 9], [0, 0]], "goal_selection": True},
        {"format": "dpp-map-instance/1", "map": str(PAPER10), "map_sha256": sha,
         "start": [9, 0], "goals": [[0, 9], [0, 0]], "goal_selection": True,
         "goal_values": ["1/2", -1]},
        {**inline, "goal_selection": True, "goal_values": [0, "0.25", 3]},
    ]


@pytest.mark.parametrize("k", range(3))
def test_both_selection_readers_read_the_same_game(k: int) -> None:
    from solver.selection.instance import selection_from_json as solver_read
    doc = _selection_documents()[k]
    a, b = instance_from_json(doc), solver_read(doc)  # the checker's one reader reads the mark
    assert a.goal_values == b.values
    game = instance_from_json(instance_to_json(b.game))  # the solver's game, through JSON
    assert (game.nodes, game.start, game.goals, game.prior) == (
        a.nodes, a.start, a.goals, a.prior)
    assert game.dist_to == a.dist_to
    # and the document the solver writes back is read the same by the checker
    assert instance_from_json(b.to_json()).goal_values == a.goal_values


def _mistakes() -> list[tuple[dict[str, Any], str]]:
    base = _selection_documents()[0]
    inline = _selection_documents()[2]
    return [({**base, "prior": ["1/2", "1/2"]}, "has no prior"),
            ({**base, "goal_selection": False}, "must be true"),
            ({**base, "goal_selection": "yes"}, "must be true"),
            ({**base, "goal_values": [1]}, "goal_values: must be a list of 2"),
            ({**base, "goal_values": "0,1"}, "goal_values: must be a list of 2"),
            ({**base, "goal_values": ["x", 0]}, "goal_values[0]"),
            ({**base, "goal_values": ["1e400", 0]}, "goal_values[0]"),
            ({**base, "goal_values": [True, 0]}, "goal_values[0]"),
            ({**base, "connectivity": 8}, "exact"),
            ({**inline, "numbers": "float"}, "exact"),
            ({**inline, "goals": inline["goals"][:1]}, "goals"),
            ({**base, "map_sha256": "0" * 64}, "map_sha256")]


@pytest.mark.parametrize("k", range(12))
def test_both_selection_readers_refuse_the_same_mistakes(k: int) -> None:
    from solver.selection.instance import selection_from_json as solver_read
    doc, words = _mistakes()[k]
    with pytest.raises(CheckerInvalid) as c_err:
        instance_from_json(doc)
    with pytest.raises(SolverInvalid) as s_err:
        solver_read(doc)
    for message in (str(c_err.value), str(s_err.value)):
        assert words in message and "\n" not in message, message


def test_the_solvers_prior_game_reader_refuses_a_selection_document() -> None:
    """The solver reads the two games with two readers (its prior game's refuses the mark in
    one line); the checker's one reader reads both (the Instance's ``goal_values``)."""
    from solver.game.instance_reading import instance_from_json as solver_instance
    doc = _selection_documents()[0]
    with pytest.raises(SolverInvalid, match="goal-selection instance"):
        solver_instance(doc)
    assert instance_from_json(doc).goal_selection
