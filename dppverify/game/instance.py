"""Reading game instances for any number of goals: documents, files and compact map instances.

The checker reads instances itself (``docs/formats.md`` §1) and validates the paper's
assumptions (Section III-A), for ``N >= 2`` goals: positive weights, distinct goals, a prior in
(0, 1) summing to exactly 1, and finite full-graph distances from the start to every goal and
between any two goals (assumption (R) of proofs/README.md; the terminal costs ``d(g^i, g^j)``).
Every violation raises :class:`InvalidInstanceError` with a one-line message naming what and
where (the parsing itself is :mod:`dppverify.game.instance_reading` and
:mod:`dppverify.game.graph_reading`). The one frozen :class:`Instance` type is
:mod:`dppverify.game.instance_type`'s, imported from here as well.

Two goals are the case ``N = 2``: a document listing exactly two goals is read under the
two-goal rules (float weights allowed, ``"numbers": "float"``; the two-goal messages), and the
instance has the paper's (primary, secondary) views :attr:`Instance.primary_goal_index`,
:attr:`Instance.tied` and :meth:`Instance.roles`, which raise :class:`NotTwoGoalsError` for
``N != 2``. Every other form of an instance (an object, bytes, a networkx graph) enters
through the one door, :func:`dppverify.game.inputs.as_instance`.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from dppio.text import plural
from dppverify.errors import InvalidInstanceError
from dppverify.formats.json_reading import (
    JsonReadError,
    Node,
    node_from_json,
    node_to_json,
    parse_json_text,
    read_json_document,
    show_node,
)
from dppverify.formats.map_instance import is_map_document
from dppverify.game.goal_selection import is_selection_document, marked, selection_parts
from dppverify.game.graph_reading import read_graph, require
from dppverify.game.grids import map_game
from dppverify.game.instance_reading import arc_arrays, exact_mode, goal_distance_fields
from dppverify.game.instance_type import Instance, Roles, finish_game

__all__ = ["Instance", "Node", "Roles", "arc_arrays", "finish_game",
           "goal_distance_fields", "instance_from_json", "load_instance", "node_from_json",
           "node_to_json", "read_instance_file", "show_node"]


def load_instance(path: str | Path) -> Instance:
    """Read and validate an instance file (:func:`instance_from_json` on its document).

    A relative map path of a compact map instance is relative to the file's directory.

    Raises
    ------
    InvalidInstanceError
        One line ``PATH: what is wrong`` for unreadable, malformed or invalid instances.

    Examples
    --------
    >>> load_instance("/nonexistent.json")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: /nonexistent.json: cannot read instance file ...
    """
    return read_instance_file(path)[0]


def read_instance_file(path: str | Path) -> tuple[Instance, bytes]:
    """:func:`load_instance`, with the bytes it parsed (read once, bounded).

    Examples
    --------
    >>> import json, tempfile
    >>> from dppverify.game.examples import triangle_document
    >>> with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
    ...     json.dump(triangle_document(), f)
    >>> inst, data = read_instance_file(f.name)
    >>> inst.n_goals, json.loads(data) == triangle_document()
    (2, True)
    """
    p = Path(path)
    try:
        doc, data = read_json_document(p, kind="instance")
    except JsonReadError as exc:
        raise InvalidInstanceError(f"{p}: {exc}") from None
    try:
        return instance_from_json(doc, base=p.parent), data
    except InvalidInstanceError as exc:
        raise InvalidInstanceError(f"{p}: {exc}") from None


def instance_from_json(doc: Any, *, base: Path | None = None) -> Instance:
    """Build a validated :class:`Instance` from an instance document (dict or JSON text).

    The one instance reader of the checker, for any ``N >= 2`` goals and for the goal-selection
    game (``goal_values`` set). A document listing
    exactly two goals is read under the two-goal rules (``"numbers": "float"`` allowed, the
    two-goal messages); one listing more is read under the N-goal rules (exact numbers only;
    :func:`~dppverify.game.instance_reading.exact_mode`). A compact map instance
    (``"format": "dpp-map-instance/1"``, :mod:`dppverify.formats.map_instance`) is read from
    its map; a relative map path is relative to ``base`` (the instance file's directory; the
    working directory when None).

    Raises
    ------
    InvalidInstanceError
        For malformed documents and instances violating the game's assumptions: one line
        naming what is wrong and where.

    Examples
    --------
    >>> instance_from_json('{"graph": {"nodes": [{"id": 1}], "edges": []}, "start": 1, '
    ...                    '"goals": [1, 1], "prior": [0.5, 0.5]}')
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: goals: the two goals must differ, both are 1
    >>> instance_from_json('{"graph": {"nodes": [{"id": 1}, {"id": 2}], "edges": []}, '
    ...     '"start": 1, "goals": [1, 2, 1], "prior": [0.5, 0.25, 0.25]}')
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: goals[2]: goal 1 is listed twice
    >>> from dppverify.game.examples import star3_document, triangle_document
    >>> instance_from_json({**star3_document(), "numbers": "float"})
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: numbers: N-goal instances must be exact \
("numbers": "exact")
    >>> instance_from_json({**triangle_document(), "numbers": "float"}).exact
    False

    A goal-selection document (no prior; ``docs/formats.md`` §1, "Goal selection") is the
    game with its goal values and the uniform reference prior:

    >>> doc = {k: v for k, v in triangle_document().items() if k != "prior"}
    >>> inst = instance_from_json({**doc, "goal_selection": True, "goal_values": [0, 1]})
    >>> inst.goal_values, inst.prior
    ((Fraction(0, 1), Fraction(1, 1)), (Fraction(1, 2), Fraction(1, 2)))
    """
    if isinstance(doc, str | bytes):
        try:
            doc = parse_json_text(doc)
        except JsonReadError as exc:
            raise InvalidInstanceError(str(exc)) from None
    if is_selection_document(doc):  # the goal-selection game: no prior, goal values
        rest, values = selection_parts(doc)
        return marked(instance_from_json(rest, base=base), values)
    if isinstance(doc, Mapping) and "format" in doc and is_map_document(doc):
        return map_game(doc, base=base)
    try:
        return _read_game(doc)
    except InvalidInstanceError:
        raise
    except (ValueError, TypeError) as exc:  # parse_number / node_from_json messages
        raise InvalidInstanceError(str(exc)) from None


def _read_game(doc: Any, *, fast: bool = True) -> Instance:
    require(isinstance(doc, Mapping), f"instance must be a JSON object, got {type(doc).__name__}")
    missing = [k for k in ("graph", "start", "goals", "prior") if k not in doc]
    require(not missing, f"instance is missing {plural(len(missing), 'key')}: "
                         f"{', '.join(missing)}")
    exact = exact_mode(doc.get("numbers", "exact"), doc["goals"])
    return finish_game(read_graph(doc["graph"], exact, fast=fast), exact=exact,
                       start=doc["start"], goals=doc["goals"], prior=doc["prior"])
