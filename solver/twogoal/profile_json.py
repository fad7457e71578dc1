"""Writing an :class:`~solver.twogoal.equilibrium.Equilibrium` as ``dpp-profile/1`` JSON."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from solver.formats.nodes import node_to_json
from solver.numbers import format_number
from solver.version import __version__

if TYPE_CHECKING:
    from solver.twogoal.equilibrium import Equilibrium

__all__ = ["PROFILE_FORMAT", "equilibrium_to_json"]

PROFILE_FORMAT = "dpp-profile/1"


def equilibrium_to_json(eq: Equilibrium) -> dict[str, Any]:
    """The strategy-profile document of ``docs/formats.md`` §2 (exact numbers as strings).

    Parameters
    ----------
    eq : Equilibrium
        The solver's result (:func:`solver.solve`).

    Returns
    -------
    dict
        A ``dpp-profile/1`` document, JSON-serializable.

    Examples
    --------
    The triangle's profile, certified by the independent checker:

    >>> from dppverify import certify
    >>> from solver import solve
    >>> from solver.game.instance import triangle
    >>> from solver.game.instance_writing import instance_to_json
    >>> inst = triangle()
    >>> doc = equilibrium_to_json(solve(inst))
    >>> [(p["path"], p["probability"]) for p in doc["attacker"]["primary"]]
    [(['s', 'g1'], '4/7'), (['s', 'g2'], '3/7')]
    >>> doc["value"]["U"], doc["phases"], doc["exact"]
    ('12/5', {'t_I': 0, 't_II': 1, 'T': 1}, True)
    >>> certify(instance_to_json(inst), doc).verdict
    'pass'
    """
    inst = eq.instance
    fmt = format_number

    def entry(nodes: tuple[Any, ...], prob: Any, label: str) -> dict[str, Any]:
        return {"path": [node_to_json(v) for v in nodes], "probability": fmt(prob),
                "label": label}

    return {
        "format": PROFILE_FORMAT,
        "goals": {"primary": node_to_json(inst.primary),
                  "secondary": node_to_json(inst.secondary)},
        "prior": {"primary": fmt(inst.b1), "secondary": fmt(inst.b2)},
        "defender": {"rule": "progress", "goal": node_to_json(inst.primary)},
        "attacker": {
            "primary": [entry(p.nodes, p.probability, p.label) for p in eq.primary_paths],
            "secondary": [entry(eq.secondary_path, 1, "xi2")],
        },
        "phases": {"t_I": eq.phases.t_I, "t_II": eq.phases.t_II, "T": eq.phases.T},
        "value": {"U1": fmt(eq.U1), "U2": fmt(eq.U2), "U": fmt(eq.U), "U_bar": fmt(eq.U_bar),
                  "VoI": fmt(eq.VoI)},
        "exact": eq.numbers.exact,
        "tolerance": eq.numbers.abs_tol,
        "solver": {"name": "solver", "version": __version__, "method": eq.method,
                   "tie_break": eq.tie_break},
    }
