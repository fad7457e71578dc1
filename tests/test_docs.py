"""The documentation runs: every example in README.md and docs/*.md is executed and compared.

- Every ```` ```console ```` block is a shell session: each ``$ `` line is run with ``bash``
  (``dpp`` and ``python`` are this checkout's), and what it prints — stdout and stderr
  together, as a terminal shows them — must match the lines shown under it, compared by the
  standard library's :class:`doctest.OutputChecker` with ``ELLIPSIS`` (``...`` matches
  anything, also across lines) and ``NORMALIZE_WHITESPACE``. A command that shows no output
  must print nothing. The exit code must be 0, or ``N`` when the command's comment says
  ``exit N``.
- Each block runs on its own in a fresh folder holding ``examples/`` (a link to the
  repository's), so a block creates every file it uses.
- A block preceded by ``<!-- console: slow -->`` is marked ``slow`` (run by ``python3 dev.py
  test -m slow``): the full density sweep and the long audit campaigns.
- Every ``>>>`` example in these files is run by :mod:`doctest` with the same options.

Commands that are not examples (installing, running the test suite, placeholders such as
``mysolver:solve``) are written in ```` ```bash ```` blocks instead. Those are not run, but
every ``dpp`` command in them must parse (subcommands, options and option values, by Click's
own parser), except lines with placeholders such as ``INSTANCE`` or ``[--flag]``.
"""

from __future__ import annotations

import doctest
import os
import re
import subprocess
import sys
import warnings
from dataclasses import dataclass
from pathlib import Path

import pytest

from tests import _guard

ROOT = Path(__file__).resolve().parents[1]
DOCS = (ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md")))
FLAGS = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
SLOW_MARK = "<!-- console: slow -->"


@dataclass(frozen=True)
class Command:
    line: int
    text: str
    expected: str
    exit_code: int


@dataclass(frozen=True)
class Block:
    path: Path
    line: int
    commands: tuple[Command, ...]
    slow: bool

    @property
    def name(self) -> str:
        return f"{self.path.relative_to(ROOT)}:{self.line}"


def parse_console_blocks(path: Path) -> list[Block]:
    """The ```` ```console ```` blocks of a Markdown file.

    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     md = Path(d) / "x.md"
    ...     _ = md.write_text("<!-- console: slow -->\\n```console\\n$ echo a  # exit 0\\na\\n"
    ...                       "$ false   # exit 1\\n```\\n")
    ...     [(c.text, c.expected, c.exit_code) for c in parse_console_blocks(md)[0].commands]
    [('echo a  # exit 0', 'a\\n', 0), ('false   # exit 1', '', 1)]
    """
    lines = path.read_text(encoding="utf-8").splitlines()
    blocks, i = [], 0
    while i < len(lines):
        if lines[i].strip() != "```console":
            i += 1
            continue
        start = i
        previous = next((x.strip() for x in reversed(lines[:start]) if x.strip()), "")
        i += 1
        commands: list[Command] = []
        while i < len(lines) and not lines[i].startswith("```"):
            if lines[i].startswith("$ "):
                text = lines[i][2:]
                code = re.search(r"#.*\bexit (\d+)", text)
                commands.append(Command(i + 1, text, "", int(code.group(1)) if code else 0))
            elif commands:
                last = commands[-1]
                commands[-1] = Command(last.line, last.text, last.expected + lines[i] + "\n",
                                       last.exit_code)
            else:
                raise AssertionError(f"{path}:{i + 1}: output before the first '$ ' command")
            i += 1
        blocks.append(Block(path, start + 1, tuple(commands), previous == SLOW_MARK))
        i += 1
    return blocks


BLOCKS = [b for path in DOCS for b in parse_console_blocks(path)]


def _shims(bin_dir: Path) -> None:
    """``dpp`` and ``python`` on PATH: this checkout's code, this interpreter."""
    bin_dir.mkdir()
    dpp = bin_dir / "dpp"
    dpp.write_text(f"#!/bin/sh\nexec '{sys.executable}' -c 'import sys; sys.argv[0] = \"dpp\"; "
                   f"from dpp import main; main()' \"$@\"\n", encoding="utf-8")
    dpp.chmod(0o755)
    for name in ("python", "python3"):  # a script, not a link: a venv is found by its path
        shim = bin_dir / name
        shim.write_text(f"#!/bin/sh\nexec '{sys.executable}' \"$@\"\n", encoding="utf-8")
        shim.chmod(0o755)


def test_the_docs_have_console_examples() -> None:
    names = {b.path.name for b in BLOCKS}
    assert {"README.md", "checker.md", "audit.md"} <= names
    assert sum(len(b.commands) for b in BLOCKS) >= 15


@pytest.mark.parametrize("block", [
    pytest.param(b, id=b.name, marks=[pytest.mark.slow] if b.slow else []) for b in BLOCKS])
def test_console_block(block: Block, tmp_path: Path) -> None:
    work = tmp_path / "work"
    work.mkdir()
    (work / "examples").symlink_to(ROOT / "examples")
    _shims(tmp_path / "bin")
    env = {k: v for k, v in os.environ.items() if not k.startswith(("DPP_", "PYTEST_"))}
    env["PATH"] = f"{tmp_path / 'bin'}{os.pathsep}{env.get('PATH', '')}"
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")]).rstrip(os.pathsep)
    env["COLUMNS"] = "100"
    checker = doctest.OutputChecker()
    for cmd in block.commands:
        where = f"{block.path.relative_to(ROOT)}:{cmd.line}: $ {cmd.text}"
        run = _guard.run(["bash", "-c", cmd.text], cwd=work, env=env, text=True,
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
        got = run.stdout
        if cmd.expected.strip():
            ok = checker.check_output(cmd.expected, got, FLAGS)
        else:
            ok = got.strip() == ""
        assert ok, f"{where}\n" + checker.output_difference(
            doctest.Example(cmd.text, cmd.expected), got, FLAGS)
        assert run.returncode == cmd.exit_code, (
            f"{where}\nexit code {run.returncode}, the docs say {cmd.exit_code}\n{got}")


@pytest.mark.parametrize("path", DOCS, ids=lambda p: str(p.relative_to(ROOT)))
def test_python_examples(path: Path) -> None:
    # a fence line ends an example's expected output, as a blank line does
    text = re.sub(r"^```.*$", "", path.read_text(encoding="utf-8"), flags=re.M)
    test = doctest.DocTestParser().get_doctest(text, {}, path.name, str(path), 0)
    runner = doctest.DocTestRunner(optionflags=FLAGS)
    runner.run(test)
    assert runner.failures == 0, f"{path.name}: {runner.failures} failing >>> example(s)"


# ``bash`` blocks are not run (installs, long campaigns, placeholders), but every ``dpp`` command
# in them must still parse: its subcommands and options exist and take the values shown.
FILE_SUFFIXES = (".json", ".csv", ".map", ".efg", ".png", ".pdf", ".svg")
PLACEHOLDER = re.compile(r"\b[A-Z]{2,}\b|\[")


def bash_dpp_commands(path: Path) -> list[tuple[int, str]]:
    """The ``dpp …`` command lines of the ```` ```bash ```` blocks (continuations joined).

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     md = Path(d) / "x.md"
    ...     _ = md.write_text("```bash\\npip install x\\n"
    ...                       "dpp solve a.json \\\\\\n  --json  # c\\n```\\n")
    ...     bash_dpp_commands(md)
    [(3, 'dpp solve a.json --json  # c')]
    """
    out: list[tuple[int, str]] = []
    inside, pending, start = False, "", 0
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        if line.startswith("```"):
            inside = line.strip() == "```bash"
            continue
        if not inside:
            continue
        if pending:
            pending += " " + line.strip()
        elif line.startswith("dpp "):
            pending, start = line.strip(), number
        if pending.endswith("\\"):
            pending = pending[:-1].rstrip()
            continue
        if pending:
            out.append((start, pending))
            pending = ""
    return out


BASH_COMMANDS = [(path, number, text) for path in DOCS for number, text in bash_dpp_commands(path)
                 if not PLACEHOLDER.search(text.split("#")[0])]


def test_the_docs_have_bash_commands() -> None:
    assert len(BASH_COMMANDS) >= 20


@pytest.mark.parametrize("path, number, text", [
    pytest.param(p, n, t, id=f"{p.relative_to(ROOT)}:{n}") for p, n, t in BASH_COMMANDS])
def test_bash_command_parses(path: Path, number: int, text: str, tmp_path: Path,
                             monkeypatch: pytest.MonkeyPatch) -> None:
    import shlex

    import click

    from dpp import main

    args = shlex.split(text, comments=True)[1:]
    monkeypatch.chdir(tmp_path)
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    for token in args:  # the files earlier commands of the session would have written
        target = tmp_path / token
        if token.endswith(FILE_SUFFIXES) and not target.exists():
            target.parent.mkdir(parents=True, exist_ok=True)
            target.touch()
    where = f"{path.relative_to(ROOT)}:{number}: {text}"
    command: click.Command = main
    ctx = command.make_context("dpp", list(args), resilient_parsing=False)
    try:
        while isinstance(command, click.Group):
            with warnings.catch_warnings():  # Click 9 moves protected_args into args
                warnings.simplefilter("ignore", DeprecationWarning)
                rest = [*getattr(ctx, "protected_args", ()), *ctx.args]
            assert rest, f"{where}: no subcommand"
            name, sub, rest = command.resolve_command(ctx, rest)
            assert sub is not None, f"{where}: unknown command"
            command, ctx = sub, sub.make_context(name or "", rest, parent=ctx)
    except click.ClickException as exc:
        pytest.fail(f"{where}: {exc.format_message()}")
