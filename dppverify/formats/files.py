"""The checker's file I/O at the edges: the shared rules of :mod:`dppio.files`, raising the
checker's :class:`OutputError`.

Every file the checker's commands write goes through :func:`write_files` (all files of one
command committed together or not at all, missing folders created and removed again on
failure, special files such as ``/dev/null`` streamed into, mode ``0666`` minus the umask;
the README's output policy, "Exit codes, limits and output files"), and every file it reads
through :func:`read_input` (larger than :data:`dppio.limits.MAX_INPUT_BYTES` refused without
reading it whole, a FIFO nobody writes read as empty). The rules live once, in
:mod:`dppio.files`, shared with the solver; this module only names the checker's error class.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

from dppio import files as _files
from dppio.inputs import read_input as read_input  # the checker's modules read through here
from dppverify.errors import CheckerError


class OutputError(CheckerError, OSError):
    """An output location cannot be written (missing permission, full disk, a folder...)."""


def write_files(files: Mapping[Any, str | bytes], *,
                remove: Iterable[str | Path] = ()) -> tuple[Path, ...]:
    """Write several files together, all of them or none (:func:`dppio.files.write_files`).

    Examples
    --------
    >>> write_files({"": "x"})
    Traceback (most recent call last):
    dppverify.formats.files.OutputError: the output path is empty
    """
    return _files.write_files(files, remove=remove, error=OutputError)


def refuse_input_as_output(output: str | Path | None, inputs: Iterable[str | Path | None], *,
                           option: str = "-o") -> None:
    """Refuse an output path that names one of the inputs
    (:func:`dppio.files.refuse_input_as_output`).

    Examples
    --------
    >>> refuse_input_as_output("out.json", [None, ""])
    >>> refuse_input_as_output("dppverify", ["dppverify/."], option="--out")
    """
    _files.refuse_input_as_output(output, inputs, option=option, error=OutputError)
