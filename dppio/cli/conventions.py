"""The ``dpp`` command-line conventions, in one place (README "Command-line conventions").

- ``-o/--output FILE`` wherever a command writes one file; ``--output-dir DIR`` wherever it
  writes a folder (the old spelling ``--out`` is a hidden, deprecated alias);
- ``--progress/--no-progress`` on every long command, default on only when stderr is a
  terminal; progress bars go to stderr;
- data (tables, JSON, summaries) on stdout; status messages ("wrote ...", warnings) on stderr;
  a result's JSON written with ``-o FILE`` leaves stdout empty (:func:`emit`).

Both the checker's commands and the solver's use these decorators, so the names cannot drift
apart.
"""

from __future__ import annotations

import functools
import json
import sys
import threading
from collections.abc import Callable
from typing import Any, TypeVar

import click

from dppio.files import write_files
from dppio.text import json_escaped, terminal_line, terminal_text

F = TypeVar("F", bound=Callable[..., Any])

PROGRESS_HELP = "Progress bars on stderr (default: only when stderr is a terminal)."


def progress_option(fn: F) -> F:
    """Add ``--progress/--no-progress`` (parameter ``progress``: True, False or None).

    Examples
    --------
    >>> from click.testing import CliRunner
    >>> @click.command()
    ... @progress_option
    ... def show(progress: bool | None) -> None:
    ...     click.echo(repr(progress))
    >>> [CliRunner().invoke(show, args).output.strip() for args in ([], ["--progress"])]
    ['None', 'True']
    """
    return click.option("--progress/--no-progress", "progress", default=None,
                        help=PROGRESS_HELP)(fn)


def want_progress(flag: bool | None) -> bool:
    """The ``--progress/--no-progress`` decision: the flag if given, else whether stderr is a
    terminal.

    Examples
    --------
    >>> want_progress(True), want_progress(False)
    (True, False)
    """
    return sys.stderr.isatty() if flag is None else flag


def status(message: str) -> None:
    """Print a status message ("wrote ...") on stderr, where every ``dpp`` command puts them.

    Examples
    --------
    >>> status("wrote out/p.json")  # goes to stderr, so doctest sees nothing
    """
    click.echo(terminal_line(message), err=True)  # what it quotes cannot forge a line


def emit(doc: Any, text: str, *, as_json: bool, output: str | None, summary: str) -> None:
    """The one output convention of the checker's commands.

    ``-o FILE``: the JSON document is written to FILE (atomically,
    :func:`dppio.files.write_files`) and ``wrote FILE: SUMMARY``
    is the only line, on stderr (stdout stays empty, with or without ``--json``). Otherwise
    stdout gets the JSON (``--json``) or the text.

    Examples
    --------
    >>> emit({"a": 1}, "a = 1", as_json=False, output=None, summary="")
    a = 1
    >>> emit({"a": 1}, "a = 1", as_json=True, output=None, summary="")
    {
      "a": 1
    }
    """
    if output is not None:
        write_files({output: json_escaped(json.dumps(doc, indent=2, ensure_ascii=False)) + "\n"})
        status(f"wrote {output}: {summary}")
    elif as_json:
        click.echo(json_escaped(json.dumps(doc, indent=2, ensure_ascii=False)))
    else:
        click.echo(terminal_text(text))


class _NonEmptyPath(click.Path):
    """A path option that refuses ``''`` (which ``Path('')`` would silently turn into ``.``)."""

    def convert(self, value: Any, param: click.Parameter | None,
                ctx: click.Context | None) -> Any:
        if isinstance(value, str) and value.strip() == "":
            self.fail("the path is empty", param, ctx)
        return super().convert(value, param, ctx)


def _with_deprecated_alias(fn: Any, param: str, old: str, new: str, required: bool,
                           kind: click.ParamType) -> Any:
    """Accept the hidden option ``old`` as a deprecated spelling of ``new`` (``param``)."""
    legacy = f"_deprecated_{param}"

    @functools.wraps(fn)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        old_value = kwargs.pop(legacy, None)
        if old_value is not None:
            if kwargs.get(param) is not None:
                raise click.UsageError(f"give {new} only ({old} is its deprecated spelling)")
            status(f"warning: {old} is deprecated; use {new}")
            kwargs[param] = old_value
        if required and kwargs.get(param) is None:
            raise click.UsageError(f"Missing option {new!r}.")
        return fn(*args, **kwargs)

    return click.option(old, legacy, type=kind, hidden=True)(wrapper)


def output_file_option(help: str, *, required: bool = False,
                       deprecated: str | None = None) -> Callable[[F], F]:
    """Add ``-o/--output FILE`` (parameter ``output``), optionally with a hidden deprecated
    alias such as ``--out``.

    Examples
    --------
    >>> from click.testing import CliRunner
    >>> @click.command()
    ... @output_file_option("The file.", deprecated="--out")
    ... def cmd(output: str | None) -> None:
    ...     click.echo(output)
    >>> CliRunner().invoke(cmd, ["-o", "a.png"]).output
    'a.png\\n'
    >>> r = CliRunner().invoke(cmd, ["--out", "b.png"])
    >>> r.stdout, r.stderr
    ('b.png\\n', 'warning: --out is deprecated; use --output\\n')
    """
    kind = _NonEmptyPath(dir_okay=False)

    def decorate(fn: F) -> F:
        if deprecated is not None:
            fn = _with_deprecated_alias(fn, "output", deprecated, "--output", required, kind)
        # with the deprecated alias the wrapper enforces `required` (either spelling counts),
        # so the help says it as click does for a required option
        shown = f"{help}  [required]" if required and deprecated is not None else help
        return click.option("-o", "--output", "output", type=kind,
                            required=required and deprecated is None, help=shown)(fn)

    return decorate


def output_dir_option(help: str, *, default: str | None = None,
                      deprecated: str | None = "--out") -> Callable[[F], F]:
    """Add ``--output-dir DIR`` (parameter ``output_dir``) with the hidden deprecated alias
    ``--out``.

    Examples
    --------
    >>> from click.testing import CliRunner
    >>> @click.command()
    ... @output_dir_option("Where to write.", default="out/x")
    ... def cmd(output_dir: str) -> None:
    ...     click.echo(output_dir)
    >>> [CliRunner().invoke(cmd, a).stdout for a in ([], ["--output-dir", "d"], ["--out", "e"])]
    ['out/x\\n', 'd\\n', 'e\\n']
    """
    kind = _NonEmptyPath(file_okay=False)

    def decorate(fn: F) -> F:
        if deprecated is not None:
            inner = fn

            @functools.wraps(inner)
            def with_default(*args: Any, **kwargs: Any) -> Any:
                if kwargs.get("output_dir") is None:
                    kwargs["output_dir"] = default
                return inner(*args, **kwargs)

            fn = _with_deprecated_alias(with_default, "output_dir", deprecated,
                                        "--output-dir", False, kind)
        shown = f"{help} [default: {default}]" if default is not None else help
        return click.option("--output-dir", "output_dir", type=kind, default=None,
                            help=shown)(fn)

    return decorate


class PhaseBar:
    """``--progress`` for a command made of a few phases: a status line on stderr shown at
    once and naming the current phase with the elapsed time (the phases' own bars, if any,
    appear below it). Does nothing when ``show`` is False.

    The elapsed time keeps counting during a long phase: a daemon thread redraws the line
    every ``interval`` seconds until :meth:`close` (a phase that computes for minutes
    without a bar of its own no longer shows a frozen ``[00:05]``).

    Examples
    --------
    >>> bar = PhaseBar(False, "solve", "reading the instance")
    >>> bar.phase("solving"); bar.close()
    """

    def __init__(self, show: bool, command: str, first: str, *,
                 interval: float = 1.0) -> None:
        self.command = command
        self.bar: Any = None
        self._stop = threading.Event()
        self._lock = threading.Lock()
        self._ticker: threading.Thread | None = None
        if show:
            from tqdm import tqdm

            self.bar = tqdm(total=None, desc=f"{command}: {first}", file=sys.stderr,
                            leave=False, bar_format="{desc} [{elapsed}]")
            self.bar.refresh()
            self._ticker = threading.Thread(target=self._tick, args=(interval,),
                                            name="PhaseBar", daemon=True)
            self._ticker.start()

    def _tick(self, interval: float) -> None:
        """Redraw the line (its elapsed time) until :meth:`close`."""
        while not self._stop.wait(interval):
            with self._lock:
                if self.bar is not None:
                    self.bar.refresh()

    def phase(self, name: str) -> None:
        """Name the next phase."""
        with self._lock:
            if self.bar is not None:
                self.bar.set_description_str(f"{self.command}: {name}")

    def close(self) -> None:
        """Stop the clock and remove the line (idempotent)."""
        self._stop.set()
        if self._ticker is not None:
            self._ticker.join()
            self._ticker = None
        with self._lock:
            if self.bar is not None:
                self.bar.close()
                self.bar = None
