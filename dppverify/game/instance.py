"""Reading game instances for any number of goals: documents, files, maps, foreign objects.

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
``N != 2``. A reader asked for ``two_goals=True`` refuses a document with more goals.
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
    read_json_file,
    show_node,
)
from dppverify.formats.map_instance import is_map_document
from dppverify.game.graph_reading import read_graph, require
from dppverify.game.grids import map_game
from dppverify.game.instance_reading import (
    NGOAL_REFUSAL,
    arc_arrays,
    goal_distance_fields,
    two_goal_rules,
)
from dppverify.game.instance_type import Instance, Roles, finish_game

__all__ = ["NGOAL_REFUSAL", "Instance", "Node", "Roles", "arc_arrays", "as_instance",
           "finish_game", "goal_distance_fields", "instance_from_json", "load_instance",
           "node_from_json", "node_to_json", "show_node"]


def as_instance(instance: Any, *, two_goals: bool = False) -> Instance:
    """An :class:`Instance` from any of the forms the public API accepts (duck typing).

    Parameters
    ----------
    instance : Instance, Mapping, str, Path, or an object with ``to_json()``
        Returned as is; parsed (a document); loaded (a file path); or, for any object with a
        ``to_json()`` method returning a document (e.g. the solver's ``Instance``), parsed
        from that document. ``dppverify`` never imports the solver: only the JSON is used.
    two_goals : bool
        Read exactly two goals (as :func:`instance_from_json`); an :class:`Instance` given
        as is must then have two goals.

    Raises
    ------
    InvalidInstanceError
        The input is none of these, or not a valid instance.

    Examples
    --------
    >>> from dppverify.game.examples import triangle_document
    >>> class Foreign:  # any object that can write the instance JSON
    ...     def to_json(self):
    ...         return triangle_document()
    >>> as_instance(Foreign()).prior
    (Fraction(7, 10), Fraction(3, 10))
    >>> as_instance(42)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    dppverify.errors.InvalidInstanceError: an instance must be ... with to_json(); got int ...
    """
    if isinstance(instance, Instance):
        if two_goals:
            require(instance.n_goals == 2, NGOAL_REFUSAL.format(n=instance.n_goals))
        return instance
    if isinstance(instance, Mapping):
        return instance_from_json(instance, two_goals=two_goals)
    if isinstance(instance, str | Path):
        return load_instance(instance, two_goals=two_goals)
    to_json = getattr(instance, "to_json", None)
    if callable(to_json):
        doc = to_json()
        if isinstance(doc, Mapping | str | bytes):
            return instance_from_json(doc, two_goals=two_goals)
    raise InvalidInstanceError(
        "an instance must be an Instance, a JSON document (dict), a file path or an object "
        f"with to_json(); got {type(instance).__name__} (the solver's Instance and "
        "Equilibrium have to_json())")


def load_instance(path: str | Path, *, two_goals: bool = False) -> Instance:
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
    p = Path(path)
    try:
        doc = read_json_file(p, kind="instance")
    except JsonReadError as exc:
        raise InvalidInstanceError(f"{p}: {exc}") from None
    try:
        return instance_from_json(doc, two_goals=two_goals, base=p.parent)
    except InvalidInstanceError as exc:
        raise InvalidInstanceError(f"{p}: {exc}") from None


def instance_from_json(doc: Any, *, two_goals: bool = False,
                       base: Path | None = None) -> Instance:
    """Build a validated :class:`Instance` from an instance document (dict or JSON text).

    The one instance reader of the checker, for any ``N >= 2`` goals. A document listing
    exactly two goals is read under the two-goal rules (``"numbers": "float"`` allowed, the
    two-goal messages); one listing more is read under the N-goal rules (exact numbers only).
    ``two_goals=True``: the caller reads two goals only; more are refused
    (:data:`NGOAL_REFUSAL`). A compact map instance (``"format": "dpp-map-instance/1"``,
    :mod:`dppverify.formats.map_instance`) is read from its map; a relative map path is
    relative to ``base`` (the instance file's directory; the working directory when None).

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
    >>> instance_from_json(star3_document(), two_goals=True)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: goals: this instance lists 3 goals; the two-goal ...
    >>> instance_from_json({**triangle_document(), "numbers": "float"}).exact
    False
    """
    if isinstance(doc, str | bytes):
        try:
            doc = parse_json_text(doc)
        except JsonReadError as exc:
            raise InvalidInstanceError(str(exc)) from None
    if isinstance(doc, Mapping) and "format" in doc and is_map_document(doc):
        return map_game(doc, two_goals=two_goals, base=base)
    try:
        return _read_game(doc, two_goals)
    except InvalidInstanceError:
        raise
    except (ValueError, TypeError) as exc:  # parse_number / node_from_json messages
        raise InvalidInstanceError(str(exc)) from None


def _read_game(doc: Any, two_goals: bool = False, *, fast: bool = True) -> Instance:
    require(isinstance(doc, Mapping), f"instance must be a JSON object, got {type(doc).__name__}")
    missing = [k for k in ("graph", "start", "goals", "prior") if k not in doc]
    require(not missing, f"instance is missing {plural(len(missing), 'key')}: "
                         f"{', '.join(missing)}")
    mode = doc.get("numbers", "exact")
    if two_goal_rules(doc["goals"], two_goals):
        require(mode in ("exact", "float"),
                f"numbers: expected \"exact\" or \"float\", got {mode!r}")
    else:
        require(mode == "exact", "numbers: N-goal instances must be exact (\"numbers\": \"exact\")")
    exact = mode == "exact"
    ids, index, directed, succ_t, pred_t, arcs = read_graph(doc["graph"], exact, fast=fast)
    return finish_game(ids, index, directed, succ_t, pred_t, arcs, exact=exact,
                       start=doc["start"], goals=doc["goals"], prior=doc["prior"],
                       two_goals=two_goals)


def goal_count(doc: Any) -> int | None:
    """The number of goals an instance document lists (None if ``goals`` is not a list).

    Examples
    --------
    >>> from dppverify.game.examples import star3_document
    >>> goal_count(star3_document()), goal_count({"goals": "g"})
    (3, None)
    """
    return len(doc["goals"]) if isinstance(doc, Mapping) and isinstance(
        doc.get("goals"), list) else None


def read_instance_document(path: str | Path) -> Any:
    """The JSON document of an instance file, read once (bounded), not yet validated.

    Raises
    ------
    InvalidInstanceError
        ``PATH: cannot read instance file (reason)`` or the JSON error.

    Examples
    --------
    >>> read_instance_document("/nonexistent.json")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: /nonexistent.json: cannot read instance file ...
    """
    try:
        return read_json_file(Path(path), kind="instance")
    except JsonReadError as exc:
        raise InvalidInstanceError(f"{path}: {exc}") from None
