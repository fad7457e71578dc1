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

from collections.abc import Sequence
from typing import Any

from dppverify.formats.json_reading import lookup_node, parse_number, parse_probability, show_node
from dppverify.game.instance import Instance
from dppverify.game.profile import Stated
from dppverify.text import show


def _node_list(game: Instance, nodes: list[int]) -> str:
    return ", ".join(show_node(game.nodes[v]) for v in nodes)


def _shown(raw: Sequence[Any]) -> str:
    """JSON node ids as a message shows them (a list is a grid cell)."""
    return ", ".join(show_node(tuple(g)) if isinstance(g, list) else show_node(g) for g in raw)


def _goal_nodes(game: Instance, stated: Stated) -> list[int] | str | None:
    """The profile's goals as instance node indices (in the profile's order), or a reason."""
    if stated.goals is None:
        return None
    found = [lookup_node(game.index, g) for g in stated.goals]
    if None in found or sorted(v for v in found if v is not None) != sorted(game.goals):
        return (f"its goals are {_shown(stated.goals)}, the instance's are "
                f"{_node_list(game, list(game.goals))}")
    return [v for v in found if v is not None]


def profile_mismatch(game: Instance, stated: Stated) -> str | None:
    """Why a profile that states ``stated`` was not made for ``game``, or None if it may have
    been.

    Parameters
    ----------
    game : Instance
        The instance (two or N goals).
    stated : Stated
        What the parsed profile says about its game (``Profile.stated``, or a
        ``ProfileError``'s ``stated`` when its format is another game's).

    Returns
    -------
    str or None
        One phrase naming the first difference: goals, prior, start, unknown nodes, ``U_bar``.

    Examples
    --------
    >>> from dppverify.game.examples import triangle_document
    >>> from dppverify.game.instance import instance_from_json
    >>> from dppverify.game.profile import stated_of
    >>> inst = instance_from_json(triangle_document())
    >>> ok = {"format": "dpp-profile/1", "goals": {"primary": "g1", "secondary": "g2"},
    ...       "prior": {"primary": "7/10", "secondary": "3/10"},
    ...       "attacker": {"primary": [{"path": ["s", "g1"], "probability": 1}]},
    ...       "value": {"U_bar": "27/10"}}
    >>> def why(doc):
    ...     return profile_mismatch(inst, stated_of(doc))
    >>> why(ok) is None
    True
    >>> print(why({**ok, "prior": {"primary": 0.6, "secondary": 0.4}}))
    it states the prior (3/5, 2/5) for the goals "g1", "g2", the instance's is (7/10, 3/10)
    >>> print(why({**ok, "goals": {"primary": "g1", "secondary": "x"}}))
    its goals are "g1", "x", the instance's are "g1", "g2"
    >>> print(why({**ok, "attacker": {"primary": [{"path": ["t", "g1"]}]}}))
    its walks visit nodes the instance does not have ("t")
    >>> print(why({**ok, "attacker": {"primary": [{"path": ["g2", "g1"]}]}}))
    its walks start at "g2", the instance's start is "s"
    >>> print(why({**ok, "value": {"U_bar": "3"}}))
    it states Ū = 3, but this instance's complete-information value is 27/10
    """
    goals = _goal_nodes(game, stated)
    if isinstance(goals, str):
        return goals
    if goals is not None and stated.prior is not None:
        why = _prior_mismatch(game, goals, stated.prior)
        if why is not None:
            return why
    unknown = [raw for raw in stated.nodes if lookup_node(game.index, raw) is None][:3]
    if unknown:
        return f"its walks visit nodes the instance does not have ({_shown(unknown)})"
    starts = {v for v in (lookup_node(game.index, raw) for raw in stated.starts)
              if v is not None}
    if starts and game.start not in starts:
        return (f"its walks start at {_node_list(game, sorted(starts))}, the instance's start "
                f"is {show_node(game.nodes[game.start])}")
    if stated.u_bar is not None and len(game.goals) == 2:
        return _u_bar_mismatch(game, stated.u_bar)
    return None


def _prior_mismatch(game: Instance, goals: list[int], prior: Sequence[Any]) -> str | None:
    try:
        given = [parse_probability(p, where="prior") for p in prior]
    except (ValueError, TypeError):
        return None
    if len(given) != len(goals):
        return None
    have = [game.prior[game.goals.index(v)] for v in goals]
    if given == have:
        return None
    return (f"it states the prior ({', '.join(show(p) for p in given)}) for the goals "
            f"{_node_list(game, goals)}, the instance's is ({', '.join(show(p) for p in have)})")


def _u_bar_mismatch(game: Instance, raw: Any) -> str | None:
    numbers = game.numbers
    try:
        claimed = parse_number(raw, where="U_bar", allow_float=not game.exact)
    except (ValueError, TypeError):
        return None
    dist = [game.dist_to[i][game.start] for i in range(2)]
    u_bar = numbers.zero()
    for p, d in zip(game.prior, dist, strict=True):
        u_bar = u_bar + numbers.product(numbers.convert(p), d)
    if numbers.equal(numbers.convert(claimed), u_bar):
        return None
    return (f"it states Ū = {show(claimed)}, but this instance's complete-information "
            f"value is {show(u_bar)}")
