"""The one writer of strategy-profile documents (``docs/formats.md`` §2 and §2b).

- ``dpp-profile/1``: two goals in the paper's labelling (primary and secondary types, the
  progress rule σ*, the phases of ξ²), written by the two-goal construction;
- ``dpp-ngoal-profile/1``: one mixed strategy per goal index, for any N, written by the
  coalition construction;
- ``dpp-selection-profile/1``: the goal-selection game's profile (the Attacker's choice ``q``,
  one mixed strategy per goal index, the Defender's rule), written by
  :mod:`solver.selection`.

The constructions write through :func:`two_goal_profile`, :func:`per_goal_profile` and
:func:`selection_profile`, which
share the walk entries, the numbers (exact ``"p/q"`` strings; floats in float mode) and the
solver's provenance block.
"""

from __future__ import annotations

from collections.abc import Hashable, Mapping, Sequence
from typing import TYPE_CHECKING, Any

from solver.formats.nodes import node_to_json
from solver.numbers import Number, NumberMode, format_number
from solver.version import __version__

if TYPE_CHECKING:
    from solver.game.instance import Instance
    from solver.game.walks import StrategyWalk

__all__ = ["NGOAL_PROFILE_FORMAT", "PROFILE_FORMAT", "SELECTION_PROFILE_FORMAT", "WITNESS_FORMAT",
           "per_goal_profile", "selection_profile", "two_goal_profile", "walk_entry"]

PROFILE_FORMAT = "dpp-profile/1"
"""The two-goal profile format (``docs/formats.md`` §2)."""

NGOAL_PROFILE_FORMAT = "dpp-ngoal-profile/1"
"""The per-goal profile format, any N (``docs/formats.md`` §2b)."""

SELECTION_PROFILE_FORMAT = "dpp-selection-profile/1"
"""The goal-selection profile format (``docs/formats.md`` §2d)."""

WITNESS_FORMAT = "dpp-witness/1"
"""The witness format ``dpp solve --witness`` writes for the trusted kernel (``docs/formats.md``
§5)."""


def walk_entry(nodes: Sequence[Hashable], probability: Number,
               label: str = "") -> dict[str, Any]:
    """One walk of a mixed strategy as the profile lists it (the JSON key stays ``"path"``;
    a walk without a label is written without one).

    Examples
    --------
    >>> from fractions import Fraction
    >>> walk_entry(((0, 0), (0, 1)), Fraction(4, 7), "xi1_I")
    {'path': [[0, 0], [0, 1]], 'probability': '4/7', 'label': 'xi1_I'}
    >>> walk_entry(("s", "a"), 1)
    {'path': ['s', 'a'], 'probability': '1'}
    """
    entry: dict[str, Any] = {"path": [node_to_json(v) for v in nodes],
                             "probability": format_number(probability)}
    if label:
        entry["label"] = label
    return entry


def _solver_block(method: str, **more: Any) -> dict[str, Any]:
    return {"name": "solver", "version": __version__, "method": method, **more}


def two_goal_profile(instance: Instance, primary: Sequence[StrategyWalk],
                     secondary: Sequence[StrategyWalk], *, phases: Mapping[str, int],
                     values: Mapping[str, Number], numbers: NumberMode, method: str,
                     tie_break: str) -> dict[str, Any]:
    """The ``dpp-profile/1`` document of a two-goal profile with the progress rule σ*.

    Parameters
    ----------
    instance : Instance
        A two-goal instance (its primary goal is the progress rule's).
    primary, secondary : sequence of StrategyWalk
        The mixed strategies of the primary and the secondary type.
    phases : mapping
        ``t_I``, ``t_II``, ``T`` of ξ².
    values : mapping
        ``U1``, ``U2``, ``U``, ``U_bar``, ``VoI``, in that order.
    numbers : NumberMode
        Exact, or float with its tolerance (written as ``exact`` and ``tolerance``).
    method, tie_break : str
        The solver's provenance.

    Examples
    --------
    >>> from solver.twogoal.equilibrium import paper_equilibrium
    >>> from solver.game.instance import triangle
    >>> doc = paper_equilibrium(triangle()).to_json()   # written by this function
    >>> doc["format"], doc["defender"], doc["value"]["U"]
    ('dpp-profile/1', {'rule': 'progress', 'goal': 'g1'}, '12/5')
    """
    return {
        "format": PROFILE_FORMAT,
        "goals": {"primary": node_to_json(instance.primary),
                  "secondary": node_to_json(instance.secondary)},
        "prior": {"primary": format_number(instance.b1),
                  "secondary": format_number(instance.b2)},
        "defender": {"rule": "progress", "goal": node_to_json(instance.primary)},
        "attacker": {
            "primary": [walk_entry(w.nodes, w.probability, w.label) for w in primary],
            "secondary": [walk_entry(w.nodes, w.probability, w.label) for w in secondary],
        },
        "phases": dict(phases),
        "value": {k: format_number(v) for k, v in values.items()},
        "exact": numbers.exact,
        "tolerance": numbers.abs_tol,
        "solver": _solver_block(method, tie_break=tie_break),
    }


def per_goal_profile(instance: Instance, strategies: Sequence[Sequence[StrategyWalk]], *,
                     defender: Mapping[str, Any], values: Mapping[str, Any], method: str,
                     **provenance: Any) -> dict[str, Any]:
    """The ``dpp-ngoal-profile/1`` document: ``strategies[θ]`` is the mixed strategy of goal
    index ``θ``, ``defender`` the Defender's rule (exact numbers only).

    Examples
    --------
    >>> from fractions import Fraction
    >>> from solver.game.instance import triangle
    >>> from solver.game.walks import StrategyWalk
    >>> inst = triangle()
    >>> walks = [[StrategyWalk.along(inst.network, (0, 2), Fraction(1))],
    ...          [StrategyWalk.along(inst.network, (0, 1), Fraction(1))]]
    >>> doc = per_goal_profile(inst, walks, defender={"rule": "guarantee", "h": ["3", "1"]},
    ...                        values={"U": "12/5"}, method="by hand")
    >>> doc["goals"], doc["attacker"][1]
    (['g1', 'g2'], [{'path': ['s', 'g2'], 'probability': '1'}])
    """
    return {
        "format": NGOAL_PROFILE_FORMAT,
        "goals": [node_to_json(g) for g in instance.goals],
        "attacker": [[walk_entry(w.nodes, w.probability) for w in mix] for mix in strategies],
        "defender": dict(defender),
        "value": dict(values),
        "exact": True,
        "tolerance": None,
        "solver": _solver_block(method, **provenance),
    }


def selection_profile(instance: Instance, strategies: Sequence[Sequence[StrategyWalk]], *,
                      choice: Sequence[Number], defender: Mapping[str, Any],
                      values: Mapping[str, Any], method: str, **provenance: Any
                      ) -> dict[str, Any]:
    """The ``dpp-selection-profile/1`` document: the Attacker chooses goal ``goals[θ]`` with
    probability ``choice[θ]`` and then plays ``strategies[θ]``; ``defender`` is the Defender's
    rule (exact numbers only).

    Examples
    --------
    >>> from fractions import Fraction
    >>> from solver.game.instance import triangle
    >>> from solver.game.walks import StrategyWalk
    >>> inst = triangle()
    >>> walks = [[StrategyWalk.along(inst.network, (0, 2), Fraction(1))],
    ...          [StrategyWalk.along(inst.network, (0, 1), Fraction(1))]]
    >>> doc = selection_profile(inst, walks, choice=[Fraction(0), Fraction(1)],
    ...                         defender={"rule": "guarantee", "h": ["3", "2"]},
    ...                         values={"V": "2"}, method="by hand")
    >>> doc["format"], doc["choice"], doc["attacker"][1]
    ('dpp-selection-profile/1', ['0', '1'], [{'path': ['s', 'g2'], 'probability': '1'}])
    """
    doc = per_goal_profile(instance, strategies, defender=defender, values=values,
                           method=method, **provenance)
    head = {"format": SELECTION_PROFILE_FORMAT, "goals": doc["goals"],
            "choice": [format_number(q) for q in choice]}
    return head | {k: v for k, v in doc.items() if k not in head}
