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

``COMMANDS`` is the list the ``dpp`` group (:mod:`dpp`) registers; :func:`main` is the
checker's own group. Commands report :class:`dppverify.errors.CheckerError` subclasses (bad
input) as one line on stderr and exit 2 themselves, so they behave the same inside the
``dpp`` group and in ``python -m dppverify``. ``certify`` exits 0 only when every check
passes, 1 when the profile is refuted, 3 when it could not decide.
"""

from __future__ import annotations

import click

from dppverify import __version__
from dppverify.cli.audit import audit_command
from dppverify.cli.certify import certify_command
from dppverify.cli.check import check_command
from dppverify.cli.errors import CheckerGroup
from dppverify.cli.export_efg import export_efg_command
from dppverify.cli.import_profile import import_profile_command
from dppverify.cli.value import value_command

COMMANDS: list[click.Command] = [certify_command, check_command, value_command, export_efg_command,
                                  import_profile_command, audit_command]
"""The checker's commands, in the order ``--help`` lists them."""


@click.group(cls=CheckerGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="dppverify")
def main() -> None:
    """dppverify: certify DPP game profiles independently of any solver."""


for _command in COMMANDS:
    main.add_command(_command)
