"""``dpp value --json`` is one ``dpp-value/1`` document for every route and every N.

Each case runs the command (``dpp value ... --json``) and checks the document's shape (every
top-level key always present, in order; the same keys in every route record), that the
numbers it states are consistent (``lower <= value <= upper``, ``exact`` only for a closed
exact bracket), and that the document agrees with the Python API (``dppverify.value``).
"""

from __future__ import annotations

import json
from fractions import Fraction
from pathlib import Path
from typing import Any

import pytest
from click.testing import CliRunner

from dppverify import value
from dppverify.cli.value import value_command
from dppverify.game.examples import hub4_document, star3_document, triangle_document
from dppverify.value_document import ROUTE_KEYS, TOP_KEYS, VALUE_FORMAT

ROOT = Path(__file__).resolve().parents[2]
PAPER10 = ["--map", str(ROOT / "examples" / "paper10.map"), "--start", "9,0",
           "--goals", "0,9", "0,0"]

METHODS = {"tree": {"tree-lp"}, "structured": {"three-field-dp", "guarantee-sets"}}


def _number(x: Any) -> Fraction | float:
    return x if isinstance(x, float) else Fraction(x)


def _document(args: list[str]) -> dict[str, Any]:
    r = CliRunner().invoke(value_command, [*args, "--json"])
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert isinstance(doc, dict)
    return doc


def _check_shape(doc: dict[str, Any], *, goals: int, route: str, horizon: int | str) -> None:
    assert tuple(doc) == TOP_KEYS and doc["format"] == VALUE_FORMAT
    assert doc["goals"] == goals and doc["route"] == route and doc["horizon"] == horizon
    assert doc["truncated"] is (horizon != "inf")
    ran = {"tree": route in ("tree", "both"), "structured": route in ("structured", "both")}
    for name, present in ran.items():
        record = doc[name]
        if not present:
            assert record is None
            continue
        assert tuple(record) == ROUTE_KEYS and record["method"] in METHODS[name]
        assert isinstance(record["details"], dict)
        lo, hi = _number(record["lower"]), _number(record["upper"])
        assert lo <= hi
        if record["exact"]:
            assert record["value"] == record["lower"] == record["upper"]
    assert (doc["agree"] is None) is (route != "both")
    lo, hi = _number(doc["lower"]), _number(doc["upper"])
    assert lo <= hi and isinstance(doc["lower_source"], str) and doc["upper_source"]
    if doc["value"] is not None:
        assert lo == _number(doc["value"]) == hi and doc["open_reason"] is None
    else:
        assert not doc["exact"] and doc["open_reason"]
    assert doc["exact"] is (doc["value"] is not None and doc["numbers"] == "exact")


@pytest.fixture(scope="module")
def files(tmp_path_factory: pytest.TempPathFactory) -> dict[str, str]:
    d = tmp_path_factory.mktemp("value_documents")
    docs = {"triangle": triangle_document(), "star3": star3_document(),
            "hub4": hub4_document()}
    out = {}
    for name, doc in docs.items():
        (d / f"{name}.json").write_text(json.dumps(doc))
        out[name] = str(d / f"{name}.json")
    return out


@pytest.mark.parametrize(("name", "goals"), [("triangle", 2), ("star3", 3), ("hub4", 4)])
@pytest.mark.parametrize(("route", "horizon"), [("structured", "inf"), ("structured", 3),
                                                ("tree", 3), ("both", 3)])
def test_one_shape_for_every_route_and_n(files: dict[str, str], name: str, goals: int,
                                         route: str, horizon: int | str) -> None:
    doc = _document([files[name], "-H", str(horizon), "--route", route])
    _check_shape(doc, goals=goals, route=route, horizon=horizon)
    api = value(files[name], horizon)
    assert doc["value"] == (None if api.value is None else str(api.value))


def test_the_default_is_the_untruncated_game(files: dict[str, str]) -> None:
    doc = _document([files["triangle"]])
    _check_shape(doc, goals=2, route="structured", horizon="inf")
    assert doc["value"] == "12/5" and doc["exact"] is True
    assert doc["structured"]["details"]["fixpoint"] is True


def test_an_open_bracket_names_both_bounds(files: dict[str, str]) -> None:
    """hub4 at H = inf: the coalition DP's 25/14 is only an upper bound (proofs/NGOAL.md);
    the value 12/7 is proved (by the refined DP), and the coalition DP stays in the details."""
    doc = _document([files["hub4"]])
    _check_shape(doc, goals=4, route="structured", horizon="inf")
    details = doc["structured"]["details"]
    assert doc["value"] == "12/7" and details["coalition_dp"]["value"] == "25/14"
    # the proof of exactness: the refined DP's sets pass the arc test (NRULE NR.1(e))
    assert "NR.1(e)" in doc["lower_source"] and doc["exact"] is True
    assert doc["structured"]["details"]["extra_normals"] == [[2, 2, 2, 1]]


def test_float_mode_has_the_same_shape() -> None:
    doc = _document([*PAPER10, "--prior", "0.6,0.4", "--connectivity", "8"])
    _check_shape(doc, goals=2, route="structured", horizon="inf")
    assert doc["numbers"] == "float" and doc["exact"] is False
    assert isinstance(doc["value"], float)


def test_n_goal_map_with_output_file(tmp_path: Path) -> None:
    out = tmp_path / "v.json"
    r = CliRunner().invoke(value_command, [*PAPER10, "9,9", "--prior", "1/2,1/3,1/6",
                                           "-o", str(out)])
    assert r.exit_code == 0 and r.stdout == "", r.output
    doc = json.loads(out.read_text())
    _check_shape(doc, goals=3, route="structured", horizon="inf")
    assert doc["structured"]["method"] == "guarantee-sets" and doc["exact"] is True
