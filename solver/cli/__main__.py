"""``python -m solver.cli``: the ``dpp`` command."""

from solver.cli import main

main()
