"""N-goal instances: parsing, validation, and the two-goal parser's refusal of N > 2."""

from __future__ import annotations

import copy
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings

from dppverify.errors import InvalidInstanceError
from dppverify.game.examples import star3_document, triangle_document
from dppverify.game.instance import Instance, instance_from_json, load_instance
from dppverify.strategies import instances


def _doc(**changes: Any) -> dict[str, Any]:
    doc = copy.deepcopy(star3_document())
    doc.update(changes)
    return doc


@pytest.mark.parametrize(("changes", "message"), [
    ({"goals": ["a"], "prior": [1]}, "at least two node ids"),
    ({"goals": ["a", "b", "a"]}, "goals[2]: goal \"a\" is listed twice"),
    ({"goals": ["a", "b", "z"]}, "goals[2]: unknown node \"z\""),
    ({"prior": ["1/2", "1/2"]}, "prior: must be a list of 3 numbers"),
    ({"prior": ["1/2", "1/3", "1/3"]}, "prior: must sum to exactly 1, got 7/6"),
    ({"prior": ["1", "0", "0"]}, "prior[0]: must lie strictly between 0 and 1"),
    ({"prior": ["1/2", "x", "1/6"]}, "prior[1]: 'x' is not a number"),
    ({"numbers": "float"}, "must be exact"),
    ({"start": "q"}, "start: unknown node \"q\""),
])
def test_invalid_documents_are_one_line_errors(changes: dict[str, Any], message: str) -> None:
    with pytest.raises(InvalidInstanceError) as info:
        instance_from_json(_doc(**changes))
    assert message in str(info.value)
    assert "\n" not in str(info.value)


def test_goals_must_reach_each_other() -> None:
    doc = _doc()
    doc["graph"]["directed"] = True
    doc["graph"]["edges"] = [{"source": "s", "target": "m"}, {"source": "m", "target": "a"},
                             {"source": "m", "target": "b"}, {"source": "m", "target": "c"},
                             {"source": "a", "target": "m"}, {"source": "b", "target": "m"}]
    with pytest.raises(InvalidInstanceError, match="goal \"a\" is unreachable from goal \"c\""):
        instance_from_json(doc)
    doc["graph"]["edges"].append({"source": "c", "target": "m"})
    assert instance_from_json(doc).dist_to[0][doc["graph"]["nodes"].index({"id": "c"})] == 2


def test_float_numbers_only_for_two_goals() -> None:
    """The one rule of the number mode: "numbers": "float" is read for two goals only."""
    assert not instance_from_json({**triangle_document(), "numbers": "float"}).exact
    with pytest.raises(InvalidInstanceError, match="N-goal instances must be exact"):
        instance_from_json({**star3_document(), "numbers": "float"})


def test_file_errors(tmp_path: Any) -> None:
    bad = tmp_path / "bad.json"
    bad.write_text("{", encoding="utf-8")
    with pytest.raises(InvalidInstanceError, match=r"bad\.json: malformed JSON at line 1"):
        load_instance(bad)
    good = tmp_path / "star.json"
    good.write_text('{"graph": {"nodes": [{"id": 0}, {"id": 1}, {"id": 2}], "edges": ['
                    '{"source": 0, "target": 1}, {"source": 1, "target": 2}]}, "start": 0, '
                    '"goals": [0, 1, 2], "prior": [0.5, 0.25, 0.25]}', encoding="utf-8")
    assert load_instance(good).hops == (0, 0, 0)
    with pytest.raises(InvalidInstanceError, match=r"star\.json: prior"):
        good.write_text(good.read_text().replace("0.25]", "0.2]"), encoding="utf-8")
        load_instance(good)


def test_the_two_goal_reader_refuses_n_goals_and_names_the_n_goal_commands() -> None:
    from solver import InstanceFormatError, instance_from_json

    assert instance_from_json(star3_document()).n_goals == 3  # the reader takes any N
    with pytest.raises(InstanceFormatError) as info:
        instance_from_json(star3_document(), two_goals=True)
    assert "lists 3 goals" in str(info.value) and "two-goal instances only" in str(info.value)
    assert ("`dpp solve`, `dpp certify`, `dpp value`, `dpp export-efg` and `dpp plot map` "
            "take N goals") in str(info.value)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(instances())
def test_both_parsers_agree_on_random_two_goal_documents(doc: dict[str, Any]) -> None:
    """One graph parser: a two-goal document gives the same game through either class."""
    two, many = instance_from_json(doc), instance_from_json(doc)
    for name in ("nodes", "directed", "succ", "pred", "start", "goals", "prior", "dist_to",
                 "hops", "exact"):
        assert getattr(two, name) == getattr(many, name), name
    assert dict(two.index) == dict(many.index)
    assert isinstance(two, Instance) and isinstance(many, Instance)
