"""dppverify never imports the solver: statically and at run time."""

from __future__ import annotations

import ast
import pkgutil
import subprocess
import sys
from pathlib import Path

import dppverify

PACKAGE = Path(dppverify.__file__).resolve().parent


def test_no_module_of_dppverify_imports_solver_statically() -> None:
    offenders = []
    for path in sorted(PACKAGE.rglob("*.py")):
        tree = ast.parse(path.read_text(), filename=str(path))
        for node in ast.walk(tree):
            names: list[str] = []
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                names = [node.module]
            offenders += [f"{path.name}: {n}" for n in names
                          if n == "solver" or n.startswith("solver.")]
        text = path.read_text()
        if "import_module(\"solver" in text or "__import__(\"solver" in text:
            offenders.append(f"{path.name}: dynamic import")
    assert not offenders


def test_importing_every_dppverify_module_loads_no_solver_module() -> None:
    modules = sorted(m.name for m in pkgutil.walk_packages([str(PACKAGE)], "dppverify.")
                     if m.name != "dppverify.__main__")
    assert "dppverify.certify" in modules and "dppverify.tree_route.tree" in modules
    code = ("import importlib, sys\n"
            f"for m in {modules!r}: importlib.import_module(m)\n"
            "import dppverify.__main__\n"
            "bad = [m for m in sys.modules if m == 'solver' or m.startswith('solver.')]\n"
            "print(bad)\n"
            "sys.exit(1 if bad else 0)\n")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          check=False)
    assert proc.returncode == 0, proc.stdout + proc.stderr
