"""Reading JSON text within the limits (``docs/formats.md``): bounded file size, nesting
depth and numerals, decimals read exactly as ``Fraction``.

The checker has its own reader (``dppverify``'s JSON reading): the two packages never share a
parser, so a reader bug is never shared (``tests/maps/test_readers_agree.py``).
"""

from __future__ import annotations

import json
from fractions import Fraction
from pathlib import Path
from typing import Any

from dppio.inputs import read_text
from dppio.limits import MAX_JSON_DEPTH, check_json_depth, check_numeral
from solver.errors import InstanceFormatError, InvalidInstanceError


def read_json(path: str | Path) -> Any:
    """Read a JSON file, decimals as exact ``Fraction``; errors name the file and line.

    Parameters
    ----------
    path : str or Path
        The file (UTF-8).

    Returns
    -------
    object
        The parsed JSON, every decimal number as a ``Fraction``.

    Raises
    ------
    InstanceFormatError
        The file cannot be read or is not JSON.

    Examples
    --------
    >>> import tempfile
    >>> tmp = tempfile.TemporaryDirectory()
    >>> p = Path(tmp.name) / "prior.json"
    >>> _ = p.write_text('{"prior": [0.7, 0.3]}')
    >>> read_json(p)
    {'prior': [Fraction(7, 10), Fraction(3, 10)]}
    >>> _ = p.write_text('{"prior": [0.7,' + chr(10) + ' 0.3')
    >>> read_json(p)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    solver.errors.InstanceFormatError: .../prior.json: malformed JSON at line 2 column 5: ...
    >>> tmp.cleanup()
    """
    p = Path(path)
    try:
        text = read_text(p)
    except OSError as exc:
        raise InstanceFormatError(f"{p}: cannot read file ({exc.strerror})") from None
    except ValueError as exc:
        raise InstanceFormatError(f"{p}: cannot read file ({exc})") from None
    try:
        return parse_json_text(text)
    except InstanceFormatError as exc:
        raise InstanceFormatError(f"{p}: {exc}") from None


def _parse_float(text: str) -> Fraction:
    check_numeral(text, where="JSON number", error=InvalidInstanceError)
    return Fraction(text)


def _parse_int(text: str) -> int:
    check_numeral(text, where="JSON number", error=InvalidInstanceError)
    return int(text)


def parse_json_text(text: str) -> Any:
    """Parse JSON text: decimals as exact ``Fraction``, within the limits of
    :mod:`solver.limits` (numeral length and exponent, nesting depth).

    Raises
    ------
    InstanceFormatError
        Malformed JSON, a numeral beyond the limits, or nesting deeper than the limit.

    Examples
    --------
    >>> parse_json_text('[0.5, 2]')
    [Fraction(1, 2), 2]
    >>> parse_json_text('[1e999999999]')  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    solver.errors.InstanceFormatError: JSON number: the exponent of '1e999999999' is beyond ...
    """
    try:
        doc = json.loads(text, parse_float=_parse_float, parse_int=_parse_int,
                         parse_constant=_reject_constant)
    except json.JSONDecodeError as exc:
        raise InstanceFormatError(
            f"malformed JSON at line {exc.lineno} column {exc.colno}: {exc.msg}") from None
    except RecursionError:
        raise InstanceFormatError(f"JSON nested deeper than {MAX_JSON_DEPTH} levels") from None
    except InvalidInstanceError as exc:
        raise InstanceFormatError(str(exc)) from None
    check_json_depth(doc, error=InstanceFormatError)
    return doc


def _reject_constant(name: str) -> Any:
    raise InstanceFormatError(f"non-finite number {name} is not allowed")
