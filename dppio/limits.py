"""The numeric and size limits both packages enforce, in one place (README, "Limits").

Beyond each limit the solver and the checker refuse with one line (exit code 2) instead of
hanging or exhausting memory. The values, the checks that refuse a numeral *before* it is
parsed and the check of a parsed JSON document's nesting depth live here once; each package
keeps its own limits of its own options (``solver/limits.py``, ``dppverify/limits.py``) and
its own parsers.

Every check raises ``error(message)``: :class:`~dppio.errors.LimitError` by default, or the
caller's own error class (the solver raises its ``InvalidInstanceError``).

Examples
--------
>>> MAX_NUMBER_DIGITS, MAX_EXPONENT
(200, 400)
>>> check_numeral("1e999999999", where="weight")
Traceback (most recent call last):
dppio.errors.LimitError: weight: the exponent of '1e999999999' is beyond the limit of 400
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable
from fractions import Fraction
from typing import Any

from dppio.errors import ErrorClass, LimitError
from dppio.text import decimal

MAX_INPUT_BYTES = 64 * 1024 * 1024
"""Largest input file read (instance, profile, certificate, ``.map``, ``.scen``, CSV): 64 MiB."""

MAX_JSON_DEPTH = 64
"""Deepest nesting of JSON arrays/objects in a document."""

MAX_NUMERAL_CHARS = 1000
"""Longest numeral (a JSON number literal or an exact string such as ``"p/q"``)."""

MAX_EXPONENT = 400
"""Largest decimal exponent written in a numeral (``1e400`` is read, ``1e401`` refused)."""

MAX_NUMBER_DIGITS = 200
"""Every number is a rational p/q with abs(p) and q below 10**200 (after reduction)."""

MAX_COMMON_DENOMINATOR_DIGITS = 100
"""The numbers of one instance (its edge weights and its prior, together) have a common
denominator below 10**100: each number within its own limit, a few hundred weights with
distinct large denominators would otherwise make every distance a fraction of thousands of
digits (minutes of arithmetic, values no profile can state within its own limits)."""

MAX_DISTRIBUTION_DENOMINATOR_DIGITS = 1000
"""The probabilities of one distribution in a profile (a mixture over walks, a Defender's
allocation, a choice of goal) have a common denominator below 10**1000: the sum that is
checked against 1 stays a number of at most that size, however many entries it has."""

MAX_FLOAT_WEIGHT_RATIO = 10**6
"""Float mode (``"numbers": "float"``): largest / smallest edge weight. Float comparisons use
a tolerance of 1e-9 relative to the largest weight, so a smaller weight must stay far above
it; exact weights have no such limit."""

MAX_MAP_CELLS = 4_000_000
"""Largest grid of a ``--map`` (rows x columns, obstacles included): a 2000 x 2000 map. Larger
maps are refused before any array is allocated; within it, the memory a game on the map
needs is estimated and checked against what the process may use (:mod:`dppio.memory`,
measured: about 1 GiB per million free cells for the checker's structured route)."""

MAX_PREFIXES_LIMIT = 10**7
"""Largest ``--max-prefixes`` accepted: a walk tree of 10**7 prefixes already takes several
GiB in the tree route's LP."""

_NUMERAL = re.compile(r"\s*[-+]?(\d*)(?:\.(\d*))?(?:[eE]([-+]?\d+))?\s*")


def check_numeral(text: str, *, where: str, error: ErrorClass = LimitError) -> None:
    """Refuse a numeral whose size alone would make parsing it hang or explode.

    Checks the length (:data:`MAX_NUMERAL_CHARS`) and the written exponent
    (:data:`MAX_EXPONENT`) before anything is converted; ``"p/q"`` strings are checked part by
    part.

    Raises
    ------
    LimitError
        (or ``error``) One line naming ``where``.

    Examples
    --------
    >>> check_numeral("3/5", where="prior[0]")
    >>> check_numeral("1" * 1001, where="w", error=ValueError)
    Traceback (most recent call last):
    ValueError: w: a numeral of 1001 characters is beyond the limit of 1000
    >>> check_numeral("\u0663/5", where="prior[0]")
    Traceback (most recent call last):
    dppio.errors.LimitError: prior[0]: '\u0663/5' is not a number (ASCII digits, no '_')
    """
    if len(text) > MAX_NUMERAL_CHARS:
        raise error(f"{where}: a numeral of {len(text)} characters is beyond the limit "
                    f"of {MAX_NUMERAL_CHARS}")
    if not text.isascii() or "_" in text:  # Python reads '١' and '1_0' as numbers; we do not
        raise error(f"{where}: {text[:40]!a} is not a number (ASCII digits, no '_')")
    for part in text.split("/", 1):
        m = _NUMERAL.fullmatch(part)
        if m and m.group(3) is not None and abs(int(m.group(3))) > MAX_EXPONENT:
            raise error(f"{where}: the exponent of {text!r} is beyond the limit of "
                        f"{MAX_EXPONENT}")


def common_denominator(denominators: Iterable[int], *, where: str,
                       digits: int = MAX_COMMON_DENOMINATOR_DIGITS,
                       error: ErrorClass = LimitError) -> int:
    """The least common multiple of ``denominators``, refused (``error``, one line naming
    ``where``) once it reaches ``10**digits``: computed step by step, it never grows past the
    bound, so a long list of large coprime denominators costs no more than a short one.

    Examples
    --------
    >>> common_denominator([2, 3, 4], where="weights")
    12
    >>> common_denominator([10**60 + 1, 10**60 + 3], where="weights")
    Traceback (most recent call last):
    dppio.errors.LimitError: weights: the numbers' common denominator reaches 10**100, beyond \
the limit (each number is within its own)
    """
    bound, m = 10 ** digits, 1
    for d in set(denominators):
        if m % d:
            m = math.lcm(m, d)
            if m >= bound:
                raise error(f"{where}: the numbers' common denominator reaches 10**{digits}, "
                            "beyond the limit (each number is within its own)")
    return m


def check_rational(x: object, *, where: str, error: ErrorClass = LimitError) -> None:
    """Refuse a rational whose numerator or denominator has more than
    :data:`MAX_NUMBER_DIGITS` digits: ``error`` (default :class:`~dppio.errors.LimitError`),
    one line naming ``where``.

    Examples
    --------
    >>> check_rational(Fraction(1, 3), where="prior[0]")
    >>> check_rational(10 ** 400, where="weight")
    Traceback (most recent call last):
    dppio.errors.LimitError: weight: 10**400 or more is beyond the limit of 10**200
    """
    if not isinstance(x, int | Fraction):
        return  # floats (float mode) are bounded by their type
    bound = 10 ** MAX_NUMBER_DIGITS
    f = Fraction(x)
    if abs(f.numerator) >= bound or f.denominator >= bound:
        big = max(abs(f.numerator), f.denominator)
        raise error(f"{where}: 10**{len(str(big)) - 1} or more is beyond the limit of "
                    f"10**{MAX_NUMBER_DIGITS}")


def check_float_weights(weights: Iterable[float | Fraction | int], *,
                        where: str = "graph.edges", error: ErrorClass = LimitError) -> None:
    """Refuse float-mode weights whose ratio largest / smallest is beyond
    :data:`MAX_FLOAT_WEIGHT_RATIO`: ``error`` (default :class:`~dppio.errors.LimitError`),
    one line naming the limit.

    Examples
    --------
    >>> check_float_weights([1.0, 2 ** 0.5])
    >>> check_float_weights([1.0, 1e300])
    Traceback (most recent call last):
    dppio.errors.LimitError: graph.edges: float weights span a ratio of 1×10^300 (1 to 1×10^300), \
beyond the float-mode limit of 10**6; give exact weights
    """
    lo = hi = None
    for w in weights:
        x = float(w)
        lo = x if lo is None or x < lo else lo
        hi = x if hi is None or x > hi else hi
    if lo is None or hi is None or lo <= 0:
        return
    if hi / lo > MAX_FLOAT_WEIGHT_RATIO:
        raise error(f"{where}: float weights span a ratio of {decimal(hi / lo)} ({decimal(lo)} "
                    f"to {decimal(hi)}), beyond the float-mode limit of 10**6; give exact weights")


def check_json_depth(doc: Any, *, error: ErrorClass = LimitError) -> None:
    """Refuse a parsed JSON document nested deeper than :data:`MAX_JSON_DEPTH` levels of
    arrays/objects: ``error`` (default :class:`~dppio.errors.LimitError`), one line.

    Examples
    --------
    >>> check_json_depth({"a": [1, [2]]})
    >>> nested: list = []
    >>> for _ in range(64):
    ...     nested = [nested]
    >>> check_json_depth(nested, error=ValueError)
    Traceback (most recent call last):
    ValueError: JSON nested deeper than 64 levels
    """
    stack = [(doc, 1)]
    while stack:
        x, depth = stack.pop()
        if isinstance(x, dict | list):
            if depth > MAX_JSON_DEPTH:
                raise error(f"JSON nested deeper than {MAX_JSON_DEPTH} levels")
            stack.extend((y, depth + 1) for y in (x.values() if isinstance(x, dict) else x))
