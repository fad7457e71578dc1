"""The checker's numeric and size limits, in one place (listed in the README, "Limits").

Beyond each limit the checker refuses with one line (exit code 2) instead of hanging or
exhausting memory. The solver keeps its own copy of the input limits (``solver/limits.py``):
the two packages never share code, and the hostile-input suite checks that they agree.

Examples
--------
>>> MAX_NUMBER_DIGITS, MAX_EXPONENT, MAX_HORIZON
(200, 400, 10000)
>>> check_numeral("1e999999999", where="weight")
Traceback (most recent call last):
ValueError: weight: the exponent of '1e999999999' is beyond the limit of 400
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from fractions import Fraction

__all__ = [
    "MAX_AUDIT_EXAMPLES",
    "MAX_EXPONENT",
    "MAX_FLOAT_WEIGHT_RATIO",
    "MAX_HORIZON",
    "MAX_INPUT_BYTES",
    "MAX_JSON_DEPTH",
    "MAX_MAP_CELLS",
    "MAX_NUMBER_DIGITS",
    "MAX_NUMERAL_CHARS",
    "MAX_PREFIXES_LIMIT",
    "MAX_TRIALS",
    "check_float_weights",
    "check_numeral",
    "check_rational",
]

MAX_INPUT_BYTES = 64 * 1024 * 1024
"""Largest instance, profile or certificate file read (bytes): 64 MiB."""

MAX_JSON_DEPTH = 64
"""Deepest nesting of JSON arrays/objects in a document."""

MAX_NUMERAL_CHARS = 1000
"""Longest numeral (a JSON number literal or an exact string such as ``"p/q"``)."""

MAX_EXPONENT = 400
"""Largest decimal exponent written in a numeral (``1e400`` is read, ``1e401`` refused)."""

MAX_NUMBER_DIGITS = 200
"""Every number is a rational p/q with |p| and q below 10**200 (after reduction)."""

MAX_HORIZON = 10_000
"""Largest horizon H of a truncated game (``--horizon``)."""

MAX_TRIALS = 10_000
"""Most random attackers per L3/L4 lemma check (``--trials``)."""

MAX_AUDIT_EXAMPLES = 1_000_000
"""Largest example budget of ``dpp audit --examples``."""

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
    """Refuse a numeral whose size alone would make parsing it hang or explode.

    Checks the length (:data:`MAX_NUMERAL_CHARS`) and the written exponent
    (:data:`MAX_EXPONENT`) before anything is converted; ``"p/q"`` strings are checked part by
    part.

    Raises
    ------
    ValueError
        One line naming ``where`` and the limit passed (length or exponent).

    Examples
    --------
    >>> check_numeral("3/5", where="prior[0]")
    >>> check_numeral("1" * 1001, where="w")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ValueError: w: a numeral of 1001 characters is beyond the limit of 1000
    """
    if len(text) > MAX_NUMERAL_CHARS:
        raise ValueError(f"{where}: a numeral of {len(text)} characters is beyond the limit "
                         f"of {MAX_NUMERAL_CHARS}")
    for part in text.split("/", 1):
        m = _NUMERAL.fullmatch(part)
        if m and m.group(3) is not None and abs(int(m.group(3))) > MAX_EXPONENT:
            raise ValueError(f"{where}: the exponent of {text!r} is beyond the limit of "
                             f"{MAX_EXPONENT}")


def check_rational(x: object, *, where: str) -> None:
    """Refuse a rational whose numerator or denominator has more than
    :data:`MAX_NUMBER_DIGITS` digits.

    Raises
    ------
    ValueError
        One line naming ``where``.

    Examples
    --------
    >>> check_rational(Fraction(1, 3), where="prior[0]")
    >>> check_rational(10 ** 400, where="weight")
    Traceback (most recent call last):
    ValueError: weight: 10**400 or more is beyond the limit of 10**200
    """
    if not isinstance(x, int | Fraction):
        return  # floats (float mode) are bounded by their type
    bound = 10 ** MAX_NUMBER_DIGITS
    f = Fraction(x)
    if abs(f.numerator) >= bound or f.denominator >= bound:
        big = max(abs(f.numerator), f.denominator)
        raise ValueError(f"{where}: 10**{len(str(big)) - 1} or more is beyond the limit of "
                         f"10**{MAX_NUMBER_DIGITS}")


def check_float_weights(weights: Iterable[float | Fraction | int], *,
                        where: str = "graph.edges") -> None:
    """Refuse float-mode weights whose ratio largest / smallest is beyond
    :data:`MAX_FLOAT_WEIGHT_RATIO`.

    Raises
    ------
    ValueError
        One line naming the limit.

    Examples
    --------
    >>> check_float_weights([1.0, 2 ** 0.5])
    >>> check_float_weights([1.0, 1e300])
    Traceback (most recent call last):
    ValueError: graph.edges: float weights span a ratio of 1e+300 (1e+00 to 1e+300), beyond \
the float-mode limit of 10**6; give exact weights
    """
    lo = hi = None
    for w in weights:
        x = float(w)
        lo = x if lo is None or x < lo else lo
        hi = x if hi is None or x > hi else hi
    if lo is None or hi is None or lo <= 0:
        return
    if hi / lo > MAX_FLOAT_WEIGHT_RATIO:
        raise ValueError(f"{where}: float weights span a ratio of {hi / lo:.0e} ({lo:.0e} to "
                    f"{hi:.0e}), beyond the float-mode limit of 10**6; give exact weights")
