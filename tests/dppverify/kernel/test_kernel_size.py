"""The trusted kernel stays small and standard-library only (proofs/KERNEL.md).

Code lines: non-blank lines that are neither comments nor docstrings (module, class and
function docstrings), counted over every module of ``dppverify/kernel/``. Imports: every
``import`` of the kernel names a module of the allowlist below or ``dppverify.kernel`` itself;
and the kernel run as a file (what ``dpp check`` runs) loads no module outside the standard
library and the kernel.
"""

from __future__ import annotations

import ast
import io
import json
import subprocess
import sys
import tokenize
from pathlib import Path

KERNEL = Path(__file__).resolve().parents[3] / "dppverify" / "kernel"
MAX_CODE_LINES = 800
STDLIB = {"__future__", "bisect", "dataclasses", "fractions", "hashlib", "importlib",
          "importlib.util", "itertools", "json", "operator", "pathlib", "re", "sys", "types",
          "typing", "collections.abc", "math", "functools"}


def code_lines(source: str) -> int:
    """Non-blank lines of ``source`` that are not comments or docstrings."""
    tree = ast.parse(source)
    doc_lines: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Module | ast.ClassDef | ast.FunctionDef | ast.AsyncFunctionDef):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) \
                    and isinstance(body[0].value.value, str):
                doc_lines.update(range(body[0].lineno, body[0].end_lineno + 1))  # type: ignore[operator]
    lines: set[int] = set()
    for tok in tokenize.generate_tokens(io.StringIO(source).readline):
        if tok.type not in (tokenize.COMMENT, tokenize.NL, tokenize.NEWLINE, tokenize.INDENT,
                            tokenize.DEDENT, tokenize.ENDMARKER):
            lines.update(range(tok.start[0], tok.end[0] + 1))
    return len(lines - doc_lines)


def test_code_lines_counts_what_it_says() -> None:
    src = ('"""doc\n\nstring"""\n\nx = 1  # c\n# only a comment\n\ndef f():\n    """d"""\n'
           "    return (1,\n            2)\n")
    assert code_lines(src) == 4  # x = 1, def f, return (1, and 2)


def test_the_kernel_has_at_most_800_code_lines() -> None:
    total = sum(code_lines(p.read_text(encoding="utf-8")) for p in KERNEL.glob("*.py"))
    assert 0 < total <= MAX_CODE_LINES, f"dppverify/kernel has {total} code lines"


def test_the_kernel_imports_only_the_standard_library_and_itself() -> None:
    for path in KERNEL.glob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            names = ([a.name for a in node.names] if isinstance(node, ast.Import) else
                     [node.module or ""] if isinstance(node, ast.ImportFrom) else [])
            for name in names:
                assert name in STDLIB or name.startswith("dppverify.kernel"), \
                    f"{path.name} imports {name}"


def _loaded(code: str) -> set[str]:
    out = subprocess.run([sys.executable, "-I", "-c", code + "; import sys, json; "
                          "print(json.dumps(sorted(sys.modules)))"],
                         capture_output=True, text=True, check=True).stdout
    return set(json.loads(out.splitlines()[-1]))


def test_the_kernel_process_loads_nothing_else() -> None:
    at_startup = _loaded("pass")  # the interpreter's own start-up (site, .pth hooks)
    loaded = _loaded(f"import runpy; runpy.run_path({str(KERNEL / '__main__.py')!r})")
    outside = [m for m in sorted(loaded - at_startup) if m.split(".")[0] not in
               sys.stdlib_module_names and not m.startswith("dppverify.kernel")
               and m != "dppverify"]
    assert not outside, f"the kernel process loads {outside}"
