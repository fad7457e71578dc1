"""The conventions every ``dpp`` command follows, shared by the solver's commands and the
checker's (neither command line imports the other's; the ``dpp`` group is :mod:`dpp`).

One module per concern: :mod:`~dppio.cli.conventions` (``-o``, ``--output-dir``,
``--progress``, status lines, the phase bar, the output rule), :mod:`~dppio.cli.errors` (the
error-reporting click group: one line and an exit code per failure),
:mod:`~dppio.cli.interrupts` (signals as clean exits), :mod:`~dppio.cli.streams` (standard
streams that fail in one line), :mod:`~dppio.cli.hints` (what a file of the wrong kind is) and
:mod:`~dppio.cli.map_options` (the ``--map`` option group; each package reads the map itself).
"""
