#!/usr/bin/env -S uv run --script
# /// script
# dependencies = ["nox>=2025.2.9"]
# ///
"""nox sessions: the same steps as ``python3 dev.py``, each in a fresh virtualenv.

    nox -s tests      # ruff, mypy, import contracts and the tests (as dev.py test)
    nox -s docs       # the documentation site, warnings as errors (as dev.py docs)
    nox -s build      # sdist and wheel, then twine check
    nox -s lint       # pre-commit on every file

``python3 dev.py`` needs nothing but Python and is what CI runs (``.ci/run``); nox is for
those who prefer it (``pip install nox``, or the ``dev`` dependency group).
"""

from __future__ import annotations

import nox

nox.needs_version = ">=2025.2.9"
nox.options.default_venv_backend = "uv|virtualenv"
EXTRAS = ".[test,peers,maps,docs]"


@nox.session
def tests(session: nox.Session) -> None:
    """Lint, type-check, import contracts, then every test not marked slow."""
    session.install("-e", EXTRAS)
    session.run("ruff", "check", "solver", "dppverify", "dppio", "tests", "proofs",
                "benchmarks", "dev.py", "noxfile.py", "docs/conf.py")
    session.run("mypy")
    session.run("lint-imports")
    session.run("pytest", "-n", "auto", "-m", "not slow", *session.posargs)


@nox.session
def docs(session: nox.Session) -> None:
    """The documentation site into docs/_build/html, warnings as errors."""
    session.install("-e", ".[docs]")
    session.run("python", "dev.py", "docs", external=False)


@nox.session(default=False)
def build(session: nox.Session) -> None:
    """Build the sdist and the wheel into dist/ and check their metadata."""
    session.install("build", "twine")
    session.run("python", "-m", "build", "--outdir", "dist")
    session.run("twine", "check", "--strict", *(str(p) for p in sorted(
        __import__("pathlib").Path("dist").glob("dppverify-*"))))


@nox.session(default=False)
def lint(session: nox.Session) -> None:
    """The pre-commit hooks on every file."""
    session.install("pre-commit")
    session.run("pre-commit", "run", "--all-files", "--show-diff-on-failure")


if __name__ == "__main__":
    nox.main()
