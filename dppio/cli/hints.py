"""What to do next when a file is not what a command expected: the wrong kind of file.

When an instance or profile file cannot be read as one, :func:`file_hint` looks at the start of
the file and says what it is instead — a MovingAI ``.map`` file (use ``--map``), a profile where
an instance belongs or the other way round (arguments swapped), a certificate, a CSV — so the
one-line error says what to do next. Only the first few KiB are read.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Literal

from dppio.examples import display_name
from dppio.inputs import peek_input

Kind = Literal["instance", "profile", "density CSV"]

PEEK_BYTES = 4096
_FORMAT = re.compile(rb'"format"\s*:\s*"([^"]{1,40})"')
_GRAPH = re.compile(rb'"graph"\s*:')


def what_is(path: str | Path) -> str | None:
    """What the file at ``path`` looks like: ``"map"``, ``"instance"``, a document format tag
    such as ``"dpp-profile/1"``, ``"csv"``, or None (unknown or unreadable).

    Examples
    --------
    >>> import os, tempfile
    >>> d = tempfile.mkdtemp()
    >>> for name, text in (("a.map", "type octile\\nheight 1\\nwidth 1\\nmap\\n.\\n"),
    ...                    ("p.json", '{"format": "dpp-profile/1", "goals": {}}'),
    ...                    ("i.json", '{"graph": {"nodes": []}, "start": 0}')):
    ...     with open(os.path.join(d, name), "w") as f:
    ...         _ = f.write(text)
    ...     print(name, what_is(os.path.join(d, name)))
    a.map map
    p.json dpp-profile/1
    i.json instance
    """
    head = peek_input(path, PEEK_BYTES)  # never opens a FIFO or device: that could block
    if head.lstrip().startswith(b"type ") or str(path).lower().endswith(".map"):
        return "map"
    tag = _FORMAT.search(head)
    if tag:
        name = tag.group(1).decode("ascii", "replace")
        return "instance" if "instance" in name else name  # e.g. dpp-map-instance/1
    if _GRAPH.search(head):
        return "instance"
    if head[:1] not in (b"{", b"[", b" ", b"\n") and b"," in head.split(b"\n", 1)[0]:
        return "csv"
    return None


def file_hint(path: str | Path, expected: Kind, command: str = "dpp certify") -> str | None:
    """A one-line hint when the file at ``path`` is clearly not a ``expected`` file.

    Parameters
    ----------
    path : str or Path
        The file given.
    expected : {"instance", "profile", "density CSV"}
        What the command wanted there.
    command : str
        The command, for the hint (e.g. ``"dpp certify"``).

    Returns
    -------
    str or None
        ``PATH is ...: do ...``, or None when the file looks like what was expected (then the
        reader's own message stands).

    Examples
    --------
    >>> import os, tempfile
    >>> folder = tempfile.mkdtemp()
    >>> p = os.path.join(folder, "p.json")
    >>> with open(p, "w") as f:
    ...     _ = f.write('{"format": "dpp-profile/1"}')
    >>> print(file_hint(p, "instance").replace(folder + os.sep, ""))
    p.json is a dpp-profile/1 document, not an instance: are the arguments swapped? \
(dpp certify INSTANCE PROFILE)
    >>> print(file_hint("m.map", "instance", "dpp solve"))  # a .map name suffices
    m.map is a MovingAI .map file: give it as dpp solve --map m.map --start R,C \
--goals R,C R,C --prior P,Q
    >>> file_hint(p, "profile") is None
    True
    """
    kind = what_is(path)
    name = display_name(path)
    if kind is None:
        return None
    if kind == "map":
        if expected == "density CSV":
            return f"{name} is a MovingAI .map file, not a density CSV: make one with " \
                   "dpp experiment density --output-dir DIR (it writes DIR/density.csv)"
        return (f"{name} is a MovingAI .map file: give it as {command} --map {name} "
                "--start R,C --goals R,C R,C --prior P,Q")
    if expected == "instance" and kind.startswith("dpp-") and "certify" not in command:
        return (f"{name} is a {kind} document, not an instance: {command} takes an instance "
                "JSON file (docs/formats.md)")
    if expected == "instance" and kind.startswith("dpp-") and "profile" in kind:
        return (f"{name} is a {kind} document, not an instance: are the arguments swapped? "
                f"({command} INSTANCE PROFILE)")
    if expected == "instance" and kind.startswith("dpp-"):
        return f"{name} is a {kind} document, not an instance"
    if expected == "profile" and kind == "instance":
        return (f"{name} is an instance, not a profile: are the arguments swapped? "
                f"({command} INSTANCE PROFILE; make a profile with dpp solve INSTANCE -o "
                "PROFILE)")
    if expected == "profile" and kind.startswith("dpp-") and "profile" not in kind:
        return f"{name} is a {kind} document, not a profile (make one with dpp solve -o)"
    if expected == "density CSV" and kind != "csv":
        what = "an instance" if kind == "instance" else f"a {kind} document"
        return (f"{name} is {what}, not a density CSV: make one with dpp experiment density "
                "--output-dir DIR (it writes DIR/density.csv)")
    return None


class hinted:
    """Context manager: an error of one of the classes ``errors`` while reading ``path``
    becomes :func:`file_hint`'s hint (the file is of another kind: swapped arguments, a
    ``.map`` file, ...) when it has one, raised as the same class.

    Examples
    --------
    >>> with hinted("/nowhere/x.map", "instance", "dpp solve", errors=(ValueError,)):
    ...     raise ValueError("cannot read /nowhere/x.map")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ValueError: /nowhere/x.map is a MovingAI .map file: give it as dpp solve --map ...
    """

    def __init__(self, path: str, kind: Kind, command: str, *,
                 errors: tuple[type[Exception], ...]) -> None:
        self.path, self.kind, self.command, self.errors = path, kind, command, errors

    def __enter__(self) -> None:
        return None

    def __exit__(self, kind: object, exc: BaseException | None, _traceback: object) -> None:
        if isinstance(exc, self.errors):
            hint = file_hint(self.path, self.kind, self.command)
            if hint is not None:
                raise type(exc)(hint) from None
