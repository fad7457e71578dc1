"""JSON node ids: a JSON scalar or list, grid cells ``[r, c]`` as ``(r, c)`` tuples."""

from __future__ import annotations

import json
from collections.abc import Hashable
from fractions import Fraction
from typing import Any

import numpy as np

from solver.errors import InstanceFormatError


def node_from_json(x: Any) -> Hashable:
    """JSON node id to Python: lists become tuples (grid cells ``[r, c]`` -> ``(r, c)``).

    Parameters
    ----------
    x : object
        A JSON scalar or list (numbers possibly as ``Fraction``, see :func:`read_json`).

    Returns
    -------
    Hashable
        Integral fractions become ``int``, other fractions ``float``.

    Raises
    ------
    InstanceFormatError
        If ``x`` is a JSON object.

    Examples
    --------
    >>> node_from_json([2, 3]), node_from_json(Fraction(4)), node_from_json("s")
    ((2, 3), 4, 's')
    >>> node_from_json({"r": 2})
    Traceback (most recent call last):
    solver.errors.InstanceFormatError: node id must be a JSON scalar or list, got object {'r': 2}
    """
    if isinstance(x, list):
        return tuple(node_from_json(y) for y in x)
    if isinstance(x, dict):
        raise InstanceFormatError(f"node id must be a JSON scalar or list, got object {x!r}")
    if isinstance(x, bool) or x is None:
        raise InstanceFormatError(f"node id: node ids are strings, numbers or lists, got "
                                  f"{json.dumps(x)}")
    if isinstance(x, Fraction):
        return int(x) if x.denominator == 1 else float(x)
    return x


def node_to_json(x: Hashable) -> Any:
    """Python node id to JSON: tuples become lists.

    Parameters
    ----------
    x : Hashable
        A node id of an :class:`Instance`.

    Returns
    -------
    object
        Serializable by :func:`json.dumps` (numpy integers become ``int``).

    Examples
    --------
    >>> node_to_json((2, 3)), node_to_json(np.int64(5)), node_to_json("s")
    ([2, 3], 5, 's')
    >>> node_from_json(node_to_json((2, 3)))
    (2, 3)
    """
    if isinstance(x, tuple):
        return [node_to_json(y) for y in x]
    if isinstance(x, np.integer):
        return int(x)
    return x
