"""A click group's commands, each imported from its module on first use.

The ``dpp`` group (:mod:`dpp`) and ``python -m dppverify`` name their commands here by module
and attribute: starting a command imports that command's module alone, not every other
command's (``dpp check`` starts in a fraction of the time the whole command line takes to
import). ``dpp --help`` imports them all, for their short help.
"""

from __future__ import annotations

import importlib
from collections.abc import Iterator, Mapping
from typing import Any

import click

Homes = Mapping[str, tuple[str, str]]
"""A command's name -> (its module, the attribute that holds the click command)."""


class LazyCommands(dict[str, click.Command]):
    """The ``commands`` mapping of a :class:`click.Group`, filled on demand from ``homes``.

    Examples
    --------
    >>> commands = LazyCommands({"check": ("dppverify.cli.check", "check_command")})
    >>> list(commands), dict.__len__(commands)   # named, not yet imported
    (['check'], 0)
    >>> commands["check"].name, dict.__len__(commands)
    ('check', 1)
    >>> commands.get("nope") is None
    True
    """

    def __init__(self, homes: Homes) -> None:
        super().__init__()
        self._homes = dict(homes)

    def _load(self, name: str) -> click.Command:
        module, attribute = self._homes[name]
        command: click.Command = getattr(importlib.import_module(module), attribute)
        dict.__setitem__(self, name, command)
        return command

    def __getitem__(self, name: str) -> click.Command:
        if dict.__contains__(self, name):
            return dict.__getitem__(self, name)
        if name not in self._homes:
            raise KeyError(name)
        return self._load(name)

    def get(self, name: str, default: Any = None) -> Any:
        """The command ``name`` (imported now if it was not), or ``default``."""
        try:
            return self[name]
        except KeyError:
            return default

    def __setitem__(self, name: str, command: click.Command) -> None:
        self._homes.pop(name, None)
        dict.__setitem__(self, name, command)

    def __contains__(self, name: object) -> bool:
        return name in self._homes or dict.__contains__(self, name)

    def __iter__(self) -> Iterator[str]:
        return iter([*self._homes, *(n for n in dict.keys(self) if n not in self._homes)])

    def __len__(self) -> int:
        return len(list(iter(self)))

    def keys(self) -> Any:
        """Every command's name (nothing is imported)."""
        return list(iter(self))

    def values(self) -> Any:
        """Every command (all imported)."""
        return [self[n] for n in self]

    def items(self) -> Any:
        """Every ``(name, command)`` (all imported)."""
        return [(n, self[n]) for n in self]
