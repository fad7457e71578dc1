"""How a ``dpp`` command fails: one line on stderr and an exit code, never a traceback.

:class:`ErrorReportingGroup` is the click group of every ``dpp`` command: an error of a class
in :attr:`~ErrorReportingGroup.user_errors` (bad input) is one line and exit 2 (or what the
group's :meth:`~ErrorReportingGroup.report` says: the checker's group has exit 3 for "could
not decide"), an internal failure one line and exit 3, a signal one line and ``128 + n``, a
standard output that cannot be written one line (a closed pipe: none) and its exit code.
Every command runs in a :func:`dppio.inputs.reading_once` block (each input read once; ``-``
is standard input, for one input only).
"""

from __future__ import annotations

import os
from typing import Any, NoReturn

import click

from dppio.cli.interrupts import Terminated, as_signal, exit_code, signals_as_exceptions
from dppio.cli.interrupts import message as interrupt_message
from dppio.cli.streams import (
    StreamError,
    flush_stdout,
    silence_stdout,
    standard_streams,
    stream_failure,
)
from dppio.errors import DppioError
from dppio.inputs import STDIN, reading_once
from dppio.memory import memory_limit_text
from dppio.text import terminal_line

OUTPUT_OPTIONS = frozenset({"-o", "--output", "--out", "--save-instance"})
"""The options whose value names an output: ``-`` after one of them is standard output."""


class ErrorReportingGroup(click.Group):
    """A click group for the ``dpp`` commands: bad input is one line and exit 2.

    Errors of the classes in :attr:`user_errors` are the user's (bad input), reported by
    :meth:`report`: one line on stderr, ``error: ...``, exit code 2. Anything else is an
    internal failure: one line, exit code 3, no traceback (set ``DPP_DEBUG=1`` to see it).
    Subclasses add their package's error classes and may report them otherwise.
    """

    user_errors: tuple[type[Exception], ...] = (DppioError,)

    def report(self, exc: Exception) -> NoReturn:
        """Report a user error in one line and exit (:func:`fail`)."""
        fail(exc)

    def main(self, *args: Any, **kwargs: Any) -> Any:
        """Run the command with SIGINT/SIGTERM/SIGHUP as exceptions (dppio.cli.interrupts):
        a signal ends it after cleaning up, with one line and exit code 128 + n; with the
        standard streams guarded (dppio.cli.streams): standard output that cannot be
        written ends it with one line (a closed pipe: quietly, 141), never a traceback."""
        with standard_streams(), signals_as_exceptions():
            try:
                try:
                    return super().main(*args, **kwargs)
                finally:
                    flush_stdout()
            except Terminated as exc:  # a signal outside invoke (e.g. while parsing)
                click.echo(interrupt_message(exc), err=True)
                raise SystemExit(exit_code(exc)) from None
            except StreamError as exc:  # standard output failed (at the last flush)
                raise SystemExit(_stream_exit(exc)) from None

    def parse_args(self, ctx: click.Context, args: list[str]) -> list[str]:
        words = args[:args.index("--")] if "--" in args else args
        inputs = [w for i, w in enumerate(words)  # `-o -` is standard output, not an input
                  if w == STDIN and (i == 0 or words[i - 1] not in OUTPUT_OPTIONS)]
        if len(inputs) > 1:  # one stream, one input (dppio.inputs)
            click.echo(f"error: {STDIN} (standard input) can stand for one input only, "
                       f"got it {len(inputs)} times", err=True)
            ctx.exit(2)
        try:
            return super().parse_args(ctx, args)
        except click.UsageError as exc:
            _usage_error(exc)
            ctx.exit(2)
            raise  # pragma: no cover - ctx.exit raises

    def invoke(self, ctx: click.Context) -> Any:
        try:
            with reading_once():  # each input read once: what is hashed is what was parsed
                return super().invoke(ctx)
        except self.user_errors as exc:
            self.report(exc)
        except click.UsageError as exc:  # click's three-line usage message, as one line
            _usage_error(exc)
            ctx.exit(2)
        except (KeyboardInterrupt, Terminated) as exc:  # one line, 130 / 143, cleaned up
            click.echo(interrupt_message(exc), err=True)
            ctx.exit(exit_code(exc))
        except StreamError as exc:  # standard output failed: one line (or none), no traceback
            ctx.exit(_stream_exit(exc))
        except MemoryError:  # the input needs more memory than this process may have
            ctx.exit(_memory_exit())
        except (click.exceptions.Exit, click.ClickException, click.Abort):
            raise
        except Exception as exc:
            if (sig := as_signal(exc)) is not None:  # a library turned the signal into this
                click.echo(interrupt_message(sig), err=True)
                ctx.exit(exit_code(sig))
            if os.environ.get("DPP_DEBUG"):
                raise
            click.echo(terminal_line(f"internal error: {type(exc).__name__}: {exc} "
                                     "(set DPP_DEBUG=1 for details)"), err=True)
            ctx.exit(3)


def _stream_exit(exc: StreamError) -> int:
    """Report a failed standard output (dppio.cli.streams) and give the exit code."""
    line, code = stream_failure(exc)
    silence_stdout()
    if line is not None:
        click.echo(line, err=True)
    return code


def _memory_exit() -> int:
    """Report an exhausted memory in one line; exit code 2, as for an input beyond a limit."""
    click.echo("error: out of memory: this input needs more memory than this process may use "
               f"({memory_limit_text()}); give a smaller input (docs/limits.md, 'Sizes and "
               "memory')", err=True)
    return 2


def _usage_error(exc: click.UsageError) -> None:
    """One line for a click usage error: the message and where to find help."""
    where = exc.ctx.command_path if exc.ctx is not None else "dpp"
    if isinstance(exc, click.exceptions.NoArgsIsHelpError):  # `dpp plot`: no help dump
        click.echo(f"error: missing command (see '{where} --help')", err=True)
        return
    message = " ".join(exc.format_message().split())
    click.echo(terminal_line(f"error: {message} (see '{where} --help')"), err=True)


def fail(exc: Exception, *, line: str | None = None, code: int = 2) -> NoReturn:
    """Report a user error in one line and exit: the signal's line and ``128 + n`` when the
    error stands for an interruption, else ``line`` (default ``error: MESSAGE``, the message on
    one line) and exit code ``code``.

    Examples
    --------
    >>> try:
    ...     fail(ValueError("no such option"))
    ... except click.exceptions.Exit as exc:
    ...     print("exit", exc.exit_code)
    exit 2
    """
    if (sig := as_signal(exc)) is not None:  # interrupted: the signal's line and code
        click.echo(interrupt_message(sig), err=True)
        raise click.exceptions.Exit(exit_code(sig))
    click.echo(terminal_line(f"error: {' '.join(str(exc).split())}") if line is None else line,
               err=True)
    raise click.exceptions.Exit(code)
