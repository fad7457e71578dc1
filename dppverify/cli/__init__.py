"""The checker's command line: ``python -m dppverify`` and the checker's ``dpp`` commands.

One module per command: :mod:`~dppverify.cli.certify` (``certify``),
:mod:`~dppverify.cli.check` (``check``: the trusted kernel in its own process),
:mod:`~dppverify.cli.value` (``value``), :mod:`~dppverify.cli.export_efg` (``export-efg``),
:mod:`~dppverify.cli.import_profile` (``import-profile``), :mod:`~dppverify.cli.audit`
(``audit``); what they share of their own:
:mod:`~dppverify.cli.errors` (the checker's errors as one line and an exit code),
:mod:`~dppverify.cli.inputs` (the horizon, the instance, read errors as hints),
:mod:`~dppverify.cli.map_options` (``--map``, read by the checker), :mod:`~dppverify.cli.table`
(the certificate as text). The conventions every ``dpp`` command follows are
:mod:`dppio.cli`; this package imports nothing of the solver.

``HOMES`` names the commands the ``dpp`` group (:mod:`dpp`) registers (``COMMANDS``: the
command objects); :func:`main` is the checker's own group. Commands report
:class:`dppverify.errors.CheckerError` subclasses (bad input) as one line on stderr and exit 2
themselves, so they behave the same inside the ``dpp`` group and in ``python -m dppverify``.
``certify`` exits 0 only when every check passes, 1 when the profile is refuted, 3 when it
could not decide.
"""

from __future__ import annotations

from typing import Any

import click

from dppio.cli.lazy import LazyCommands
from dppverify import __version__
from dppverify.cli.errors import CheckerGroup

HOMES: dict[str, tuple[str, str]] = {
    "certify": ("dppverify.cli.certify", "certify_command"),
    "check": ("dppverify.cli.check", "check_command"),
    "value": ("dppverify.cli.value", "value_command"),
    "export-efg": ("dppverify.cli.export_efg", "export_efg_command"),
    "import-profile": ("dppverify.cli.import_profile", "import_profile_command"),
    "audit": ("dppverify.cli.audit", "audit_command"),
}
"""The checker's commands by name, in the order ``--help`` lists them: each one's module and
attribute, imported when the command runs (:class:`dppio.cli.lazy.LazyCommands`)."""


@click.group(cls=CheckerGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="dppverify")
def main() -> None:
    """dppverify: certify DPP game profiles independently of any solver."""


main.commands = LazyCommands(HOMES)


def __getattr__(name: str) -> Any:
    """``COMMANDS``: the checker's commands (all imported), in ``HOMES`` order."""
    if name != "COMMANDS":
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    return [main.commands[n] for n in HOMES]
