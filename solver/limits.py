"""The solver's input limits, in one place (listed in the README, "Limits").

Beyond each limit the solver refuses with one line (exit code 2) instead of hanging or
exhausting memory. The checker keeps its own copy (``dppverify/limits.py``; the packages
share no code) with the same values, and the hostile-input suite checks both.

Examples
--------
>>> check_numeral("1e999999999", where="weight")  # doctest: +ELLIPSIS
Traceback (most recent call last):
solver.errors.InvalidInstanceError: weight: the exponent of '1e999999999' is beyond ...
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterable
from fractions import Fraction
from pathlib import Path
from typing import BinaryIO

from solver.errors import InvalidInstanceError

__all__ = [
    "MAX_DENSITY_GRIDS",
    "MAX_DENSITY_SIZE",
    "MAX_EXPONENT",
    "MAX_FLOAT_WEIGHT_RATIO",
    "MAX_INPUT_BYTES",
    "MAX_JSON_DEPTH",
    "MAX_MAP_CELLS",
    "MAX_NUMBER_DIGITS",
    "MAX_NUMERAL_CHARS",
    "MAX_PREFIXES_LIMIT",
    "check_float_weights",
    "check_numeral",
    "check_rational",
    "open_input",
]

MAX_INPUT_BYTES = 64 * 1024 * 1024
"""Largest instance JSON or ``.map`` file read (bytes): 64 MiB."""

MAX_JSON_DEPTH = 64
"""Deepest nesting of JSON arrays/objects in a document."""

MAX_NUMERAL_CHARS = 1000
"""Longest numeral (a JSON number literal or an exact string such as ``"p/q"``)."""

MAX_EXPONENT = 400
"""Largest decimal exponent written in a numeral."""

MAX_NUMBER_DIGITS = 200
"""Every number is a rational p/q with |p| and q below 10**200 (after reduction)."""

MAX_DENSITY_SIZE = 200
"""Largest grid side of ``dpp experiment density --size``."""

MAX_DENSITY_GRIDS = 100_000
"""Most grids of one density sweep (samples x densities)."""

MAX_FLOAT_WEIGHT_RATIO = 10**6
"""Float mode (``"numbers": "float"``): largest / smallest edge weight. Float comparisons use
a tolerance of 1e-9 relative to the largest weight, so a smaller weight must stay far above
it; exact weights have no such limit."""

MAX_MAP_CELLS = 4_000_000
"""Largest grid of a ``--map`` (rows x columns, obstacles included): a 2000 x 2000 map. Larger
maps are refused before any array is allocated (the memory budget: about 1 GiB per
4 million cells for the checker's structured route)."""

MAX_PREFIXES_LIMIT = 10**7
"""Largest ``--max-prefixes`` accepted: a walk tree of 10**7 prefixes already takes several
GiB in the tree route's LP."""

_NUMERAL = re.compile(r"\s*[-+]?(\d*)(?:\.(\d*))?(?:[eE]([-+]?\d+))?\s*")


def check_numeral(text: str, *, where: str) -> None:
    """Refuse a numeral whose length or written exponent is beyond the limits.

    Examples
    --------
    >>> check_numeral("3/5", where="prior[0]")
    """
    if len(text) > MAX_NUMERAL_CHARS:
        raise InvalidInstanceError(f"{where}: a numeral of {len(text)} characters is beyond "
                                   f"the limit of {MAX_NUMERAL_CHARS}")
    for part in text.split("/", 1):
        m = _NUMERAL.fullmatch(part)
        if m and m.group(3) is not None and abs(int(m.group(3))) > MAX_EXPONENT:
            raise InvalidInstanceError(f"{where}: the exponent of {text!r} is beyond the limit "
                                       f"of {MAX_EXPONENT}")


def check_rational(x: object, *, where: str) -> None:
    """Refuse an exact number with more than :data:`MAX_NUMBER_DIGITS` digits above or below
    the fraction bar.

    Examples
    --------
    >>> check_rational(10 ** 400, where="weight")
    Traceback (most recent call last):
    solver.errors.InvalidInstanceError: weight: 10**400 or more is beyond the limit of 10**200
    """
    if not isinstance(x, int | Fraction):
        return
    bound = 10 ** MAX_NUMBER_DIGITS
    f = Fraction(x)
    if abs(f.numerator) >= bound or f.denominator >= bound:
        big = max(abs(f.numerator), f.denominator)
        raise InvalidInstanceError(f"{where}: 10**{len(str(big)) - 1} or more is beyond the "
                                   f"limit of 10**{MAX_NUMBER_DIGITS}")


def check_float_weights(weights: Iterable[float | Fraction | int], *,
                        where: str = "graph.edges") -> None:
    """Refuse float-mode weights whose ratio largest / smallest is beyond
    :data:`MAX_FLOAT_WEIGHT_RATIO`.

    Raises
    ------
    InvalidInstanceError
        One line naming the limit.

    Examples
    --------
    >>> check_float_weights([1.0, 2 ** 0.5])
    >>> check_float_weights([1.0, 1e300])
    Traceback (most recent call last):
    solver.errors.InvalidInstanceError: graph.edges: float weights span a ratio of 1e+300 \
(1e+00 to 1e+300), beyond the float-mode limit of 10**6; give exact weights
    """
    lo = hi = None
    for w in weights:
        x = float(w)
        lo = x if lo is None or x < lo else lo
        hi = x if hi is None or x > hi else hi
    if lo is None or hi is None or lo <= 0:
        return
    if hi / lo > MAX_FLOAT_WEIGHT_RATIO:
        raise InvalidInstanceError(f"{where}: float weights span a ratio of {hi / lo:.0e} "
                                   f"({lo:.0e} to {hi:.0e}), beyond the float-mode limit of "
                                   "10**6; give exact weights")


def open_input(path: str | Path) -> BinaryIO:
    """Open an input file for reading; a FIFO that nobody writes reads as empty instead of
    blocking (opened non-blocking, then switched back to blocking reads).

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     os.mkfifo(Path(d) / "fifo")
    ...     with open_input(Path(d) / "fifo") as fh:
    ...         fh.read()
    b''
    """
    fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_NOCTTY", 0))
    try:
        os.set_blocking(fd, True)
        return os.fdopen(fd, "rb")
    except BaseException:
        os.close(fd)
        raise
