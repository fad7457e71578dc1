"""Reading JSON documents: the one home of the primitives every parser of the checker uses.

The instance parsers (two goals and N goals) and the profile parsers (``dpp-profile/1`` and
``dpp-ngoal-profile/1``) read their documents with these functions and nothing else, so a
document passes through this module once on its way to a parsed object:

- :func:`read_json_document` / :func:`parse_json`: bounded file reading and JSON text with exact
  decimals (``docs/formats.md``, "Numbers"), one-line errors;
- :func:`parse_number`, :func:`parse_probability`: one exact number (``3``, ``0.6`` = 3/5,
  ``"p/q"``), one probability;
- :func:`node_from_json`, :func:`lookup_node`, :func:`show_node`, :func:`node_to_json`: node
  ids (JSON lists become tuples: ``[2, 3]`` is the grid cell ``(2, 3)``);
- :func:`resolve_walk`: a JSON walk ``[s0, …, s_t]`` checked against a game and turned into
  node indices.

Arithmetic on the numbers read here (``normalize``, formatting) stays in
:mod:`dppverify.exact`; this module only turns JSON into values.

Examples
--------
>>> doc = parse_json('{"path": ["s", [2, 3]], "p": 0.6}')
>>> [node_from_json(x) for x in doc["path"]], parse_number(doc["p"], where="p")
(['s', (2, 3)], Fraction(3, 5))
"""

from __future__ import annotations

import json
import math
from collections.abc import Hashable, Mapping, Sequence
from fractions import Fraction
from numbers import Integral, Rational
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from dppio.limits import (
    MAX_JSON_DEPTH,
    MAX_NUMERAL_CHARS,
    check_json_depth,
    check_numeral,
    check_rational,
)
from dppverify.exact import Number, normalize
from dppverify.formats.files import read_input

Node = Hashable
"""A node id after JSON conversion (lists become tuples)."""


class JsonReadError(ValueError):
    """A file cannot be read or is not JSON; the message is one line without the file name."""


# --- JSON text ------------------------------------------------------------------------------

def _reject_constant(name: str) -> Any:
    raise ValueError(f"non-finite number {name} is not allowed")


def _parse_float(text: str) -> Fraction:
    check_numeral(text, where="JSON number")
    return Fraction(text)


def _parse_int(text: str) -> int:
    if len(text) > MAX_NUMERAL_CHARS:  # an integer literal has no exponent to check
        check_numeral(text, where="JSON number")
    return int(text)


def parse_json(text: str | bytes) -> Any:
    """Parse JSON text with decimal literals as exact ``Fraction`` (``NaN``/``Infinity`` refused).

    Numerals beyond the limits of :mod:`dppio.limits` (length, exponent) and documents
    nested deeper than ``MAX_JSON_DEPTH`` are refused before they can hang the parser.

    Raises ``ValueError`` (``json.JSONDecodeError`` for syntax errors; ``UnicodeDecodeError``
    for bytes that are not UTF-8).

    Examples
    --------
    >>> parse_json('{"p": 0.6, "q": 2}')
    {'p': Fraction(3, 5), 'q': 2}
    >>> parse_json("[" * 100 + "]" * 100)
    Traceback (most recent call last):
    ValueError: JSON nested deeper than 64 levels
    """
    raw = text.encode("utf-8", "surrogatepass") if isinstance(text, str) else None
    fast = raw is not None and _LONG_DIGITS not in raw.translate(_DIGIT_MAP)
    try:  # without a long digit run every integer literal passes _parse_int: json's int is it
        doc = json.loads(text, parse_float=_parse_float, parse_int=None if fast else _parse_int,
                         parse_constant=_reject_constant)
    except RecursionError:
        raise ValueError(f"JSON nested deeper than {MAX_JSON_DEPTH} levels") from None
    if raw is not None and b"\\" not in raw:
        _check_text_depth(raw)
    else:
        check_json_depth(doc, error=ValueError)
    return doc


_DIGIT_MAP = bytes(48 if 48 <= i <= 57 else 32 for i in range(256))
"""``bytes.translate`` table: digits to ``0``, every other byte to a space."""

_LONG_DIGITS = b"0" * MAX_NUMERAL_CHARS
"""A digit run this long may be an integer literal :func:`_parse_int` refuses."""

_BRACKETS_AND_QUOTES = bytes(i for i in range(256) if i not in b'"[]{}')
"""Deleting these bytes keeps the structure of a JSON text: quotes and brackets."""

_NESTING = np.zeros(256, dtype=np.int8)
_NESTING[[ord("["), ord("{")]] = 1
_NESTING[[ord("]"), ord("}")]] = -1


def _check_text_depth(raw: bytes) -> None:
    """:func:`~dppio.limits.check_json_depth` on the text of a parsed document without backslashes.

    Without escapes every ``"`` opens or closes a string, so the brackets outside strings are
    those after an even number of quotes; a container's depth is the number of brackets open
    after its own (UTF-8 continuation bytes are never ASCII).
    """
    b = np.frombuffer(raw.translate(None, _BRACKETS_AND_QUOTES), dtype=np.uint8)
    if not b.size:
        return
    step = _NESTING[b]
    step[(np.cumsum(b == ord('"'), dtype=np.int64) & 1).astype(bool)] = 0
    if int(np.cumsum(step, dtype=np.int64).max()) > MAX_JSON_DEPTH:
        raise ValueError(f"JSON nested deeper than {MAX_JSON_DEPTH} levels")


def parse_json_text(text: str | bytes, *, profile: bool = False) -> Any:
    """:func:`parse_json` with the one-line message of the document's kind on failure.

    Instance documents say ``malformed JSON at line L column C: …``, profile documents
    ``not JSON (line L column C: …)``.

    Raises
    ------
    JsonReadError
        The text is not JSON (or nests too deep, or holds a numeral beyond the limits).

    Examples
    --------
    >>> parse_json_text('{"a": }')
    Traceback (most recent call last):
    dppverify.formats.json_reading.JsonReadError: malformed JSON at line 1 column 7: Expecting value
    >>> parse_json_text('{"a": }', profile=True)
    Traceback (most recent call last):
    dppverify.formats.json_reading.JsonReadError: not JSON (line 1 column 7: Expecting value)
    """
    try:
        return parse_json(text)
    except json.JSONDecodeError as exc:
        raise JsonReadError(
            f"not JSON (line {exc.lineno} column {exc.colno}: {exc.msg})" if profile else
            f"malformed JSON at line {exc.lineno} column {exc.colno}: {exc.msg}") from None
    except (ValueError, RecursionError) as exc:
        raise JsonReadError(f"not JSON ({exc})" if profile else
                            f"malformed JSON: {exc}") from None


def read_json_document(source: str | Path | bytes, *, kind: str) -> tuple[Any, bytes]:
    """Read a JSON document from a file (bounded, :func:`~dppverify.formats.files.read_input`) or
    bytes, with the bytes it parsed (a file's exactly as read).

    Parameters
    ----------
    source : str, Path or bytes
        A file path, or the JSON text itself as bytes.
    kind : str
        ``"instance"`` or ``"profile"``: names the file in the message and picks the
        wording of :func:`parse_json_text`.

    Returns
    -------
    (object, bytes)
        The document (exact numbers) and the bytes parsed.

    Raises
    ------
    JsonReadError
        ``cannot read KIND file (reason)`` or the JSON message, without the file name (the
        caller prefixes it and picks its error class).

    Examples
    --------
    >>> read_json_document(b'{"a": 1}', kind="instance")
    ({'a': 1}, b'{"a": 1}')
    >>> read_json_document("/nonexistent.json", kind="instance")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify...JsonReadError: cannot read instance file (No such file or directory)
    """
    if isinstance(source, bytes):
        return parse_json_text(source, profile=kind == "profile"), source
    try:
        data = read_input(source)
        text = data.decode("utf-8")
    except (OSError, UnicodeDecodeError, ValueError) as exc:
        reason = (exc.strerror if isinstance(exc, OSError) else
                  "not UTF-8 text" if isinstance(exc, UnicodeDecodeError) else str(exc))
        raise JsonReadError(f"cannot read {kind} file ({reason})") from None
    return parse_json_text(text, profile=kind == "profile"), data


# --- numbers --------------------------------------------------------------------------------

def parse_number(value: object, *, where: str, allow_float: bool = False) -> Number:
    """Parse one number of a JSON document exactly.

    Parameters
    ----------
    value : object
        An ``int``, a ``Fraction`` (a JSON decimal literal read with
        ``parse_float=Fraction``), a string ``"p/q"`` / ``"0.25"``, or a ``float``.
    where : str
        Names the value in the error message.
    allow_float : bool
        Float mode: decimal literals and floats become binary floats.

    Returns
    -------
    int, Fraction or float
        Exact (``int`` when integral) unless ``allow_float`` is set.

    Raises
    ------
    ValueError
        One line naming ``where`` when ``value`` is not a finite number (the callers turn it
        into the error class of their document).

    Examples
    --------
    >>> parse_number("3/5", where="prior"), parse_number(Fraction("0.6"), where="prior")
    (Fraction(3, 5), Fraction(3, 5))
    >>> parse_number(4, where="w"), parse_number("2/1", where="w")
    (4, 2)
    >>> parse_number(Fraction("0.1"), where="w", allow_float=True)
    0.1
    >>> parse_number("x", where="weight of edge 3")
    Traceback (most recent call last):
    ValueError: weight of edge 3: 'x' is not a number
    """
    if isinstance(value, bool) or value is None:
        raise ValueError(f"{where}: expected a number, got {json.dumps(value)}")
    if isinstance(value, Rational):
        exact = normalize(Fraction(int(value.numerator), int(value.denominator)))
        check_rational(exact, where=where)
        if allow_float and not isinstance(value, Integral):
            return float(exact)
        return exact
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ValueError(f"{where}: expected a finite number, got {value!r}")
        return value if allow_float else normalize(Fraction(repr(value)))
    if isinstance(value, str):
        check_numeral(value, where=where)
        try:
            exact = normalize(Fraction(value.strip()))
        except (ValueError, ZeroDivisionError):
            raise ValueError(f"{where}: {value!r} is not a number") from None
        check_rational(exact, where=where)
        return exact
    raise ValueError(f"{where}: expected a number, got {type(value).__name__}")


def parse_probability(value: object, *, where: str) -> Fraction:
    """Parse one probability exactly: a number in ``[0, 1]``.

    Raises
    ------
    ValueError
        ``where: …`` when ``value`` is not a number or lies outside ``[0, 1]``.

    Examples
    --------
    >>> parse_probability("4/7", where="p"), parse_probability(1, where="p")
    (Fraction(4, 7), Fraction(1, 1))
    >>> parse_probability(1.5, where="attacker[0][1].probability")
    Traceback (most recent call last):
    ValueError: attacker[0][1].probability: probability 3/2 is outside [0, 1]
    """
    x = Fraction(parse_number(value, where=where))
    if not 0 <= x <= 1:
        raise ValueError(f"{where}: probability {x} is outside [0, 1]")
    return x


# --- nodes ----------------------------------------------------------------------------------

def node_from_json(x: Any, *, where: str = "node id") -> Node:
    """Convert a JSON node id: lists become tuples (``[2, 3]`` is the grid cell ``(2, 3)``).

    Examples
    --------
    >>> node_from_json([2, 3]), node_from_json("s"), node_from_json(7)
    ((2, 3), 's', 7)
    """
    if isinstance(x, list):
        return tuple(node_from_json(y, where=where) for y in x)
    if isinstance(x, dict):
        raise ValueError(f"{where} must be a JSON scalar or list, got an object")
    if isinstance(x, bool) or x is None:
        raise ValueError(f"{where}: node ids are strings, numbers or lists, got "
                         f"{json.dumps(x)}")
    if isinstance(x, Fraction):
        return int(x) if x.denominator == 1 else float(x)
    return x


def lookup_node(index: Mapping[Node, int], raw: Any) -> int | None:
    """The index of the JSON node id ``raw``, or None when it is no node (or no node id).

    Examples
    --------
    >>> index = {"s": 0, (2, 3): 1}
    >>> lookup_node(index, [2, 3]), lookup_node(index, "t"), lookup_node(index, {"id": 1})
    (1, None, None)
    """
    try:
        return index.get(node_from_json(raw))
    except (ValueError, TypeError):
        return None


def node_to_json(x: Node) -> Any:
    """Inverse of :func:`node_from_json` (tuples become lists).

    Examples
    --------
    >>> node_to_json((2, 3))
    [2, 3]
    """
    if isinstance(x, tuple):
        return [node_to_json(y) for y in x]
    return x


def show_node(x: Node) -> str:
    """A node id as it is written in JSON, for messages.

    Examples
    --------
    >>> show_node((2, 3)), show_node("s")
    ('[2, 3]', '"s"')
    """
    try:
        return json.dumps(node_to_json(x))
    except (TypeError, ValueError):
        return repr(x)


# --- walks ----------------------------------------------------------------------------------

class WalkGame(Protocol):
    """What :func:`resolve_walk` needs of a game (two-goal ``Instance`` and ``Instance``)."""

    @property
    def nodes(self) -> Sequence[Node]: ...

    @property
    def index(self) -> Mapping[Node, int]: ...

    @property
    def start(self) -> int: ...

    def is_goal(self, node: int) -> bool: ...

    def weight(self, u: int, v: int) -> Number | None: ...


def resolve_walk(game: WalkGame, raw: Any, *, complete: bool,
                 subject: str = "path") -> tuple[int, ...] | str:
    """Resolve a JSON walk to node indices, or say (one line) what is wrong with it.

    A walk starts at ``s0``, follows arcs of the graph, and stops at the FIRST goal it
    reaches (paper Sec. III-A). ``complete`` walks (attacker paths) must end at a goal;
    otherwise (Defender table entries) the walk must have at least one step.

    Parameters
    ----------
    game : WalkGame
        The instance (two goals or N goals).
    raw : Any
        The JSON walk: a list of node ids.
    complete : bool
        True for attacker paths, False for Defender table walks.
    subject : str
        Names the walk at the start of each message (``"path"``, ``"walk"``); ``""`` gives
        messages without a subject (``"[2]: unknown node …"``, ``"starts at …"``).

    Examples
    --------
    >>> from dppverify.game.examples import triangle
    >>> inst = triangle()
    >>> resolve_walk(inst, ["s", "g1"], complete=True)
    (0, 1)
    >>> resolve_walk(inst, ["s", "x"], complete=True)
    'path[1]: unknown node "x"'
    >>> resolve_walk(inst, ["g1"], complete=True, subject="")
    'starts at "g1", not at the start "s"'
    >>> resolve_walk(inst, ["s"], complete=False, subject="walk")
    'walk must have at least one step (the Defender acts after each move)'
    """
    lead = f"{subject} " if subject else ""
    if not isinstance(raw, list) or not raw:
        return f"{lead}must be a non-empty list of node ids"
    fast = _resolve_walk_fast(game, raw, complete=complete)
    if fast is not None:
        return fast
    walk: list[int] = []
    for k, x in enumerate(raw):
        try:
            v = node_from_json(x, where=f"{subject}[{k}]")
            idx = game.index.get(v)
        except (ValueError, TypeError):
            return f"{subject}[{k}] is not a node id"
        if idx is None:
            return f"{subject}[{k}]: unknown node {show_node(v)}"
        if k == 0 and idx != game.start:
            return (f"{lead}starts at {show_node(v)}, not at the start "
                    f"{show_node(game.nodes[game.start])}")
        if k > 0:
            prev = walk[-1]
            if game.is_goal(prev):
                return (f"{lead}reaches goal {show_node(game.nodes[prev])} at step {k - 1} "
                        f"and continues (the game ends at the first goal)")
            if game.weight(prev, idx) is None:
                return f"{subject}[{k}]: no edge {show_node(game.nodes[prev])} -> {show_node(v)}"
        walk.append(idx)
    if complete and not game.is_goal(walk[-1]):
        return f"{lead}ends at {show_node(game.nodes[walk[-1]])}, which is not a goal"
    if not complete and len(walk) < 2:
        return f"{lead}must have at least one step (the Defender acts after each move)"
    return tuple(walk)


def _resolve_walk_fast(game: WalkGame, raw: list[Any], *, complete: bool
                       ) -> tuple[int, ...] | None:
    """:func:`resolve_walk` of a valid walk with its arcs looked up in one pass; None when
    anything is wrong (the caller's step-by-step loop then finds the first problem)."""
    along = getattr(game, "weights_along", None)
    if along is None or len(raw) < 2:
        return None
    walk: list[int] = []
    index = game.index
    try:
        for k, x in enumerate(raw):
            if type(x) is list and len(x) == 2 and type(x[0]) is int and type(x[1]) is int:
                idx = index.get((x[0], x[1]))  # a grid cell, the common case: no recursion
            else:
                idx = index.get(node_from_json(x, where=f"[{k}]"))
            if idx is None or (k > 0 and game.is_goal(walk[-1])):
                return None
            walk.append(idx)
    except (ValueError, TypeError):
        return None
    if walk[0] != game.start or (complete and not game.is_goal(walk[-1])):
        return None
    if any(w is None for w in along(walk)):
        return None
    return tuple(walk)
