"""The horizon argument of the Python API: the untruncated game or a truncated one.

This is the one horizon type of the package (``dpp``'s ``-H/--horizon`` reads the same):
:func:`dppverify.certify` and :func:`dppverify.value` take ``horizon=None`` or ``"inf"``
(the untruncated game, the default) or a non-negative integer ``H`` (the game truncated at
``H``, an explicit request). Anything else is a :class:`~dppverify.errors.HorizonError` with
one line, never a raw ``TypeError``.
"""

from __future__ import annotations

import math
import numbers
from typing import Any

from dppverify.errors import HorizonError
from dppverify.limits import MAX_HORIZON

INFINITE_WORDS = ("inf", "infinity")
"""The words (any case) that mean the untruncated game, H = inf."""


def parse_horizon(horizon: Any) -> int | None:
    """``None`` for the untruncated game, else the integer ``H``.

    Parameters
    ----------
    horizon : None, "inf", float("inf") or int
        None, ``"inf"`` / ``"infinity"`` (any case) and ``math.inf`` all mean the untruncated
        game; an integer (or an integral string such as ``"3"``) ``0 <= H <= MAX_HORIZON``
        the game truncated at ``H``.

    Returns
    -------
    int or None

    Raises
    ------
    HorizonError
        Anything else, in one line.

    Examples
    --------
    >>> parse_horizon(None), parse_horizon("inf"), parse_horizon(float("inf")), parse_horizon(3)
    (None, None, None, 3)
    >>> parse_horizon(-1)
    Traceback (most recent call last):
    dppverify.errors.HorizonError: the horizon must be a non-negative integer or 'inf', got -1
    >>> parse_horizon(2.5)
    Traceback (most recent call last):
    dppverify.errors.HorizonError: the horizon must be a non-negative integer or 'inf', got 2.5
    """
    if horizon is None:
        return None
    bad = HorizonError(f"the horizon must be a non-negative integer or 'inf', got {horizon!r}")
    if isinstance(horizon, bool):
        raise bad
    if isinstance(horizon, str):
        text = horizon.strip().lower()
        if text in INFINITE_WORDS:
            return None
        if not text.isdigit():
            raise bad
        h = int(text)
    elif isinstance(horizon, float):
        if math.isinf(horizon) and horizon > 0:
            return None
        if not horizon.is_integer():
            raise bad
        h = int(horizon)
    elif isinstance(horizon, numbers.Integral):
        h = int(horizon)
    else:
        raise bad
    if h < 0:
        raise bad
    if h > MAX_HORIZON:
        raise HorizonError(f"the horizon {h} is beyond the limit of {MAX_HORIZON}")
    return h
