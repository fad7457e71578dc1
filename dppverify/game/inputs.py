"""The checker's one door: every input converted once, at the edge, with what was parsed.

:func:`as_instance` and :func:`as_profile` take an input in any form the public API accepts —
the object itself, a JSON document (dict), JSON bytes, a file path (read once and bounded
through :mod:`dppio.inputs`: inside a :func:`~dppio.inputs.reading_once` block every later
read of the path returns the bytes read here), or any object with ``to_json()`` — and
:func:`as_instance` also a networkx ``Graph``/``DiGraph`` with ``start=``, ``goals=`` and
``prior=`` (``weight=`` names the edge attribute). Everything below the door takes the typed
:class:`~dppverify.game.instance.Instance` and :class:`~dppverify.game.profile.Profile`.
:func:`read_instance` and :func:`read_profile` return the same value together with what they
parsed (:class:`Parsed`), which is what a certificate's provenance hashes
(:mod:`dppverify.provenance`): what was hashed is what was parsed.

Examples
--------
>>> import networkx as nx
>>> g = nx.Graph()
>>> g.add_weighted_edges_from([("s", "g1", 3), ("s", "g2", 2), ("g2", "g1", 2)])
>>> inst = as_instance(g, start="s", goals=["g1", "g2"], prior=["7/10", "3/10"])
>>> inst.labels(inst.goals), inst.dist_to[0][inst.start]
(('g1', 'g2'), 3)
>>> as_instance(g, start="s")
Traceback (most recent call last):
dppverify.errors.InvalidInstanceError: a networkx graph needs the keywords start=, goals= and \
prior= (missing: goals=, prior=)
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Generic, TypedDict, TypeVar, Unpack

from dppverify.errors import InvalidInstanceError, ProfileError
from dppverify.formats.json_reading import JsonReadError, read_json_document
from dppverify.game.instance import Instance, instance_from_json, read_instance_file
from dppverify.game.profile import Profile, profile_from_json

__all__ = ["GraphKeys", "Parsed", "as_instance", "as_profile", "read_instance", "read_profile"]

T = TypeVar("T")


@dataclass(frozen=True)
class Parsed(Generic[T]):
    """A value read at the door and what was parsed to make it.

    Attributes
    ----------
    value : Instance or Profile
        The typed value.
    data : bytes, Mapping or None
        The bytes parsed (a file's exactly as read, or JSON text given as bytes), the
        document given, or None for an object given as is (it has no bytes).
    map_file : tuple of str, optional
        For a grid read from a MovingAI ``.map`` file (``--map``): the file's path and the
        sha256 of its bytes.
    folder : Path, optional
        Where a relative ``map`` path of a compact map instance starts (the instance file's
        folder, or the ``.map`` file's for ``--map``); None: the working directory.
    """

    value: T
    data: bytes | Mapping[str, Any] | None = None
    map_file: tuple[str, str] | None = None
    folder: Path | None = None


class GraphKeys(TypedDict, total=False):
    """The keywords that go with a networkx graph: ``start``, ``goals`` and ``prior`` as node
    ids and numbers (as in an instance document), and ``weight``, the edge attribute holding
    the weights (default ``"weight"``; a missing attribute, or ``weight=None``, is 1)."""

    start: Any
    goals: Any
    prior: Any
    weight: str | None


def as_instance(instance: Any, **graph: Unpack[GraphKeys]) -> Instance:
    """The :class:`~dppverify.game.instance.Instance` of any accepted form (see the module).

    Parameters
    ----------
    instance : Instance, Mapping, bytes, str, Path, networkx graph, or an object with ``to_json()``
        Returned as is; parsed (a document, or JSON bytes); read once (a file path); converted
        (a networkx ``Graph`` or ``DiGraph``, with ``start=``, ``goals=``, ``prior=``); or parsed
        from ``to_json()`` (e.g. the solver's ``Instance``: ``dppverify`` never imports the
        solver, only the JSON is used).
    **graph : GraphKeys
        ``start``, ``goals``, ``prior`` and ``weight``: with a networkx graph only.

    Returns
    -------
    Instance

    Raises
    ------
    InvalidInstanceError
        One line: the input is none of these, not a valid instance (``PATH: ...`` for a file),
        or a networkx graph without its keywords.

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
    return read_instance(instance, **graph).value


def read_instance(instance: Any, **graph: Unpack[GraphKeys]) -> Parsed[Instance]:
    """:func:`as_instance`, with what was parsed (:class:`Parsed`; one given is returned).

    Examples
    --------
    >>> from dppverify.game.examples import triangle, triangle_document
    >>> read_instance(triangle_document()).data == triangle_document()
    True
    >>> read_instance(triangle()).data is None
    True
    """
    if _is_networkx(instance):
        return Parsed(instance_from_json(_networkx_document(instance, graph)))
    if graph:
        raise InvalidInstanceError(
            f"the keywords {', '.join(f'{k}=' for k in graph)} go with a networkx graph; the "
            f"instance given is a {type(instance).__name__} (its document names start, goals "
            f"and prior itself)")
    if isinstance(instance, Parsed):
        return instance
    if isinstance(instance, Instance):
        return Parsed(instance)
    if isinstance(instance, Mapping | bytes):
        return Parsed(instance_from_json(instance), instance)
    if isinstance(instance, str | Path):
        inst, data = read_instance_file(instance)
        return Parsed(inst, data, folder=None if str(instance) == "-" else
                      Path(instance).resolve().parent)
    to_json = getattr(instance, "to_json", None)
    if callable(to_json):
        doc = to_json()
        if isinstance(doc, Mapping | str | bytes):
            return Parsed(instance_from_json(doc), doc if isinstance(doc, Mapping) else None)
    raise InvalidInstanceError(
        "an instance must be an Instance, a JSON document (dict), JSON bytes, a file path, a "
        "networkx graph (with start=, goals=, prior=) or an object with to_json(); got "
        f"{type(instance).__name__} (the solver's Instance and Equilibrium have to_json())")


def as_profile(profile: Any, instance: Instance) -> Profile:
    """The :class:`~dppverify.game.profile.Profile` of ``profile`` resolved against ``instance``.

    Parameters
    ----------
    profile : Profile, Mapping, bytes, str, Path, or an object with ``to_json()``
        Returned as is (a profile read against this instance); parsed (a document, or JSON
        bytes); read once (a file path); or parsed from ``to_json()`` (the solver's results).
        A ``dpp-profile/1`` document for two goals, a ``dpp-ngoal-profile/1`` one for any N.
    instance : Instance
        The game the profile claims to solve.

    Returns
    -------
    Profile
        Everything wrong inside the document is one of its defects (the certificate refutes
        the profile), never an exception.

    Raises
    ------
    ProfileError
        One line: the input is none of these, not JSON, or not a JSON object tagged with a
        format of the instance's game (``PATH: ...`` for a file).

    Examples
    --------
    >>> from dppverify.game.examples import star3, triangle, triangle_profile
    >>> as_profile(triangle_profile(), triangle()).wellformed
    True
    >>> as_profile(b"[", triangle())
    Traceback (most recent call last):
    dppverify.errors.ProfileError: profile: not JSON (line 1 column 2: Expecting value)
    >>> as_profile(triangle_profile(), star3())  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    dppverify.errors.ProfileError: profile: "format" must be "dpp-ngoal-profile/1" for an ...
    """
    return read_profile(profile, instance).value


def read_profile(profile: Any, instance: Instance) -> Parsed[Profile]:
    """:func:`as_profile`, with what was parsed (:class:`Parsed`; one given is returned).

    Examples
    --------
    >>> from dppverify.game.examples import triangle, triangle_profile
    >>> read_profile(b'{"format": "dpp-profile/1"}', triangle()).data
    b'{"format": "dpp-profile/1"}'
    """
    if isinstance(profile, Parsed):
        return profile
    if isinstance(profile, Profile):
        return Parsed(profile)
    if isinstance(profile, str | Path | bytes):
        name = "profile" if isinstance(profile, bytes) else str(profile)
        try:
            doc, data = read_json_document(profile, kind="profile")
        except JsonReadError as exc:
            raise ProfileError(f"{name}: {exc}") from None
        return Parsed(profile_from_json(doc, instance, name=name), data)
    doc = profile
    to_json = getattr(profile, "to_json", None)
    if not isinstance(profile, Mapping) and callable(to_json):
        doc = to_json()
    if isinstance(doc, Mapping):
        return Parsed(profile_from_json(doc, instance), doc)
    raise ProfileError("a profile must be a Profile, a JSON document (dict), a file path, JSON "
                       f"bytes or an object with to_json(); got {type(profile).__name__} (the "
                       "solver's results have to_json())")


def _is_networkx(x: Any) -> bool:
    """True for a networkx graph (duck-typed: networkx is not imported for the others)."""
    return (not isinstance(x, Mapping) and callable(getattr(x, "is_directed", None))
            and callable(getattr(x, "is_multigraph", None)) and hasattr(x, "adj"))


def _networkx_document(g: Any, keys: GraphKeys) -> dict[str, Any]:
    """The instance document of a networkx graph and its keywords (node ids as JSON values)."""
    missing = [f"{k}=" for k in ("start", "goals", "prior") if keys.get(k) is None]
    if missing:
        raise InvalidInstanceError("a networkx graph needs the keywords start=, goals= and "
                                   f"prior= (missing: {', '.join(missing)})")
    if g.is_multigraph():
        raise InvalidInstanceError(f"a networkx {type(g).__name__} may hold parallel edges: "
                                   "give a Graph or DiGraph (one weight per edge)")
    attr = keys.get("weight", "weight")
    goals = keys["goals"]
    if not isinstance(goals, list | tuple):
        raise InvalidInstanceError(f"goals=: must be a list of node ids, got "
                                   f"{type(goals).__name__}")
    prior = keys["prior"]
    return {"graph": {"directed": bool(g.is_directed()),
                      "nodes": [{"id": _json_id(v)} for v in g.nodes],
                      "edges": [{"source": _json_id(u), "target": _json_id(v),
                                 "weight": 1 if attr is None else d.get(attr, 1)}
                                for u, v, d in g.edges(data=True)]},
            "start": _json_id(keys["start"]), "goals": [_json_id(v) for v in goals],
            "prior": list(prior) if isinstance(prior, list | tuple) else prior}


def _json_id(v: Any) -> Any:
    """A node id as a JSON value: tuples (grid cells) become lists."""
    return [_json_id(x) for x in v] if isinstance(v, tuple) else v
