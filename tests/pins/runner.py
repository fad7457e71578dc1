"""Run one pin case and render its normalized record (used by ``make_pins.py`` and the test).

A case runs in a fresh temporary directory holding copies of ``tests/pins/data/*`` and of
``examples/`` (as ``examples/``), so that every path on a command line is relative and short.
Each step is one command: ``dpp ...`` runs in this process through click's ``CliRunner`` on
``dpp.main`` (the ``dpp`` entry point); ``dpp! ...`` and ``python -m dppverify ...`` run
as subprocesses (their certificates record the real command line). The record holds, per step,
the exit code, stdout and stderr, then every file the case wrote, each normalized
(``normalize.py``).

Only ``dpp.main`` and the documented command line are used: no module whose path may
move is imported.
"""

from __future__ import annotations

import os
import shutil
import sys
import tempfile
import warnings
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from click.testing import CliRunner

from tests import _guard
from tests.pins.cases import Case
from tests.pins.normalize import REPO, normalize

__all__ = ["EXPECTED", "record", "run_case"]

HERE = Path(__file__).resolve().parent
DATA = HERE / "data"
EXPECTED = HERE / "expected"
_DPP_SCRIPT = "import sys; sys.argv[0] = 'dpp'; from dpp import main; main()"


@contextmanager
def _cwd(path: Path) -> Iterator[None]:
    old = Path.cwd()
    os.chdir(path)
    try:
        yield
    finally:
        os.chdir(old)


def _subprocess(argv: list[str], work: Path) -> tuple[int, str, str]:
    env = {k: v for k, v in os.environ.items() if k != "DPP_DEBUG"}
    env["PYTHONPATH"] = os.pathsep.join([str(REPO), *filter(None, [env.get("PYTHONPATH")])])
    done = _guard.run(argv, cwd=work, env=env, capture_output=True, text=True,
                      encoding="utf-8", check=False)
    return done.returncode, done.stdout, done.stderr


def _in_process(args: list[str], work: Path) -> tuple[int, str, str, str]:
    from dpp import main

    with _cwd(work), warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = CliRunner().invoke(main, args, prog_name="dpp")
    extra = ""
    exc = result.exception
    if exc is not None and not isinstance(exc, SystemExit):
        extra += f"--- exception\n{type(exc).__name__}: {exc}\n"
    seen = sorted({f"{w.category.__name__}: {w.message}" for w in caught})
    if seen:
        extra += "--- warnings\n" + "".join(f"{w}\n" for w in seen)
    return result.exit_code, result.stdout, result.stderr, extra


def _section(title: str, text: str) -> str:
    if text and not text.endswith("\n"):
        text += "\n(no newline at end)\n"
    return f"--- {title}\n{text}"


def run_case(case: Case) -> str:
    """Run ``case`` in a fresh temporary directory; return its normalized record.

    Examples
    --------
    >>> from tests.pins.cases import Case
    >>> print(run_case(Case("demo", (("dpp", "value", "triangle.json"),))), end="")
    # case demo
    $ dpp value triangle.json
    --- exit 0
    --- stdout
    V_H (H = inf) = 12/5 (≈ 2.4) exactly; structured route (2 DP steps, fixpoint reached, \
int64, <T> s)
    --- stderr
    """
    with tempfile.TemporaryDirectory(prefix="dpp-pin-") as tmp:
        work = Path(tmp)
        for src in DATA.iterdir():
            shutil.copyfile(src, work / src.name)
        shutil.copytree(REPO / "examples", work / "examples")
        before = {p.relative_to(work) for p in work.rglob("*")}
        out = [f"# case {case.name}\n"]
        for step in case.steps:
            prog, args = step[0], list(step[1:])
            out.append(f"$ {' '.join((prog, *args))}\n")
            extra = ""
            if prog == "dpp":
                code, stdout, stderr, extra = _in_process(args, work)
            elif prog == "dpp!":
                code, stdout, stderr = _subprocess([sys.executable, "-c", _DPP_SCRIPT, *args],
                                                   work)
            elif prog == "python -m dppverify":
                code, stdout, stderr = _subprocess([sys.executable, "-m", "dppverify", *args],
                                                   work)
            else:
                raise ValueError(f"unknown program {prog!r} in case {case.name}")
            here = prog == "dpp"
            out.append(f"--- exit {code}\n")
            out.append(_section("stdout", normalize(stdout, workdir=work, in_process=here)))
            out.append(_section("stderr", normalize(stderr, workdir=work, in_process=here)))
            out.append(normalize(extra, workdir=work, in_process=here))
        in_process = any(step[0] == "dpp" for step in case.steps)  # wrote the files
        made = sorted(p for p in work.rglob("*")
                      if p.relative_to(work) not in before and p.is_file())
        for path in made:
            text = path.read_text(encoding="utf-8", errors="replace")
            out.append(_section(f"file {path.relative_to(work).as_posix()}",
                                normalize(text, workdir=work, in_process=in_process)))
        return "".join(out)


def record(case: Case) -> Path:
    """The expected file of ``case``."""
    return EXPECTED / f"{case.name}.txt"
