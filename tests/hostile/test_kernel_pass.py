"""Hostile probes, fourth round: the commands and formats added with the trusted kernel —
``dpp check`` and its witness files, goal selection, ``dpp import-profile``, ``examples:NAME`` —
and the numbers every reader shares.

Each probe runs the real ``dpp`` in a session of its own under CPU and memory limits
(``_harness.run_probe``): exit code, one stderr line where an error is expected, no traceback,
no file changed but those named. The classes (each reproduced before its fix where one was
needed):

- witness files: truncated, not UTF-8, nested, NaN/Infinity, a float or a boolean label, a
  5,000-digit denominator, an extra key, another profile's witness, a directory, a FIFO without
  a writer (the kernel blocked in ``open`` forever), a shell's ``<(...)`` (the kernel's process
  did not have the descriptor);
- ``dpp check``'s options: ``-o`` naming an input, ``-o`` into a missing folder (created, as
  every command does), ``examples:NAME`` unknown, a map given as INSTANCE, ``--map`` with cells
  of another game;
- common denominators: a few hundred weights with coprime 190-digit denominators (each within
  its own limit) made ``value``, ``solve`` and ``certify`` fail with an internal error after
  seconds to minutes; a profile whose mixture has thousands of such probabilities took the
  kernel and the checker minutes (quadratic sums) and then an internal error; both are now one
  line at the door;
- exact weights past int64: a weight 1/(10**19 + 1) made ``dpp certify`` fail (its kernel
  witness) and ``dpp solve --witness`` (float conversions of the exact numerators);
- a hub of thousands of arcs: the kernel looked each step's arc up by a scan (quadratic);
- numerals: ``'\u0661'`` (an Arabic-Indic one) and ``1_0`` were read as numbers by the checker,
  the solver and the options, and one of them by the kernel (parser disagreement);
- goal selection and ``import-profile``: the option and format edges (already one line: pinned).
"""

from __future__ import annotations

import hashlib
import json
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from tests.hostile._harness import Probe, check, listing, run, run_probe
from tests.hostile.test_probes import _combine

pytestmark = pytest.mark.hostile

Setup = Callable[[Path], None]
TRI = "tri.json"
MAP = ["--map", "paper10.map", "--start", "9,0", "--goals", "0,9", "0,0"]
CHECK = ["check", TRI, "prof.json"]


def _sha(d: Path, name: str) -> str:
    return hashlib.sha256((d / name).read_bytes()).hexdigest()


def _witness_doc(d: Path, profile: str = "prof.json") -> dict[str, Any]:
    """The triangle's witness for the solver's profile (the numbers ``dpp solve --witness``
    writes; the kernel verifies each, so a wrong one would not PASS)."""
    return {"format": "dpp-witness/1", "instance_sha256": _sha(d, TRI),
            "profile_sha256": _sha(d, profile), "denominator": 1,
            "distances": [[3, 0, 2], [2, 2, 0]],
            "types": [{"trie": [3]}, {"trie": [1], "P": [2, 2, 0], "Q": [4, 2, 2]}]}


def _witness(name: str = "w.json", edit: Callable[[str], str | bytes] = lambda t: t) -> Setup:
    def setup(d: Path) -> None:
        text = edit(json.dumps(_witness_doc(d)))
        (d / name).write_bytes(text if isinstance(text, bytes) else text.encode())
    return setup


def _write(name: str, text: str | bytes) -> Setup:
    def setup(d: Path) -> None:
        (d / name).write_bytes(text if isinstance(text, bytes) else text.encode())
    return setup


def _coprime_path(name: str, k: int) -> Setup:
    """A path of ``k + 1`` edges whose weights 1/(10**190 + i) are each within the number
    limit (10**200) but share no small common denominator."""
    def setup(d: Path) -> None:
        nodes = ["s", *(f"v{i}" for i in range(k)), "g1", "g2"]
        edges: list[dict[str, Any]] = [{"source": nodes[i], "target": nodes[i + 1],
                                        "weight": f"1/{10 ** 190 + i}"} for i in range(k + 1)]
        edges.append({"source": nodes[k], "target": "g2", "weight": 1})
        (d / name).write_text(json.dumps({
            "graph": {"nodes": [{"id": x} for x in nodes], "edges": edges}, "start": "s",
            "goals": ["g1", "g2"], "prior": ["1/2", "1/2"]}))
    return setup


def _past_int64(name: str, digits: int) -> Setup:
    """The triangle with one weight 1/(10**digits + 1) and a prior over 10**digits + 3."""
    def setup(d: Path) -> None:
        big = 10 ** digits
        (d / name).write_text(json.dumps({
            "graph": {"nodes": [{"id": x} for x in ("s", "g1", "g2")],
                      "edges": [{"source": "s", "target": "g1", "weight": 3},
                                {"source": "s", "target": "g2", "weight": f"1/{big + 1}"},
                                {"source": "g1", "target": "g2", "weight": 2}]},
            "start": "s", "goals": ["g1", "g2"],
            "prior": [f"1/{big + 3}", f"{big + 2}/{big + 3}"]}))
    return setup


def _fan(k: int, coprime: bool) -> Setup:
    """fan.json: ``s`` with ``k`` two-step walks to g1 (a hub of ``k`` arcs); fanp.json: a
    table profile mixing them (probabilities 1/(10**190 + i) when ``coprime``, else 1/k);
    fanw.json: a witness tied to both (its numbers are wrong: the kernel never reaches them)."""
    def setup(d: Path) -> None:
        nodes = ["s", "g1", "g2", *(f"a{i}" for i in range(k))]
        edges = [{"source": "s", "target": "g2"}]
        for i in range(k):
            edges += [{"source": "s", "target": f"a{i}"}, {"source": f"a{i}", "target": "g1"}]
        inst = {"graph": {"nodes": [{"id": x} for x in nodes], "edges": edges}, "start": "s",
                "goals": ["g1", "g2"], "prior": ["1/2", "1/2"]}
        walks = [{"path": ["s", f"a{i}", "g1"],
                  "probability": f"1/{10 ** 190 + i}" if coprime else f"1/{k}"}
                 for i in range(k)]
        prof = {"format": "dpp-ngoal-profile/1",
                "attacker": [walks, [{"path": ["s", "g2"], "probability": 1}]],
                "defender": {"rule": "table", "default": ["1/2", "1/2"], "entries": []}}
        (d / "fan.json").write_text(json.dumps(inst))
        (d / "fanp.json").write_text(json.dumps(prof))
        n = len(nodes)
        (d / "fanw.json").write_text(json.dumps({
            "format": "dpp-witness/1", "instance_sha256": _sha(d, "fan.json"),
            "profile_sha256": _sha(d, "fanp.json"), "denominator": 1,
            "distances": [[0] * n, [0] * n],
            "types": [{"trie": [0], "exit": [0] * n}, {"trie": [0], "exit": [0] * n}]}))
    return setup


def _fifo(name: str) -> Setup:
    def setup(d: Path) -> None:
        import os

        os.mkfifo(d / name)
    return setup


def _mkdir(name: str) -> Setup:
    return lambda d: (d / name).mkdir()


def _prior(name: str, prior: list[str]) -> Setup:
    def setup(d: Path) -> None:
        doc = json.loads((d / TRI).read_text())
        doc["prior"] = prior
        (d / name).write_text(json.dumps(doc))
    return setup


def _solve(*args: str) -> Setup:
    def setup(d: Path) -> None:
        r = run(["solve", *args], d)
        assert r.code == 0, r.stderr
    return setup


PROBES: list[tuple[str, Probe, Setup | None]] = []


def probe(name: str, args: list[str], setup: Setup | None = None, **kw: Any) -> None:
    PROBES.append((name, Probe(args, **kw), setup))


# --- witness files ----------------------------------------------------------------------------
probe("check: the right witness passes", [*CHECK, "w.json"], _witness(), code=0, one_line=False)
probe("check: a truncated witness", [*CHECK, "w.json"], _witness(edit=lambda t: t[:50]),
      contains="witness: not JSON")
probe("check: a witness that is not UTF-8", [*CHECK, "w.json"], _write("w.json", b"\xff\xfe\0"),
      contains="witness: not JSON")
probe("check: a witness nested 100000 deep", [*CHECK, "w.json"],
      _write("w.json", "[" * 100000 + "]" * 100000), contains="nested too deeply")
probe("check: NaN as the denominator", [*CHECK, "w.json"],
      _witness(edit=lambda t: t.replace('"denominator": 1', '"denominator": NaN')),
      contains="NaN")
probe("check: Infinity as a label", [*CHECK, "w.json"],
      _witness(edit=lambda t: t.replace("[3, 0, 2]", "[Infinity, 0, 2]")), contains="Infinity")
probe("check: a float label", [*CHECK, "w.json"],
      _witness(edit=lambda t: t.replace("[3, 0, 2]", "[3.0, 0, 2]")), contains="integers")
probe("check: a boolean label", [*CHECK, "w.json"],
      _witness(edit=lambda t: t.replace("[3, 0, 2]", "[true, 0, 2]")), contains="integers")
probe("check: a negative label is not proved (exit 3)", [*CHECK, "w.json"],
      _witness(edit=lambda t: t.replace("[3, 0, 2]", "[-3, 0, 2]")), code=3, one_line=False)
probe("check: a 5000-digit denominator", [*CHECK, "w.json"],
      _witness(edit=lambda t: t.replace('"denominator": 1', '"denominator": 1' + "0" * 5000)),
      contains="not JSON")
probe("check: a key not in the format", [*CHECK, "w.json"],
      _witness(edit=lambda t: t[:-1] + ', "zzz": 1}'), contains="zzz")
probe("check: the witness of another profile", ["check", TRI, "p2.json", "w.json"],
      _combine(_witness(), _write("p2.json", '{"format": "dpp-profile/1"}')),
      contains="another profile")
probe("check: a folder as the witness", [*CHECK, "wd"], _mkdir("wd"), contains="directory")
probe("check: a FIFO without a writer reads empty (no hang)", [*CHECK, "ff"], _fifo("ff"),
      contains="witness: not JSON", cpu=20)

# --- dpp check's options -----------------------------------------------------------------------
probe("check -o the witness", [*CHECK, "w.json", "-o", "w.json"], _witness(),
      contains="is an input")
probe("check --json -o the profile", [*CHECK, "w.json", "--json", "-o", "prof.json"],
      _witness(), contains="is an input")
probe("check -o into a missing folder: created", [*CHECK, "w.json", "-o", "new/v.json"],
      _witness(), code=0, changes=("new",), contains="wrote new/v.json")
probe("check examples:NAME unknown", ["check", "examples:nope", "prof.json", "w.json"],
      _witness(), contains="unknown example")
probe("check examples:../../etc/passwd", ["check", "examples:../../etc/passwd", "prof.json",
                                          "w.json"], _witness(), contains="unknown example")
probe("check: a map given as INSTANCE", ["check", "paper10.map", "prof.json", "w.json"],
      _witness(), contains="instance: not JSON")
probe("check --map examples:paper10, another game's cells",
      ["check", "--map", "examples:paper10", "--start", "9,1", "--goals", "0,9", "0,0",
       "--prior", "0.6,0.4", "mp.json", "mw.json"],
      _solve("--map", "examples:paper10", "--start", "9,0", "--goals", "0,9", "0,0", "--prior",
             "0.6,0.4", "-o", "mp.json", "--witness", "mw.json"),
      changes=("mp.json", "mw.json"), contains="another instance")
probe("check --map examples:paper10, a cell outside the map",
      ["check", "--map", "examples:paper10", "--start", "9,0", "--goals", "0,19", "0,0",
       "--prior", "0.6,0.4", "prof.json", "w.json"], _witness(), contains="unknown node")
probe("check --map with - for the witness", ["check", *MAP, "--prior", "0.6,0.4", "prof.json",
                                             "-"], _witness(), contains="are files")

# --- common denominators: one line at the door, for every reader ----------------------------
for cmd in (["value", "cp.json"], ["solve", "cp.json"], ["certify", "cp.json", "prof.json"],
            ["export-efg", "cp.json", "-H", "1", "-o", "g.efg"], ["check", "cp.json",
                                                                   "prof.json", "w.json"]):
    probe(f"300 coprime 190-digit denominators: {cmd[0]}", cmd,
          _combine(_coprime_path("cp.json", 300), _witness()), contains="common denominator",
          cpu=30)
probe("a mixture of 3000 coprime probabilities: check (kernel)",
      ["check", "fan.json", "fanp.json", "fanw.json"], _fan(3000, True),
      contains="common denominator", cpu=30)
probe("a mixture of 3000 coprime probabilities: certify refutes it",
      ["certify", "fan.json", "fanp.json"], _fan(3000, True), code=1, one_line=False, cpu=60)
probe("a hub of 20000 arcs, 20000 walks: the kernel decides in bounded time",
      ["check", "fan.json", "fanp.json", "fanw.json"], _fan(20000, False), code=3,
      one_line=False, cpu=30)
for digits in (19, 49):
    probe(f"a weight 1/(10**{digits} + 1): solve --witness, certify, check agree",
          ["check", "big.json", "bp.json", "bw.json"],
          _combine(_past_int64("big.json", digits),
                   _solve("big.json", "-o", "bp.json", "--witness", "bw.json")),
          code=0, one_line=False, changes=("bp.json", "bw.json"))
    probe(f"a weight 1/(10**{digits} + 1): certify PASS", ["certify", "big.json", "bp.json"],
          _combine(_past_int64("big.json", digits), _solve("big.json", "-o", "bp.json")),
          code=0, one_line=False, changes=("bp.json",))
for cmd in (["solve", "big.json"], ["certify", "big.json", "prof.json"], ["value", "big.json"],
            ["check", "big.json", "prof.json", "w.json"]):
    probe(f"weight and prior over 10**50: {cmd[0]} refuses at the door", cmd,
          _combine(_past_int64("big.json", 50), _witness()), contains="common denominator")

# --- numerals: ASCII digits only, in every reader ---------------------------------------------
for text, label in (("\u0663/5", "an Arabic-Indic three"), ("3_0/50", "an underscore")):
    for cmd in (["value", "ar.json"], ["solve", "ar.json"], ["certify", "ar.json", "prof.json"],
                ["check", "ar.json", "prof.json", "w.json"]):
        probe(f"prior {label}: {cmd[0]}", cmd,
              _combine(_prior("ar.json", [text, "2/5"]), _witness()),
              contains="not a number" if cmd[0] != "check" else "prior")
probe("--prior with an Arabic-Indic zero", ["value", *MAP, "--prior", "\u0660.6,0.4"],
      contains="ASCII")
probe("--start with an Arabic-Indic nine", ["value", "--map", "paper10.map", "--start",
                                            "\u0669,0", "--goals", "0,9", "0,0", "--prior",
                                            "0.6,0.4"], contains="--start")
probe("--goal-values with an Arabic-Indic one", ["value", *MAP, "--goal-selection",
                                                 "--goal-values", "\u0661,0"], contains="ASCII")
probe("--goal-values 1_0,0", ["value", *MAP, "--goal-selection", "--goal-values", "1_0,0"],
      contains="ASCII")

# --- goal selection ---------------------------------------------------------------------------
probe("solve --goal-selection --prior", ["solve", *MAP, "--goal-selection", "--prior", "0.6,0.4"],
      contains="no --prior")
for values in ("1,2,3", "1", "", "1,x", "nan,0", "1e999999,0", "1" * 5000 + ",0"):
    probe(f"--goal-values {values[:12]!r}", ["solve", *MAP, "--goal-selection", "--goal-values",
                                              values], contains="--goal-values")
probe("--goal-values without --goal-selection", ["solve", *MAP, "--prior", "0.6,0.4",
                                                 "--goal-values", "1,2"],
      contains="--goal-selection")
probe("a selection profile on a prior instance", ["certify", *MAP, "--prior", "0.6,0.4",
                                                  "sp.json"],
      _solve(*MAP, "--goal-selection", "-o", "sp.json"), changes=("sp.json",),
      contains="dpp-selection-profile/1")
probe("a prior profile on examples:paper10-selection: refuted",
      ["certify", "examples:paper10-selection", "pr.json"],
      _solve(*MAP, "--prior", "0.6,0.4", "-o", "pr.json"), code=1, changes=("pr.json",),
      contains="another instance")
probe("solve --goal-selection --witness", ["solve", *MAP, "--goal-selection", "-o", "s.json",
                                           "--witness", "w.json"], contains="--witness")
probe("export-efg examples:paper10-selection -H 2 (no goal within reach)",
      ["export-efg", "examples:paper10-selection", "-H", "2", "-o", "g.efg"],
      contains="nearest goal")

# --- import-profile -----------------------------------------------------------------------------
IMPORT = ["import-profile", TRI, "ne.csv", "-H", "2", "-o", "ip.json"]
probe("import-profile: the right line", IMPORT, _write("ne.csv", "NE,1,0,0,1,1,0,0,1\n"), code=0,
      changes=("ip.json",))
PEER_LINES: tuple[tuple[str | bytes, str], ...] = (
                    ("NE,1,0\n", "2 probabilities"), ("NE,nan,0,0,1,1,0,0,1\n", "nan"),
                    ("NE,-1,2,0,1,1,0,0,1\n", "negative"), (b"\xff\xfe\0", "UTF-8"),
                    ("NE," + ",".join(["1/" + "3" * 900] * 8) + "\n", "not 1"),
                    ('{"T1 p0 h-": {"go g1": 1, "go g2": 0}}', "missing"),
                    ('{"0-0-x": [[0, 1.0]]}', "OpenSpiel"))
for peer, words in PEER_LINES:
    probe(f"import-profile: {words}", IMPORT, _write("ne.csv", peer), contains=words)
probe("import-profile: the .efg itself", ["import-profile", TRI, "g.efg", "-H", "2", "-o",
                                          "ip.json"],
      lambda d: None if run(["export-efg", TRI, "-H", "2", "-o", "g.efg"], d).code == 0
      else pytest.fail("export-efg failed"),
      changes=("g.efg",), contains="not a behaviour profile")
probe("import-profile -o the peer profile", [*IMPORT[:-1], "ne.csv"],
      _write("ne.csv", "NE,1,0,0,1,1,0,0,1\n"), contains="is an input")
probe("import-profile examples:nope", ["import-profile", "examples:nope", "ne.csv", "-H", "2",
                                       "-o", "ip.json"],
      _write("ne.csv", "NE,1,0,0,1,1,0,0,1\n"), contains="unknown example")
probe("import-profile --map examples:paper10 with a cell off the map",
      ["import-profile", "--map", "examples:paper10", "--start", "0,0", "--goals", "99,99",
       "0,9", "--prior", "0.5,0.5", "ne.csv", "-H", "2", "-o", "ip.json"],
      _write("ne.csv", "NE,1\n"), contains="outside")

# --- examples:NAME in every command that takes an instance --------------------------------------
EX = "examples:paper10"
for args in (["solve", EX], ["value", EX], ["certify", EX, "prof.json"],
             ["export-efg", EX, "-H", "1", "-o", "g.efg"], ["plot", "map", EX, "-o", "m.png"],
             ["experiment", "compare", EX, "--output-dir", "cmp"]):
    probe(f"{args[0]} examples:paper10 (a map, not an instance)", args, contains="--map")
probe("value --map examples:nope", ["value", "--map", "examples:nope", *MAP[2:], "--prior",
                                    "0.6,0.4"], contains="unknown example")
probe("value --map examples:triangle (an instance, not a map)",
      ["value", "--map", "examples:triangle", *MAP[2:], "--prior", "0.6,0.4"],
      contains="line 1")


@pytest.mark.parametrize("name, probe_, setup", PROBES, ids=[p[0] for p in PROBES])
def test_kernel_pass_probe(scratch: Path, name: str, probe_: Probe, setup: Setup | None) -> None:
    run_probe(scratch, name, probe_, setup)


def test_names_are_unique() -> None:
    assert len({p[0] for p in PROBES}) == len(PROBES)


def test_check_reads_a_shell_s_process_substitution(scratch: Path) -> None:
    """``dpp check I P <(cat W)``: the shell's ``/dev/fd/N`` is read by the kernel's own
    process (it was "No such file or directory": the descriptor was not passed); a descriptor
    that is not open is one line."""
    _witness()(scratch)
    before = listing(scratch)
    python = f"{sys.executable} -m dpp"
    for script, code in ((f"exec {python} check tri.json prof.json <(cat w.json)", 0),
                         (f"exec {python} check tri.json prof.json /dev/fd/77", 2)):
        result = run([], scratch, program=["bash", "-c", script])
        check(result, Probe([], code=code, one_line=code == 2), before, listing(scratch))
        if code == 0:
            assert result.stdout.startswith("PASS"), result.stdout
        else:
            assert "/dev/fd/77: cannot read" in result.stderr, result.stderr
