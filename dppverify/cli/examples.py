"""Fixtures for the examples of the CLI modules: a command that shows what an option decorator
passes, and a file with given text in a fresh temporary folder.
"""

from __future__ import annotations

import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

import click

__all__ = ["echo_command", "scratch_file"]


def echo_command(decorate: Callable[[Any], Any], parameter: str,
                 show: Callable[[Any], object] = str) -> click.Command:
    """A command decorated by ``decorate`` that echoes ``show`` of its keyword ``parameter``.

    Examples
    --------
    >>> from click.testing import CliRunner
    >>> cmd = echo_command(click.option("--n", "n", type=int, default=1), "n", repr)
    >>> CliRunner().invoke(cmd, ["--n", "3"]).output
    '3\\n'
    """
    def command(**kwargs: Any) -> None:
        click.echo(show(kwargs[parameter]))

    return click.command()(decorate(command))


def scratch_file(name: str, text: str) -> str:
    """Write ``text`` to a file ``name`` in a new temporary folder and return its path.

    Examples
    --------
    >>> p = scratch_file("a.txt", "hello")
    >>> Path(p).name, Path(p).read_text()
    ('a.txt', 'hello')
    """
    path = Path(tempfile.mkdtemp()) / name
    path.write_text(text)
    return str(path)
