"""Checker commands of the ``dpp`` CLI (certify, value, export-efg, audit).

``COMMANDS`` is the list the ``dpp`` group registers. Commands raise
:class:`dppverify.errors.CheckerError` subclasses for bad input; the group prints them
as one line and exits 2.
"""

from __future__ import annotations

import click

__all__ = ["COMMANDS"]

COMMANDS: list[click.Command] = []
