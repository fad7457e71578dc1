"""Hostile probes, third round: numbers in documents, for both readers (the solver's
and the checker's are kept apart on purpose). A numeral with a huge exponent, an integer of
5000 digits, ``Infinity`` where an integer belongs, a CSV field of 300 KB: each is one line and
exit 2 within the CPU limit, never a hang, an ``OverflowError`` or ``int_max_str_digits``.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from tests.hostile._harness import Probe, run_probe

pytestmark = pytest.mark.hostile

Setup = Callable[[Path], None]

HUGE_EXP = "1e999999999"
DIGITS = "1" * 5000


def _json(name: str, edit: Callable[[dict[str, Any]], object], source: str = "tri.json",
          raw: Callable[[str], str] = lambda t: t) -> Setup:
    def setup(d: Path) -> None:
        doc = json.loads((d / source).read_text())
        edit(doc)
        (d / name).write_text(raw(json.dumps(doc)))
    return setup


def _certificate(edit: Callable[[dict[str, Any]], object],
                 raw: Callable[[str], str] = lambda t: t) -> Setup:
    def setup(d: Path) -> None:
        import dppverify

        cert = dppverify.certify(json.loads((d / "tri.json").read_text()),
                                 json.loads((d / "prof.json").read_text())).to_json()
        edit(cert)
        (d / "cert.json").write_text(raw(json.dumps(cert)))
    return setup


def _set(path: tuple[Any, ...], value: object) -> Callable[[dict[str, Any]], None]:
    def edit(doc: dict[str, Any]) -> None:
        node: Any = doc
        for key in path[:-1]:
            node = node[key]
        node[path[-1]] = value
    return edit


def _map_instance(d: Path) -> None:
    import hashlib

    digest = hashlib.sha256((d / "paper10.map").read_bytes()).hexdigest()
    (d / "mi.json").write_text(json.dumps({
        "format": "dpp-map-instance/1", "map": "paper10.map", "map_sha256": digest,
        "start": [9, 0], "goals": [[0, 9], [0, 0]], "prior": [HUGE_EXP, "0.4"],
        "connectivity": 4}))


def _text(name: str, text: str) -> Setup:
    def setup(d: Path) -> None:
        (d / name).write_text(text)
    return setup


NGOAL = {"graph": {"nodes": [{"id": n} for n in "sabc"],
                   "edges": [{"source": "s", "target": t, "weight": 1} for t in "abc"]},
         "start": "s", "goals": ["a", "b", "c"], "prior": ["1/3", "1/3", "1/3"]}
CSV_HEAD = "density,sample,attempts,obstacles,defender,attacker,U1,U2,U,U_bar,VoI,VoI_float\n"
CSV_ROW = "0,0,1,0,sigma*,gamma*,6,0,18/5,24/5,1/4,0.25\n"
VERIFY = ["certify", "--verify-provenance", "cert.json", "tri.json", "prof.json"]

PROBES: list[tuple[str, Probe, Setup | None]] = []


def probe(name: str, args: list[str], setup: Setup | None = None, **kw: object) -> None:
    kw.setdefault("cpu", 30)  # a hang is a CPU-limit kill, never a pass
    PROBES.append((name, Probe(args, **kw), setup))  # type: ignore[arg-type]


# --- priors --------------------------------------------------------------------------------
probe("batch --prior with a huge exponent", ["batch", "s.scen", "-o", "b.csv", "--prior",
                                             f"{HUGE_EXP},0.5"], contains="exponent")
probe("batch --prior of 5000 digits", ["batch", "s.scen", "-o", "b.csv", "--prior",
                                       f"{DIGITS},0.5"], contains="1000")
for cmd in (["solve"], ["value"], ["certify", "x", "prof.json"]):
    args = [c if c != "x" else "p.json" for c in cmd]
    where = args[1:] if len(args) > 1 else []
    probe(f"{cmd[0]} prior string with a huge exponent", [cmd[0], "p.json", *where[1:]],
          _json("p.json", _set(("prior", 0), HUGE_EXP)), contains="exponent")
    probe(f"{cmd[0]} prior number with a huge exponent", [cmd[0], "p.json", *where[1:]],
          _json("p.json", _set(("prior", 0), "HUGE"),
                raw=lambda t: t.replace('"HUGE"', HUGE_EXP)), contains="exponent")
    probe(f"{cmd[0]} weight of 5000 digits", [cmd[0], "p.json", *where[1:]],
          _json("p.json", _set(("graph", "edges", 0, "weight"), "BIG"),
                raw=lambda t: t.replace('"BIG"', DIGITS)), contains="1000")
probe("solve N-goal prior with a huge exponent", ["solve", "n.json"],
      _text("n.json", json.dumps({**NGOAL, "prior": [HUGE_EXP, "1/3", "1/3"]})),
      contains="exponent")
probe("value N-goal prior with a huge exponent", ["value", "n.json"],
      _text("n.json", json.dumps({**NGOAL, "prior": [HUGE_EXP, "1/3", "1/3"]})),
      contains="exponent")
probe("solve compact map instance, prior with a huge exponent", ["solve", "mi.json"],
      _map_instance, contains="exponent")
probe("certify compact map instance, prior with a huge exponent",
      ["certify", "mi.json", "prof.json"], _map_instance, contains="exponent")
probe("certify profile probability with a huge exponent", ["certify", "tri.json", "q.json"],
      _json("q.json", _set(("attacker", "primary", 0, "probability"), "1e-999999999"),
            source="prof.json"), code=1, one_line=False)  # a malformed profile: refuted
probe("certify profile probability of 5000 digits", ["certify", "tri.json", "q.json"],
      _json("q.json", _set(("attacker", "primary", 0, "probability"), "BIG"),
            source="prof.json", raw=lambda t: t.replace('"BIG"', DIGITS)), contains="1000")
# --- certificates ----------------------------------------------------------------------------
probe("verify-provenance: horizon Infinity", VERIFY,
      _certificate(_set(("horizon",), "INF"), raw=lambda t: t.replace('"INF"', "Infinity")),
      contains="horizon")
probe("verify-provenance: horizon 1e300", VERIFY,
      _certificate(_set(("horizon",), 1e300)), contains="horizon")
probe("verify-provenance: a number with a huge exponent", VERIFY,
      _certificate(_set(("checks", 0, "numbers", "defects"), HUGE_EXP)), contains="exponent")
probe("verify-provenance: an integer of 5000 digits", VERIFY,
      _certificate(_set(("seed",), "BIG"), raw=lambda t: t.replace('"BIG"', DIGITS)),
      contains="not JSON")
probe("verify-provenance: tree size Infinity", VERIFY,
      _certificate(_set(("tree", "prefixes"), "INF"),
                   raw=lambda t: t.replace('"INF"', "Infinity")), contains="prefixes")
# --- CSV and text inputs ---------------------------------------------------------------------
probe("plot voi: a field of 300 KB", ["plot", "voi", "d.csv", "-o", "v.png"],
      _text("d.csv", CSV_HEAD + CSV_ROW.replace("sigma*", "s" * 300_000)))
probe("plot voi: a density of 5000 digits", ["plot", "voi", "d.csv", "-o", "v.png"],
      _text("d.csv", CSV_HEAD + DIGITS + CSV_ROW[1:]))
probe("plot voi: VoI_float not a number", ["plot", "voi", "d.csv", "-o", "v.png"],
      _text("d.csv", CSV_HEAD + CSV_ROW.replace("0.25", "abc")))
probe("plot voi: VoI_float with a huge exponent", ["plot", "voi", "d.csv", "-o", "v.png"],
      _text("d.csv", CSV_HEAD + CSV_ROW.replace("0.25", HUGE_EXP)))
probe("map height of 5000 digits", ["solve", "--map", "h.map", "--start", "0,0", "--goals",
                                    "0,1", "0,2", "--prior", "1/2,1/2"],
      _text("h.map", f"type octile\nheight {DIGITS}\nwidth 3\nmap\n...\n"))
probe("map height with a huge exponent (checker)",
      ["value", "--map", "h.map", "--start", "0,0", "--goals", "0,1", "0,2", "--prior",
       "1/2,1/2"], _text("h.map", f"type octile\nheight {HUGE_EXP}\nwidth 3\nmap\n...\n"))
probe("batch: .scen cells of 5000 digits", ["batch", "d.scen", "-o", "b.csv", "--no-progress"],
      _text("d.scen", f"version 1\n0\tpaper10.map\t10\t10\t{DIGITS}\t0\t0\t0\t1\n"),
      code=2, one_line=False, changes=("b.csv",))


@pytest.mark.parametrize("name, probe_, setup", PROBES, ids=[p[0] for p in PROBES])
def test_number_probe(scratch: Path, name: str, probe_: Probe, setup: Setup | None) -> None:
    def with_scen(d: Path) -> None:
        (d / "s.scen").write_text("version 1\n0\tpaper10.map\t10\t10\t0\t9\t9\t0\t18\n")
        if setup is not None:
            setup(d)
    result = run_probe(scratch, name, probe_, with_scen)
    if name == "certify profile probability with a huge exponent":
        assert "exponent" in result.stdout and "profile.wellformed" in result.stdout


def test_enough_number_probes() -> None:
    assert len(PROBES) >= 25
    assert len({p[0] for p in PROBES}) == len(PROBES)
