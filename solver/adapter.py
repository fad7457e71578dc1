"""The solver as an audit target: ``solve_json(instance_doc) -> profile_doc``.

``dpp audit --solver solver.adapter:solve_json`` audits this package's solver with the
independent checker (``docs/audit.md``); any other solver with the same signature can be
audited the same way.
"""

from __future__ import annotations

from typing import Any

from solver.solution import solve

__all__ = ["solve_json"]


def solve_json(instance_doc: dict[str, Any]) -> dict[str, Any]:
    """Solve an instance document (``docs/formats.md`` §1) and return its profile document:
    ``dpp-profile/1`` for two goals (§2), ``dpp-ngoal-profile/1`` for more (§2b).

    Parameters
    ----------
    instance_doc : dict
        An instance document, any number of goals.

    Returns
    -------
    dict
        The profile document of :func:`solver.solve`.

    Examples
    --------
    The triangle of ``examples/triangle.json``:

    >>> import json
    >>> from pathlib import Path
    >>> doc = json.loads((Path(__file__).parents[1] / "examples" / "triangle.json").read_text())
    >>> profile = solve_json(doc)
    >>> profile["format"], profile["value"]["U"]
    ('dpp-profile/1', '12/5')
    >>> [(p["path"], p["probability"]) for p in profile["attacker"]["primary"]]
    [(['s', 'g1'], '4/7'), (['s', 'g2'], '3/7')]
    """
    return solve(instance_doc).to_json()
