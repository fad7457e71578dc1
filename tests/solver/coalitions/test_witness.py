"""The solver's guarantee-rule witness (``solver.coalitions.witness``): the trusted kernel
accepts it, it agrees with the checker's emitter (``dppverify.structured.witness``) in every
number the two have in common, and a mutated one is rejected."""

from __future__ import annotations

import copy
import json
from fractions import Fraction
from pathlib import Path
from typing import Any

import pytest
from click.testing import CliRunner

from dpp import main
from dppverify.game.examples import hub4_document, star3_document
from dppverify.kernel import check
from dppverify.kernel.reading import sha256
from solver.coalitions.witness import guarantee_witness
from solver.solution import solve
from tests.dppverify.kernel._witnesses import engine_witness
from tests.solver._ngoal_families import GADGET, draw

CASES = {"star3": star3_document, "hub4": hub4_document, "gadget": lambda: GADGET,
         "hub-1-4": lambda: draw("hub", 1, 4), "digraph-0-3": lambda: draw("digraph", 0, 3),
         "grid-2-4": lambda: draw("grid", 2, 4)}


def _documents(name: str) -> tuple[bytes, bytes, dict[str, Any]]:
    doc = CASES[name]()
    res = solve(doc)
    assert res.coalitions is not None
    ib, pb = json.dumps(doc).encode(), json.dumps(res.to_json()).encode()
    w = guarantee_witness(res.coalitions, instance_sha256=sha256(ib), profile_sha256=sha256(pb))
    return ib, pb, w


def _rational(w: dict[str, Any]) -> dict[str, Any]:
    """The numbers of a witness independent of its denominator (and of the stage duals, which
    are not unique)."""
    S = w["denominator"]

    def f(xs: list[int | None]) -> list[Fraction | None]:
        return [None if x is None else Fraction(x, S) for x in xs]
    g = w["guarantee"]
    return {"distances": [f(d) for d in w["distances"]], "m": [f(r) for r in g["m"]],
            "covers": g["covers"], "sigma": [s["sigma"] for s in g["steps"]],
            "shas": (w["instance_sha256"], w["profile_sha256"])}


@pytest.mark.parametrize("name", sorted(CASES))
def test_kernel_accepts_and_matches_the_checker(name: str) -> None:
    ib, pb, mine = _documents(name)
    verdict = check(ib, pb, json.dumps(mine).encode())
    assert verdict.status == "pass", verdict.message
    theirs = engine_witness(ib, pb)
    assert _rational(mine) == _rational(theirs)
    # the denominator is the least one the labels need; the checker's is a multiple of it
    assert theirs["denominator"] % mine["denominator"] == 0
    assert [len(s["duals"]) for s in mine["guarantee"]["steps"]] == \
        [len(s["duals"]) for s in theirs["guarantee"]["steps"]]


@pytest.mark.parametrize("where", ["sigma", "dual", "m", "cover"])
def test_a_mutated_witness_is_rejected(where: str) -> None:
    ib, pb, w = _documents("hub4")
    bad = copy.deepcopy(w)
    g = bad["guarantee"]
    step = next(s for s in g["steps"] if len(set(s["sigma"])) > 1)
    if where == "sigma":  # move mass between two types: still in the simplex
        s = step["sigma"]
        i = max(range(len(s)), key=lambda t: Fraction(s[t]))
        j = (i + 1) % len(s)
        d = Fraction(s[i]) / 2
        step["sigma"][i] = str(Fraction(step["sigma"][i]) - d)
        step["sigma"][j] = str(Fraction(step["sigma"][j]) + d)
    elif where == "dual":
        step["duals"][0]["z"] = str(Fraction(step["duals"][0]["z"]) - 1)
    elif where == "m":
        v = next(v for v, x in enumerate(g["m"][0]) if x)
        g["m"][0][v] += 1
    else:
        g["covers"] = []
    assert check(ib, pb, json.dumps(bad).encode()).status != "pass"


def test_dpp_solve_witness_for_three_goals(tmp_path: Path) -> None:
    inst = tmp_path / "star3.json"
    inst.write_text(json.dumps(star3_document()))
    p, w = tmp_path / "p.json", tmp_path / "w.json"
    run = CliRunner().invoke(main, ["solve", str(inst), "-o", str(p), "--witness", str(w)])
    assert run.exit_code == 0, run.output
    res = solve(star3_document())
    assert res.coalitions is not None
    expected = guarantee_witness(res.coalitions, instance_sha256=sha256(inst.read_bytes()),
                                 profile_sha256=sha256(p.read_bytes()))
    assert json.loads(w.read_text()) == expected
    run = CliRunner().invoke(main, ["check", str(inst), str(p), str(w)])
    assert run.exit_code == 0 and "PASS" in run.output, run.output


def test_dpp_solve_witness_on_a_three_goal_map(tmp_path: Path) -> None:
    game = ["--map", "examples:paper10", "--start", "9,0", "--goals", "0,9", "0,0", "9,9",
            "--prior", "1/2,1/3,1/6"]
    p, w = tmp_path / "p.json", tmp_path / "w.json"
    run = CliRunner().invoke(main, ["solve", *game, "-o", str(p), "--witness", str(w)])
    assert run.exit_code == 0, run.output
    run = CliRunner().invoke(main, ["check", *game, str(p), str(w)])
    assert run.exit_code == 0 and "PASS" in run.output, run.output
