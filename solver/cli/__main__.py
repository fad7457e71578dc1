"""``python -m solver.cli``: the ``dpp`` command."""

from solver.cli import main

if __name__ == "__main__":  # importing the module (autosummary, doctests) runs nothing
    main()
