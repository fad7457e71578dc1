"""``python -m dppverify``: the checker's commands without the solver.

The same ``certify`` and ``value`` commands as ``dpp certify`` / ``dpp value``, in a tiny
group of their own (:func:`dppverify.cli.main`), so that the checker is usable where the
solver is not installed.
"""

from __future__ import annotations

from dppverify.cli import main

if __name__ == "__main__":
    main(prog_name="python -m dppverify")
