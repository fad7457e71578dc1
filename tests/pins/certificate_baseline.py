"""Record every certificate the checker writes on the pinned inputs, and compare two records.

Usage (from the repository root)::

    PYTHONPATH=. python tests/pins/certificate_baseline.py write DIR     # record into DIR
    PYTHONPATH=. python tests/pins/certificate_baseline.py compare DIR   # this tree vs DIR

A refactor of the checker must leave every certificate as it was, byte for byte. This script
records, one file per run (``DIR/<name>.txt``: the exit code, then stdout, then stderr, or the
exception raised), the ``dpp certify --json`` output of

- every ``dpp certify`` step of the CLI pins (``cases.py``; ``--json`` added, ``-o`` dropped,
  the steps before it replayed so that solved profiles exist), in-process;
- every conformance case (``tests/data/conformance_cases.json``) and every N-goal case
  (``tests/data/ngoal_cases.json``): the solver's profile, certified on the untruncated game
  and at the case's horizon (``dppverify.certify`` from Python);
- the documented examples (the bundled games' profiles, as in the docstrings and
  ``docs/checker.md``).

Nothing is normalized but the ``dppverify`` version of the provenance record (when the
package version changes): the comparison is byte for byte. ``compare`` prints every name that
differs (with a unified diff of the first lines) and exits 1 if any does.
"""

from __future__ import annotations

import difflib
import json
import re
import shutil
import sys
import tempfile
import warnings
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

if __package__ in (None, ""):  # run as a script: make ``tests.pins`` importable
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent.parent))

from click.testing import CliRunner

from tests.pins.cases import CASES
from tests.pins.runner import _cwd

REPO = Path(__file__).resolve().parent.parent.parent
DATA = REPO / "tests" / "pins" / "data"
_VERSION = re.compile(r'"dppverify": "[^"]*"')


def _dpp(args: list[str], work: Path) -> str:
    from dpp import main

    with _cwd(work), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = CliRunner().invoke(main, args, prog_name="dpp")
    return f"exit {result.exit_code}\n--- stdout\n{result.stdout}--- stderr\n{result.stderr}"


def _json_args(args: list[str]) -> list[str]:
    """A certify step's arguments with ``--json`` and without ``-o FILE``."""
    out: list[str] = []
    skip = False
    for a in args:
        if skip:
            skip = False
            continue
        if a in ("-o", "--output"):
            skip = True
            continue
        out.append(a)
    return out if "--json" in out else [*out, "--json"]


def _pin_runs() -> Iterator[tuple[str, Callable[[], str]]]:
    """One run per ``dpp certify`` step of every pin case (the case replayed each time)."""
    for case in CASES:
        for k, step in enumerate(case.steps):
            args = list(step[1:])
            if args[:1] != ["certify"] or "--verify-provenance" in args:
                continue
            yield f"pin-{case.name}-{k}", (lambda c=case, k=k: _replay(c.steps, k))


def _replay(steps: tuple[tuple[str, ...], ...], last: int) -> str:
    with tempfile.TemporaryDirectory(prefix="dpp-baseline-") as tmp:
        work = Path(tmp)
        for src in DATA.iterdir():
            shutil.copyfile(src, work / src.name)
        shutil.copytree(REPO / "examples", work / "examples")
        for step in steps[:last]:
            _dpp(list(step[1:]), work)
        return _dpp(_json_args(list(steps[last][1:])), work)


def _api(instance: Any, profile: Any, **options: Any) -> str:
    import dppverify

    try:
        cert = dppverify.certify(instance, profile, **options)
    except Exception as exc:  # the record is what happened
        return f"raised {type(exc).__name__}: {exc}\n"
    return json.dumps(cert.to_json(), indent=2, ensure_ascii=False) + "\n"


def _solved(doc: dict[str, Any]) -> Any:
    import solver

    try:
        return solver.solve(doc).to_json()
    except Exception as exc:  # the record says so
        return f"the solver raised {type(exc).__name__}: {exc}"


def _case_runs(path: Path, prefix: str, horizon_of: Callable[[dict[str, Any]], Any]
               ) -> Iterator[tuple[str, Callable[[], str]]]:
    cases = json.loads(path.read_text(encoding="utf-8"))
    for i, case in enumerate(cases):
        def run(case: dict[str, Any] = case) -> str:
            profile = _solved(case["instance"])
            if isinstance(profile, str):
                return profile + "\n"
            out = ["--- H = inf\n", _api(case["instance"], profile)]
            h = horizon_of(case)
            if h is not None:
                out += [f"--- H = {h}\n", _api(case["instance"], profile, horizon=h,
                                               max_prefixes=20_000)]
            return "".join(out)
        yield f"{prefix}-{i:03d}", run


def _conformance_horizon(case: dict[str, Any]) -> Any:
    return case.get("expected", {}).get("H")


def _example_runs() -> Iterator[tuple[str, Callable[[], str]]]:
    from dppverify.game import examples as ex

    star_bad = ex.star3_profile()
    star_bad["defender"]["default"] = [0, 1, 0]
    runs: list[tuple[str, Callable[[], str]]] = [
        ("triangle", lambda: _api(ex.triangle_document(), ex.triangle_profile())),
        ("triangle-object", lambda: _api(ex.triangle(), ex.triangle_profile())),
        ("triangle-wrong", lambda: _api(ex.triangle_document(),
                                        ex.triangle_profile(ex.triangle_attacker("3/7", "4/7")))),
        ("triangle-h1", lambda: _api(ex.triangle_document(), ex.triangle_profile(), horizon=1)),
        ("triangle-h4", lambda: _api(str(REPO / "examples" / "triangle.json"),
                                     ex.triangle_profile(), horizon=4)),
        ("triangle-h3-both", lambda: _api(ex.triangle_document(), ex.triangle_profile(),
                                          horizon=3, route="both")),
        ("triangle-bytes", lambda: _api(json.dumps(ex.triangle_document()).encode(),
                                        json.dumps(ex.triangle_profile()).encode())),
        ("kite-naive", lambda: _api(ex.kite_document(), ex.kite_naive_profile())),
        ("kite-naive-h1", lambda: _api(ex.kite_document(), ex.kite_naive_profile(), horizon=1)),
        ("star3-h2", lambda: _api(ex.star3_document(), ex.star3_profile(), horizon=2)),
        ("star3-h2-object", lambda: _api(ex.star3(), ex.star3_profile(), horizon=2)),
        ("star3-bad-h2", lambda: _api(ex.star3_document(), star_bad, horizon=2)),
        ("star3-inf", lambda: _api(ex.star3_document(), ex.star3_profile())),
        ("star3-h2-both", lambda: _api(ex.star3_document(), ex.star3_profile(), horizon=2,
                                       route="both")),
        ("hub4-solved", lambda: _api(ex.hub4_document(), _solved(ex.hub4_document()))),
        ("hub4-solved-h4", lambda: _api(ex.hub4_document(), _solved(ex.hub4_document()),
                                        horizon=4)),
    ]
    yield from runs


def runs() -> Iterator[tuple[str, Callable[[], str]]]:
    """Every recorded run: ``(name, run)``."""
    yield from _pin_runs()
    yield from _case_runs(REPO / "tests" / "data" / "conformance_cases.json", "conformance",
                          _conformance_horizon)
    yield from _case_runs(REPO / "tests" / "data" / "ngoal_cases.json", "ngoal",
                          lambda case: case.get("horizon"))
    yield from _example_runs()


def _normalized(text: str) -> str:
    return _VERSION.sub('"dppverify": "<VERSION>"', text)


def main(argv: list[str]) -> int:
    """``write DIR`` or ``compare DIR`` (see the module docstring); the exit status."""
    if len(argv) != 2 or argv[0] not in ("write", "compare"):
        print(__doc__)
        return 2
    mode, where = argv[0], Path(argv[1])
    if mode == "write":
        where.mkdir(parents=True, exist_ok=True)
    differ = 0
    names = []
    for name, run in runs():
        names.append(name)
        got = _normalized(run())
        path = where / f"{name}.txt"
        if mode == "write":
            path.write_text(got, encoding="utf-8")
            continue
        want = path.read_text(encoding="utf-8") if path.exists() else "(no record)\n"
        if got != want:
            differ += 1
            diff = list(difflib.unified_diff(want.splitlines(True), got.splitlines(True),
                                             fromfile=f"baseline/{name}", tofile="this tree"))
            print("".join(diff[:40]), end="")
    if mode == "compare":
        extra = sorted({p.stem for p in where.glob("*.txt")} - set(names))
        for name in extra:
            print(f"recorded but not run: {name}")
        print(f"{len(names)} runs, {differ} differ, {len(extra)} missing")
        return 1 if differ or extra else 0
    print(f"{len(names)} runs written to {where}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
