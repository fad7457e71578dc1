"""``dpp solve`` (the real command, in its own process) answers on the gadget and hub
families' N = 4/5 draws: exit 0, a certified profile, never a refusal for arithmetic reasons.

``test_no_arithmetic_refusal.py`` asks the solver's construction in-process; this asks the
command a user runs, which also reads the instance, certifies the answer and writes it (the
int64 refusal was once the command's line "the vertices' common denominator … leaves int64 …
no profile written"). The draws that take the solver under ten seconds run by default; the
five-goal ones that need extra normals (about a minute each) are ``slow``.
"""

from __future__ import annotations

import json
import random
from pathlib import Path
from typing import Any

import pytest

from tests.hostile._harness import run
from tests.solver._ngoal_families import GADGET, draw, hub

ARITHMETIC = ("int64", "exact range", "denominator", "hadamard", "overflow")
"""Words of a refusal for arithmetic reasons."""

QUICK: list[tuple[str, dict[str, Any]]] = [
    ("the N = 4 gadget", GADGET),
    ("hub N = 4 seed 0", hub(random.Random(0), 4)),
    ("finite hub N = 4 seed 0", hub(random.Random(0), 4, dag=True)),
    ("hub N = 5 seed 1", hub(random.Random(1), 5)),
    ("finite hub N = 5 seed 1", hub(random.Random(1), 5, dag=True)),
    ("solver family hub N = 5 seed 0", draw("hub", 0, 5)),
]
"""One draw of each family and N by default (the gadget, the hub and the finite hub at
N = 4 and 5, the solver's own hub family)."""
SLOW: list[tuple[str, dict[str, Any]]] = [
    ("hub N = 5 seed 2", hub(random.Random(2), 5)),
    ("finite hub N = 5 seed 2", hub(random.Random(2), 5, dag=True)),
    ("hub N = 5 seed 0", hub(random.Random(0), 5)),
    ("finite hub N = 5 seed 0 (once refused)", hub(random.Random(0), 5, dag=True)),
    ("finite hub N = 5 seed 7 (once refused)", hub(random.Random(7), 5, dag=True)),
    *((f"solver family hub N = {n} seed {s}", draw("hub", s, n)) for n in (4, 5)
      for s in range(1, 4)),
]


def _solved(tmp_path: Path, doc: dict[str, Any]) -> None:
    (tmp_path / "i.json").write_text(json.dumps(doc))
    result = run(["solve", "i.json", "-o", "p.json"], tmp_path, cpu=900)
    text = result.stderr.lower()
    assert not any(w in text for w in ARITHMETIC), result.stderr
    assert result.code == 0, result.stderr
    assert "certified" in result.stderr, result.stderr
    profile = json.loads((tmp_path / "p.json").read_text())
    assert len(profile["attacker"]) == len(doc["goals"])


@pytest.mark.parametrize("name, doc", QUICK, ids=[q[0] for q in QUICK])
def test_solve_answers_the_quick_draws(tmp_path: Path, name: str, doc: dict[str, Any]) -> None:
    _solved(tmp_path, doc)


@pytest.mark.slow
@pytest.mark.parametrize("name, doc", SLOW, ids=[q[0] for q in SLOW])
def test_solve_answers_the_slow_draws(tmp_path: Path, name: str, doc: dict[str, Any]) -> None:
    _solved(tmp_path, doc)
