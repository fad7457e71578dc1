"""The ``dpp solve`` command: outputs, atomic files, one-line errors with exit code 2."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from dpp import main

ROOT = Path(__file__).resolve().parents[3]
TRIANGLE = str(ROOT / "examples" / "triangle.json")


def _run(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(main, list(args))
    return result.exit_code, result.stdout, result.stderr


def test_summary_and_json() -> None:
    code, out, _ = _run("solve", TRIANGLE)
    assert code == 0 and "U* (value)          = 12/5" in out and "VoI*" in out
    code, out, _ = _run("solve", TRIANGLE, "--json")
    doc = json.loads(out)
    assert code == 0 and doc["format"] == "dpp-profile/1" and doc["value"]["U"] == "12/5"


def test_output_file(tmp_path: Path) -> None:
    target = tmp_path / "p.json"
    code, out, err = _run("solve", TRIANGLE, "-o", str(target))
    assert code == 0 and out == "" and err.startswith(f"wrote {target}: U* = 12/5")
    assert json.loads(target.read_text())["attacker"]["secondary"][0]["path"] == ["s", "g2"]


def test_map_input(tmp_path: Path) -> None:
    m = tmp_path / "g.map"
    m.write_text("type octile\nheight 3\nwidth 3\nmap\n...\n.@.\n...\n")
    code, out, err = _run("solve", "--map", str(m), "--start", "0,0", "--goals", "2,2", "0,2",
                          "--prior", "3/5,2/5", "--json")
    assert code == 0, err
    assert json.loads(out)["goals"] == {"primary": [2, 2], "secondary": [0, 2]}


@pytest.mark.parametrize("args,message", [
    (("solve", "nope.json"), "nope.json: cannot read file"),
    (("solve",), "missing INSTANCE: give an instance JSON file, or --map FILE"),
    (("solve", "--map", "x.map", "--start", "0,0"), "--map needs"),
    (("solve", "--map", TRIANGLE, "--start", "0,0", "--goals", "1,1", "0,1", "--prior", "0.5,0.5"),
     "line 1: expected 'key value' header"),
])
def test_bad_input_is_one_line_exit_2(args: tuple[str, ...], message: str) -> None:
    code, out, err = _run(*args)
    assert code == 2
    assert message in err and len(err.strip().splitlines()) == 1
    assert "Traceback" not in out + err


def test_failed_solve_leaves_no_partial_output(tmp_path: Path) -> None:
    bad = tmp_path / "bad.json"
    doc = json.loads(Path(TRIANGLE).read_text())
    doc["graph"]["directed"] = True
    doc["graph"]["edges"] = [e for e in doc["graph"]["edges"] if e["source"] != "g2"]
    bad.write_text(json.dumps(doc))
    target = tmp_path / "p.json"
    code, _, err = _run("solve", str(bad), "-o", str(target))
    assert code == 2 and "unreachable" in err
    assert not target.exists() and list(tmp_path.iterdir()) == [bad]
