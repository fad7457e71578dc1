"""Six goals and more: the coalition DP refuses with one line; a finite horizon takes the tree."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from dppverify.cli.value import value_command
from dppverify.errors import OptionError
from dppverify.game.instance import instance_from_json
from dppverify.structured.coalition import coalition_value


def _star(n: int) -> dict[str, object]:
    return {"graph": {"directed": False, "nodes": [{"id": i} for i in range(n + 1)],
                      "edges": [{"source": 0, "target": i} for i in range(1, n + 1)]},
            "start": 0, "goals": list(range(1, n + 1)), "prior": [f"1/{n}"] * n}


def test_coalition_dp_refuses_six_goals() -> None:
    with pytest.raises(OptionError, match="2 to 5 goals, not 6"):
        coalition_value(instance_from_json(_star(6)), None)


@pytest.mark.parametrize("args", [["--horizon", "inf"],
                                  ["--horizon", "3", "--route", "structured"],
                                  ["--horizon", "3", "--route", "both"]])
def test_value_needs_a_finite_tree_horizon_beyond_five_goals(tmp_path: Path,
                                                             args: list[str]) -> None:
    path = tmp_path / "six.json"
    path.write_text(json.dumps(_star(6)))
    result = CliRunner().invoke(value_command, [str(path), *args])
    assert result.exit_code == 2
    assert result.output.strip().count("\n") == 0 and "2 to 5 goals, not 6" in result.output


def test_six_goals_at_a_finite_horizon_take_the_tree(tmp_path: Path) -> None:
    path = tmp_path / "six.json"
    path.write_text(json.dumps(_star(6)))
    result = CliRunner().invoke(value_command, [str(path), "--horizon", "2", "--json"])
    assert result.exit_code == 0, result.output
    doc = json.loads(result.output)
    # each type's one step ends on its goal: the Defender sees it and guards that goal
    assert doc["route"] == "tree" and doc["goals"] == 6 and doc["value"] == "1"
