"""The docstring standard (networkx's rule): the public API has full numpy-style docstrings,
everything else a short one.

*Public* means a name in the ``__all__`` of a module that docs/cli.md's "Python API" table
lists; only those modules have an ``__all__``. A public function's docstring has a summary,
``Parameters`` (when it takes any), ``Returns`` (unless it returns None), ``Raises`` (when its
body raises) and ``Examples`` that run (``>>>``: the doctests run them); a public class has a
docstring. A name a front door re-exports is checked where it is defined. Every other
top-level function and class of the packages has a docstring; a contract is stated once, where
it is enforced. Click commands are checked like any function, without the sections: their
``--help`` is their documentation. The scan reads the sources with :mod:`ast`, so it imports
none of the modules it checks.
"""

from __future__ import annotations

import ast
import re
from dataclasses import dataclass
from functools import cache
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("solver", "dppverify", "dppio", "dpp")

PENDING: dict[str, str] = {
    "dppverify.game.instance.instance_from_json": "the one reader of the certification "
                                                  "pipeline replaces it",
    "dppverify.game.instance.load_instance": "the one reader of the certification pipeline "
                                             "replaces it",
}
"""Public names whose docstrings are not complete yet, with why; an entry that passes fails
the test, so the list only shrinks."""

ALL_PENDING = frozenset((
    "dppverify/checks/lemmas/__init__.py", "dppverify/checks/per_goal_records.py",
    "dppverify/checks/runners.py", "dppverify/checks/structured.py",
    "dppverify/checks/structured_guarantee.py", "dppverify/checks/structured_per_goal.py",
    "dppverify/checks/structured_twogoal.py", "dppverify/checks/suites.py",
    "dppverify/cli/certify.py", "dppverify/cli/export_efg.py", "dppverify/cli/inputs.py",
    "dppverify/cli/value.py", "dppverify/game/distances.py", "dppverify/game/inputs.py",
    "dppverify/game/instance.py", "dppverify/game/profile.py", "dppverify/game/profile_types.py",
    "dppverify/registry.py", "dppverify/routes.py", "dppverify/strategies/instances.py",
    "dppverify/structured/cover.py", "dppverify/structured/proved_value.py",
    "dppverify/tree_route/efg.py", "dppverify/tree_route/per_goal_checks.py",
    "dppverify/value_document.py", "solver/cli/experiment.py", "solver/cli/solve.py",
    "solver/coalitions/construction.py", "solver/coalitions/normal_attacker.py",
    "solver/experiments/density.py", "solver/game/profile_writing.py",
))
"""Internal modules that still have an ``__all__``: modules other branches rework now (the
certification pipeline's second stage, batch and its outputs, goal selection, the kernel, the
documentation site), and two facades whose importers still take re-exported names from them
(``game/profile.py``, ``checks/lemmas``); each loses it when that work lands. The list only
shrinks."""


@dataclass(frozen=True)
class Public:
    where: str  # "path:line name"
    kind: str  # "function", "click" or "class"
    docstring: str


def public_modules() -> list[str]:
    """The modules of docs/cli.md's "Python API" table, in its order."""
    text = (ROOT / "docs" / "cli.md").read_text(encoding="utf-8")
    section = text[text.index("## Python API"):]
    section = section[:section.index("\n## ", 1)]
    rows = [line for line in section.splitlines() if line.startswith("| `")]
    return [re.match(r"\| `([\w.]+)`", row).group(1) for row in rows]  # type: ignore[union-attr]


def _path(module: str) -> Path:
    base = ROOT.joinpath(*module.split("."))
    return base / "__init__.py" if base.is_dir() else base.with_suffix(".py")


def _exported(module: ast.Module) -> list[str] | None:
    """The names of ``__all__`` (None when the module has none); ``+=`` extensions included."""
    names: list[str] | None = None
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
        found = [e.value for e in value.elts
                 if isinstance(e, ast.Constant) and isinstance(e.value, str)]
        names = found if names is None or not isinstance(node, ast.AugAssign) else names + found
    return names


def _is_click(function: ast.FunctionDef | ast.AsyncFunctionDef) -> bool:
    """Decorated with ``@click.command``/``@click.group`` or ``@<group>.command/.group``."""
    for decorator in function.decorator_list:
        target = decorator.func if isinstance(decorator, ast.Call) else decorator
        if isinstance(target, ast.Attribute) and target.attr in ("command", "group"):
            return True
    return False


def scan_source(source: str, where: str) -> list[Public]:
    """The top-level functions and classes of one module's source whose names do not start
    with ``_``."""
    found = []
    for node in ast.parse(source).body:
        if not isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
            continue
        if node.name.startswith("_"):
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
    """Every such function and class of the packages (read once per test session)."""
    found: list[Public] = []
    for package in PACKAGES:
        for path in sorted((ROOT / package).rglob("*.py")):
            found += scan_source(path.read_text(encoding="utf-8"),
                                 path.relative_to(ROOT).as_posix())
    return tuple(found)


def _definition(module: str, name: str) -> tuple[str, ast.AST] | None:
    """Where ``name`` of ``module`` is defined: the module itself, or the package module it
    is imported from (followed); None for a constant, an alias or a lazy import."""
    for _ in range(6):
        tree = ast.parse(_path(module).read_text(encoding="utf-8"))
        for node in tree.body:
            if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef) \
                    and node.name == name:
                return f"{module}.{name}", node
        source = next((node for node in ast.walk(tree) if isinstance(node, ast.ImportFrom)
                       and node.module and node.module.split(".")[0] in PACKAGES
                       and any((a.asname or a.name) == name for a in node.names)), None)
        if source is None or source.module is None:
            return None
        name = next(a.name for a in source.names if (a.asname or a.name) == name)
        module = source.module
    return None


def missing_sections(node: ast.AST) -> list[str]:
    """What a public definition's docstring lacks (networkx's rule)."""
    assert isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef)
    doc = ast.get_docstring(node) or ""
    if not doc.strip():
        return ["a docstring"]
    if isinstance(node, ast.ClassDef) or _is_click(node):
        return []
    missing = []
    args = node.args
    named = [a.arg for a in (*args.posonlyargs, *args.args, *args.kwonlyargs)]
    if [n for n in named if n not in ("self", "cls")] and not _section(doc, "Parameters"):
        missing.append("Parameters")
    returns_none = isinstance(node.returns, ast.Constant) and node.returns.value is None
    if not returns_none and not (_section(doc, "Returns") or _section(doc, "Yields")):
        missing.append("Returns")
    raises = any(isinstance(n, ast.Raise) and n.exc is not None for n in ast.walk(node))
    if raises and not _section(doc, "Raises"):
        missing.append("Raises")
    if ">>>" not in doc:
        missing.append("Examples")
    return missing


def _section(doc: str, title: str) -> bool:
    return re.search(rf"^{title}\n-+$", doc, re.MULTILINE) is not None


@cache
def public_problems() -> dict[str, str]:
    """``module.name`` -> what its docstring lacks, for every public name."""
    problems = {}
    for module in public_modules():
        tree = ast.parse(_path(module).read_text(encoding="utf-8"))
        for name in _exported(tree) or ():
            found = _definition(module, name)
            if found is None:
                continue
            where, node = found
            missing = missing_sections(node)
            if missing:
                problems[where] = ", ".join(missing)
    return problems


def test_the_public_modules_exist_and_have_an_all() -> None:
    modules = public_modules()
    assert "dppverify" in modules and "solver" in modules and len(modules) >= 8
    for module in modules:
        assert _path(module).is_file(), module
        tree = ast.parse(_path(module).read_text(encoding="utf-8"))
        assert _exported(tree), f"{module} is public API: it needs an __all__"


def test_only_the_public_modules_have_an_all() -> None:
    public = {_path(m).relative_to(ROOT).as_posix() for m in public_modules()}
    having = {path.relative_to(ROOT).as_posix() for package in PACKAGES
              for path in (ROOT / package).rglob("*.py")
              if _exported(ast.parse(path.read_text(encoding="utf-8"))) is not None}
    extra = sorted(having - public - ALL_PENDING)
    assert not extra, "an __all__ in a module that is not public API:\n" + "\n".join(extra)
    done = sorted(ALL_PENDING - having)
    assert not done, "no __all__ any more, remove from ALL_PENDING:\n" + "\n".join(done)


def test_public_names_have_full_numpy_docstrings() -> None:
    problems = {k: v for k, v in public_problems().items() if k not in PENDING}
    assert not problems, "public names whose docstrings lack sections:\n" + "\n".join(
        f"{k}: {v}" for k, v in sorted(problems.items()))


def test_every_pending_docstring_is_still_incomplete() -> None:
    done = sorted(set(PENDING) - set(public_problems()))
    assert not done, "complete now, remove from PENDING:\n" + "\n".join(done)


def test_every_function_and_class_has_a_docstring() -> None:
    found = scan()
    assert len(found) > 300, "the scan found too few definitions: is it still looking?"
    missing = [p.where for p in found if not p.docstring.strip()]
    assert not missing, "functions and classes without a docstring:\n" + "\n".join(missing)


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

def plain(x: int) -> int:
    """No sections."""

def documented(x: int) -> int:
    """Twice.

    Parameters
    ----------
    x : int

    Returns
    -------
    int

    Raises
    ------
    ValueError

    Examples
    --------
    >>> documented(1)
    2
    """
    if x < 0:
        raise ValueError(x)
    return 2 * x

def late() -> None:
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
    assert found["Thing"].docstring == "" and found["late"].docstring == ""
    assert _exported(ast.parse(_SAMPLE)) == ["plain", "cmd", "sub", "group", "Thing",
                                              "documented", "late"]


def test_the_sections_rule_on_a_sample_module() -> None:
    nodes = {n.name: n for n in ast.parse(_SAMPLE).body
             if isinstance(n, ast.FunctionDef | ast.ClassDef)}
    assert missing_sections(nodes["documented"]) == []
    assert missing_sections(nodes["plain"]) == ["Parameters", "Returns", "Examples"]
    assert missing_sections(nodes["late"]) == ["a docstring"]
    assert missing_sections(nodes["cmd"]) == [] and missing_sections(nodes["Thing"]) == [
        "a docstring"]
