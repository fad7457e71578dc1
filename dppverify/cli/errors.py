"""How the checker's commands fail: one line on stderr and an exit code, never a traceback.

:class:`ErrorReportingGroup` is the click group of ``dpp`` and ``python -m dppverify``: a
:class:`~dppverify.errors.CheckerError` (bad input) is ``error: ...`` and exit 2, an
:class:`~dppverify.errors.UndecidedError` is ``undecided: ...`` and exit 3, an internal
failure one line and exit 3, a signal one line and ``128 + n``. Commands report their own
errors with :func:`fail`, so that they behave the same inside either group. Every command
runs in a :func:`dppio.inputs.reading_once` block (each input read once; ``-`` is standard
input, for one input only).
"""

from __future__ import annotations

import os
from typing import Any, NoReturn

import click

from dppio.inputs import STDIN, reading_once
from dppio.memory import memory_limit_text
from dppio.text import terminal_line
from dppverify.cli.interrupts import Terminated, as_signal, exit_code, signals_as_exceptions
from dppverify.cli.interrupts import message as interrupt_message
from dppverify.cli.streams import (
    StreamError,
    flush_stdout,
    silence_stdout,
    standard_streams,
    stream_failure,
)
from dppverify.errors import CheckerError, LPError, UndecidedError

__all__ = ["OUTPUT_OPTIONS", "ErrorReportingGroup", "error_code", "error_line", "fail"]

OUTPUT_OPTIONS = frozenset({"-o", "--output", "--out", "--save-instance"})
"""The options whose value names an output: ``-`` after one of them is standard output."""


class ErrorReportingGroup(click.Group):
    """A click group for the ``dpp`` commands: bad input is one line and exit 2.

    Errors of the classes in :attr:`user_errors` are the user's (bad input): one line on
    stderr, ``error: ...``, exit code 2. Anything else is an internal failure: one line, exit
    code 3, no traceback (set ``DPP_DEBUG=1`` to see it). Subclasses add their package's error
    classes (``dpp``'s group adds the solver's).
    """

    user_errors: tuple[type[Exception], ...] = (CheckerError,)

    def main(self, *args: Any, **kwargs: Any) -> Any:
        """Run the command with SIGINT/SIGTERM/SIGHUP as exceptions (dppverify.cli.interrupts):
        a signal ends it after cleaning up, with one line and exit code 128 + n; with the
        standard streams guarded (dppverify.cli.streams): standard output that cannot be
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
            fail(exc)
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
    """Report a failed standard output (dppverify.cli.streams) and give the exit code."""
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


def error_code(exc: Exception) -> int:
    """The exit code of an error: 3 ("could not decide") when a numerical solver failed on
    input that passed every check (:class:`~dppverify.errors.LPError`), else 2 (bad input).

    Examples
    --------
    >>> from dppverify.errors import OptionError
    >>> error_code(LPError("x")), error_code(OptionError("y"))
    (3, 2)
    """
    return 3 if isinstance(exc, LPError) else 2


def error_line(exc: Exception) -> str:
    """The one line printed for an error (:func:`error_code` tells its exit code).

    Examples
    --------
    >>> error_line(LPError("value LP: CLARABEL returned status 'infeasible'"))
    "error: could not decide: value LP: CLARABEL returned status 'infeasible' (a numerical \
failure of the checker on a valid input, not an error in it)"
    """
    text = " ".join(str(exc).split())
    if isinstance(exc, LPError):
        return terminal_line(f"error: could not decide: {text} (a numerical failure of the "
                             "checker on a valid input, not an error in it)")
    return terminal_line(f"error: {text}")


def fail(exc: Exception) -> NoReturn:
    """Report a user error in one line and exit: ``undecided: ...`` (exit 3) for an
    :class:`~dppverify.errors.UndecidedError`, the signal's line and ``128 + n`` when the error
    stands for an interruption, else :func:`error_line` and :func:`error_code`.

    Examples
    --------
    >>> from dppverify.errors import OptionError
    >>> try:
    ...     fail(OptionError("no such option"))
    ... except click.exceptions.Exit as exc:
    ...     print("exit", exc.exit_code)
    exit 2
    """
    if isinstance(exc, UndecidedError):  # "could not decide": exit 3, never a verdict
        click.echo(terminal_line(f"undecided: {' '.join(str(exc).split())}"), err=True)
        raise click.exceptions.Exit(3)
    if (sig := as_signal(exc)) is not None:  # interrupted: the signal's line and code
        click.echo(interrupt_message(sig), err=True)
        raise click.exceptions.Exit(exit_code(sig))
    click.echo(error_line(exc), err=True)
    raise click.exceptions.Exit(error_code(exc))

