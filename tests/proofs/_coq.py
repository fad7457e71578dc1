"""The differential harness of proofs/coq: corpora of (instance, profile, witness) documents,
their mutants, and the verdicts of the extracted Coq checker and of ``dppverify.kernel``.

The extracted checker is ``proofs/coq/extracted/kcheck`` (``python3 dev.py coq`` builds it);
``proofs/coq/translate.py`` turns the three documents into its token stream. Run as a script
(``python tests/proofs/_coq.py [--cases N]``) it prints the agreement table of the full
differential run.
"""

from __future__ import annotations

import copy
import json
import random
import subprocess
import sys
from collections import Counter
from collections.abc import Iterable, Iterator
from fractions import Fraction
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
if str(ROOT) not in sys.path:  # run as a script
    sys.path.insert(0, str(ROOT))

from dppverify.kernel import check  # noqa: E402
from dppverify.kernel.reading import sha256  # noqa: E402

KCHECK = ROOT / "proofs" / "coq" / "extracted" / "kcheck"
PINS = ROOT / "tests" / "pins" / "data"
CASES = ROOT / "tests" / "data" / "conformance_cases.json"

Docs = tuple[bytes, bytes, bytes]


def translator() -> Any:
    """``proofs/coq/translate.py``'s :func:`tokens` (a standalone script, loaded by path)."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("coq_translate",
                                                  ROOT / "proofs" / "coq" / "translate.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.tokens


def coq_verdicts(docs: Iterable[Docs]) -> list[str]:
    """The extracted checker's verdict on each triple (one process for all of them)."""
    tokens = translator()
    lines = [tokens(*d) for d in docs]
    out = subprocess.run([str(KCHECK)], input="\n".join(lines) + "\n", capture_output=True,
                         text=True, check=True, timeout=600)
    verdicts = out.stdout.split("\n")[:-1]
    assert len(verdicts) == len(lines), out.stderr
    return verdicts


def python_verdict(docs: Docs) -> str:
    """The Python kernel's status on the triple."""
    return check(*docs).status


def as_bytes(doc: Any) -> bytes:
    return doc if isinstance(doc, bytes) else json.dumps(doc).encode()


def engine_triple(instance: Any, profile: Any) -> Docs | None:
    """The two documents with the engine's witness (None where the engine writes none)."""
    from dppverify.game.instance import instance_from_json
    from dppverify.game.profile import profile_from_json
    from dppverify.structured.witness import witness_document

    ib, pb = as_bytes(instance), as_bytes(profile)
    inst = instance_from_json(json.loads(ib))
    prof = profile_from_json(json.loads(pb), inst)
    if not prof.wellformed:
        return None
    try:
        w = witness_document(inst, prof, instance_sha256=sha256(ib), profile_sha256=sha256(pb))
    except ValueError:  # a Defender without a table witness (the guarantee rule)
        return None
    return ib, pb, as_bytes(w)


def _rehash(w: dict[str, Any], ib: bytes, pb: bytes) -> bytes:
    return as_bytes({**w, "instance_sha256": sha256(ib), "profile_sha256": sha256(pb)})


def _scaled(w: dict[str, Any], k: int) -> dict[str, Any]:
    """The same witness over the denominator ``k·S``."""
    out = copy.deepcopy(w)
    out["denominator"] = w["denominator"] * k

    def times(xs: list[Any]) -> list[Any]:
        return [None if x is None else k * x for x in xs]
    out["distances"] = [times(d) for d in w["distances"]]
    out["types"] = [{key: times(xs) for key, xs in rec.items()} for rec in w["types"]]
    return out


def mutants(triple: Docs, rng: random.Random, count: int) -> Iterator[tuple[str, Docs]]:
    """``count`` mutants of a triple: a potential or distance label moved up or down by
    ``1/(k·S)`` or set to null, a mixture's probability moved between two of its walks (so
    ``U`` and the masses change), the prior moved (the masses), a table entry changed, the
    witness's shape broken (denominator, a list's length, a record's keys)."""
    ib, pb, wb = triple
    w, prof, inst = json.loads(wb), json.loads(pb), json.loads(ib)
    if "guarantee" in w:
        yield from _guarantee_mutants(triple, rng, count)
        return
    if "types" not in w:
        return
    made = 0
    for _ in range(8 * count):
        if made >= count:
            return
        kind = rng.choice(["potential", "potential", "potential", "distance", "mixture",
                           "prior", "entry", "shape"])
        if kind in ("potential", "distance"):
            k = rng.choice([2, 3, 7])
            m = _scaled(w, k)
            lists = (m["distances"] if kind == "distance" else
                     [xs for rec in m["types"] for xs in rec.values()])
            lists = [xs for xs in lists if xs]
            if not lists:
                continue
            xs = rng.choice(lists)
            i = rng.randrange(len(xs))
            xs[i] = rng.choice([1, -1, None]) if xs[i] is None else rng.choice(
                [xs[i] + 1, xs[i] - 1, xs[i] + 1, None])
            yield f"{kind} label", (ib, pb, as_bytes(m))
        elif kind == "mixture":
            p = copy.deepcopy(prof)
            mixes = (p["attacker"] if isinstance(p["attacker"], list) else
                     list(p["attacker"].values()))
            mixes = [m for m in mixes if len(m) >= 2]
            if not mixes:
                continue
            mix = rng.choice(mixes)
            a, b = rng.sample(range(len(mix)), 2)
            pa = Fraction(str(mix[a]["probability"]))
            d = rng.choice([Fraction(1, 7), Fraction(1, 3), pa])
            d = min(d, pa)
            mix[a]["probability"] = str(pa - d)
            mix[b]["probability"] = str(Fraction(str(mix[b]["probability"])) + d)
            pb2 = as_bytes(p)
            yield "mixture probability", (ib, pb2, _rehash(w, ib, pb2))
        elif kind == "prior":
            ib2 = _prior_moved(inst, rng)
            yield "prior", (ib2, pb, _rehash(w, ib2, pb))
        elif kind == "shape":
            m = copy.deepcopy(w)
            how = rng.choice(["denominator", "list", "key"])
            if how == "denominator":
                m["denominator"] = rng.choice([0, -1])
            elif how == "list":
                rec = rng.choice(m["types"])
                key = rng.choice(sorted(rec))
                rec[key] = rec[key][:-1]
            else:
                rec = rng.choice(m["types"])
                rec.pop(rng.choice(sorted(rec)))
            yield f"witness shape ({how})", (ib, pb, as_bytes(m))
        else:
            p = copy.deepcopy(prof)
            entries = p.get("defender", {}).get("entries")
            if not entries:
                continue
            e = rng.choice(entries)
            if "probability" in e:
                e["probability"] = str(rng.choice([Fraction(0), Fraction(1), Fraction(1, 2)]))
            else:
                n = len(e["probabilities"])
                j = rng.randrange(n)
                e["probabilities"] = [int(i == j) for i in range(n)]
            pb2 = as_bytes(p)
            yield "table entry", (ib, pb2, _rehash(w, ib, pb2))
        made += 1


def _prior_moved(inst: dict[str, Any], rng: random.Random) -> bytes:
    """The instance with some prior mass (at most 1/10) moved from one type to another."""
    i2 = copy.deepcopy(inst)
    pr = [Fraction(str(x)) for x in i2["prior"]]
    a, b = rng.sample(range(len(pr)), 2)
    d = min(pr[a] / 2, Fraction(1, 10))
    pr[a], pr[b] = pr[a] - d, pr[b] + d
    i2["prior"] = [str(x) for x in pr]
    return as_bytes(i2)


def _moved(x: Any, rng: random.Random) -> str:
    return str(Fraction(str(x)) + rng.choice([Fraction(1, 7), Fraction(-1, 7), Fraction(1, 2)]))


def _guarantee_mutants(triple: Docs, rng: random.Random, count: int
                       ) -> Iterator[tuple[str, Docs]]:
    """Mutants of a guarantee-rule witness: a label m_a(v) moved by ``1/(k·S)`` or nulled, a
    σ entry moved (with or without the sum kept at 1), a dual's or a cover's entry moved, the
    rule's ``h`` or the prior moved, the record's shape broken."""
    ib, pb, wb = triple
    w, prof, inst = json.loads(wb), json.loads(pb), json.loads(ib)
    made = 0
    for _ in range(8 * count):
        if made >= count:
            return
        m = copy.deepcopy(w)
        g = m["guarantee"]
        kind = rng.choice(["m label", "m label", "sigma", "sigma", "dual", "cover", "h",
                           "prior", "shape"])
        if kind == "m label":
            k = rng.choice([2, 3, 7])
            m["denominator"] *= k
            m["distances"] = [[None if x is None else k * x for x in d] for d in m["distances"]]
            g["m"] = [[None if x is None else k * x for x in row] for row in g["m"]]
            row = rng.choice(g["m"])
            i = rng.randrange(len(row))
            row[i] = rng.choice([1, 0]) if row[i] is None else rng.choice(
                [row[i] + 1, row[i] - 1, None])
        elif kind in ("sigma", "dual"):
            if not g["steps"]:
                continue
            st = rng.choice(g["steps"])
            if kind == "sigma":
                i, j = rng.sample(range(len(st["sigma"])), 2)
                d = Fraction(rng.choice([1, 2]), 7)
                st["sigma"][i] = str(Fraction(str(st["sigma"][i])) + d)
                if rng.random() < 0.7:
                    st["sigma"][j] = str(Fraction(str(st["sigma"][j])) - d)
            else:
                if not st["duals"]:
                    continue
                du = rng.choice(st["duals"])
                key = rng.choice(["y", "z", "fix"] if du["fix"] else ["y", "z"])
                if key == "z":
                    du["z"] = _moved(du["z"], rng)
                else:
                    i = rng.randrange(len(du[key]))
                    du[key][i] = _moved(du[key][i], rng)
        elif kind == "cover":
            if not g.get("covers"):
                continue
            c = rng.choice(g["covers"])
            i = rng.randrange(len(c))
            c[i] = _moved(c[i], rng)
        elif kind == "shape":
            how = rng.choice(["steps", "sigma", "duals", "key"])
            if how == "steps" and g["steps"]:
                g["steps"] = g["steps"][:-1]
            elif how == "sigma" and g["steps"]:
                g["steps"][0]["sigma"] = g["steps"][0]["sigma"][:-1]
            elif how == "duals" and g["steps"]:
                g["steps"][0]["duals"] = g["steps"][0]["duals"][1:]
            else:
                g.pop(rng.choice(["m", "steps"]))
            kind = f"shape ({how})"
        else:
            if kind == "h":
                p2 = copy.deepcopy(prof)
                i = rng.randrange(len(p2["defender"]["h"]))
                p2["defender"]["h"][i] = _moved(p2["defender"]["h"][i], rng)
                ib2, pb2 = ib, as_bytes(p2)
            else:
                ib2, pb2 = _prior_moved(inst, rng), pb
            yield f"guarantee {kind}", (ib2, pb2, _rehash(m, ib2, pb2))
            made += 1
            continue
        yield f"guarantee {kind}", (ib, pb, as_bytes(m))
        made += 1


def conformance_triples(limit: int | None = None) -> Iterator[tuple[str, Docs]]:
    """Each conformance case with the solver's profile and the engine's witness."""
    from solver.adapter import solve_json

    for case in json.loads(CASES.read_text())[:limit]:
        t = engine_triple(case["instance"], solve_json(case["instance"]))
        if t is not None:
            yield f"conformance {case['name']}", t


def pinned_triples(quick: bool = False) -> Iterator[tuple[str, Docs]]:
    """Every pinned instance with the solver's profile, and every pinned profile (``quick``:
    fewer than four goals)."""
    from solver.adapter import solve_json

    names = sorted(p.stem for p in PINS.glob("*.json"))
    for name in names:
        try:
            doc = json.loads((PINS / f"{name}.json").read_bytes())
        except ValueError:  # the pinned malformed documents
            continue
        if not (isinstance(doc, dict) and "graph" in doc and "goals" in doc) or (
                quick and len(doc["goals"]) >= 4):
            continue
        t = engine_triple(doc, solve_json(doc))
        if t is not None:
            yield f"pinned {name}", t
        for prof in names:
            if prof.startswith(name + "_") and prof.endswith("profile"):
                t = engine_triple(doc, json.loads((PINS / f"{prof}.json").read_bytes()))
                if t is not None:
                    yield f"pinned {prof}", t


def grid_triples(rng: random.Random, count: int) -> Iterator[tuple[str, Docs]]:
    """Random 4-connected grids (6×6 to 20×20, a sixth of the cells off the first row and
    column blocked) with the solver's profile and the engine's witness: larger product graphs
    than the conformance cases."""
    from solver.adapter import solve_json

    for _ in range(count):
        R = rng.randint(6, 20)
        free = {(r, c) for r in range(R) for c in range(R)  # row 0 and column 0 stay free
                if r == 0 or c == 0 or rng.random() > 1 / 6}
        nodes = sorted(free)
        edges = [{"source": list(a), "target": list(b)} for a in nodes
                 for b in ((a[0] + 1, a[1]), (a[0], a[1] + 1)) if b in free]
        b1 = rng.choice(["1/2", "3/5", "4/5"])
        doc = {"graph": {"nodes": [{"id": list(x)} for x in nodes], "edges": edges},
               "start": [R - 1, 0], "goals": [[0, R - 1], [0, 0]],
               "prior": [b1, str(1 - Fraction(b1))]}
        t = engine_triple(doc, solve_json(doc))
        if t is not None:
            yield f"grid {R}x{R}", t


NGOAL = ROOT / "tests" / "data" / "ngoal_cases.json"


def guarantee_triples(rng: random.Random, count: int, quick: bool = False
                      ) -> Iterator[tuple[str, Docs]]:
    """The N-goal conformance cases and ``count`` random N-goal instances (3 or 4 goals on
    small random graphs), each with the solver's guarantee-rule profile and the engine's
    witness (where the solver certifies one); ``quick``: three goals only (a four-goal
    vertex table takes seconds per witness, in either kernel)."""
    from solver.adapter import solve_json
    from solver.errors import DPPError

    docs = [(f"ngoal {c['name'].split(',')[0]}", c["instance"])
            for c in json.loads(NGOAL.read_text()) if not quick or len(c["instance"]["goals"]) < 4]
    for k in range(count):
        n, N = rng.randint(5, 7), 3 if quick else rng.choice([3, 3, 4])
        nodes = [f"v{i}" for i in range(n)]
        edges = {(i, i + 1) for i in range(n - 1)} | {
            tuple(sorted(rng.sample(range(n), 2))) for _ in range(n)}
        goals = rng.sample(nodes[1:], N)
        prior = [Fraction(rng.randint(1, 4)) for _ in range(N)]
        prior = [x / sum(prior) for x in prior]
        docs.append((f"random {k}", {
            "graph": {"nodes": [{"id": x} for x in nodes],
                      "edges": [{"source": nodes[a], "target": nodes[b],
                                 "weight": rng.choice([1, 1, 2, "3/2"])}
                                for a, b in sorted(edges)]},
            "start": nodes[0], "goals": goals, "prior": [str(x) for x in prior]}))
    for name, doc in docs:
        try:
            prof = solve_json(doc)
        except DPPError:  # the solver's budget: no certified profile to check
            continue
        t = engine_triple(doc, prof)
        if t is not None:
            yield f"guarantee {name}", t


def compare(named: Iterable[tuple[str, Docs]]) -> tuple[Counter[tuple[str, str, str]],
                                                         list[tuple[str, str, str]]]:
    """Run both kernels on every triple: the table (kind, Python, Coq) -> count and the
    disagreements (kind, Python, Coq)."""
    named = list(named)
    coq = coq_verdicts(d for _, d in named)
    table: Counter[tuple[str, str, str]] = Counter()
    bad = []
    for (kind, docs), c in zip(named, coq, strict=True):
        p = python_verdict(docs)
        base = kind.startswith(("conformance", "pinned", "grid")) or (
            kind.startswith("guarantee") and kind.split(" ")[1] in ("ngoal", "random"))
        table[(kind.split(" ")[0] if base else kind, p, c)] += 1
        if p != c:
            bad.append((kind, p, c))
    return table, bad


def corpus(rng: random.Random, cases: int | None, per: int, grids: int = 0, ngoal: int = 0,
           quick: bool = False) -> Iterator[tuple[str, Docs]]:
    """Conformance, pinned, ``grids`` random grid and ``ngoal`` random guarantee-rule
    triples, each followed by ``per`` mutants (``quick``: no four-goal instances)."""
    for name, t in [*conformance_triples(cases), *pinned_triples(quick), *grid_triples(rng, grids),
                    *guarantee_triples(rng, ngoal, quick)]:
        yield name, t
        yield from mutants(t, rng, per)


if __name__ == "__main__":
    import argparse

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cases", type=int, default=None, help="conformance cases (default all)")
    ap.add_argument("--per", type=int, default=6, help="mutants per triple")
    ap.add_argument("--grids", type=int, default=12, help="random grid instances")
    ap.add_argument("--ngoal", type=int, default=30, help="random guarantee-rule instances")
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args()
    table, bad = compare(corpus(random.Random(args.seed), args.cases, args.per, args.grids,
                                args.ngoal))
    print("| corpus | Python kernel | extracted Coq checker | count |")
    print("|---|---|---|---|")
    for (k, p, c), n in sorted(table.items()):
        print(f"| {k} | {p} | {c} | {n} |")
    print(f"witnesses: {sum(table.values())}; disagreements: {len(bad)}")
    for b in bad[:20]:
        print("DISAGREE", *b)
    sys.exit(1 if bad else 0)
