"""Single-threaded BLAS for the ``dpp`` command, set before numpy is imported.

The matrices of this project are small (the N-goal coalition DP's per-layer products are at
most a few thousand rows wide): a second BLAS thread costs more in start-up and hand-over than
it saves (measured: the N = 5 coalition DP on room-32-32-4 runs about twice as fast with one
thread on the 2-core benchmark machine; docs/benchmarks.md). ``solver.cli`` imports this module
first, so the ``dpp`` process starts with ``OPENBLAS_NUM_THREADS``, ``OMP_NUM_THREADS`` and
``MKL_NUM_THREADS`` set to 1 unless the environment already sets them (a user's choice wins).
Importing the library (``import solver``, ``import dppverify``) changes nothing.

>>> import os
>>> os.environ["OPENBLAS_NUM_THREADS"] != ""
True
"""

from __future__ import annotations

import os

BLAS_THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")
"""The variables set (to ``"1"``) when absent."""

for _name in BLAS_THREAD_VARIABLES:
    os.environ.setdefault(_name, "1")
