"""The docstring standard: every public function has a runnable example, every public class
a docstring.

"Public" means top-level in a module of ``solver/`` or ``dppverify/``, not starting with
``_``, and listed in the module's ``__all__`` (every name, when a module has no
``__all__``). Click commands and groups are excepted: their ``--help`` is their
documentation and their tests use click's ``CliRunner``. The scan reads the sources with
:mod:`ast`, so it imports none of the modules it checks.
"""

from __future__ import annotations

import ast
from dataclasses import dataclass
from functools import cache
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("solver", "dppverify", "dppio")


@dataclass(frozen=True)
class Public:
    where: str  # "path:line name"
    kind: str  # "function", "click" or "class"
    docstring: str


def _exported(module: ast.Module) -> set[str] | None:
    """The names of ``__all__`` (None when the module has none); ``+=`` extensions included."""
    names: set[str] | None = None
    for node in module.body:
        if isinstance(node, ast.Assign):
            targets, value = node.targets, node.value
        elif isinstance(node, ast.AnnAssign | ast.AugAssign) and node.value is not None:
            targets, value = [node.target], node.value
        else:
            continue
        if not any(isinstance(t, ast.Name) and t.id == "__all__" for t in targets):
            continue
        if not isinstance(value, ast.List | ast.Tuple):
            raise AssertionError(f"__all__ at line {node.lineno} is not a literal list")
        found = {e.value for e in value.elts
                 if isinstance(e, ast.Constant) and isinstance(e.value, str)}
        names = found if names is None or not isinstance(node, ast.AugAssign) else names | found
    return names


def _is_click(function: ast.FunctionDef | ast.AsyncFunctionDef) -> bool:
    """Decorated with ``@click.command``/``@click.group`` or ``@<group>.command/.group``."""
    for decorator in function.decorator_list:
        target = decorator.func if isinstance(decorator, ast.Call) else decorator
        if isinstance(target, ast.Attribute) and target.attr in ("command", "group"):
            return True
    return False


def scan_source(source: str, where: str) -> list[Public]:
    """The public functions and classes of one module's source."""
    module = ast.parse(source)
    exported = _exported(module)
    found = []
    for node in module.body:
        if not isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
            continue
        if node.name.startswith("_") or (exported is not None and node.name not in exported):
            continue
        if isinstance(node, ast.ClassDef):
            kind = "class"
        else:
            kind = "click" if _is_click(node) else "function"
        found.append(Public(f"{where}:{node.lineno} {node.name}", kind,
                            ast.get_docstring(node) or ""))
    return found


@cache
def scan() -> tuple[Public, ...]:
    """Every public function and class of the packages (read once per test session)."""
    found: list[Public] = []
    for package in PACKAGES:
        for path in sorted((ROOT / package).rglob("*.py")):
            found += scan_source(path.read_text(encoding="utf-8"),
                                 path.relative_to(ROOT).as_posix())
    return tuple(found)


def test_public_functions_have_runnable_examples() -> None:
    functions = [p for p in scan() if p.kind == "function"]
    assert len(functions) > 50, "the scan found too few functions: is it still looking?"
    missing = [p.where for p in functions if ">>>" not in p.docstring]
    assert not missing, "public functions without a >>> example:\n" + "\n".join(missing)


def test_public_classes_have_docstrings() -> None:
    classes = [p for p in scan() if p.kind == "class"]
    assert len(classes) > 30, "the scan found too few classes: is it still looking?"
    missing = [p.where for p in classes if not p.docstring.strip()]
    assert not missing, "public classes without a docstring:\n" + "\n".join(missing)


def test_only_click_commands_are_excepted() -> None:
    excepted = {p.where.split()[-1] for p in scan() if p.kind == "click"}
    assert "main" in excepted and "certify_command" in excepted
    assert all(name == "main" or name.endswith(("_command", "_group")) for name in excepted)


_SAMPLE = '''
import click
__all__ = ["plain", "cmd", "sub", "group", "Thing", "documented"]
__all__ += ["late"]

@click.group()
def group() -> None:
    """Group."""

@group.command("sub")
def sub() -> None:
    """Sub."""

@click.command
def cmd() -> None:
    """Cmd."""

def plain() -> None:
    """No example."""

def documented() -> None:
    """
    >>> 1
    1
    """

def late() -> None:
    pass

def not_exported() -> None:
    pass

class Thing:
    pass

def _private() -> None:
    pass
'''


def test_scan_classifies_a_sample_module() -> None:
    found = {p.where.split()[-1]: p for p in scan_source(_SAMPLE, "sample.py")}
    assert set(found) == {"group", "sub", "cmd", "plain", "documented", "late", "Thing"}
    assert {n for n, p in found.items() if p.kind == "click"} == {"group", "sub", "cmd"}
    assert found["Thing"].kind == "class" and found["Thing"].docstring == ""
    assert ">>>" in found["documented"].docstring and ">>>" not in found["plain"].docstring
    assert found["late"].docstring == ""


def test_scan_without_all_takes_every_public_name() -> None:
    found = scan_source("def f() -> None:\n    pass\n\ndef _g() -> None:\n    pass\n", "x.py")
    assert [p.where for p in found] == ["x.py:1 f"]
