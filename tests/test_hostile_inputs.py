"""The hostile-input suite: every command, fed malformed, extreme or contradictory input,
answers with its exit code, exactly one non-empty line on stderr, no traceback, and leaves no
file behind. Table-driven; cases run in-process (click's CliRunner) in a scratch folder whose
listing is compared before and after; a SIGALRM guard (not a timing test) ends a case that
hangs."""

from __future__ import annotations

import json
import os
import shutil
from collections.abc import Iterator
from pathlib import Path

import pytest
from click.testing import CliRunner

from dpp import main as dpp_main
from dppverify.__main__ import main as checker_main
from tests import _guard
from tests.hostile._harness import write_template

ROOT = Path(__file__).resolve().parents[1]
CORPUS = ROOT / "tests" / "data" / "invalid"
MANIFEST = json.loads((CORPUS / "manifest.json").read_text())
GUARD_CPU_SECONDS = 120
"""CPU budget per case (tests/_guard.py: CPU time, and no CPU at all for minutes is a hang):
generous, only there so that a hang fails instead of blocking."""

INSTANCES = sorted(n for n, m in MANIFEST.items() if m["kind"] == "instance")
MAPS = sorted(n for n, m in MANIFEST.items() if m["kind"] == "map")
MAP_CELLS = ["--start", "0,0", "--goals", "0,1", "0,2", "--prior", "0.5,0.5"]


def _paper_map(*, map_file: str = "paper10.map", start: str = "9,0", prior: str = "0.6,0.4"
               ) -> list[str]:
    """``dpp solve --map`` on the paper's map game, with one part changed."""
    return ["solve", "--map", map_file, "--start", start, "--goals", "0,9", "0,0", "--prior",
            prior]

CASES: list[tuple[str, str, list[str], int]] = []
"""(id, program ``dpp`` or ``dppverify``, arguments, expected exit code)."""


def case(program: str, args: list[str], code: int = 2, name: str | None = None) -> None:
    shown = " ".join(a.replace(str(CORPUS) + "/", "invalid/") for a in args)
    CASES.append((name or f"{program} {shown}"[:90], program, args, code))


for doc in INSTANCES:
    bad = str(CORPUS / doc)
    case("dpp", ["solve", bad])
    case("dpp", ["solve", bad, "--json", "-o", "p.json"])
    case("dpp", ["value", bad, "-H", "2"])
    case("dpp", ["certify", bad, "prof.json"])
    case("dpp", ["export-efg", bad, "-H", "1", "-o", "g.efg"])
    case("dpp", ["experiment", "compare", bad, "--output-dir", "cmp"])
    case("dpp", ["plot", "map", bad, "-o", "fig"])
    case("dppverify", ["value", bad, "-H", "2"])
    case("dppverify", ["certify", "tri.json", bad])  # as a profile, too
for m in MAPS:
    bad = str(CORPUS / m)
    case("dpp", ["solve", "--map", bad, *MAP_CELLS])
    case("dpp", ["experiment", "compare", "--map", bad, *MAP_CELLS])
    case("dpp", ["plot", "map", "--map", bad, *MAP_CELLS, "-o", "fig"])
    case("dpp", ["plot", "beliefs", "--map", bad, *MAP_CELLS, "-o", "fig"])

for program in ("dpp", "dppverify"):
    for args in (["--bogus"], ["no-such-command"], ["certify"], ["certify", "tri.json"],
                 ["certify", "tri.json", "prof.json", "--bogus"],
                 ["certify", "tri.json", "prof.json", "-H", "-1"],
                 ["certify", "tri.json", "prof.json", "-H", "1000000000"],
                 ["certify", "tri.json", "prof.json", "--trials", "1000000000"],
                 ["certify", "tri.json", "prof.json", "--seed", "x"],
                 ["certify", "tri.json", "prof.json", "--max-prefixes", "0"],
                 ["certify", "/dev/zero", "prof.json"], ["certify", "tri.json", "/dev/zero"],
                 ["certify", "missing.json", "prof.json"], ["certify", "tri.json", "missing.json"],
                 ["certify", "tri.json", "tri.json"], ["certify", ".", "prof.json"],
                 ["value", "tri.json", "--route", "tree"], ["value", "tri.json", "-H", "abc"],
                 ["value", "tri.json", "-H", "1000000000"], ["value", "tri.json", "-H", "-1"],
                 ["value", "/dev/zero", "-H", "1"], ["value", "missing.json", "-H", "1"],
                 ["value", "tri.json", "-H", "1", "--route", "nope"],
                 ["export-efg", "tri.json", "-H", "1"],
                 ["export-efg", "tri.json", "-H", "1", "-o", ""],
                 ["export-efg", "tri.json", "-H", "1", "-o", "tri.json/g.efg"],
                 ["export-efg", "tri.json", "-H", "1", "-o", "."],
                 ["export-efg", "tri.json", "-H", "1000000000", "-o", "g.efg"],
                 ["export-efg", "tri.json", "-H", "4", "-o", "g.efg", "--max-nodes", "0"],
                 ["audit"], ["audit", "--solver", "nocolon"],
                 ["audit", "--solver", "no_such_module_xyz:f"],
                 ["audit", "--solver", "json:nope"], ["audit", "--solver", "json:__doc__"],
                 ["audit", "--solver-cmd", "no-such-program-xyz {instance} {profile}"],
                 ["audit", "--solver-cmd", "prog {instance}"],
                 ["audit", "--solver-cmd", "prog '{instance} {profile}"],
                 ["audit", "--solver", "json:dumps", "--solver-cmd", "p {instance} {profile}"],
                 ["audit", "--solver", "json:dumps", "--examples", "0"],
                 ["audit", "--solver", "json:dumps", "--examples", "10000000"],
                 ["audit", "--solver", "json:dumps", "--seed", "-1"],
                 ["audit", "--solver", "json:dumps", "--timeout", "0"],
                 ["audit", "--solver", "json:dumps", "--max-nodes", "1"],
                 ["audit", "--solver", "json:dumps", "--shrink-calls", "-1"],
                 ["audit", "--solver", "json:dumps", "--output-dir", ""]):
        case(program, args)

for args in (["solve"], ["solve", "tri.json", "-o", ""], ["solve", "tri.json", "-o", "."],
             ["solve", "tri.json", "-o", "tri.json/p.json"], ["solve", "/dev/zero"],
             ["solve", "missing.json"], ["solve", "."], ["solve", "tri.json", "--start", "0,0"],
             ["solve", "--map", "paper10.map"],
             _paper_map(prior="0.6"), _paper_map(start="x"), _paper_map(prior="0.6,0.6"),
             _paper_map(prior="1e999999999,0"), _paper_map(map_file="/dev/zero"),
             _paper_map(map_file="missing.map"),
             ["experiment", "compare", "--output-dir", ""],
             ["experiment", "compare", "--output-dir", "tri.json"],
             ["experiment", "compare", "missing.json"],
             ["experiment", "density", "--samples", "1000000000000"],
             ["experiment", "density", "--samples", "0"],
             ["experiment", "density", "--samples", "1000", "--densities", "0,10,20,30,40," * 40],
             ["experiment", "density", "--size", "100000"],
             ["experiment", "density", "--size", "1"],
             ["experiment", "density", "--seed", "-1"],
             ["experiment", "density", "--dask", "not an address"],
             ["experiment", "density", "--densities", "x"],
             ["experiment", "density", "--densities", ""],
             ["experiment", "density", "--workers", "0"],
             ["experiment", "density", "--output-dir", ""],
             ["experiment", "nope"],
             ["plot", "map", "-o", ""], ["plot", "map"], ["plot", "map", "--bogus", "-o", "f"],
             ["plot", "map", "-o", "tri.json/fig"], ["plot", "map", "missing.json", "-o", "f"],
             ["plot", "beliefs", "-o", ""], ["plot", "beliefs", "-o", "f", "--defender", "x"],
             ["plot", "voi", "missing.csv", "-o", "f.png"], ["plot", "voi", "-o", "f.png"],
             ["plot", "voi", "/dev/zero", "-o", "f.png"],
             ["plot", "voi", "tri.json", "-o", "f.png"],
             ["plot", "nope"]):
    case("dpp", args)


def _listing(root: Path) -> list[str]:
    return sorted(str(p.relative_to(root)) for p in root.rglob("*"))


@pytest.fixture(scope="module")
def scratch_template(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A folder with a valid instance, its profile and the bundled map."""
    return write_template(tmp_path_factory.mktemp("hostile-template"))


@pytest.fixture
def scratch(scratch_template: Path, tmp_path: Path,
            monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    d = tmp_path / "cwd"
    shutil.copytree(scratch_template, d)
    monkeypatch.chdir(d)
    yield d


def test_at_least_150_cases() -> None:
    assert len(CASES) >= 150
    assert len({c[0] for c in CASES}) == len(CASES)


@pytest.mark.parametrize("name, program, args, code", CASES, ids=[c[0] for c in CASES])
def test_hostile_input(scratch: Path, name: str, program: str, args: list[str],
                       code: int) -> None:
    before = _listing(scratch)
    with _guard.progress_guard(GUARD_CPU_SECONDS):  # CPU seconds: load does not stretch them
        main = dpp_main if program == "dpp" else checker_main
        result = CliRunner().invoke(main, args, prog_name=program,
                                    env={"DPP_DEBUG": None, "COLUMNS": "200"})
    stderr = result.stderr
    assert "Traceback" not in result.output and "Traceback" not in stderr
    assert result.exception is None or isinstance(result.exception, SystemExit), \
        repr(result.exception)
    assert result.exit_code == code, (result.exit_code, stderr, result.stdout[-300:])
    lines = stderr.splitlines()
    assert len(lines) == 1 and lines[0].strip(), stderr
    assert _listing(scratch) == before
    assert os.stat(scratch).st_mode  # the folder itself is still there
