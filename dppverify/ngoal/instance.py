"""N-goal instances: parse and validate the instance JSON with ``N >= 2`` goals.

The document is the two-goal instance format (``docs/formats.md`` §1) with ``goals`` a list of
``N >= 2`` distinct nodes and ``prior`` a list of ``N`` numbers in (0, 1) summing to exactly 1.
Validity: every goal is reachable from the start and from every other goal (the terminal
costs ``d(g^i, g^j)`` are finite). Exact numbers only (``"numbers": "float"`` is refused).
Every violation raises :class:`~dppverify.errors.InvalidInstanceError` with one line naming
what and where. The document is read by the same parser as the two-goal instance
(:func:`dppverify.game.instance.read_game`); :class:`NInstance` adds the N-goal views.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from dppverify.errors import InvalidInstanceError
from dppverify.exact import Number
from dppverify.formats.json_reading import JsonReadError, read_json_file
from dppverify.game.instance import GameInstance, load_game, read_game

__all__ = ["NInstance", "goal_count", "load_ninstance", "ninstance_from_json",
           "read_instance_document"]


@dataclass(frozen=True, eq=False)
class NInstance(GameInstance):
    """A validated N-goal game instance with exact distances.

    A :class:`~dppverify.game.instance.GameInstance` read by the shared parser
    (:func:`~dppverify.game.instance.read_game`), with every attribute of that class; for N goals
    they read:

    Attributes
    ----------
    goals : tuple of int
        The N goals in document order; type ``θ`` (0-based) walks to ``goals[θ]``.
    prior : tuple of Fraction
        ``prior[θ]``: the probability of type ``θ``.
    exact : bool
        Always True: N-goal instances are exact.
    dist_to : tuple
        ``dist_to[θ][v]`` = full-graph ``d(v, goals[θ])`` (``math.inf`` if unreachable).

    Examples
    --------
    >>> doc = {"graph": {"nodes": [{"id": "s"}, {"id": "a"}, {"id": "b"}, {"id": "c"}],
    ...        "edges": [{"source": "s", "target": "a"}, {"source": "s", "target": "b"},
    ...                  {"source": "s", "target": "c", "weight": 2}]},
    ...        "start": "s", "goals": ["a", "b", "c"], "prior": ["1/2", "1/3", "1/6"]}
    >>> inst = ninstance_from_json(doc)
    >>> inst.n_goals, inst.prior[2], inst.dist_to[2][inst.goals[0]], inst.exact
    (3, Fraction(1, 6), 3, True)
    """

    @property
    def n_goals(self) -> int:
        """Number of goals ``N``."""
        return len(self.goals)

    def goal_slot(self, node: int) -> int | None:
        """The type ``θ`` whose goal is ``node``, or None if ``node`` is not a goal."""
        try:
            return self.goals.index(node)
        except ValueError:
            return None

    def terminal(self, goal: int, theta: int) -> Number:
        """Type ``θ``'s terminal cost at goal node ``goal``: ``d(goal, g^θ)``."""
        return self.dist_to[theta][goal]


def goal_count(doc: Any) -> int | None:
    """The number of goals an instance document lists (None if ``goals`` is not a list).

    Used by the command line to dispatch between the two-goal and the N-goal checker.

    Examples
    --------
    >>> goal_count({"goals": ["a", "b", "c"]}), goal_count({"goals": 3})
    (3, None)
    """
    if isinstance(doc, Mapping) and isinstance(doc.get("goals"), list):
        return len(doc["goals"])
    return None


def read_instance_document(path: str | Path) -> Any:
    """Read an instance file as a JSON document (decimals exact), one-line errors.

    Raises
    ------
    InvalidInstanceError
        ``PATH: what is wrong`` for unreadable or malformed files.

    Examples
    --------
    >>> read_instance_document("/nonexistent.json")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: /nonexistent.json: cannot read instance file ...
    """
    p = Path(path)
    try:
        return read_json_file(p, kind="instance")
    except JsonReadError as exc:
        raise InvalidInstanceError(f"{p}: {exc}") from None


def load_ninstance(path: str | Path) -> NInstance:
    """Read and validate an N-goal instance file.

    Examples
    --------
    >>> load_ninstance("/nonexistent.json")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: /nonexistent.json: cannot read instance file ...
    """
    return load_game(path, NInstance, two_goals=False)


def ninstance_from_json(doc: Mapping[str, Any] | str | bytes) -> NInstance:
    """Build a validated :class:`NInstance` from an instance document (dict or JSON text).

    Raises
    ------
    InvalidInstanceError
        For malformed documents and instances violating the game's assumptions.

    Examples
    --------
    >>> ninstance_from_json('{"graph": {"nodes": [{"id": 1}, {"id": 2}], "edges": []}, '
    ...     '"start": 1, "goals": [1, 2, 1], "prior": [0.5, 0.25, 0.25]}')
    Traceback (most recent call last):
    dppverify.errors.InvalidInstanceError: goals[2]: goal 1 is listed twice
    """
    return read_game(doc, NInstance, two_goals=False)
