"""solver: the constructive Perfect Bayesian Nash equilibrium of the DPP game, for any number
of goals (:func:`solve`; two goals: the paper's σ*, more: the coalition construction).

>>> import networkx as nx
>>> from solver import Instance, solve
>>> g = nx.Graph()
>>> g.add_weighted_edges_from([("s", "g2", 2), ("g2", "g1", 2), ("s", "g1", 3)])
>>> str(solve(Instance(g, "s", ("g1", "g2"), ("7/10", "3/10"))).U)
'12/5'
"""

from __future__ import annotations

import warnings
from typing import TYPE_CHECKING, Any

from solver.version import __version__

_LAZY = {"Solution": "solver.solution", "solve": "solver.solution",
         "summarize": "solver.solution", "Equilibrium": "solver.twogoal.equilibrium",
         "DPPError": "solver.errors", "InstanceFormatError": "solver.errors",
         "InvalidInstanceError": "solver.errors", "Instance": "solver.game.instance",
         "instance_from_json": "solver.game.instance_reading",
         "instance_to_json": "solver.game.instance_writing",
         "load_instance": "solver.game.instance_reading",
         "StrategyWalk": "solver.game.walks"}
"""The public names, each imported on first use (``import solver`` stays cheap)."""

_DEPRECATED = {"StrategyPath": ("StrategyWalk", "solver.game.walks"),
               "equilibrium_to_json": ("_to_json", "solver")}
"""Old public names: still served, with a DeprecationWarning naming what replaces them."""

if TYPE_CHECKING:
    from solver.errors import DPPError, InstanceFormatError, InvalidInstanceError
    from solver.game.instance import Instance
    from solver.game.instance_reading import instance_from_json, load_instance
    from solver.game.instance_writing import instance_to_json
    from solver.game.walks import StrategyWalk
    from solver.solution import Solution, solve, summarize
    from solver.twogoal.equilibrium import Equilibrium

__all__ = ["DPPError", "Equilibrium", "Instance", "InstanceFormatError",
           "InvalidInstanceError", "Solution", "StrategyWalk", "__version__",
           "instance_from_json", "instance_to_json", "load_instance", "solve", "summarize"]


def _to_json(result: Any) -> dict[str, Any]:
    """``result.to_json()``: what the deprecated ``solver.equilibrium_to_json`` does."""
    doc: dict[str, Any] = result.to_json()
    return doc


def __getattr__(name: str) -> Any:
    """Import a public name from its module on first use."""
    import importlib

    if name in _DEPRECATED:
        new, module = _DEPRECATED[name]
        use = "the result's to_json()" if new == "_to_json" else f"solver.{new}"
        warnings.warn(f"solver.{name} is deprecated: use {use}", DeprecationWarning,
                      stacklevel=2)
        return getattr(importlib.import_module(module), new)
    home = _LAZY.get(name)
    if home is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(home), name)
    globals()[name] = value
    return value
