"""Every third-party package the code imports is declared in pyproject.toml.

The import statements of ``solver/`` and ``dppverify/`` (and ``pytest.importorskip`` calls)
are read with :mod:`ast`; each top-level module that is not the standard library or the
project itself is mapped to the distribution that provides it and must be declared:

- a module imported at the top of a runtime module: in ``[project] dependencies``;
- a runtime import inside a function (an optional feature, e.g. ``distributed``): in the
  dependencies or any extra;
- tests/, proofs/, benchmarks/: in the dependencies or the ``test``, ``peers``, ``maps`` or
  ``bench`` extras (what ``python3 dev.py test`` / ``bench`` install).
"""

from __future__ import annotations

import ast
import re
import sys
import tomllib
from collections.abc import Iterator
from functools import cache
from importlib.metadata import packages_distributions
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
FIRST_PARTY = {"solver", "dppverify", "dppio", "dpp", "tests", "proofs", "benchmarks", "examples",
               # helper modules next to the benchmark scripts, imported by them as scripts
               *(p.stem for p in (ROOT / "benchmarks").glob("_*.py"))}
DEV_EXTRAS = ("test", "peers", "maps", "bench")


def _norm(name: str) -> str:
    return re.sub(r"[-_.]+", "-", name).lower()


def _requirement_names(requirements: list[str]) -> set[str]:
    """``dask[distributed]>=2024.1`` declares dask and (through its extra) distributed."""
    names = set()
    for req in requirements:
        m = re.match(r"\s*([A-Za-z0-9._-]+)(?:\[([^\]]*)\])?", req)
        assert m, f"unparsable requirement {req!r}"
        names.add(_norm(m.group(1)))
        names.update(_norm(x) for x in (m.group(2) or "").split(",") if x.strip())
    return names


def _project() -> dict[str, set[str]]:
    with open(ROOT / "pyproject.toml", "rb") as f:
        project = tomllib.load(f)["project"]
    groups = {"": _requirement_names(project["dependencies"])}
    for extra, reqs in project.get("optional-dependencies", {}).items():
        groups[extra] = _requirement_names(reqs)
    return groups


def _imports(path: Path) -> Iterator[tuple[str, bool]]:
    """(top-level module, imported at module level?) for every import in ``path``."""
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    nested = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
            nested.update(id(n) for n in ast.walk(node) if n is not node)
    for node in ast.walk(tree):
        top = id(node) not in nested
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield alias.name.split(".")[0], top
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            yield node.module.split(".")[0], top
        elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
              and node.func.attr == "importorskip" and node.args
              and isinstance(node.args[0], ast.Constant) and isinstance(node.args[0].value, str)):
            yield node.args[0].value.split(".")[0], False


def _third_party(folders: tuple[str, ...]) -> Iterator[tuple[str, bool, Path]]:
    for folder in folders:
        for path in sorted((ROOT / folder).rglob("*.py")):
            for module, top in _imports(path):
                if module not in sys.stdlib_module_names and module not in FIRST_PARTY:
                    yield module, top, path


@cache
def _module_distributions() -> dict[str, list[str]]:
    return packages_distributions()


SAME_MODULE = {"cvxpy": {"cvxpy", "cvxpy-base"}}
"""Distributions that install the same import package: we declare the light ``cvxpy-base``
(no bundled SCS/OSQP/HiGHS), a machine may have the full ``cvxpy``."""


def _distributions(module: str) -> set[str]:
    found = {_norm(d) for d in _module_distributions().get(module, [module])}
    return found | SAME_MODULE.get(module, set())


def test_runtime_imports_are_declared() -> None:
    groups = _project()
    extras = set().union(*(v for k, v in groups.items() if k))
    seen = set()
    for module, top, path in _third_party(("solver", "dppverify", "dppio", "dpp")):
        seen.add(module)
        allowed = groups[""] if top else groups[""] | extras
        where = "[project] dependencies" if top else "the dependencies or an extra"
        assert _distributions(module) & allowed, (
            f"{path.relative_to(ROOT)} imports {module!r}, not declared in {where}")
    assert {"numpy", "networkx", "click", "mpmath"} <= seen  # the scan sees real imports


def test_test_and_benchmark_imports_are_declared() -> None:
    groups = _project()
    allowed = groups[""].union(*(groups.get(e, set()) for e in DEV_EXTRAS))
    seen = set()
    for module, _, path in _third_party(("tests", "proofs", "benchmarks")):
        seen.add(module)
        assert _distributions(module) & allowed, (
            f"{path.relative_to(ROOT)} imports {module!r}, declared in no dependency "
            f"list that `python3 dev.py test` installs")
    assert {"pytest", "hypothesis", "pyspiel"} <= seen


@pytest.mark.parametrize("source, expected", [
    ("import mpmath\ndef f():\n    from distributed import Client\n",
     [("mpmath", True), ("distributed", False)]),
    ("from . import x\nimport os.path\npytest.importorskip('pygambit')\n",
     [("os", True), ("pygambit", False)]),
])
def test_import_scanner(tmp_path: Path, source: str, expected: list[tuple[str, bool]]) -> None:
    path = tmp_path / "m.py"
    path.write_text(source, encoding="utf-8")
    assert sorted(_imports(path)) == sorted(expected)


def test_requirement_names_include_extras_of_requirements() -> None:
    assert _requirement_names(["dask[distributed]>=2024.1", "open-spiel==2.0.2"]) == {
        "dask", "distributed", "open-spiel"}
