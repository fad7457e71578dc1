"""Does a profile look made for another instance? A diagnosis for ``dpp certify``'s note.

When ``dpp certify INSTANCE PROFILE`` refutes a profile, :func:`profile_mismatch` says whether
PROFILE looks computed for another game: a profile naming other goals, another prior, another
start, cells the instance does not have, or a complete-information value ``U_bar`` that is not
this instance's. The verdict is the certificate's (exit 1, the failing check naming the claim:
docs/formats.md, "One verdict"; ``dppverify.certify`` and ``dpp audit`` give the same);
this only adds one ``note:`` line saying what to do. Only the profile's identity is compared
here (goals, prior, start, node ids and the stated ``U_bar``, which depends on the instance
alone). Works for any number of goals (``dpp-profile/1`` and ``dpp-ngoal-profile/1``).
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from typing import Any

from dppverify.formats.json_reading import lookup_node, parse_number, parse_probability, show_node
from dppverify.game.instance import Instance
from dppverify.text import show

__all__ = ["profile_mismatch"]


def _node_list(game: Instance, nodes: list[int]) -> str:
    return ", ".join(show_node(game.nodes[v]) for v in nodes)


def _walks(doc: Mapping[str, Any]) -> Iterator[list[Any]]:
    """Every walk (a ``path`` member) listed under ``attacker`` (either format), skipping
    malformed entries."""
    attacker = doc.get("attacker")
    groups: list[Any] = []
    if isinstance(attacker, Mapping):
        groups = [attacker.get("primary"), attacker.get("secondary")]
    elif isinstance(attacker, list):
        groups = attacker
    for group in groups:
        if not isinstance(group, list):
            continue
        for entry in group:
            if isinstance(entry, Mapping) and isinstance(entry.get("path"), list):
                yield entry["path"]


def _goal_nodes(game: Instance, doc: Mapping[str, Any]) -> list[int] | str | None:
    """The profile's goals as instance node indices (in the profile's order), or a reason."""
    raw = doc.get("goals")
    if isinstance(raw, Mapping):
        raw = [raw.get("primary"), raw.get("secondary")]
    if not isinstance(raw, list) or not raw:
        return None
    found = [lookup_node(game.index, g) for g in raw]
    theirs = ", ".join(show_node(g) if not isinstance(g, list) else show_node(tuple(g))
                       for g in raw)
    ours = _node_list(game, list(game.goals))
    if None in found or sorted(v for v in found if v is not None) != sorted(game.goals):
        return f"its goals are {theirs}, the instance's are {ours}"
    return [v for v in found if v is not None]


def profile_mismatch(game: Instance, doc: Any) -> str | None:
    """Why the profile document ``doc`` was not made for ``game``, or None if it may have been.

    Parameters
    ----------
    game : Instance
        The instance (two or N goals).
    doc : Any
        The parsed profile document (anything; malformed parts are left to the certificate).

    Returns
    -------
    str or None
        One phrase naming the first difference: goals, prior, start, unknown nodes, ``U_bar``.

    Examples
    --------
    >>> from dppverify.game.examples import triangle_document
    >>> from dppverify.game.instance import instance_from_json
    >>> inst = instance_from_json(triangle_document())
    >>> ok = {"format": "dpp-profile/1", "goals": {"primary": "g1", "secondary": "g2"},
    ...       "prior": {"primary": "7/10", "secondary": "3/10"},
    ...       "attacker": {"primary": [{"path": ["s", "g1"], "probability": 1}]},
    ...       "value": {"U_bar": "27/10"}}
    >>> profile_mismatch(inst, ok) is None
    True
    >>> print(profile_mismatch(inst, {**ok, "prior": {"primary": 0.6, "secondary": 0.4}}))
    it states the prior (3/5, 2/5) for the goals "g1", "g2", the instance's is (7/10, 3/10)
    >>> print(profile_mismatch(inst, {**ok, "goals": {"primary": "g1", "secondary": "x"}}))
    its goals are "g1", "x", the instance's are "g1", "g2"
    >>> print(profile_mismatch(inst, {**ok, "attacker": {"primary": [{"path": ["t", "g1"]}]}}))
    its walks visit nodes the instance does not have ("t")
    >>> print(profile_mismatch(inst, {**ok, "attacker": {"primary": [{"path": ["g2", "g1"]}]}}))
    its walks start at "g2", the instance's start is "s"
    >>> print(profile_mismatch(inst, {**ok, "value": {"U_bar": "3"}}))
    it states Ū = 3, but this instance's complete-information value is 27/10
    """
    if not isinstance(doc, Mapping):
        return None
    goals = _goal_nodes(game, doc)
    if isinstance(goals, str):
        return goals
    numbers = game.numbers
    prior = doc.get("prior")
    if goals is not None and isinstance(prior, Mapping | list):
        raw = ([prior.get("primary"), prior.get("secondary")] if isinstance(prior, Mapping)
               else prior)
        try:
            stated = [parse_probability(p, where="prior") for p in raw]
        except (ValueError, TypeError):
            stated = None
        if stated is not None and len(stated) == len(goals):
            have = [game.prior[game.goals.index(v)] for v in goals]
            if stated != have:
                return (f"it states the prior ({', '.join(show(p) for p in stated)}) for the "
                        f"goals {_node_list(game, goals)}, the instance's is "
                        f"({', '.join(show(p) for p in have)})")
    unknown: list[Any] = []
    starts: set[int] = set()
    for walk in _walks(doc):
        for k, raw_node in enumerate(walk):
            v = lookup_node(game.index, raw_node)
            if v is None:
                if len(unknown) < 3 and raw_node not in unknown:
                    unknown.append(raw_node)
            elif k == 0:
                starts.add(v)
    if unknown:
        shown = ", ".join(show_node(tuple(u) if isinstance(u, list) else u) for u in unknown)
        return f"its walks visit nodes the instance does not have ({shown})"
    if starts and game.start not in starts:
        return (f"its walks start at {_node_list(game, sorted(starts))}, the instance's start "
                f"is {show_node(game.nodes[game.start])}")
    value = doc.get("value")
    if isinstance(value, Mapping) and "U_bar" in value and len(game.goals) == 2:
        try:
            claimed = parse_number(value["U_bar"], where="U_bar", allow_float=not game.exact)
        except (ValueError, TypeError):
            return None
        dist = [game.dist_to[i][game.start] for i in range(2)]
        u_bar = numbers.zero()
        for p, d in zip(game.prior, dist, strict=True):
            u_bar = u_bar + numbers.product(numbers.convert(p), d)
        if not numbers.equal(numbers.convert(claimed), u_bar):
            return (f"it states Ū = {show(claimed)}, but this instance's "
                    f"complete-information value is {show(u_bar)}")
    return None
