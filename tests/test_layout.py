"""The layout of both packages: one layer table in the README, docs/architecture.md and the
import-linter contracts of pyproject.toml, and no module named for N goals.

A documentation table lists the layers bottom to top, one row per layer (a row may hold
several adjacent layers of the contract); a package's top-level module or sub-package is named
in backticks (``errors``, ``game/``). The table agrees with the contract when every top-level
module is in both, and no row places a module below one that the contract puts under it.
"""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("dppverify", "solver")


def _children(package: str) -> set[str]:
    """The top-level modules and sub-packages of ``package``."""
    base = ROOT / package
    names = {p.stem for p in base.glob("*.py") if p.stem != "__init__"}
    names |= {p.name for p in base.iterdir() if (p / "__init__.py").exists()}
    return names


def _contract_layers(package: str) -> list[set[str]]:
    """The layers of ``package``'s layers contract, bottom to top."""
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())
    contracts = [c for c in config["tool"]["importlinter"]["contracts"]
                 if c["type"] == "layers" and c.get("containers") == [package]]
    assert len(contracts) == 1, f"one layers contract for {package}"
    return [set(re.split(r"\s*[|:]\s*", layer.strip())) for layer in contracts[0]["layers"]][::-1]


def _table(text: str, header: str) -> list[list[str]]:
    """The rows (cells) of the markdown table whose header line starts with ``header``."""
    lines = text.splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith(header))
    rows = []
    for line in lines[start + 2:]:
        if not line.startswith("|"):
            break
        rows.append([cell.strip() for cell in line.strip().strip("|").split("|")])
    return rows


def _row_names(cells: list[str], package: str, names: set[str]) -> list[set[str]]:
    """Per row, the top-level names of ``package`` the cells name in backticks."""
    out = []
    for cell in cells:
        tokens = {t.rstrip("/").rstrip("*") for t in re.findall(r"`([^`]+)`", cell)}
        out.append(tokens & names)
    return out


def _doc_tables() -> list[tuple[str, str, list[set[str]]]]:
    readme = (ROOT / "README.md").read_text()
    arch = (ROOT / "docs" / "architecture.md").read_text()
    out = []
    joint = _table(readme, "| layer | checker `dppverify/` | solver `solver/` |")
    for column, package in ((1, "dppverify"), (2, "solver")):
        cells = [row[column] for row in joint]
        out.append(("README.md", package, _row_names(cells, package, _children(package))))
    checker, solver = (_table(arch[arch.index(h):], "| layer | package / module |")
                       for h in ("## The checker", "## The solver"))
    for rows, package in ((checker, "dppverify"), (solver, "solver")):
        cells = [row[1] for row in rows]
        out.append(("docs/architecture.md", package, _row_names(cells, package,
                                                                 _children(package))))
    return out


@pytest.mark.parametrize("package", PACKAGES)
def test_the_contract_places_every_module(package: str) -> None:
    placed = set().union(*_contract_layers(package))
    assert _children(package) - {"__main__"} <= placed | {"__main__"}, \
        f"modules of {package} outside its layers contract"
    assert placed <= _children(package), f"{package}'s contract names no such module"


@pytest.mark.parametrize(("doc", "package", "rows"), _doc_tables(),
                         ids=lambda x: x if isinstance(x, str) else "")
def test_the_docs_tables_agree_with_the_contract(doc: str, package: str,
                                                   rows: list[set[str]]) -> None:
    layer_of = {name: k for k, layer in enumerate(_contract_layers(package)) for name in layer}
    row_of: dict[str, int] = {}
    for k, names in enumerate(rows):
        for name in names:
            row_of.setdefault(name, k)  # the lowest row naming it (cli/certify is not certify)
    missing = set(layer_of) - set(row_of)
    assert not missing, f"{doc}: the {package} table omits {sorted(missing)}"
    for a in layer_of:
        for b in layer_of:
            if layer_of[a] > layer_of[b]:
                assert row_of[a] >= row_of[b], (
                    f"{doc}: the {package} table puts {a} below {b}, the contract above it")


def _architecture_rows(header: str) -> list[set[str]]:
    """Per row of docs/architecture.md's table under ``header``: the names it gives in
    backticks (``game/`` as ``game``)."""
    arch = (ROOT / "docs" / "architecture.md").read_text()
    rows = _table(arch[arch.index(header):], "| ")
    names = [[t.rstrip("/").rstrip("*") for t in re.findall(r"`([^`]+)`", row[0] + row[1])]
             for row in rows]
    return [{part for t in row for part in (t, t.rsplit("/", 1)[-1])} for row in names]


@pytest.mark.parametrize(("package", "header"), [("dppverify", "## The checker"),
                                                 ("solver", "## The solver"),
                                                 ("dppio", "# Architecture")])
def test_the_architecture_tables_name_every_module(package: str, header: str) -> None:
    """Every module of a sub-package (``game/distances.py``) is named in the row that names
    its sub-package (``game/``); a ``structured*`` prefix names the modules it starts."""
    rows = _architecture_rows(header)
    missing = []
    for path in sorted((ROOT / package).rglob("*.py")):
        parts = path.relative_to(ROOT / package).with_suffix("").parts
        if parts[-1] in ("__init__", "__main__") or (len(parts) < 2 and package != "dppio"):
            continue  # the top-level modules of dppverify and solver: the layer tables
        folder, name = (parts[-2] if len(parts) > 1 else package), parts[-1]
        if not any(folder in row and (name in row or any(
                name.startswith(t) for t in row if len(t) > 3)) for row in rows):
            missing.append("/".join(parts))
    assert not missing, f"docs/architecture.md does not name {missing}"


def test_no_module_is_named_for_n_goals() -> None:
    """One core serves any N: only the ``dpp experiment ngoal`` command's modules say ngoal."""
    found = sorted(str(p.relative_to(ROOT)) for package in PACKAGES
                   for p in (ROOT / package).rglob("*ngoal*"))
    assert found == ["solver/cli/experiment_ngoal.py", "solver/experiments/ngoal.py"]


def test_the_solver_root_holds_the_front_door_and_the_core() -> None:
    loose = sorted(p.stem for p in (ROOT / "solver").glob("*.py"))
    assert loose == ["__init__", "adapter", "errors", "limits", "numbers", "solution", "threads",
                     "version"]


@pytest.mark.parametrize("package", PACKAGES)
def test_the_tests_mirror_the_package(package: str) -> None:
    """``tests/<package>/<layer>/`` holds the tests of ``<package>/<layer>/``: no other folder."""
    folders = {p.name for p in (ROOT / "tests" / package).iterdir()
               if p.is_dir() and p.name != "__pycache__"}
    assert folders, f"tests/{package}/ has no layer folders"
    assert folders <= _children(package), f"tests/{package}/ has folders no layer of {package} has"


def test_every_folder_of_modules_is_a_package() -> None:
    """A folder of modules without ``__init__.py`` is a namespace package, which setuptools
    leaves out of the wheel: every one is a package."""
    loose = sorted(str(folder.relative_to(ROOT)) for package in (*PACKAGES, "dppio", "dpp")
                   for folder in {p.parent for p in (ROOT / package).rglob("*.py")}
                   if not (folder / "__init__.py").is_file())
    assert loose == []
