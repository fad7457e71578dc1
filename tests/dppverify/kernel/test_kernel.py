"""The trusted kernel (proofs/KERNEL.md) on the pinned and conformance cases: the engine's
witnesses are accepted on equilibria; mutated witnesses, mutated profiles and
non-equilibrium profiles are rejected, with the failing inequality or the counterexample named;
a witness for other bytes is bad input."""

from __future__ import annotations

import copy
import json
import random
import shutil
from fractions import Fraction
from pathlib import Path
from typing import Any

import pytest

from dppverify.cli.check import run_kernel
from dppverify.kernel import check
from dppverify.kernel.reading import sha256
from solver.adapter import solve_json
from tests.dppverify.kernel._witnesses import as_bytes, engine_witness, kernel_verdict

ROOT = Path(__file__).resolve().parents[3]
PINS = ROOT / "tests" / "pins" / "data"
CASES = json.loads((ROOT / "tests" / "data" / "conformance_cases.json").read_text())


def _pin(name: str) -> bytes:
    return (PINS / f"{name}.json").read_bytes()


@pytest.mark.parametrize("case", CASES, ids=[c["name"] for c in CASES])
def test_every_conformance_case_is_accepted_with_the_engine_witness(case: dict[str, Any]) -> None:
    profile = solve_json(case["instance"])
    v = kernel_verdict(case["instance"], profile)
    assert v.status == "pass", v.message


@pytest.mark.parametrize("case", CASES, ids=[c["name"] for c in CASES])
def test_the_solver_witness_is_the_engine_witness(case: dict[str, Any]) -> None:
    """``dpp solve --witness`` (the solver's own fields) writes the same numbers as the engine:
    the same labels over the same denominator, accepted by the kernel."""
    from solver.game.instance_reading import as_instance
    from solver.twogoal.witness import twogoal_witness

    i = as_bytes(case["instance"])
    profile = solve_json(case["instance"])
    w = twogoal_witness(as_instance(case["instance"]), instance_sha256=sha256(i),
                        profile_sha256=sha256(as_bytes(profile)))
    assert kernel_verdict(i, profile, w).status == "pass"
    assert w == engine_witness(i, profile)


@pytest.mark.parametrize(("instance", "profile", "status", "says"), [
    ("triangle", "triangle_profile", "pass", "PASS: a weak PBNE"),
    ("triangle", "triangle_bad_profile", "refuted", "not greedy at the reached prefix"),
    ("kite", "kite_naive_profile", "refuted", "type 1: the walk of counterexamples[0] costs 1"),
    ("star3", "star3_profile", "refuted", "costs 0 < U = 1: regret > 0"),
])
def test_pinned_profiles(instance: str, profile: str, status: str, says: str) -> None:
    v = kernel_verdict(_pin(instance), _pin(profile))
    assert v.status == status and says in v.message, v


def test_a_witness_for_other_bytes_is_bad_input() -> None:
    i, p = _pin("triangle"), _pin("triangle_profile")
    w = engine_witness(i, p)
    assert check(i + b" ", p, as_bytes(w)).status == "bad-input"
    v = check(i, p + b"\n", as_bytes(w))
    assert v.status == "bad-input" and "profile_sha256" in v.message
    for bad in ({**w, "denominator": 0}, {**w, "extra": 1}, {**w, "distances": w["distances"][:1]},
                {**w, "types": [{**w["types"][0], "exit": [0, 0, 0]}, w["types"][1]]}):
        assert check(i, p, as_bytes(bad)).status == "bad-input", bad
    assert check(i, p, b"[1, 2").status == "bad-input"


def _scaled(w: dict[str, Any], k: int) -> dict[str, Any]:
    """The same witness over the denominator ``k·S`` (every label times ``k``)."""
    out = copy.deepcopy(w)
    out["denominator"] *= k

    def times(xs: list[Any]) -> list[Any]:
        return [None if x is None else k * x for x in xs]
    out["distances"] = [times(d) for d in w["distances"]]
    out["types"] = [{key: times(xs) for key, xs in rec.items()} for rec in w["types"]]
    return out


def _mutants(w: dict[str, Any], rng: random.Random) -> list[tuple[str, dict[str, Any], str]]:
    """Labels moved up by a small rational (1/k of the witness's unit); each must break the
    inequality named by the third entry (exact labels are tight wherever they are finite)."""
    out = []
    k = rng.choice([2, 3, 7])
    for j, d in enumerate(w["distances"]):
        v = rng.choice([i for i, x in enumerate(d) if x is not None])
        m = _scaled(w, k)
        m["distances"][j][v] += rng.choice([-1, 1])
        out.append((f"distances[{j}][{v}]", m, f"distances[{j}]"))
    for t, rec in enumerate(w["types"]):
        m = _scaled(w, k)
        m["types"][t]["trie"][0] += 1
        out.append((f"types[{t}].trie[0]", m, "fails"))
        for key in set(rec) - {"trie"}:
            v = rng.choice([i for i, x in enumerate(rec[key]) if x is not None])
            m = _scaled(w, k)
            m["types"][t][key][v] += 1
            out.append((f"types[{t}].{key}[{v}]", m, "fails"))
    return out


@pytest.mark.parametrize("case", CASES[::6], ids=[c["name"] for c in CASES[::6]])
def test_raised_labels_are_not_proved_and_the_inequality_is_named(case: dict[str, Any]) -> None:
    profile = solve_json(case["instance"])
    w = engine_witness(case["instance"], profile)
    rng = random.Random(case["name"])
    for name, m, says in _mutants(w, rng):
        v = kernel_verdict(case["instance"], profile, m)
        assert v.status == "undecided" and says in v.message, (name, v)


def _rehashed(w: dict[str, Any], profile: Any) -> dict[str, Any]:
    return {**w, "profile_sha256": sha256(as_bytes(profile))}


def test_a_profile_paying_more_than_the_witness_bound_is_not_proved() -> None:
    """The U check: the same potentials for a profile whose secondary also plays a dearer walk."""
    i, p = _pin("triangle"), json.loads(_pin("triangle_profile"))
    w = engine_witness(i, p)
    q = copy.deepcopy(p)  # secondary: s g2 (cost 1) and s g1 (cost 3 for it)
    q["attacker"]["secondary"] = [{"path": ["s", "g2"], "probability": "1/2"},
                                  {"path": ["s", "g1"], "probability": "1/2"}]
    v = kernel_verdict(i, q, _rehashed(w, q))
    assert v.status in ("undecided", "refuted"), v
    assert "U <= phi(start) fails" in v.message or "not greedy" in v.message
    assert kernel_verdict(i, q).status == "refuted"  # the engine's witness has the walk


@pytest.mark.parametrize("case", CASES[::9], ids=[c["name"] for c in CASES[::9]])
def test_moved_masses_are_refuted_or_not_proved(case: dict[str, Any]) -> None:
    """Moving probability between a type's walks changes the masses (and U): the kernel never
    accepts what the engine refutes, and refutes when the engine's witness has a walk."""
    import dppverify

    profile = solve_json(case["instance"])
    for key in ("primary", "secondary"):
        mix = profile["attacker"][key]
        if len(mix) < 2:
            continue
        q = copy.deepcopy(profile)
        a, b = (Fraction(e["probability"]) for e in mix[:2])
        q["attacker"][key][0]["probability"] = str(a + b)
        q["attacker"][key][1]["probability"] = "0"
        engine = dppverify.certify(case["instance"], q).verdict
        v = kernel_verdict(case["instance"], q)
        assert (v.status == "pass") == (engine == "pass"), (v, engine)


def test_dpp_check_runs_the_kernel_alone(tmp_path: Path) -> None:
    i, p = _pin("kite"), _pin("kite_naive_profile")
    (tmp_path / "i.json").write_bytes(i)
    (tmp_path / "p.json").write_bytes(p)
    (tmp_path / "w.json").write_bytes(as_bytes(engine_witness(i, p)))
    r = run_kernel([str(tmp_path / f) for f in ("i.json", "p.json", "w.json")])
    assert r.returncode == 1 and r.stdout.decode().startswith("REFUTED: type 1: the walk")
    assert r.stdout.decode().count("\n") == 1 and not r.stderr
    r = run_kernel([str(tmp_path / "i.json"), str(tmp_path / "p.json"), "-"],
                   stdin=(tmp_path / "w.json").read_bytes())
    assert r.returncode == 1
    r = run_kernel([str(tmp_path / "p.json"), str(tmp_path / "i.json"), str(tmp_path / "w.json")])
    assert r.returncode == 2 and r.stderr.decode().count("\n") == 1 and not r.stdout


def test_a_map_instance_is_read_from_its_folder(tmp_path: Path) -> None:
    shutil.copy(ROOT / "examples" / "paper10.map", tmp_path / "paper10.map")
    data = (tmp_path / "paper10.map").read_bytes()
    doc = {"format": "dpp-map-instance/1", "map": "paper10.map", "map_sha256": sha256(data),
           "start": [9, 0], "goals": [[0, 9], [0, 0]], "prior": ["3/5", "2/5"]}
    (tmp_path / "i.json").write_text(json.dumps(doc))
    from dppverify.game.instance import instance_from_json

    full = instance_from_json(doc, base=tmp_path)
    profile = solve_json(json.loads(json.dumps(_full_document(full))))
    i = (tmp_path / "i.json").read_bytes()
    w = engine_witness(_full_document(full), profile)
    w["instance_sha256"] = sha256(i)
    v = check(i, as_bytes(profile), as_bytes(w), base_dir=tmp_path)
    assert v.status == "pass", v
    assert check(i, as_bytes(profile), as_bytes(w), base_dir=ROOT).status == "bad-input"


def _full_document(inst: Any) -> dict[str, Any]:
    """The node-link document of a grid instance (cells in row-major order)."""
    nodes = [list(x) for x in inst.nodes]
    edges = [{"source": nodes[v], "target": nodes[u], "weight": 1}
             for v in range(inst.n_nodes) for u, _ in inst.succ[v] if u > v]
    return {"graph": {"nodes": [{"id": x} for x in nodes], "edges": edges},
            "start": list(inst.nodes[inst.start]),
            "goals": [list(inst.nodes[g]) for g in inst.goals],
            "prior": [str(b) for b in inst.prior]}


# -- the guarantee rule (N goals) ------------------------------------------------------------

@pytest.mark.parametrize("name", ["star3", "star3_equal_prior",
                                  pytest.param("hub4", marks=pytest.mark.slow),
                                  pytest.param("hub4_undirected", marks=pytest.mark.slow)])
def test_the_solver_guarantee_rule_profiles_are_accepted(name: str) -> None:
    doc = _pin(name)
    profile = solve_json(json.loads(doc))
    assert profile["defender"]["rule"] == "guarantee"
    v = kernel_verdict(doc, profile)
    assert v.status == "pass" and "guarantee rule" in v.message, v


@pytest.mark.slow
def test_guarantee_witness_mutants_are_not_proved() -> None:
    """The four-goal hub with its extra normals: a label off the DP, the covers of the extra
    directions dropped, σ moved, a stage dual broken, a prefix missing."""
    doc = _pin("hub4")
    profile = solve_json(json.loads(doc))
    w = engine_witness(doc, profile)
    g = w["guarantee"]

    def mutated(change: Any) -> Any:
        m = copy.deepcopy(w)
        change(m["guarantee"])
        return kernel_verdict(doc, profile, m)

    v = mutated(lambda x: x["m"][6].__setitem__(1, x["m"][6][1] + 1))
    assert v.status == "undecided" and "not the rule's DP" in v.message, v
    v = mutated(lambda x: x.__setitem__("covers", []))  # the extra normals need the covers
    assert v.status == "undecided" and "arc condition" in v.message, v
    s0 = g["steps"][0]["sigma"]
    moved = [str(Fraction(s0[0]) + Fraction(1, 7)), str(Fraction(s0[1]) - Fraction(1, 7)), *s0[2:]]
    v = mutated(lambda x: x["steps"][0].__setitem__("sigma", moved))
    assert v.status == "undecided" and "steps[0]" in v.message, v
    v = mutated(lambda x: x["steps"][0]["duals"][0].__setitem__("z", "-1"))
    assert v.status == "undecided" and "dual of stage 1" in v.message, v
    v = mutated(lambda x: x["steps"].pop())
    assert v.status == "bad-input", v


def test_star3_guarantee_mutants_are_not_proved() -> None:
    doc = _pin("star3")
    profile = solve_json(json.loads(doc))
    w = engine_witness(doc, profile)
    for i, label in enumerate(w["guarantee"]["m"]):
        v = next(k for k, x in enumerate(label) if x)
        m = copy.deepcopy(w)
        m["guarantee"]["m"][i][v] += 1
        assert kernel_verdict(doc, profile, m).status == "undecided", (i, v)
    m = copy.deepcopy(w)
    m["guarantee"]["steps"][-1]["sigma"] = list(reversed(m["guarantee"]["steps"][-1]["sigma"]))
    assert kernel_verdict(doc, profile, m).status in ("undecided", "refuted")


def test_a_guarantee_rule_with_a_larger_h_is_not_proved() -> None:
    doc = _pin("star3")
    profile = solve_json(json.loads(doc))
    q = copy.deepcopy(profile)
    q["defender"]["h"] = [str(Fraction(x) + 1) for x in q["defender"]["h"]]
    w = {**engine_witness(doc, profile), "profile_sha256": sha256(as_bytes(q))}
    v = kernel_verdict(doc, q, w)
    assert v.status == "undecided" and "start set" in v.message, v
