"""``python -m dpp``: the ``dpp`` command."""

from dpp import main

main()
