"""dppverify.formats.json_reading: the one home of the JSON reading primitives.

Every parser (two-goal and N-goal instances and profiles) reads numbers, node ids and walks
through this module only; the walk messages of both profile formats come from one function.
"""

from __future__ import annotations

import ast
from functools import partial
from pathlib import Path

import pytest

from dppverify.errors import InvalidInstanceError, ProfileError
from dppverify.formats.json_reading import (
    JsonReadError,
    lookup_node,
    read_json_document,
    resolve_walk,
)
from dppverify.game.examples import star3, triangle
from dppverify.game.inputs import as_profile
from dppverify.game.instance import load_instance

ROOT = Path(__file__).resolve().parents[3]
PARSERS = ("dppverify/game/instance.py", "dppverify/game/profile.py",
           "dppverify/game/instance_reading.py", "dppverify/game/graph_reading.py",
           "dppverify/game/profile_types.py")
PRIMITIVES = {"parse_json", "parse_number", "node_from_json", "show_node", "lookup_node",
              "resolve_walk", "read_json_document", "parse_json_text", "read_input"}


@pytest.mark.parametrize("path", PARSERS)
def test_parsers_take_their_primitives_from_json_reading(path: str) -> None:
    tree = ast.parse((ROOT / path).read_text(encoding="utf-8"))
    sources = {alias.name: node.module for node in ast.walk(tree)
               if isinstance(node, ast.ImportFrom) for alias in node.names}
    used = {name: module for name, module in sources.items() if name in PRIMITIVES}
    assert used, f"{path} reads no JSON primitive"
    assert set(used.values()) == {"dppverify.formats.json_reading"}, used


@pytest.mark.parametrize("raw, subject, complete, want", [
    (["s", "g1"], "path", True, (0, 1)),
    ([], "path", True, "path must be a non-empty list of node ids"),
    (["s", {"x": 1}], "path", True, "path[1] is not a node id"),
    (["s", "zz"], "", True, '[1]: unknown node "zz"'),
    (["g2"], "path", True, 'path starts at "g2", not at the start "s"'),
    (["g2"], "", True, 'starts at "g2", not at the start "s"'),
    (["s", "g2", "g1"], "path", True,
     'path reaches goal "g2" at step 1 and continues (the game ends at the first goal)'),
    (["s"], "path", True, 'path ends at "s", which is not a goal'),
    (["s"], "walk", False, "walk must have at least one step (the Defender acts after each move)"),
    (["s"], "", False, "must have at least one step (the Defender acts after each move)"),
])
def test_resolve_walk_messages(raw: list[object], subject: str, complete: bool,
                               want: object) -> None:
    assert resolve_walk(triangle(), raw, complete=complete, subject=subject) == want


def test_resolve_walk_reads_both_instance_kinds() -> None:
    inst = star3()
    assert resolve_walk(inst, ["s", "m", "b"], complete=True) == (0, 1, 3)
    assert resolve_walk(inst, ["s", "b"], complete=True, subject="") == '[1]: no edge "s" -> "b"'


def test_lookup_node_never_raises() -> None:
    index = triangle().index
    assert [lookup_node(index, x) for x in ("g1", None, [[]], {"a": 1}, True)] == [
        1, None, None, None, None]


@pytest.mark.parametrize("kind, want", [("instance", "cannot read instance file"),
                                        ("profile", "cannot read profile file")])
def test_read_json_document_is_bounded(kind: str, want: str) -> None:
    with pytest.raises(JsonReadError, match=want):
        read_json_document("/dev/zero", kind=kind)


def test_every_document_reader_refuses_dev_zero_in_one_line() -> None:
    for load, error in ((partial(as_profile, instance=triangle()), ProfileError),
                        (partial(as_profile, instance=star3()), ProfileError),
                        (load_instance, InvalidInstanceError)):
        with pytest.raises(error) as exc:
            load("/dev/zero")
        text = str(exc.value)
        assert text.startswith("/dev/zero: cannot read ") and "\n" not in text, text
